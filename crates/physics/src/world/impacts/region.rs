//! The event loop over a run of slots: its impacts one by one in the order
//! they happen, each between its two bodies alone (see the module above).
//! Two runs that share no neighbours are resolved side by side.

use super::neighbours::Neighbours;
use super::{Candidate, IMPACTS_PER_BALL, Setting, Struck, packed};
use crate::balls::{Tint, sphere_inertia};
use crate::ccd::{bounce_off_wall, first_impact, first_touch};
use crate::events::{Event, EventKind};
use crate::room::{Room, Surface};
use crate::sphere_impact::{Sphere, collide_spheres};
use glam::DVec3;
use std::collections::BinaryHeap;

/// What every run reads and none changes.
pub(super) struct Fixed<'a> {
    pub position: &'a [DVec3],
    pub radius: &'a [f64],
    pub mass: &'a [f64],
    pub inv_mass: &'a [f64],
    /// Per slot, how many other balls it may touch (see [`packed`]).
    pub partners: &'a [u8],
    pub neighbours: &'a Neighbours,
    pub room: &'a Room,
    pub setting: &'a Setting,
}

/// What impacts change, slot by slot, for the slots from `first` on.
pub(super) struct Moving<'a> {
    pub first: usize,
    pub velocity: &'a mut [DVec3],
    pub spin: &'a mut [DVec3],
    pub tint: &'a mut [Tint],
    /// How far back the start of its path has moved (see above).
    pub shift: &'a mut [DVec3],
    /// How many impacts it has met this step, and when the last.
    pub met: &'a mut [u32],
    pub last: &'a mut [f64],
    /// Its velocity before its first impact, once it has met one.
    pub start_velocity: &'a mut [DVec3],
    /// Whether it rests on another ball, once asked: 0 not yet, 1 no, 2 yes.
    pub stacked: &'a mut [u8],
}

impl<'a> Moving<'a> {
    /// The slots before `slot`, and those from it on.
    pub fn split_at(self, slot: usize) -> (Moving<'a>, Moving<'a>) {
        let at = slot - self.first;
        let (velocity, velocity_b) = self.velocity.split_at_mut(at);
        let (spin, spin_b) = self.spin.split_at_mut(at);
        let (tint, tint_b) = self.tint.split_at_mut(at);
        let (shift, shift_b) = self.shift.split_at_mut(at);
        let (met, met_b) = self.met.split_at_mut(at);
        let (last, last_b) = self.last.split_at_mut(at);
        let (start_velocity, start_velocity_b) = self.start_velocity.split_at_mut(at);
        let (stacked, stacked_b) = self.stacked.split_at_mut(at);
        let before = Moving {
            first: self.first,
            velocity,
            spin,
            tint,
            shift,
            met,
            last,
            start_velocity,
            stacked,
        };
        let after = Moving {
            first: slot,
            velocity: velocity_b,
            spin: spin_b,
            tint: tint_b,
            shift: shift_b,
            met: met_b,
            last: last_b,
            start_velocity: start_velocity_b,
            stacked: stacked_b,
        };
        (before, after)
    }

    /// Where slot `i` is at time `t` of the step, but for the fall that
    /// gravity gives every ball alike.
    fn path_at(&self, fixed: &Fixed, i: usize, t: f64) -> DVec3 {
        let k = i - self.first;
        fixed.position[i] + self.shift[k] + self.velocity[k] * t
    }

    /// Slot `i`'s velocity as the stage began.
    fn velocity_at_start(&self, i: usize) -> DVec3 {
        let k = i - self.first;
        if self.met[k] > 0 {
            self.start_velocity[k]
        } else {
            self.velocity[k]
        }
    }

    /// When slot `i` met its last impact (0 if none).
    fn last(&self, i: usize) -> f64 {
        self.last[i - self.first]
    }

    /// How many impacts slot `i` has met.
    fn met(&self, i: usize) -> u32 {
        self.met[i - self.first]
    }

    /// Whether slot `i` rests, or is about to rest, on another ball: one of
    /// its contacts lies below it (within 60 degrees of straight down),
    /// within one of its radii, and neither closes on it nor leaves it
    /// faster than an impact bounces as the stage began (so in a scene
    /// where every impact bounces, nothing rests on anything; and the
    /// answer does not hang on when it is asked, nor on which impacts came
    /// before). Such a ball is part of a heap, and a blow on it is the
    /// heap's: the contact solver takes it with the heap as one body.
    /// Followed ball by ball, a blow into a heap (or a heap's landing) sets
    /// balls bouncing against neighbours the solver then cannot hold apart
    /// within the step, and costs far more than it shows. Without gravity
    /// nothing rests on anything.
    pub fn rests_on_another(&self, fixed: &Fixed, i: usize) -> bool {
        let setting = fixed.setting;
        let (position, radius) = (fixed.position, fixed.radius);
        setting.fall > 0.0
            && fixed.neighbours.of(i).iter().any(|&j| {
                let j = j as usize;
                let d = position[i] - position[j];
                let close = d.length() <= 2.0 * radius[i] + radius[j];
                let relative = self.velocity_at_start(i) - self.velocity_at_start(j);
                let settling = relative.dot(d).abs() <= setting.bounce_threshold * d.length();
                close && d.y >= 0.5 * d.length() && settling
            })
    }

    /// The impact of slots `i` and `j`, if they touch, closing fast enough
    /// to bounce, between time `from` and the step's end.
    pub fn pair_impact(&self, fixed: &Fixed, i: usize, j: usize, from: f64) -> Option<Candidate> {
        let setting = fixed.setting;
        let (a, b) = (i.min(j), i.max(j));
        let d = self.path_at(fixed, a, from) - self.path_at(fixed, b, from);
        let v = self.velocity[a - self.first] - self.velocity[b - self.first];
        let reach = fixed.radius[a] + fixed.radius[b];
        let t = first_touch(d, v, reach, setting.dt - from)?;
        let n = (d + v * t).normalize_or_zero();
        (v.dot(n) < -setting.threshold).then(|| Candidate {
            time: from + t,
            ball: a as u32,
            struck: Struck::Ball(b as u32),
            versions: [self.met(a), self.met(b)],
        })
    }

    /// The impact of slot `i` on wall `s`, if it reaches it between time
    /// `from` and the step's end fast enough to bounce.
    pub fn wall_impact(&self, fixed: &Fixed, i: usize, s: Surface, from: f64) -> Option<Candidate> {
        let setting = fixed.setting;
        let n = s.inward_normal();
        let (dt, g) = (setting.dt, setting.gravity);
        let at = self.path_at(fixed, i, from) + 0.5 * g * (from * from - from * dt);
        let distance = fixed.room.distance(s, at) - fixed.radius[i];
        let normal_velocity = n.dot(self.velocity[i - self.first] + g * (from - 0.5 * dt));
        let t = first_impact(distance, normal_velocity, n.dot(g), dt - from)?;
        // Too slow to bounce when it gets there: the contact solver holds it.
        (-(normal_velocity + n.dot(g) * t) > setting.threshold).then(|| Candidate {
            time: from + t,
            ball: i as u32,
            struck: Struck::Wall(s),
            versions: [self.met(i), 0],
        })
    }
}

/// A run's own lists.
#[derive(Debug, Default)]
pub(super) struct Lists {
    /// The impacts due, earliest first.
    pub queue: BinaryHeap<Candidate>,
    /// The slots that met an impact, and those asked whether they are
    /// stacked.
    pub touched: Vec<u32>,
    pub asked: Vec<u32>,
    pub events: Vec<Event>,
    /// The impulse the walls gave the run's balls (N s).
    pub wall_impulse: DVec3,
}

/// Slots whose impacts wait for the pass over all slots: those with
/// neighbours across the line between two runs resolved side by side.
#[derive(Debug, Default)]
pub(super) struct Border {
    /// The first slot `waits` covers.
    pub first: usize,
    pub waits: Vec<bool>,
}

impl Border {
    /// Marks the slots of `slots` that have a neighbour on the other side
    /// of `line`, the first slot of the second run.
    pub fn mark(&mut self, neighbours: &Neighbours, slots: std::ops::Range<usize>, line: usize) {
        self.first = slots.start;
        self.waits.clear();
        self.waits.extend(slots.map(|i| {
            let across = |&j: &u32| ((j as usize) < line) != (i < line);
            neighbours.of(i).iter().any(across)
        }));
    }

    /// The slots that wait.
    pub fn slots(&self) -> impl Iterator<Item = usize> + '_ {
        let waiting = self.waits.iter().enumerate().filter(|(_, w)| **w);
        waiting.map(|(k, _)| self.first + k)
    }

    /// Whether slot `i` waits.
    pub fn holds(&self, i: usize) -> bool {
        i.checked_sub(self.first)
            .and_then(|k| self.waits.get(k))
            .is_some_and(|&w| w)
    }
}

/// A run of slots whose impacts are resolved together, in time order.
pub(super) struct Run<'a> {
    pub fixed: &'a Fixed<'a>,
    pub moving: Moving<'a>,
    pub lists: &'a mut Lists,
    /// Slots left to a later pass (none in the pass over all slots).
    pub border: Option<&'a Border>,
}

impl Run<'_> {
    /// Resolves the queued impacts in time order, and those they lead to.
    pub fn resolve(&mut self) {
        while let Some(c) = self.lists.queue.pop() {
            let i = c.ball as usize;
            let fresh = match c.struck {
                Struck::Ball(j) => {
                    self.moving.met(i) == c.versions[0]
                        && self.moving.met(j as usize) == c.versions[1]
                }
                Struck::Wall(_) => self.moving.met(i) == c.versions[0],
            };
            if !fresh {
                continue;
            }
            let (happened, j) = match c.struck {
                Struck::Ball(j) => {
                    let j = j as usize;
                    (self.collide_balls(i, j, c.time), Some(j))
                }
                Struck::Wall(s) => (self.bounce_ball(i, s, c.time), None),
            };
            if !happened {
                continue;
            }
            for k in [Some(i), j].into_iter().flatten() {
                if self.moving.met(k) < IMPACTS_PER_BALL {
                    self.queue_all_of(k, c.time);
                }
            }
        }
    }

    /// Whether slot `i`'s impacts wait for a later pass.
    fn waits(&self, i: usize) -> bool {
        self.border.is_some_and(|b| b.holds(i))
    }

    /// [`Moving::rests_on_another`], worked out once per slot.
    fn stacked(&mut self, i: usize) -> bool {
        let k = i - self.moving.first;
        match self.moving.stacked[k] {
            1 => return false,
            2 => return true,
            _ => {}
        }
        let stacked = self.moving.rests_on_another(self.fixed, i);
        self.moving.stacked[k] = if stacked { 2 } else { 1 };
        self.lists.asked.push(i as u32);
        stacked
    }

    /// Queues the impact of slots `i` and `j` if they touch, closing fast
    /// enough to bounce, between time `from` (or either's last impact, if
    /// later) and the step's end, and neither lies in a heap.
    pub fn queue_pair(&mut self, i: usize, j: usize, from: f64) {
        let partners = self.fixed.partners;
        if packed(partners, i) || packed(partners, j) || self.waits(i) || self.waits(j) {
            return;
        }
        let from = from.max(self.moving.last(i)).max(self.moving.last(j));
        let Some(c) = self.moving.pair_impact(self.fixed, i, j, from) else {
            return;
        };
        if !self.stacked(i) && !self.stacked(j) {
            self.lists.queue.push(c);
        }
    }

    /// Queues the impact of slot `i` on wall `s` if it reaches it between
    /// time `from` (or its last impact, if later) and the step's end.
    pub fn queue_wall(&mut self, i: usize, s: Surface, from: f64) {
        if packed(self.fixed.partners, i) || self.waits(i) {
            return;
        }
        let from = from.max(self.moving.last(i));
        if let Some(c) = self.moving.wall_impact(self.fixed, i, s, from) {
            self.lists.queue.push(c);
        }
    }

    /// Queues every impact slot `i` may meet from time `from` on, now that
    /// its path has changed: with the walls within its reach, and with the
    /// balls it has a contact with. (Others lie beyond its reach for this
    /// step: the next step finds them.)
    fn queue_all_of(&mut self, i: usize, from: f64) {
        let (fixed, setting) = (self.fixed, self.fixed.setting);
        let start = self.moving.path_at(fixed, i, from);
        let end = self.moving.path_at(fixed, i, setting.dt);
        let fall = 0.5 * setting.fall * setting.dt * setting.dt;
        let reach = fixed.radius[i] + fall;
        let room = fixed.room;
        if room.nearest_distance(start).min(room.nearest_distance(end)) <= reach {
            for s in Surface::ALL {
                self.queue_wall(i, s, from);
            }
        }
        for &j in fixed.neighbours.of(i) {
            self.queue_pair(i, j as usize, from);
        }
    }

    /// The two-body collision of slots `i` and `j` at time `t`, if they
    /// still close fast enough to bounce; returns whether they collided.
    fn collide_balls(&mut self, i: usize, j: usize, t: f64) -> bool {
        let (fixed, setting) = (self.fixed, self.fixed.setting);
        let d = self.moving.path_at(fixed, i, t) - self.moving.path_at(fixed, j, t);
        let Some(n) = d.try_normalize() else {
            return false;
        };
        let (ki, kj) = (i - self.moving.first, j - self.moving.first);
        let sphere = |slot: usize, k: usize| Sphere {
            velocity: self.moving.velocity[k],
            spin: self.moving.spin[k],
            radius: fixed.radius[slot],
            inv_mass: fixed.inv_mass[slot],
        };
        let (a, b) = (sphere(i, ki), sphere(j, kj));
        let closing = -(a.velocity - b.velocity).dot(n);
        if closing <= setting.threshold {
            return false;
        }
        // Along n, v1' = ((m1 - m2) v1 + 2 m2 v2) / (m1 + m2) scaled by e
        // (P2); across it, friction sticks or slides (F1).
        let Some(change) =
            collide_spheres(&a, &b, n, setting.ball_restitution, setting.ball_friction)
        else {
            return false;
        };
        let [dvi, dvj] = change.velocity;
        self.keep_start_velocity(i);
        self.keep_start_velocity(j);
        let moving = &mut self.moving;
        moving.velocity[ki] += dvi;
        moving.velocity[kj] += dvj;
        moving.spin[ki] += change.spin[0];
        moving.spin[kj] += change.spin[1];
        moving.shift[ki] -= dvi * t;
        moving.shift[kj] -= dvj * t;
        let fall = 0.5 * setting.gravity * (t * t - t * setting.dt);
        let centre_j = moving.path_at(fixed, j, t) + fall;
        if closing > setting.event_threshold {
            self.lists.events.push(Event {
                kind: EventKind::BallBall { a: i, b: j },
                point: centre_j + n * fixed.radius[j],
                normal: n,
                speed: closing,
                within_step: t,
            });
        }
        self.note_impact(i, t);
        self.note_impact(j, t);
        true
    }

    /// Slot `i`'s bounce off wall `s` at time `t`, if it still approaches
    /// it fast enough; returns whether it bounced.
    fn bounce_ball(&mut self, i: usize, s: Surface, t: f64) -> bool {
        let (fixed, setting) = (self.fixed, self.fixed.setting);
        let n = s.inward_normal();
        let (dt, g) = (setting.dt, setting.gravity);
        let k = i - self.moving.first;
        // The instantaneous velocity at the moment of impact.
        let u = self.moving.velocity[k] + g * (t - 0.5 * dt);
        let speed = -n.dot(u);
        if speed <= setting.threshold {
            return false;
        }
        let body = (
            fixed.radius[i],
            fixed.mass[i],
            sphere_inertia(fixed.mass[i], fixed.radius[i]),
        );
        let (after, spin, _) = bounce_off_wall(
            (u, self.moving.spin[k]),
            n,
            body,
            setting.wall_restitution,
            setting.wall_friction,
        );
        let dv = after - u;
        self.lists.wall_impulse += fixed.mass[i] * dv;
        self.keep_start_velocity(i);
        let moving = &mut self.moving;
        moving.velocity[k] += dv;
        moving.spin[k] = spin;
        moving.shift[k] -= dv * t;
        if speed > setting.event_threshold {
            let centre = moving.path_at(fixed, i, t) + 0.5 * g * (t * t - t * dt);
            moving.tint[k] = Tint::Surface(s);
            self.lists.events.push(Event {
                kind: EventKind::BallSurface {
                    ball: i,
                    surface: s,
                },
                point: fixed.room.foot(s, centre),
                normal: n,
                speed,
                within_step: t,
            });
        }
        self.note_impact(i, t);
        true
    }

    /// Keeps slot `i`'s velocity as the stage began, before its first
    /// impact changes it.
    fn keep_start_velocity(&mut self, i: usize) {
        let k = i - self.moving.first;
        if self.moving.met[k] == 0 {
            self.moving.start_velocity[k] = self.moving.velocity[k];
        }
    }

    /// Counts an impact of slot `i` at time `t`.
    fn note_impact(&mut self, i: usize, t: f64) {
        let k = i - self.moving.first;
        if self.moving.met[k] == 0 {
            self.lists.touched.push(i as u32);
        }
        self.moving.met[k] += 1;
        self.moving.last[k] = t;
    }
}
