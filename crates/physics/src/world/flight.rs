//! Step 4: the bodies move. Balls fly along exact parabolas and bounce
//! exactly off the walls; tumblers integrate their grounded rolling and
//! sliding equations.

use crate::balls::Tint;
use crate::ccd::{bounce_off_wall, first_impact};
use crate::events::{Event, EventKind};
use crate::room::Surface;
use crate::tumbler::GroundedParams;
use glam::DVec3;

use super::World;

impl World {
    /// Rolling resistance: a ball pressed on a surface loses rolling speed
    /// in proportion to the normal impulse, until it stops.
    pub(super) fn apply_rolling_resistance(&mut self) {
        let coefficient = self.config.room.rolling_resistance;
        for c in &self.contacts.walls {
            if c.pushed <= 0.0 {
                continue;
            }
            let (i, n) = (c.ball as usize, c.normal());
            let v = self.balls.velocity[i];
            let tangential = v - v.dot(n) * n;
            let speed = tangential.length();
            let loss = coefficient * c.pushed * self.balls.inv_mass[i];
            let keep = if speed > loss {
                1.0 - loss / speed
            } else {
                0.0
            };
            let kept = v.dot(n) * n + tangential * keep;
            self.impulses.surfaces += self.balls.mass[i] * (kept - v);
            self.balls.velocity[i] = kept;
            self.balls.spin[i] *= keep;
        }
    }

    /// Moves every ball along its parabola, bouncing exactly off the walls.
    pub(super) fn move_balls(&mut self, dt: f64, gravity: DVec3) {
        let room = self.room;
        let solver = &self.config.solver;
        let (e, mu) = (self.config.room.restitution, self.config.room.friction);
        for i in 0..self.balls.len() {
            self.scratch.hit_wall[i] = false;
            if !self.balls.alive[i] {
                continue;
            }
            let r = self.balls.radius[i];
            if self.scratch.ball_partners[i] > 0 {
                // Its walls are in the solver already (see `collect_contacts`):
                // the step-average velocity carries it along its parabola,
                // from where its impacts moved the path's start.
                let v = self.balls.velocity[i];
                let start = self.balls.position[i] + self.scratch.impacts.shift(i);
                self.balls.position[i] = room.clamp_sphere(start + v * dt, r);
                self.balls.velocity[i] = v + 0.5 * dt * gravity;
                continue;
            }
            let m = self.balls.mass[i];
            let inertia = self.balls.inertia(i);
            let mut x = self.balls.position[i];
            // Instantaneous velocity at the start of the step.
            let mut u = self.balls.velocity[i] - 0.5 * dt * gravity;
            let mut spin = self.balls.spin[i];
            let mut g = gravity;
            let mut left = dt;
            for _ in 0..8 {
                let mut first: Option<(f64, Surface)> = None;
                for s in Surface::ALL {
                    let n = s.inward_normal();
                    let d0 = room.distance(s, x) - r;
                    if let Some(t) = first_impact(d0, n.dot(u), n.dot(g), left)
                        && first.is_none_or(|(best, _)| t < best)
                    {
                        first = Some((t, s));
                    }
                }
                let Some((t, s)) = first else {
                    x += u * left + 0.5 * g * left * left;
                    u += g * left;
                    left = 0.0;
                    break;
                };
                x += u * t + 0.5 * g * t * t;
                u += g * t;
                left -= t;
                let n = s.inward_normal();
                // Sit exactly on the wall.
                x += n * (r - room.distance(s, x));
                let speed = -n.dot(u);
                self.scratch.hit_wall[i] = true;
                // Slower than the threshold, it comes to rest on the wall.
                let bounces = speed > solver.bounce_threshold;
                let restitution = if bounces { e } else { 0.0 };
                let before = u;
                (u, spin, _) = bounce_off_wall((u, spin), n, (r, m, inertia), restitution, mu);
                self.impulses.surfaces += m * (u - before);
                if !bounces && n.dot(g) < 0.0 {
                    // Resting on it: the wall carries gravity from here on.
                    let carried = n.dot(g) * n;
                    g -= carried;
                    self.impulses.surfaces -= m * carried * left;
                }
                if speed > solver.event_threshold {
                    self.balls.tint[i] = Tint::Surface(s);
                    self.events.push(Event {
                        kind: EventKind::BallSurface {
                            ball: i,
                            surface: s,
                        },
                        point: x - r * n,
                        normal: n,
                        speed,
                        within_step: dt - left,
                    });
                }
            }
            // Bouncing ever faster on a floor (an elastic ball nearly at
            // rest) it ends the step where its bounces left it: the wall
            // held it up for the rest.
            self.impulses.surfaces -= m * g * left;
            self.balls.position[i] = room.clamp_sphere(x, r);
            self.balls.velocity[i] = u;
            self.balls.spin[i] = spin;
        }
    }

    pub(super) fn move_tumblers(&mut self, dt: f64) {
        let params = GroundedParams {
            shape: &self.shape,
            gravity: self.config.gravity,
            friction: self.config.tumblers.floor_friction,
            damping: self.config.tumblers.damping,
            grab: &self.config.grab,
        };
        for t in &mut self.tumblers {
            t.choose_mode(&params);
            t.integrate(&params, dt);
        }
    }
}
