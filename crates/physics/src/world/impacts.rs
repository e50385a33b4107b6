//! Step 3, restitution in time order: the impacts of the coming step,
//! resolved one by one in the order they happen, each between its two
//! bodies alone (after Mirtich's impulse-based simulation, and the
//! collision pass of Guendelman, Bridson and Fedkiw).
//!
//! A contact solver resolves the contacts it is given together, as one
//! coupled system: right for a pile at rest, wrong for impacts, which it
//! stops where each should bounce (a room of elastic balls runs down, and
//! Newton's cradle moves as one). Here every impact is the two-body
//! collision of the 1-D formulas (P2) along the line of centres at the
//! moment of touching, or a ball's bounce off a wall, and an impact that
//! sets a touching neighbour moving is met in its turn, at the same
//! instant: the cradle's impulse runs down the row, and at restitution 1
//! every impact keeps both momentum and energy.
//!
//! Within the step a ball moves along `x + v t + g (t^2 - t dt) / 2`, with
//! `v` its step-average velocity; an impact at time `t` that changes `v` by
//! `dv` keeps the path up to `t` by moving the start back by `dv t` (the
//! ball's `shift`), so the step's move ends where the ball really is.
//! The contact solver then sees the impacts done: the pairs and walls of
//! the balls that met something carry their new gaps and approach speeds.
//!
//! Only balls in the solver's hands take part (those near another ball);
//! a ball alone meets its walls exactly in flight (see `flight`), and a
//! tumbler's impacts bounce in the predict stage.

use crate::balls::Tint;
use crate::ccd::{bounce_off_wall, contact_normal, first_impact, first_touch};
use crate::contact::{Pair, PairSlots};
use crate::events::{Event, EventKind};
use crate::room::Surface;
use glam::DVec3;
use std::cmp::Ordering;
use std::collections::BinaryHeap;

use super::World;

/// Below this approach speed (m/s) two surfaces rest on each other, whatever
/// the bounce threshold: the contact solver holds them.
const RESTING_SPEED: f64 = 1e-6;

/// The most impacts one ball takes part in within a step. A ball caught in
/// a tight cluster could otherwise be struck back and forth without end;
/// past this, its contacts are left to the contact solver, which stops them.
const IMPACTS_PER_BALL: u32 = 8;

/// A ball with more contacts than this lies packed in a crowd (a plane of
/// touching balls gives each six; a fast ball counts every ball it could
/// reach within the step). An impact on it is the contact solver's, which
/// stops it with the crowd: a heap takes a blow as one body.
const PACKED: u8 = 8;

/// What a ball strikes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Struck {
    Ball(u32),
    Wall(Surface),
}

/// An impact due at `time`, found when its balls had met `versions`
/// impacts: stale once either has met another since.
#[derive(Clone, Copy, Debug)]
struct Candidate {
    time: f64,
    ball: u32,
    struck: Struck,
    versions: [u32; 2],
}

impl Candidate {
    /// Equal times are taken in a fixed order, so that a rerun is
    /// bit-identical.
    fn key(&self) -> (u32, u64) {
        let struck = match self.struck {
            Struck::Ball(j) => j as u64,
            Struck::Wall(s) => (1 << 40) + s.index() as u64,
        };
        (self.ball, struck)
    }
}

impl PartialEq for Candidate {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}

impl Eq for Candidate {}

impl PartialOrd for Candidate {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Candidate {
    /// The earliest first out of a [`BinaryHeap`] (a max-heap).
    fn cmp(&self, other: &Self) -> Ordering {
        other
            .time
            .total_cmp(&self.time)
            .then_with(|| other.key().cmp(&self.key()))
    }
}

/// The impacts stage's working storage, kept between steps.
#[derive(Debug, Default)]
pub(super) struct Impacts {
    queue: BinaryHeap<Candidate>,
    /// Per slot: how far back the start of its path has moved (see above).
    shift: Vec<DVec3>,
    /// Per slot: how many impacts it has met this step, and when the last.
    met: Vec<u32>,
    last: Vec<f64>,
    /// The slots that met an impact this step.
    touched: Vec<u32>,
    /// The pairs that may collide within the step, from the contacts.
    due: Vec<Pair>,
    /// Per slot, the balls it has a contact with this step (the pairs'
    /// other slots): `neighbours[first[i]..first[i + 1]]`.
    first: Vec<u32>,
    neighbours: Vec<u32>,
    /// Where the next neighbour of each slot goes while they are listed.
    cursor: Vec<u32>,
    /// Whether the neighbours are listed this step (only once needed).
    listed: bool,
    /// Per slot: whether it rests on another ball (see [`World::stacked`]),
    /// once asked: 0 not yet, 1 no, 2 yes; and the slots asked.
    stacked: Vec<u8>,
    asked: Vec<u32>,
}

impl Impacts {
    /// Lists each slot's neighbours from the contacts' pairs, by counting
    /// sort: in slot order, whatever the threads found them in. `partners`
    /// holds how many each slot has, counted while the pairs were found.
    fn list_neighbours(&mut self, pair_slots: &[Vec<PairSlots>], partners: &[u8]) {
        let slots = partners.len();
        let first = &mut self.first;
        first.clear();
        first.resize(slots + 1, 0);
        if partners.contains(&u8::MAX) {
            // A count that saturated: count again, in full.
            for &[i, j] in pair_slots.iter().flatten() {
                first[i as usize + 1] += 1;
                first[j as usize + 1] += 1;
            }
        } else {
            for (count, &n) in first[1..].iter_mut().zip(partners) {
                *count = u32::from(n);
            }
        }
        for k in 0..slots {
            first[k + 1] += first[k];
        }
        self.cursor.clear();
        self.cursor.extend_from_slice(&first[..slots]);
        self.neighbours.clear();
        self.neighbours.resize(first[slots] as usize, 0);
        for &[i, j] in pair_slots.iter().flatten() {
            for (a, b) in [(i, j), (j, i)] {
                let at = &mut self.cursor[a as usize];
                self.neighbours[*at as usize] = b;
                *at += 1;
            }
        }
        self.listed = true;
    }

    /// Per slot: how far the start of its path moved this step.
    pub(super) fn shift(&self, slot: usize) -> DVec3 {
        self.shift.get(slot).copied().unwrap_or(DVec3::ZERO)
    }

    /// Whether slot `i` met an impact this step.
    fn met(&self, i: usize) -> bool {
        self.met[i] > 0
    }

    /// Forgets the step's impacts, ready for `slots` balls.
    pub(super) fn clear(&mut self, slots: usize) {
        for &i in &self.touched {
            self.shift[i as usize] = DVec3::ZERO;
            self.met[i as usize] = 0;
            self.last[i as usize] = 0.0;
        }
        self.touched.clear();
        for &i in &self.asked {
            self.stacked[i as usize] = 0;
        }
        self.asked.clear();
        self.stacked.resize(slots, 0);
        self.queue.clear();
        self.listed = false;
        self.shift.resize(slots, DVec3::ZERO);
        self.met.resize(slots, 0);
        self.last.resize(slots, 0.0);
    }
}

/// What the impacts stage reads of the world, apart from the balls.
struct Setting {
    dt: f64,
    gravity: DVec3,
    threshold: f64,
    ball_restitution: f64,
    wall_restitution: f64,
    wall_friction: f64,
}

impl World {
    /// Resolves the step's impacts in the order they happen (see the module
    /// above), on the step-average velocities.
    pub(super) fn resolve_impacts(&mut self, dt: f64, gravity: DVec3) {
        let mut impacts = std::mem::take(&mut self.scratch.impacts);
        impacts.clear(self.balls.len());
        let threshold = self.config.solver.bounce_threshold.max(RESTING_SPEED);
        let due = |p: &Pair| closes_fast(p, threshold, dt);
        self.contacts.copy_pairs_where(due, &mut impacts.due);
        let setting = Setting {
            dt,
            gravity,
            threshold,
            ball_restitution: self.config.balls.restitution,
            wall_restitution: self.config.room.restitution,
            wall_friction: self.config.room.friction,
        };
        if !impacts.due.is_empty() {
            impacts.list_neighbours(&self.contacts.pair_slots, &self.scratch.ball_partners);
        }
        for k in 0..impacts.due.len() {
            let Pair { i, j, .. } = impacts.due[k];
            self.queue_pair(&mut impacts, &setting, i as usize, j as usize, 0.0);
        }
        // Gravity may speed a ball towards a wall by at most this within the step.
        let fall = self.config.gravity * dt;
        for c in &self.contacts.walls {
            let reaches = c.gap + c.approach.min(0.0) * dt - 0.5 * fall * dt <= 0.0;
            let fast = c.approach - fall < -threshold;
            if self.scratch.ball_partners[c.ball as usize] > 0 && reaches && fast {
                self.queue_wall(&mut impacts, &setting, c.ball as usize, c.surface, 0.0);
            }
        }
        while let Some(c) = impacts.queue.pop() {
            let i = c.ball as usize;
            let fresh = match c.struck {
                Struck::Ball(j) => {
                    impacts.met[i] == c.versions[0] && impacts.met[j as usize] == c.versions[1]
                }
                Struck::Wall(_) => impacts.met[i] == c.versions[0],
            };
            if !fresh {
                continue;
            }
            let (happened, j) = match c.struck {
                Struck::Ball(j) => {
                    let j = j as usize;
                    (
                        self.collide_balls(&mut impacts, &setting, i, j, c.time),
                        Some(j),
                    )
                }
                Struck::Wall(s) => (self.bounce_ball(&mut impacts, &setting, i, s, c.time), None),
            };
            if !happened {
                continue;
            }
            if !impacts.listed {
                impacts.list_neighbours(&self.contacts.pair_slots, &self.scratch.ball_partners);
            }
            for k in [Some(i), j].into_iter().flatten() {
                if impacts.met[k] < IMPACTS_PER_BALL {
                    self.queue_all_of(&mut impacts, &setting, k, c.time);
                }
            }
        }
        if !impacts.touched.is_empty() || !impacts.due.is_empty() {
            self.hand_impacts_to_contacts(&impacts, &setting);
        }
        self.scratch.impacts = impacts;
    }

    /// Where slot `i` is at time `t` of the step, but for the fall that
    /// gravity gives every ball alike.
    fn path_at(&self, impacts: &Impacts, i: usize, t: f64) -> DVec3 {
        self.balls.position[i] + impacts.shift[i] + self.balls.velocity[i] * t
    }

    /// Whether slot `i` rests, or is about to rest, on another ball: one of
    /// its contacts lies below it (within 60 degrees of straight down),
    /// within one of its radii, and neither closes on it nor leaves it faster
    /// than an impact bounces (so in a scene where every impact bounces,
    /// nothing rests on anything). Such a ball is part of a heap, and a blow
    /// on it is the heap's: the contact solver takes it with the heap as one
    /// body. Followed ball by ball, a blow into a heap (or a heap's landing)
    /// sets balls bouncing against neighbours the solver then cannot hold
    /// apart within the step, and costs far more than it shows. Without
    /// gravity nothing rests on anything.
    fn stacked(&self, impacts: &mut Impacts, i: usize) -> bool {
        match impacts.stacked[i] {
            1 => return false,
            2 => return true,
            _ => {}
        }
        if !impacts.listed {
            impacts.list_neighbours(&self.contacts.pair_slots, &self.scratch.ball_partners);
        }

        let balls = &self.balls;
        let (first, last) = (impacts.first[i] as usize, impacts.first[i + 1] as usize);
        let stacked = self.config.gravity > 0.0
            && impacts.neighbours[first..last].iter().any(|&j| {
                let d = balls.position[i] - balls.position[j as usize];
                let close = d.length() <= 2.0 * balls.radius[i] + balls.radius[j as usize];
                let settling = (balls.velocity[i] - balls.velocity[j as usize])
                    .dot(d)
                    .abs()
                    <= self.config.solver.bounce_threshold * d.length();
                close && d.y >= 0.5 * d.length() && settling
            });
        impacts.stacked[i] = if stacked { 2 } else { 1 };
        impacts.asked.push(i as u32);
        stacked
    }

    /// Queues the impact of slots `i` and `j` if they touch, closing fast
    /// enough to bounce, between time `from` and the step's end.
    fn queue_pair(&self, impacts: &mut Impacts, setting: &Setting, i: usize, j: usize, from: f64) {
        let (a, b) = (i.min(j), i.max(j));
        let d = self.path_at(impacts, a, from) - self.path_at(impacts, b, from);
        let v = self.balls.velocity[a] - self.balls.velocity[b];
        let reach = self.balls.radius[a] + self.balls.radius[b];
        let partners = &self.scratch.ball_partners;
        let mut in_heap = |k| packed(partners, k) || self.stacked(impacts, k);
        if in_heap(a) || in_heap(b) {
            return;
        }
        let Some(t) = first_touch(d, v, reach, setting.dt - from) else {
            return;
        };
        let n = (d + v * t).normalize_or_zero();
        if v.dot(n) < -setting.threshold {
            impacts.queue.push(Candidate {
                time: from + t,
                ball: a as u32,
                struck: Struck::Ball(b as u32),
                versions: [impacts.met[a], impacts.met[b]],
            });
        }
    }

    /// Queues the impact of slot `i` on wall `s` if it reaches it between
    /// time `from` and the step's end.
    fn queue_wall(
        &self,
        impacts: &mut Impacts,
        setting: &Setting,
        i: usize,
        s: Surface,
        from: f64,
    ) {
        if packed(&self.scratch.ball_partners, i) {
            return;
        }
        let n = s.inward_normal();
        let (dt, g) = (setting.dt, setting.gravity);
        let at = self.path_at(impacts, i, from) + 0.5 * g * (from * from - from * dt);
        let distance = self.room.distance(s, at) - self.balls.radius[i];
        let normal_velocity = n.dot(self.balls.velocity[i] + g * (from - 0.5 * dt));
        let Some(t) = first_impact(distance, normal_velocity, n.dot(g), dt - from) else {
            return;
        };
        // Too slow to bounce when it gets there: the contact solver holds it.
        if -(normal_velocity + n.dot(g) * t) > setting.threshold {
            impacts.queue.push(Candidate {
                time: from + t,
                ball: i as u32,
                struck: Struck::Wall(s),
                versions: [impacts.met[i], 0],
            });
        }
    }

    /// Queues every impact slot `i` may meet from time `from` on, now that
    /// its path has changed: with the walls within its reach, and with the
    /// balls it has a contact with. (Others lie beyond its reach for this
    /// step: the next step finds them.)
    fn queue_all_of(&self, impacts: &mut Impacts, setting: &Setting, i: usize, from: f64) {
        let (start, end) = (
            self.path_at(impacts, i, from),
            self.path_at(impacts, i, setting.dt),
        );
        let fall = 0.5 * self.config.gravity * setting.dt * setting.dt;
        let reach = self.balls.radius[i] + fall;
        if self
            .room
            .nearest_distance(start)
            .min(self.room.nearest_distance(end))
            <= reach
        {
            for s in Surface::ALL {
                self.queue_wall(impacts, setting, i, s, from);
            }
        }
        let (first, last) = (impacts.first[i] as usize, impacts.first[i + 1] as usize);
        for k in first..last {
            let j = impacts.neighbours[k] as usize;
            self.queue_pair(impacts, setting, i, j, from);
        }
    }

    /// The two-body collision of slots `i` and `j` at time `t`, if they
    /// still close fast enough to bounce; returns whether they collided.
    fn collide_balls(
        &mut self,
        impacts: &mut Impacts,
        setting: &Setting,
        i: usize,
        j: usize,
        t: f64,
    ) -> bool {
        let d = self.path_at(impacts, i, t) - self.path_at(impacts, j, t);
        let Some(n) = d.try_normalize() else {
            return false;
        };
        let balls = &mut self.balls;
        let closing = -(balls.velocity[i] - balls.velocity[j]).dot(n);
        let (wi, wj) = (balls.inv_mass[i], balls.inv_mass[j]);
        if closing <= setting.threshold || wi + wj <= 0.0 {
            return false;
        }
        // v1' = ((m1 - m2) v1 + 2 m2 v2) / (m1 + m2) along n, scaled by e (P2).
        let impulse = (1.0 + setting.ball_restitution) * closing / (wi + wj);
        let (dvi, dvj) = (n * (impulse * wi), n * (-impulse * wj));
        balls.velocity[i] += dvi;
        balls.velocity[j] += dvj;
        impacts.shift[i] -= dvi * t;
        impacts.shift[j] -= dvj * t;
        let fall = 0.5 * setting.gravity * (t * t - t * setting.dt);
        let centre_j =
            self.balls.position[j] + impacts.shift[j] + self.balls.velocity[j] * t + fall;
        if closing > self.config.solver.event_threshold {
            self.events.push(Event {
                kind: EventKind::BallBall { a: i, b: j },
                point: centre_j + n * self.balls.radius[j],
                normal: n,
                speed: closing,
            });
        }
        note_impact(impacts, i, t);
        note_impact(impacts, j, t);
        true
    }

    /// Slot `i`'s bounce off wall `s` at time `t`, if it still approaches
    /// it fast enough; returns whether it bounced.
    fn bounce_ball(
        &mut self,
        impacts: &mut Impacts,
        setting: &Setting,
        i: usize,
        s: Surface,
        t: f64,
    ) -> bool {
        let n = s.inward_normal();
        let (dt, g) = (setting.dt, setting.gravity);
        let balls = &mut self.balls;
        // The instantaneous velocity at the moment of impact.
        let u = balls.velocity[i] + g * (t - 0.5 * dt);
        let speed = -n.dot(u);
        if speed <= setting.threshold {
            return false;
        }
        let body = (balls.radius[i], balls.mass[i], balls.inertia(i));
        let (after, spin, _) = bounce_off_wall(
            (u, balls.spin[i]),
            n,
            body,
            setting.wall_restitution,
            setting.wall_friction,
        );
        let dv = after - u;
        balls.velocity[i] += dv;
        balls.spin[i] = spin;
        impacts.shift[i] -= dv * t;
        if speed > self.config.solver.event_threshold {
            let centre = self.path_at(impacts, i, t) + 0.5 * g * (t * t - t * dt);
            self.balls.tint[i] = Tint::Surface(s);
            self.events.push(Event {
                kind: EventKind::BallSurface {
                    ball: i,
                    surface: s,
                },
                point: self.room.foot(s, centre),
                normal: n,
                speed,
            });
        }
        note_impact(impacts, i, t);
        true
    }

    /// Hands the impacts' outcome to the contact solver: the pairs and
    /// walls of the balls that met one start from where their paths now
    /// begin, at their new approach speeds (so that none is taken for an
    /// impact again).
    fn hand_impacts_to_contacts(&mut self, impacts: &Impacts, setting: &Setting) {
        let balls = &self.balls;
        let partners = &self.scratch.ball_partners;
        let threshold = setting.threshold;
        let dt = setting.dt;
        let due = |p: &Pair| closes_fast(p, threshold, dt);
        self.contacts.update_pairs(|p| {
            let (i, j) = (p.i as usize, p.j as usize);
            let free = !packed(partners, i) && !packed(partners, j);
            if !(impacts.met(i) || impacts.met(j) || free && due(p)) {
                return;
            }
            // Both move in straight lines from the later of their last
            // impacts: the contact's normal is found from there on, and its
            // gap is along it from where their paths now start. Free balls
            // that only pass by are held apart where they come closest.
            let pass_by = if free { threshold } else { f64::INFINITY };
            let from = impacts.last[i].max(impacts.last[j]);
            let v = balls.velocity[i] - balls.velocity[j];
            let start =
                (balls.position[i] + impacts.shift[i]) - (balls.position[j] + impacts.shift[j]);
            let d = start + v * from;
            let reach = balls.radius[i] + balls.radius[j];
            if let Some(n) = d.try_normalize() {
                p.normal = contact_normal(d, v, reach, dt - from, pass_by).map_or(n, |(n, _)| n);
                p.gap = start.dot(p.normal) - reach;
            }
            p.approach = v.dot(p.normal);
        });
        // A wall's approach is the ball's normal velocity before gravity's
        // half step (see `collect_contacts`).
        let half_kick = 0.5 * setting.dt * setting.gravity;
        for c in self.contacts.walls.iter_mut() {
            let i = c.ball as usize;
            if impacts.met(i) {
                let n = c.normal();
                c.gap += impacts.shift[i].dot(n);
                c.approach = (balls.velocity[i] - half_kick).dot(n);
            }
        }
    }
}

/// Whether pair `p`'s contact, as found, closes within the step faster
/// than an impact bounces: an impact due, or balls passing close by.
fn closes_fast(p: &Pair, threshold: f64, dt: f64) -> bool {
    p.approach < -threshold && p.gap + p.approach * dt <= 0.0
}

/// Whether slot `i` lies packed in a crowd (see [`PACKED`]).
fn packed(partners: &[u8], i: usize) -> bool {
    partners[i] > PACKED
}

/// Counts an impact of slot `i` at time `t`.
fn note_impact(impacts: &mut Impacts, i: usize, t: f64) {
    if impacts.met[i] == 0 {
        impacts.touched.push(i as u32);
    }
    impacts.met[i] += 1;
    impacts.last[i] = t;
}
