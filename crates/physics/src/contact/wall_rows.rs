//! Ball-wall contacts as a solver stage iterates on them: the normal
//! impulse, then Coulomb friction at the contact point, so that a sliding
//! ball starts to roll.

use crate::balls::{Balls, sphere_inertia};
use crate::room::Surface;
use glam::DVec3;

use super::{Contacts, PARALLEL_PAIRS, WallContact, accumulate};

/// A ball-wall contact as a solver stage iterates on it: as [`super::PairRow`],
/// only what the iterations read, with its ball's build worked out once
/// (divisions are slow).
#[derive(Clone, Copy, Debug)]
struct WallRow {
    slot: u32,
    surface: Surface,
    /// The ball's mass and its inverse: the wall does not move.
    mass: f64,
    inv_mass: f64,
    /// The normal velocity the stage drives the ball to, at least.
    target: f64,
    /// Coulomb friction coefficient (0: the stage solves no friction).
    friction: f64,
    radius: f64,
    inv_inertia: f64,
    /// Mass along a tangent at the contact point: 2m/7 for a solid sphere.
    tangent_mass: f64,
}

/// A wall row's accumulated impulses: along the normal and the two tangents.
#[derive(Clone, Copy, Debug, Default)]
struct WallImpulse {
    normal: f64,
    friction: [f64; 2],
}

impl WallImpulse {
    fn starting(normal: f64) -> WallImpulse {
        WallImpulse {
            normal,
            friction: [0.0; 2],
        }
    }
}

/// The wall rows of a stage, and the impulses each has accumulated (apart,
/// as in [`super::RowBand`]).
#[derive(Clone, Debug, Default)]
pub(super) struct WallRows {
    rows: Vec<WallRow>,
    impulses: Vec<WallImpulse>,
    /// Each surface's frame, by surface index: worked out once a stage.
    frames: [WallFrame; 6],
}

impl Contacts {
    /// Fills the wall rows from the ball-wall contacts that `row` chooses,
    /// in order, with the target and friction coefficient it gives them;
    /// each starts from its contact's impulse, applied already.
    pub(super) fn start_wall_rows<F>(&mut self, balls: &Balls, row: F)
    where
        F: Fn(&WallContact) -> Option<(f64, f64)> + Sync,
    {
        let walls = &self.walls;
        let build = |c: &WallContact| {
            let (target, friction) = row(c)?;
            let row = WallRow::new(c.ball as usize, c.surface, balls, target, friction);
            Some((row, WallImpulse::starting(c.impulse)))
        };
        // On one thread: a parallel filter gathers its pieces in lists,
        // which costs more than the rows.
        let WallRows {
            rows,
            impulses,
            frames,
        } = &mut self.wall_rows;
        *frames = Surface::ALL.map(WallFrame::of);
        let mut built = (std::mem::take(rows), std::mem::take(impulses));
        built.0.clear();
        built.1.clear();
        built.extend(walls.iter().filter_map(build));
        (*rows, *impulses) = built;
    }

    /// One Gauss-Seidel sweep over the wall rows.
    ///
    /// A ball-wall contact moves its ball alone, so different balls' rows
    /// are solved side by side; each ball's own in their order, which keeps
    /// the result the same on any number of threads.
    pub(super) fn sweep_wall_rows(&mut self, balls: &mut Balls) {
        let parallel =
            self.wall_rows.rows.len() >= PARALLEL_BALL_WALLS && self.pair_count() >= PARALLEL_PAIRS;
        let WallRows {
            rows,
            impulses,
            frames,
        } = &mut self.wall_rows;
        let view = BallSlices {
            velocity: &mut balls.velocity,
            spin: &mut balls.spin,
            first: 0,
        };
        sweep_wall_rows(rows, impulses, view, frames, parallel);
    }

    /// Hands each ball-wall contact its row's normal impulse, 0 for the
    /// contacts without a row; `chosen` tells them as in
    /// [`Contacts::start_wall_rows`]. Returns the impulse the rows gave
    /// their balls over the stage, warm start and friction included (N s).
    pub(super) fn keep_wall_impulses<F>(&mut self, chosen: F) -> DVec3
    where
        F: Fn(&WallContact) -> bool,
    {
        let WallRows {
            rows,
            impulses,
            frames,
        } = &self.wall_rows;
        let given = rows
            .iter()
            .zip(impulses)
            .fold(DVec3::ZERO, |sum, (row, held)| {
                let frame = &frames[row.surface.index()];
                sum + frame.normal * held.normal
                    + frame.tangents[0] * held.friction[0]
                    + frame.tangents[1] * held.friction[1]
            });
        let mut impulses = self.wall_rows.impulses.iter();
        for c in &mut self.walls {
            c.impulse = if chosen(c) {
                impulses.next().map_or(0.0, |k| k.normal)
            } else {
                0.0
            };
        }
        given
    }
}

/// A surface's inward normal, the two tangents friction acts along, and
/// the axes about which friction along each turns a ball (normal x tangent).
#[derive(Clone, Copy, Debug, Default)]
struct WallFrame {
    normal: DVec3,
    tangents: [DVec3; 2],
    turns: [DVec3; 2],
}

impl WallFrame {
    fn of(surface: Surface) -> WallFrame {
        let normal = surface.inward_normal();
        let (t1, t2) = normal.any_orthonormal_pair();
        WallFrame {
            normal,
            tangents: [t1, t2],
            turns: [normal.cross(t1), normal.cross(t2)],
        }
    }
}

impl WallRow {
    fn new(slot: usize, surface: Surface, balls: &Balls, target: f64, friction: f64) -> WallRow {
        let (mass, inv_mass, radius) = (balls.mass[slot], balls.inv_mass[slot], balls.radius[slot]);
        let inv_inertia = 1.0 / sphere_inertia(mass, radius);
        WallRow {
            slot: slot as u32,
            surface,
            mass: if inv_mass > 0.0 { 1.0 / inv_mass } else { 0.0 },
            inv_mass,
            target,
            friction,
            radius,
            inv_inertia,
            tangent_mass: 1.0 / (inv_mass + radius * radius * inv_inertia),
        }
    }

    /// One Gauss-Seidel update of the row, as [`super::Bodies::solve_normal`] for a
    /// ball on a wall, then Coulomb friction at the contact point, so that
    /// a sliding ball starts to roll.
    #[inline]
    fn solve(
        &self,
        impulse: &mut WallImpulse,
        velocity: &mut DVec3,
        spin: &mut DVec3,
        frame: &WallFrame,
    ) {
        let n = frame.normal;
        let delta = accumulate(&mut impulse.normal, self.mass, velocity.dot(n), self.target);
        *velocity += n * (delta * self.inv_mass);
        let limit = self.friction * impulse.normal;
        if limit == 0.0 && impulse.friction == [0.0; 2] {
            // Nothing to hold and nothing held: most speculative contacts.
            return;
        }
        // The contact point lies at -radius n: its slip along t is
        // v.t + (spin x -rn).t = v.t - r spin.(n x t), and an impulse along
        // t there turns the ball about -(n x t).
        let r = self.radius;
        for k in 0..2 {
            let (t, turn) = (frame.tangents[k], frame.turns[k]);
            let held = &mut impulse.friction[k];
            let slip = velocity.dot(t) - r * spin.dot(turn);
            let total = (*held - self.tangent_mass * slip).clamp(-limit, limit);
            let delta = total - *held;
            *held = total;
            *velocity += t * (delta * self.inv_mass);
            *spin -= turn * (r * delta * self.inv_inertia);
        }
    }
}

/// Below this many ball-wall contacts, or [`PARALLEL_PAIRS`] pairs, they are
/// solved on one thread (the crowded pit of the thread test has more).
const PARALLEL_BALL_WALLS: usize = 512;

/// The velocities and spins of the balls from slot `first` on.
struct BallSlices<'a> {
    velocity: &'a mut [DVec3],
    spin: &'a mut [DVec3],
    first: usize,
}

/// Solves wall rows (in slot order) whose balls lie in `balls`, halving the
/// work across threads between two balls.
fn sweep_wall_rows(
    rows: &[WallRow],
    impulses: &mut [WallImpulse],
    balls: BallSlices,
    frames: &[WallFrame; 6],
    parallel: bool,
) {
    if parallel && rows.len() >= PARALLEL_BALL_WALLS / 2 {
        let mut half = rows.len() / 2;
        while half < rows.len() && rows[half].slot == rows[half - 1].slot {
            half += 1;
        }
        if let Some(split) = rows.get(half).map(|r| r.slot as usize) {
            let (left, right) = rows.split_at(half);
            let (left_impulses, right_impulses) = impulses.split_at_mut(half);
            let (lv, rv) = balls.velocity.split_at_mut(split - balls.first);
            let (ls, rs) = balls.spin.split_at_mut(split - balls.first);
            let (left_balls, right_balls) = (
                BallSlices {
                    velocity: lv,
                    spin: ls,
                    first: balls.first,
                },
                BallSlices {
                    velocity: rv,
                    spin: rs,
                    first: split,
                },
            );
            rayon::join(
                || sweep_wall_rows(left, left_impulses, left_balls, frames, parallel),
                || sweep_wall_rows(right, right_impulses, right_balls, frames, parallel),
            );
            return;
        }
    }
    for (row, impulse) in rows.iter().zip(impulses) {
        let k = row.slot as usize - balls.first;
        let frame = &frames[row.surface.index()];
        row.solve(impulse, &mut balls.velocity[k], &mut balls.spin[k], frame);
    }
}
