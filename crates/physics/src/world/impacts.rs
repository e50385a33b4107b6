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

use crate::balls::{Balls, Tint};
use crate::ccd::{bounce_off_wall, contact_normal, first_impact, first_touch};
use crate::config::WorldConfig;
use crate::contact::{PARALLEL_PAIRS, Pair, PairSlots, solve_predict};
use crate::events::{Event, EventKind};
use crate::room::Surface;
use glam::DVec3;
use rayon::prelude::*;
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
    /// Per slot that met an impact: its velocity before the first.
    start_velocity: Vec<DVec3>,
    /// The slots that met an impact this step.
    touched: Vec<u32>,
    /// Per band, the slots of the pairs that may collide within the step,
    /// picked out as the pairs are found (see [`Impacts::due_bands`]).
    due: Vec<Vec<PairSlots>>,
    /// Per slot, the balls it has a contact with this step (the pairs'
    /// other slots): `neighbours[first[i]..first[i + 1]]`.
    first: Vec<u32>,
    neighbours: Vec<u32>,
    /// Where the next neighbour of each slot goes while they are listed.
    cursor: Vec<u32>,
    /// Per band of due pairs, the impacts they are found to be due.
    found: Vec<Vec<Candidate>>,
    /// Whether the neighbours are listed this step (only once needed).
    listed: bool,
    /// Whether any pair's contact is to be handed the impacts' outcome.
    pairs_changed: bool,
    /// Per slot: whether it rests on another ball (see [`World::stacked`]),
    /// once asked: 0 not yet, 1 no, 2 yes; and the slots asked.
    stacked: Vec<u8>,
    asked: Vec<u32>,
}

impl Impacts {
    /// Lists each slot's neighbours from the contacts' pairs, by counting
    /// sort: in slot order, whatever the threads found them in. `partners`
    /// holds how many each slot has, counted while the pairs were found;
    /// `layers` the first slot of each grid layer (see [`Contacts`]).
    fn list_neighbours(
        &mut self,
        pair_slots: &[Vec<PairSlots>],
        layers: &[usize],
        partners: &[u8],
    ) {
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
        // Every entry is written below: the old ones need no clearing.
        self.neighbours.resize(first[slots] as usize, 0);
        let bands = Bands {
            pair_slots,
            layers,
            first,
        };
        bands.scatter(0..pair_slots.len(), &mut self.cursor, &mut self.neighbours);
        self.listed = true;
    }

    /// Ready for `bands` bands of due pairs, emptied, for the pair search
    /// to fill: the pairs whose contact, as found, [`closes_fast`].
    pub(super) fn due_bands(&mut self, bands: usize) -> &mut [Vec<PairSlots>] {
        self.due.resize_with(bands, Vec::new);
        self.due.iter_mut().for_each(Vec::clear);
        &mut self.due
    }

    /// Whether any pair is due.
    fn any_due(&self) -> bool {
        self.due.iter().any(|band| !band.is_empty())
    }

    /// Per slot: how far the start of its path moved this step.
    pub(super) fn shift(&self, slot: usize) -> DVec3 {
        self.shift.get(slot).copied().unwrap_or(DVec3::ZERO)
    }

    /// Whether slot `i` met an impact this step.
    fn met(&self, i: usize) -> bool {
        self.met[i] > 0
    }

    /// Slot `i`'s velocity as the stage began.
    fn velocity_at_start(&self, i: usize, balls: &Balls) -> DVec3 {
        if self.met(i) {
            self.start_velocity[i]
        } else {
            balls.velocity[i]
        }
    }

    /// Keeps slot `i`'s velocity `v` as the stage began, before its first
    /// impact changes it.
    fn keep_start_velocity(&mut self, i: usize, v: DVec3) {
        if !self.met(i) {
            self.start_velocity[i] = v;
        }
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
        self.start_velocity.resize(slots, DVec3::ZERO);
    }
}

/// Below this many pairs, a run of bands lists its neighbours on one thread.
const LIST_ALONE: usize = 16_384;

/// The pairs' slots band by band, as [`Impacts::list_neighbours`] scatters
/// them into each slot's neighbours.
struct Bands<'a> {
    pair_slots: &'a [Vec<PairSlots>],
    layers: &'a [usize],
    /// Where each slot's neighbours begin.
    first: &'a [u32],
}

impl Bands<'_> {
    /// Writes the neighbours of the slots of layers `run.start..run.end`,
    /// which band `z` shares with band `z - 1` only (its pairs join layers
    /// `z` and `z + 1`): `cursor` and `neighbours` hold those slots' own
    /// parts, so that runs of bands are written on their own threads, and
    /// each slot's neighbours come in band order, as on one thread.
    fn scatter(&self, run: std::ops::Range<usize>, cursor: &mut [u32], neighbours: &mut [u32]) {
        let (lo, hi) = (self.layers[run.start], self.layers[run.end]);
        let pairs: usize = self.pair_slots[run.clone()].iter().map(Vec::len).sum();
        if pairs >= LIST_ALONE && run.len() > 1 {
            // Split where half the pairs lie before.
            let mut before = 0;
            let mid = run.start
                + 1
                + self.pair_slots[run.start..run.end - 1]
                    .iter()
                    .take_while(|band| {
                        before += band.len();
                        2 * before < pairs
                    })
                    .count();
            let at = self.layers[mid];
            let (cursor_lo, cursor_hi) = cursor.split_at_mut(at - lo);
            let entries = (self.first[at] - self.first[lo]) as usize;
            let (neighbours_lo, neighbours_hi) = neighbours.split_at_mut(entries);
            rayon::join(
                || self.scatter(run.start..mid, cursor_lo, neighbours_lo),
                || self.scatter(mid..run.end, cursor_hi, neighbours_hi),
            );
            return;
        }
        let base = self.first[lo];
        let mut put = |a: u32, b: u32| {
            let at = &mut cursor[a as usize - lo];
            neighbours[(*at - base) as usize] = b;
            *at += 1;
        };
        // A pair's first slot lies in its band's layer, the second in the
        // same layer or the next.
        if let Some(shared) = run.start.checked_sub(1) {
            for &[i, j] in &self.pair_slots[shared] {
                if j as usize >= lo {
                    put(j, i);
                }
            }
        }
        for &[i, j] in self.pair_slots[run].iter().flatten() {
            put(i, j);
            if (j as usize) < hi {
                put(j, i);
            }
        }
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
        let threshold = impact_threshold(&self.config);
        let setting = Setting {
            dt,
            gravity,
            threshold,
            ball_restitution: self.config.balls.restitution,
            wall_restitution: self.config.room.restitution,
            wall_friction: self.config.room.friction,
        };
        let any_due = impacts.any_due();
        if any_due {
            impacts.list_neighbours(
                &self.contacts.pair_slots,
                &self.contacts.layers,
                &self.scratch.ball_partners,
            );
        }
        if any_due {
            self.queue_due_pairs(&mut impacts, &setting);
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
                impacts.list_neighbours(
                    &self.contacts.pair_slots,
                    &self.contacts.layers,
                    &self.scratch.ball_partners,
                );
            }
            for k in [Some(i), j].into_iter().flatten() {
                if impacts.met[k] < IMPACTS_PER_BALL {
                    self.queue_all_of(&mut impacts, &setting, k, c.time);
                }
            }
        }
        impacts.pairs_changed = !impacts.touched.is_empty() || any_due;
        if !impacts.touched.is_empty() {
            self.hand_walls_to_contacts(&impacts, &setting);
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
    /// than an impact bounces as the stage began (so in a scene where every
    /// impact bounces, nothing rests on anything; and the answer does not
    /// hang on when it is first asked, nor on which impacts came before). Such a ball is part of a heap, and a blow
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
            impacts.list_neighbours(
                &self.contacts.pair_slots,
                &self.contacts.layers,
                &self.scratch.ball_partners,
            );
        }
        let stacked = self.rests_on_another(impacts, i);
        impacts.stacked[i] = if stacked { 2 } else { 1 };
        impacts.asked.push(i as u32);
        stacked
    }

    /// [`World::stacked`], worked out afresh, once the neighbours are listed.
    fn rests_on_another(&self, impacts: &Impacts, i: usize) -> bool {
        let balls = &self.balls;
        let (first, last) = (impacts.first[i] as usize, impacts.first[i + 1] as usize);
        let velocity = |k: usize| impacts.velocity_at_start(k, balls);
        self.config.gravity > 0.0
            && impacts.neighbours[first..last].iter().any(|&j| {
                let j = j as usize;
                let d = balls.position[i] - balls.position[j];
                let close = d.length() <= 2.0 * balls.radius[i] + balls.radius[j];
                let settling = (velocity(i) - velocity(j)).dot(d).abs()
                    <= self.config.solver.bounce_threshold * d.length();
                close && d.y >= 0.5 * d.length() && settling
            })
    }

    /// Queues the impact of slots `i` and `j` if they touch, closing fast
    /// enough to bounce, between time `from` and the step's end, and
    /// neither lies in a heap.
    fn queue_pair(&self, impacts: &mut Impacts, setting: &Setting, i: usize, j: usize, from: f64) {
        let partners = &self.scratch.ball_partners;
        if packed(partners, i) || packed(partners, j) {
            return;
        }
        let Some(c) = self.pair_impact(impacts, setting, i, j, from) else {
            return;
        };
        if !self.stacked(impacts, i) && !self.stacked(impacts, j) {
            impacts.queue.push(c);
        }
    }

    /// The impact of slots `i` and `j`, if they touch, closing fast enough
    /// to bounce, between time `from` and the step's end.
    fn pair_impact(
        &self,
        impacts: &Impacts,
        setting: &Setting,
        i: usize,
        j: usize,
        from: f64,
    ) -> Option<Candidate> {
        let (a, b) = (i.min(j), i.max(j));
        let d = self.path_at(impacts, a, from) - self.path_at(impacts, b, from);
        let v = self.balls.velocity[a] - self.balls.velocity[b];
        let reach = self.balls.radius[a] + self.balls.radius[b];
        let t = first_touch(d, v, reach, setting.dt - from)?;
        let n = (d + v * t).normalize_or_zero();
        (v.dot(n) < -setting.threshold).then(|| Candidate {
            time: from + t,
            ball: a as u32,
            struck: Struck::Ball(b as u32),
            versions: [impacts.met[a], impacts.met[b]],
        })
    }

    /// Queues the impacts of the due pairs, found band by band on all
    /// threads (before any impact, each is the same wherever it is found),
    /// then made one queue.
    fn queue_due_pairs(&self, impacts: &mut Impacts, setting: &Setting) {
        let mut found = std::mem::take(&mut impacts.found);
        found.resize_with(impacts.due.len(), Vec::new);
        let partners = &self.scratch.ball_partners;
        let impacts_now = &*impacts;
        let stacked = |k| self.rests_on_another(impacts_now, k);
        let find = |(band, found): (&Vec<PairSlots>, &mut Vec<Candidate>)| {
            found.clear();
            for &[i, j] in band {
                let (i, j) = (i as usize, j as usize);
                if packed(partners, i) || packed(partners, j) {
                    continue;
                }
                if let Some(c) = self.pair_impact(impacts_now, setting, i, j, 0.0)
                    && !stacked(i)
                    && !stacked(j)
                {
                    found.push(c);
                }
            }
        };
        let due = impacts.due.iter().map(Vec::len).sum::<usize>();
        if due >= PARALLEL_PAIRS {
            impacts.due.par_iter().zip(&mut found).for_each(find);
        } else {
            impacts.due.iter().zip(&mut found).for_each(find);
        }
        // Heaped all at once: no one's place is sought more than once.
        let mut queue = std::mem::take(&mut impacts.queue).into_vec();
        queue.clear();
        for band in &found {
            queue.extend_from_slice(band);
        }
        impacts.queue = BinaryHeap::from(queue);
        impacts.found = found;
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
        impacts.keep_start_velocity(i, balls.velocity[i]);
        impacts.keep_start_velocity(j, balls.velocity[j]);
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
        impacts.keep_start_velocity(i, balls.velocity[i]);
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

    /// Hands the impacts' outcome on the walls to the contact solver: the
    /// walls of the balls that met an impact start from where their paths
    /// now begin, at their new approach speeds (so that none is taken for
    /// an impact again). The pairs get theirs as the predict stage builds
    /// their rows (see [`World::predict_after_impacts`]).
    fn hand_walls_to_contacts(&mut self, impacts: &Impacts, setting: &Setting) {
        // A wall's approach is the ball's normal velocity before gravity's
        // half step (see `collect_contacts`).
        let half_kick = 0.5 * setting.dt * setting.gravity;
        for c in self.contacts.walls.iter_mut() {
            let i = c.ball as usize;
            if impacts.met(i) {
                let n = c.normal();
                c.gap += impacts.shift[i].dot(n);
                c.approach = (self.balls.velocity[i] - half_kick).dot(n);
            }
        }
    }

    /// Step 4, the contact solver's predict stage, each pair handed the
    /// impacts' outcome as its row is built: in the pass over the pairs the
    /// stage makes anyway, where a pass of its own would stream them all
    /// from memory for the few that changed.
    pub(super) fn predict_after_impacts(&mut self, warm_start: bool) {
        let impacts = std::mem::take(&mut self.scratch.impacts);
        let partners = std::mem::take(&mut self.scratch.ball_partners);
        let threshold = impact_threshold(&self.config);
        let dt = self.config.solver.dt;
        let hand = |p: &mut Pair, balls: &Balls| {
            if impacts.pairs_changed {
                hand_pair(p, balls, &impacts, &partners, threshold, dt);
            }
        };
        solve_predict(&mut self.step_context(warm_start), &hand);
        self.scratch.impacts = impacts;
        self.scratch.ball_partners = partners;
    }
}

/// Hands the impacts' outcome to pair `p`: if either ball met an impact,
/// or both are free and the pair was due, its contact starts from where
/// their paths now begin, at their new approach speed (so that it is not
/// taken for an impact again).
#[inline(always)]
fn hand_pair(
    p: &mut Pair,
    balls: &Balls,
    impacts: &Impacts,
    partners: &[u8],
    threshold: f64,
    dt: f64,
) {
    let (i, j) = (p.i as usize, p.j as usize);
    let free = || !packed(partners, i) && !packed(partners, j);
    let met = impacts.met(i) || impacts.met(j);
    if !(met || closes_fast(p.gap, p.approach, threshold, dt) && free()) {
        return;
    }
    // Both move in straight lines from the later of their last impacts:
    // the contact's normal is found from there on, and its gap is along it
    // from where their paths now start. Free balls that only pass by are
    // held apart where they come closest.
    let pass_by = if free() { threshold } else { f64::INFINITY };
    let from = impacts.last[i].max(impacts.last[j]);
    let v = balls.velocity[i] - balls.velocity[j];
    let start = (balls.position[i] + impacts.shift[i]) - (balls.position[j] + impacts.shift[j]);
    let d = start + v * from;
    let reach = balls.radius[i] + balls.radius[j];
    if let Some(n) = d.try_normalize() {
        p.normal = contact_normal(d, v, reach, dt - from, pass_by).map_or(n, |(n, _)| n);
        p.gap = start.dot(p.normal) - reach;
    }
    p.approach = v.dot(p.normal);
}

/// The approach speed below which nothing bounces, and the impacts stage
/// leaves a contact to the contact solver.
pub(super) fn impact_threshold(config: &WorldConfig) -> f64 {
    config.solver.bounce_threshold.max(RESTING_SPEED)
}

/// Whether a pair's contact, as found (`gap` and `approach` along its
/// normal), closes within the step faster than an impact bounces: an
/// impact due, or balls passing close by.
pub(super) fn closes_fast(gap: f64, approach: f64, threshold: f64, dt: f64) -> bool {
    approach < -threshold && gap + approach * dt <= 0.0
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
