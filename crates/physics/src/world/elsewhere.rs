//! A world whose balls are simulated elsewhere (the GPU engine): it hands
//! its balls over and steps its tumblers and fireball alone, and the balls'
//! pushes on its tumblers come back as impulses.

use crate::balls::Balls;
use crate::tumbler::grounded_solve;
use glam::{DMat3, DVec3};

use super::{BuildError, World};

impl World {
    /// Takes every ball out of the world: from here it steps its tumblers
    /// and fireball alone. [`World::reset_balls`] and [`World::throw_ball`]
    /// put balls back in, to be taken again.
    pub fn take_balls(&mut self) -> Balls {
        let taken = self.balls.clone();
        self.balls.truncate(0);
        self.scratch.hit_wall.clear();
        self.ball_hold = None;
        for w in [&mut self.warm, &mut self.warm_next] {
            w.begin(&[], 0, 0);
        }
        taken
    }

    /// Puts balls simulated elsewhere back into the world, to report them
    /// (its energy, a trace line) before they are taken again with
    /// [`World::take_balls`]; a step with them in would simulate them here.
    pub fn put_balls(&mut self, balls: Balls) {
        self.scratch.hit_wall = vec![false; balls.len()];
        self.balls = balls;
    }

    /// The balls drawn afresh as the scene starts them (see
    /// [`World::reset_balls`]), taken out of the world as by
    /// [`World::take_balls`].
    pub fn fresh_balls(&mut self) -> Result<Balls, BuildError> {
        let b = &self.config.balls;
        self.balls = Balls::with_uniform(b.total(), b.radius, b.mass);
        self.scratch.hit_wall = vec![false; b.total()];
        self.reset_balls()?;
        Ok(self.take_balls())
    }

    /// How tumbler `t` answers a push while it rolls: the point it turns
    /// about (where it touches the floor) and the inverse of its inertia
    /// about that point, in world axes. A push `j` at `p` turns it by
    /// `inverse * ((p - pivot) x j)`.
    pub fn tumbler_pivot(&self, t: usize) -> Option<(DVec3, DMat3)> {
        let tumbler = self.tumblers.get(t)?;
        Some((
            tumbler.contact_point(),
            tumbler.contact_inertia_inverse(&self.shape),
        ))
    }

    /// Gives tumbler `t` a push from balls simulated elsewhere: `impulse`
    /// in all (N s) and its `moment` about the tumbler's bottom centre
    /// (N m s), from balls of `pushing_mass` in all (kg). Rolling, the floor
    /// holds the contact point and the tumbler turns about it; sliding, the
    /// floor pushes up only, as for a ball's push in this world.
    ///
    /// The balls met the tumbler as if it could not move; the push is
    /// shared as if they moved with it, the tumbler's mass over its own and
    /// theirs. Without that share, a crowd heavier than the tumbler would
    /// push it back harder than it pushed them, and the next step harder
    /// still.
    pub fn push_tumbler(&mut self, t: usize, impulse: DVec3, moment: DVec3, pushing_mass: f64) {
        let Some(tumbler) = self.tumblers.get(t) else {
            return;
        };
        let strength = impulse.length();
        if !strength.is_finite() || strength <= 0.0 || !moment.is_finite() {
            return;
        }
        let shape = &self.shape;
        let share = shape.mass / (shape.mass + pushing_mass.max(0.0));
        let (impulse, moment) = (impulse * share, moment * share);
        let strength = strength * share;
        let centre = tumbler.bottom_center();
        let (angular, linear) = match tumbler.mode {
            crate::tumbler::FloorMode::Rolling => {
                let contact = tumbler.contact_point();
                let about_contact = moment + (centre - contact).cross(impulse);
                let dw = tumbler.contact_inertia_inverse(shape) * about_contact;
                (dw, tumbler.bottom_radius * dw.cross(DVec3::Y))
            }
            mode => {
                let g = tumbler.center_of_mass();
                let about_g = moment + (centre - g).cross(impulse);
                let sol = grounded_solve(
                    shape,
                    tumbler.orientation,
                    mode,
                    self.config.tumblers.floor_friction,
                    impulse / strength,
                    about_g / strength,
                );
                (sol.dw * strength, sol.planar * strength)
            }
        };
        let tumbler = &mut self.tumblers[t];
        tumbler.angular_velocity += angular;
        tumbler.center_velocity += linear;
    }
}
