//! Step 1: every contact that may act during the coming step, found at
//! its start. Speculative: a contact is kept if its gap could close
//! within the step, so that nothing tunnels into anything.

use crate::balls::PARALLEL_BALLS;
use crate::ccd::contact_normal;
use crate::contact::{BodyRef, Contact, Pair, PairSlots, WallContact};
use crate::room::Surface;
use glam::DVec3;
use rayon::prelude::*;

use super::impacts::{closes_fast, impact_threshold};
use super::{TOUCH_SLOP, World};

/// What the pair search fills for one grid layer: its band of pairs, their
/// slots, and the slots of those due to collide (see `impacts`).
type BandOut<'a> = (
    (&'a mut Vec<Pair>, &'a mut Vec<PairSlots>),
    &'a mut Vec<PairSlots>,
);

impl World {
    /// All contacts that may act during the coming step.
    pub(super) fn collect_contacts(&mut self, dt: f64) {
        self.collect_ball_pairs(dt);
        self.collect_wall_contacts(dt);
        self.collect_tumbler_contacts(dt);
        // Approach speeds before anything moves: what restitution acts on
        // (pairs and walls have theirs from when they were found).
        let step = self.step_context(false);
        let (bodies, contacts) = (&step.bodies, step.contacts);
        for c in contacts.tumbler_contacts.iter_mut() {
            c.approach = bodies.normal_velocity(c);
        }
    }

    /// How far a contact may be from touching and still be kept: a
    /// contact is kept if its gap could close within the step, up to one
    /// ball radius (the grid's cell allows for that).
    fn speculative_reach(&self) -> f64 {
        self.config.balls.radius
    }

    /// Pairs of balls that may touch within the step, band by band.
    fn collect_ball_pairs(&mut self, dt: f64) {
        let balls = &self.balls;
        let reach_cap = self.speculative_reach();
        let contacts = &mut self.contacts;

        // Each ball's share of the pair test below: its radius and how far
        // it could fly, so that resting balls look no further than touching;
        // widened by more than `f32` rounds off in a room of any size.
        let (spheres, speed) = (&mut self.scratch.pair_spheres, &mut self.scratch.speed);
        speed.clear();
        speed.extend(balls.velocity.iter().map(|v| v.length()));
        spheres.clear();
        spheres.extend((0..balls.len()).map(|i| {
            let p = balls.position[i];
            let reach = balls.radius[i] + (2.0 * speed[i] * dt).min(reach_cap) + TOUCH_SLOP;
            let rounding = 1e-6 * (1.0 + p.abs().max_element());
            p.as_vec3().extend((reach + rounding) as f32)
        }));
        let (spheres, speed) = (&self.scratch.pair_spheres, &self.scratch.speed);
        let grid = &self.grid;
        contacts.reset(grid.layer_count());
        grid.layer_slots(&mut contacts.layers);
        // The impacts stage's pairs, picked out here while each pair is found.
        let due_bands = self.scratch.impacts.due_bands(grid.layer_count());
        let threshold = impact_threshold(&self.config);
        let find_pairs = |(z, ((band, slots), due)): (usize, BandOut)| {
            grid.for_each_close_pair_in_layer(spheres, z, |i, j| {
                let d = balls.position[i] - balls.position[j];
                let dist = d.length();
                let gap = dist - balls.radius[i] - balls.radius[j];
                let relative = balls.velocity[i] - balls.velocity[j];
                if kept_as_pair(gap, speed[i] + speed[j], dt, reach_cap) && dist > 0.0 {
                    // Gravity moves both alike, so within the step they close
                    // along a straight line: take the normal where they meet.
                    // (Balls that only pass by keep the line of centres here;
                    // the impacts stage turns free ones' where they come
                    // closest.)
                    let reach = balls.radius[i] + balls.radius[j];
                    let (n, gap) = contact_normal(d, relative, reach, dt, f64::INFINITY)
                        .unwrap_or((d / dist, gap));
                    // Approach speed before anything moves: what restitution acts on.
                    let approach = relative.dot(n);
                    band.push(Pair::new(i, j, n, gap, approach));
                    slots.push([i as u32, j as u32]);
                    if closes_fast(gap, approach, threshold, dt) {
                        due.push([i as u32, j as u32]);
                    }
                }
            });
        };
        // Each layer fills its own band, so the pairs come out in the same
        // order on any number of threads.
        if balls.len() >= PARALLEL_BALLS {
            contacts
                .bands
                .par_iter_mut()
                .zip(&mut contacts.pair_slots)
                .zip(due_bands)
                .enumerate()
                .for_each(find_pairs);
        } else {
            let bands = contacts.bands.iter_mut().zip(&mut contacts.pair_slots);
            bands.zip(due_bands).enumerate().for_each(find_pairs);
        }
        contacts.count_pairs();
    }

    /// Balls against the walls, once each ball's partners are counted.
    fn collect_wall_contacts(&mut self, dt: f64) {
        let balls = &self.balls;
        let cfg = &self.config;
        let reach_cap = self.speculative_reach();
        let contacts = &mut self.contacts;
        let room = &self.room;
        let speed = &self.scratch.speed;

        // Balls resting on or touching a wall. A lone ball's impacts are
        // found exactly while moving (see `move_balls`); a ball pressed by
        // others gets a speculative contact with every wall it could reach
        // in the step, so that it stops there with them instead of bouncing
        // back into them (which would sink balls into each other).
        let partners = &mut self.scratch.ball_partners;
        partners.clear();
        partners.resize(balls.len(), 0);
        contacts.sweep_pair_slots(partners, &|[i, j], partners, first| {
            for k in [i as usize - first, j as usize - first] {
                partners[k] = partners[k].saturating_add(1);
            }
        });
        let partners = &self.scratch.ball_partners;
        let bounce_threshold = cfg.solver.bounce_threshold;
        let touch_walls = |i: usize, into: &mut Vec<WallContact>| {
            let crowded = partners[i] > 0;
            // Most balls of a crowd lie beyond any wall's reach below, and
            // beyond the nearest wall is beyond them all (with a slop's
            // margin for rounding).
            let widest = if crowded {
                (speed[i] * dt).max(reach_cap)
            } else {
                0.0
            };
            let clearance = room.nearest_distance(balls.position[i]) - balls.radius[i];
            if clearance > widest + 2.0 * TOUCH_SLOP {
                return;
            }
            for s in Surface::ALL {
                let gap = room.distance(s, balls.position[i]) - balls.radius[i];
                let n = s.inward_normal();
                // Others may push it as far as it could fly: allow for both.
                let reach = if crowded {
                    (-balls.velocity[i].dot(n) * dt).max(reach_cap)
                } else {
                    0.0
                };
                // Its approach speed before anything moves: what
                // restitution acts on.
                let approach = balls.velocity[i].dot(n);
                // A lone ball meets a wall fast enough to bounce exactly in
                // flight; the contact would stop it first.
                let bounces_in_flight = !crowded && approach < -bounce_threshold;
                if gap <= reach + TOUCH_SLOP && !bounces_in_flight {
                    let gap = if gap > TOUCH_SLOP { gap } else { gap.min(0.0) };
                    into.push(WallContact::new(i, s, gap, approach));
                }
            }
        };
        // Layer by layer, each into its own list, then in layer order: the
        // same contacts in the same order on any number of threads.
        let layers = &contacts.layers;
        let by_layer = &mut self.scratch.wall_contacts_by_layer;
        by_layer.resize_with(layers.len() - 1, Vec::new);
        let fill = |(z, into): (usize, &mut Vec<WallContact>)| {
            into.clear();
            (layers[z]..layers[z + 1]).for_each(|i| touch_walls(i, into));
        };
        if balls.len() >= PARALLEL_BALLS {
            by_layer.par_iter_mut().enumerate().for_each(fill);
        } else {
            by_layer.iter_mut().enumerate().for_each(fill);
        }
        for layer in by_layer.iter() {
            contacts.walls.extend_from_slice(layer);
        }
    }

    /// Every contact of a tumbler: with balls, other tumblers and walls.
    fn collect_tumbler_contacts(&mut self, dt: f64) {
        let balls = &self.balls;
        let cfg = &self.config;
        let reach_cap = self.speculative_reach();
        let contacts = &mut self.contacts;
        let room = &self.room;

        // Balls against tumblers: the grid narrows to balls near the bounding
        // sphere, then the six spheres give the contact (P7).
        let shape = &self.shape;
        for (ti, t) in self.tumblers.iter().enumerate() {
            let centre = t.center + t.orientation * DVec3::new(0.0, shape.bound_height, 0.0);
            let speed = t.point_velocity(centre).length()
                + t.angular_velocity.length() * shape.bound_radius;
            let reach =
                shape.bound_radius + cfg.balls.radius + (speed * dt).min(reach_cap) + reach_cap;
            let grid = &self.grid;
            grid.for_each_in_box(
                centre - DVec3::splat(reach),
                centre + DVec3::splat(reach),
                |bi| {
                    if balls.position[bi].distance(centre) > reach {
                        return;
                    }
                    for (si, s) in shape.spheres.iter().enumerate() {
                        let c = t.sphere_center(shape, si);
                        let d = balls.position[bi] - c;
                        let dist = d.length();
                        let gap = dist - s.radius - balls.radius[bi];
                        let closing = (balls.velocity[bi] - t.point_velocity(c)).length() * dt;
                        if gap < closing.min(reach_cap) + TOUCH_SLOP && dist > 0.0 {
                            let n = d / dist;
                            let mut contact = Contact::new(
                                BodyRef::Ball(bi),
                                BodyRef::Tumbler(ti, si),
                                n,
                                c + n * s.radius,
                                gap,
                                cfg.tumblers.restitution,
                            );
                            // The ball's friction rules (see `tumbler_friction`).
                            contact.friction = cfg.balls.friction;
                            contacts.tumbler_contacts.push(contact);
                        }
                    }
                },
            );
        }

        // Tumblers against each other and against the walls (the floor holds
        // the round bottom exactly; see `tumbler`).
        let n_tumblers = self.tumblers.len();
        for a in 0..n_tumblers {
            let ta = &self.tumblers[a];
            for b in a + 1..n_tumblers {
                let tb = &self.tumblers[b];
                let ca = ta.center + ta.orientation * DVec3::new(0.0, shape.bound_height, 0.0);
                let cb = tb.center + tb.orientation * DVec3::new(0.0, shape.bound_height, 0.0);
                if ca.distance(cb) > 2.0 * shape.bound_radius + 2.0 * reach_cap {
                    continue;
                }
                for (si, s) in shape.spheres.iter().enumerate() {
                    let pa = ta.sphere_center(shape, si);
                    for (sj, s2) in shape.spheres.iter().enumerate() {
                        let pb = tb.sphere_center(shape, sj);
                        let d = pa - pb;
                        let dist = d.length();
                        let gap = dist - s.radius - s2.radius;
                        let closing = (ta.point_velocity(pa) - tb.point_velocity(pb)).length() * dt;
                        if gap < closing.min(reach_cap) + TOUCH_SLOP && dist > 0.0 {
                            let n = d / dist;
                            contacts.tumbler_contacts.push(Contact::new(
                                BodyRef::Tumbler(a, si),
                                BodyRef::Tumbler(b, sj),
                                n,
                                pb + n * s2.radius,
                                gap,
                                cfg.tumblers.restitution,
                            ));
                        }
                    }
                }
            }
            for (si, s) in shape.spheres.iter().enumerate() {
                let c = ta.sphere_center(shape, si);
                let speed = ta.point_velocity(c).length() * dt;
                // The floor holds the round bottom exactly; it meets the
                // other spheres only when the tumbler is knocked far over.
                let walls = if si == 0 {
                    &Surface::ALL[1..]
                } else {
                    &Surface::ALL[..]
                };
                for wall in walls {
                    let gap = room.distance(*wall, c) - s.radius;
                    if gap < speed.min(reach_cap) + TOUCH_SLOP {
                        let n = wall.inward_normal();
                        contacts.tumbler_contacts.push(Contact::new(
                            BodyRef::Tumbler(a, si),
                            BodyRef::Wall(*wall),
                            n,
                            c - n * s.radius,
                            gap,
                            cfg.tumblers.restitution,
                        ));
                    }
                }
            }
        }
    }
}

/// Whether two balls `gap` apart at the step's start, with speeds adding up
/// to `speeds`, are kept as a pair: if they could touch within the step.
/// Either ball may bounce off a wall within the step and come back at up to
/// its speed: that is allowed for (which covers their relative speed too).
fn kept_as_pair(gap: f64, speeds: f64, dt: f64, reach_cap: f64) -> bool {
    gap < (2.0 * speeds * dt).min(reach_cap) + TOUCH_SLOP
}
