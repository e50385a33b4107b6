//! Step 6: overlaps the solver left are pushed apart, never adding
//! energy.

use crate::contact::{BodyRef, Pair, PairSlots};
use crate::room::Surface;
use glam::{DQuat, DVec3};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use super::{TOUCH_SLOP, World, per_ball, sum_in_runs};

/// Overlaps smaller than this are left alone (metres).
const OVERLAP_SLOP: f64 = 1e-5;
/// Balls sunk into each other deeper than this share of their radii's sum
/// are pushed apart down to it (see `push_apart_sunk_balls`).
const SUNK_SLOP: f64 = 0.005;
/// Sweeps over the pairs that push sunk balls apart, and the share of an
/// overlap that one push removes.
const PUSH_SWEEPS: usize = 4;
const PUSH_SHARE: f64 = 0.5;

impl World {
    /// Pushes apart balls that have sunk into each other (P3).
    ///
    /// The solver stops contacts from approaching but never pushes them
    /// apart, which would add energy. Yet in a deep pile the iterations
    /// leave some approach, and overlaps would grow step after step: the
    /// pile would creep into itself. So the pairs are swept on positions
    /// too, each push moving the two balls apart along their line of centres
    /// in inverse proportion to their masses, walls holding them. Lifting
    /// the balls costs potential energy: if it costs more than `budget`, every
    /// push is shortened alike to fit. The energy a pile loses by sinking in
    /// a step is thus exactly what lifting it back costs.
    pub(super) fn push_apart_sunk_balls(&mut self, budget: f64) {
        let balls = &mut self.balls;
        self.scratch.unpushed.clone_from(&balls.position);
        let (radius, inv_mass) = (&balls.radius, &balls.inv_mass);
        let mut pushed = false;
        for _ in 0..PUSH_SWEEPS {
            let pushed_now = AtomicBool::new(false);
            let push = |[i, j]: PairSlots, position: &mut [DVec3], first: usize| {
                let (i, j) = (i as usize, j as usize);
                let d = position[i - first] - position[j - first];
                let reach = (radius[i] + radius[j]) * (1.0 - SUNK_SLOP);
                // Most pairs are not sunk: tell them without a square root.
                if d.length_squared() >= reach * reach {
                    return;
                }
                let dist = d.length();
                let overlap = reach - dist;
                if overlap > 0.0 && dist > 0.0 {
                    let push = d * (PUSH_SHARE * overlap / (dist * (inv_mass[i] + inv_mass[j])));
                    position[i - first] += push * inv_mass[i];
                    position[j - first] -= push * inv_mass[j];
                    // Written once: threads writing one flag over and over
                    // would take its memory from each other.
                    if !pushed_now.load(Ordering::Relaxed) {
                        pushed_now.store(true, Ordering::Relaxed);
                    }
                }
            };
            self.contacts.sweep_pair_slots(&mut balls.position, &push);
            if !pushed_now.into_inner() {
                break;
            }
            pushed = true;
            let room = &self.room;
            per_ball(&mut balls.position, radius, |p, &r| {
                *p = room.clamp_sphere(*p, r)
            });
        }
        if !pushed {
            return;
        }
        let g = self.config.gravity;
        let unpushed = &self.scratch.unpushed;
        let lift = |i: usize| balls.mass[i] * g * (balls.position[i].y - unpushed[i].y);
        let cost: f64 = sum_in_runs(balls.len(), |run| run.map(lift).sum());
        if cost > budget {
            let share = (budget / cost).max(0.0);
            per_ball(&mut balls.position, unpushed, |p, &from| {
                *p = from + (*p - from) * share
            });
        }
    }

    /// Pushes apart bodies that still overlap: a lone pair of balls along
    /// their line of centres, weighted by mass and paid from their own
    /// motion; a ball out of a tumbler; tumblers only sideways over the
    /// floor. Crowds of balls were pushed apart together already (see
    /// `push_apart_sunk_balls`).
    pub(super) fn separate_overlaps(&mut self) {
        let shape = Arc::clone(&self.shape);
        let shape = &*shape;
        let mut lone_pairs = std::mem::take(&mut self.scratch.picked_pairs);
        let partners = &self.scratch.ball_partners;
        let lone = |p: &Pair| partners[p.i as usize] == 1 && partners[p.j as usize] == 1;
        self.contacts.copy_pairs_where(lone, &mut lone_pairs);
        for p in &lone_pairs {
            self.separate_balls(p.i as usize, p.j as usize);
        }
        self.scratch.picked_pairs = lone_pairs;
        for k in 0..self.contacts.tumbler_contacts.len() {
            let c = &self.contacts.tumbler_contacts[k];
            match (c.a, c.b) {
                (BodyRef::Ball(i), BodyRef::Tumbler(t, s)) => {
                    let centre = self.tumblers[t].sphere_center(shape, s);
                    let d = self.balls.position[i] - centre;
                    let dist = d.length();
                    let overlap = self.balls.radius[i] + shape.spheres[s].radius - dist;
                    if overlap > OVERLAP_SLOP && dist > 0.0 {
                        let push = self.push_inside(i, d / dist * overlap);
                        let rise = self.balls.mass[i] * push.y * self.config.gravity;
                        let part = self.pay_for_rise(&[i], rise);
                        self.balls.position[i] += push * part;
                    }
                }
                (BodyRef::Tumbler(a, sa), BodyRef::Tumbler(b, sb)) => {
                    let d = self.tumblers[a].sphere_center(shape, sa)
                        - self.tumblers[b].sphere_center(shape, sb);
                    let flat = DVec3::new(d.x, 0.0, d.z);
                    let overlap = shape.spheres[sa].radius + shape.spheres[sb].radius - d.length();
                    if overlap > OVERLAP_SLOP && flat.length() > 1e-9 {
                        let push = flat.normalize() * (0.5 * overlap * d.length() / flat.length());
                        self.tumblers[a].center += push;
                        self.tumblers[b].center -= push;
                    }
                }
                _ => {}
            }
        }
        for t in &mut self.tumblers {
            // A sphere in the floor: turn the tumbler back towards upright
            // about its bottom's centre, which only lowers its centre of mass.
            for (si, s) in shape.spheres.iter().enumerate().skip(1) {
                let c = t.sphere_center(shape, si);
                let overlap = s.radius - self.room.distance(Surface::Floor, c);
                let axis = t.axis();
                let lever = s.height * axis.cross(DVec3::Y).length();
                if overlap > OVERLAP_SLOP && lever > 1e-6 {
                    let turn = (overlap / lever).min(0.2);
                    let about = axis.cross(DVec3::Y).normalize();
                    let kinetic = t.kinetic_energy(shape);
                    t.orientation =
                        (DQuat::from_axis_angle(about, turn) * t.orientation).normalize();
                    // Turning changes how the same velocities carry energy:
                    // never let the correction add any.
                    let turned = t.kinetic_energy(shape);
                    if turned > kinetic {
                        let keep = (kinetic / turned).sqrt();
                        t.angular_velocity *= keep;
                        t.center_velocity *= keep;
                    }
                }
            }
            for (si, s) in shape.spheres.iter().enumerate() {
                let c = t.sphere_center(shape, si);
                let inside = self.room.clamp_sphere(c, s.radius);
                let shift = DVec3::new(inside.x - c.x, 0.0, inside.z - c.z);
                t.center += shift;
            }
        }
        let room = &self.room;
        per_ball(&mut self.balls.position, &self.balls.radius, |p, &r| {
            *p = room.clamp_sphere(*p, r)
        });
    }

    /// Pushes two overlapping balls apart along their line of centres.
    fn separate_balls(&mut self, i: usize, j: usize) {
        let d = self.balls.position[i] - self.balls.position[j];
        let dist = d.length();
        let overlap = self.balls.radius[i] + self.balls.radius[j] - dist;
        if overlap > OVERLAP_SLOP && dist > 0.0 {
            let n = d / dist;
            // Weighted by mass the pair's centre of mass stays put;
            // a ball lying on a wall cannot be pushed into it.
            let (wi, wj) = match (self.pressed_on_wall(i, n), self.pressed_on_wall(j, -n)) {
                (false, true) => (1.0, 0.0),
                (true, false) => (0.0, 1.0),
                // Free, or pinned both ways: each moves as far as its walls allow.
                _ => (self.balls.inv_mass[i], self.balls.inv_mass[j]),
            };
            // Never down: pushing balls down for free is a ratchet that
            // lets a pile sink into itself (the ball below cannot be
            // pushed up again unless it pays for the rise).
            let up = |d: DVec3| DVec3::new(d.x, d.y.max(0.0), d.z);
            let di = up(self.push_inside(i, n * (overlap * wi / (wi + wj))));
            let dj = up(self.push_inside(j, -n * (overlap * wj / (wi + wj))));
            let rise = self.balls.mass[i] * di.y + self.balls.mass[j] * dj.y;
            let part = self.pay_for_rise(&[i, j], rise * self.config.gravity);
            self.balls.position[i] += di * part;
            self.balls.position[j] += dj * part;
        }
    }

    /// The part of moving ball `i` by `push` that keeps it inside the room.
    fn push_inside(&self, i: usize, push: DVec3) -> DVec3 {
        let p = self.balls.position[i];
        self.room.clamp_sphere(p + push, self.balls.radius[i]) - p
    }

    /// Whether ball `i` lies on a wall that a push along `dir` would drive it into.
    fn pressed_on_wall(&self, i: usize, dir: DVec3) -> bool {
        let (p, r) = (self.balls.position[i], self.balls.radius[i]);
        Surface::ALL.iter().any(|&s| {
            self.room.distance(s, p) - r <= TOUCH_SLOP && dir.dot(s.inward_normal()) < 0.0
        })
    }

    /// Separating overlaps must not create energy: raising balls by
    /// `energy` joules of potential energy is paid from their kinetic energy.
    /// Returns the share of the push that was paid for (1 when it was free).
    fn pay_for_rise(&mut self, balls: &[usize], energy: f64) -> f64 {
        if energy <= 0.0 {
            return 1.0;
        }
        let kinetic: f64 = balls.iter().map(|&i| self.balls.kinetic_energy(i)).sum();
        let (keep, part) = if kinetic > energy {
            (((kinetic - energy) / kinetic).sqrt(), 1.0)
        } else {
            (0.0, kinetic / energy)
        };
        for &i in balls {
            let p = self.balls.mass[i] * self.balls.velocity[i];
            self.impulses.guard += (keep - 1.0) * p;
            self.balls.velocity[i] *= keep;
            self.balls.spin[i] *= keep;
        }
        part
    }
}
