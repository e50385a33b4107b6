//! The fireball's flight: substeps short enough that it cannot pass
//! through a ball, at constant speed.

use crate::events::{Event, EventKind};
use crate::room::Surface;

use super::World;

impl World {
    /// Moves the fireball in substeps short enough that it cannot pass
    /// through a ball, bouncing off walls, tumblers and balls at constant speed.
    pub(super) fn move_fireball(&mut self, dt: f64) {
        let Some(mut f) = self.fireball.take() else {
            return;
        };
        let min_radius = f.radius.min(self.config.balls.radius);
        let substeps = ((f.speed * dt) / (0.5 * min_radius)).ceil().max(1.0) as usize;
        let h = dt / substeps as f64;
        let shape = &self.shape;
        let friction = self.config.tumblers.floor_friction;
        for substep in 1..=substeps {
            let within_step = substep as f64 * h;
            f.position += f.velocity * h;
            for s in Surface::ALL {
                let n = s.inward_normal();
                let d = self.room.distance(s, f.position) - f.radius;
                if d < 0.0 {
                    f.position += n * -d;
                    let vn = f.velocity.dot(n);
                    if vn < 0.0 {
                        f.velocity -= 2.0 * vn * n;
                        self.events.push(Event {
                            kind: EventKind::FireballSurface { surface: s },
                            point: f.position - n * f.radius,
                            normal: n,
                            speed: -vn,
                            within_step,
                        });
                    }
                }
            }
            for i in 0..self.balls.len() {
                if !self.balls.alive[i] {
                    continue;
                }
                let d = f.position - self.balls.position[i];
                let dist = d.length();
                let overlap = f.radius + self.balls.radius[i] - dist;
                if overlap <= 0.0 || dist == 0.0 {
                    continue;
                }
                let n = d / dist;
                let vn = (f.velocity - self.balls.velocity[i]).dot(n);
                if self.config.fireball.consumes_balls {
                    // Caught: the ball leaves the world; the fireball flies on.
                    self.balls.alive[i] = false;
                    self.events.push(Event {
                        kind: EventKind::FireballBall { ball: i },
                        point: self.balls.position[i] + n * self.balls.radius[i],
                        normal: n,
                        speed: (-vn).max(0.0),
                        within_step,
                    });
                    continue;
                }
                f.position += n * overlap;
                if vn < 0.0 {
                    // An elastic impulse between equal partners, then the
                    // fireball resumes its constant speed.
                    let j = -2.0 * vn / (1.0 / f.mass + self.balls.inv_mass[i]);
                    self.balls.velocity[i] -= n * (j * self.balls.inv_mass[i]);
                    f.velocity += n * (j / f.mass);
                    f.restore_speed(n);
                    self.events.push(Event {
                        kind: EventKind::FireballBall { ball: i },
                        point: self.balls.position[i] + n * self.balls.radius[i],
                        normal: n,
                        speed: -vn,
                        within_step,
                    });
                }
            }
            for (ti, t) in self.tumblers.iter_mut().enumerate() {
                for (si, s) in shape.spheres.iter().enumerate() {
                    let c = t.sphere_center(shape, si);
                    let d = f.position - c;
                    let dist = d.length();
                    let overlap = f.radius + s.radius - dist;
                    if overlap <= 0.0 || dist == 0.0 {
                        continue;
                    }
                    let n = d / dist;
                    f.position += n * overlap;
                    let point = c + n * s.radius;
                    let vn = (f.velocity - t.point_velocity(point)).dot(n);
                    if vn < 0.0 {
                        let inv = t.contact_inertia_inverse(shape);
                        // Response to an impulse along -n (pushing the tumbler away).
                        let r = t.impulse_response(shape, &inv, friction, point, -n);
                        let w = (r.center_velocity + r.angular_velocity.cross(point - t.center))
                            .dot(-n);
                        let j = -2.0 * vn / (1.0 / f.mass + w);
                        t.apply_response(&r, j);
                        f.velocity += n * (j / f.mass);
                        f.restore_speed(n);
                        self.events.push(Event {
                            kind: EventKind::FireballTumbler {
                                tumbler: ti,
                                sphere: si,
                            },
                            point,
                            normal: n,
                            speed: -vn,
                            within_step,
                        });
                    }
                }
            }
            f.position = self.room.clamp_sphere(f.position, f.radius);
        }
        self.fireball = Some(f);
    }
}
