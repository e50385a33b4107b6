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
use crate::ccd::contact_normal;
use crate::config::WorldConfig;
use crate::contact::{PARALLEL_PAIRS, Pair, PairSlots, WallContact, solve_predict};
use crate::events::Event;
use crate::room::Surface;
use glam::DVec3;
use neighbours::Neighbours;
use rayon::prelude::*;
use region::{Border, Fixed, Lists, Moving, Run};
use std::cmp::Ordering;
use std::collections::BinaryHeap;

use super::World;

mod neighbours;
mod region;

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

/// At least this many impacts due as the step begins, and the room's
/// impacts are resolved in two runs side by side, one for each half of its
/// grid layers, and those across the line between them after: a landing
/// pit meets thousands a step, which one thread would take in turn.
const SIDE_BY_SIDE: usize = 256;

/// What impacts change, slot by slot (see [`Moving`]).
#[derive(Debug, Default)]
struct PerSlot {
    shift: Vec<DVec3>,
    met: Vec<u32>,
    last: Vec<f64>,
    start_velocity: Vec<DVec3>,
    stacked: Vec<u8>,
}

/// The impacts stage's working storage, kept between steps.
#[derive(Debug, Default)]
pub(super) struct Impacts {
    per_slot: PerSlot,
    /// The lists of the two runs side by side; the first serves the run
    /// over all slots too.
    lists: [Lists; 2],
    /// Per band, the slots of the pairs that may collide within the step,
    /// picked out as the pairs are found (see [`Impacts::due_bands`]).
    due: Vec<Vec<PairSlots>>,
    neighbours: Neighbours,
    /// Per band of due pairs, the impacts they are found to be due.
    found: Vec<Vec<Candidate>>,
    /// Those of them that wait for the run over all slots.
    waiting: Vec<Candidate>,
    border: Border,
    /// Whether any pair's contact is to be handed the impacts' outcome.
    pairs_changed: bool,
}

impl Impacts {
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
        self.per_slot
            .shift
            .get(slot)
            .copied()
            .unwrap_or(DVec3::ZERO)
    }

    /// Whether slot `i` met an impact this step.
    fn met(&self, i: usize) -> bool {
        self.per_slot.met[i] > 0
    }

    /// Whether any slot met an impact this step.
    fn any_met(&self) -> bool {
        self.lists.iter().any(|l| !l.touched.is_empty())
    }

    /// The impulse the walls gave the balls in this step's impacts (N s).
    pub(super) fn wall_impulse(&self) -> DVec3 {
        self.lists[0].wall_impulse + self.lists[1].wall_impulse
    }

    /// Forgets the step's impacts, ready for `slots` balls.
    pub(super) fn clear(&mut self, slots: usize) {
        let per_slot = &mut self.per_slot;
        for lists in &mut self.lists {
            for &i in &lists.touched {
                per_slot.shift[i as usize] = DVec3::ZERO;
                per_slot.met[i as usize] = 0;
                per_slot.last[i as usize] = 0.0;
            }
            for &i in &lists.asked {
                per_slot.stacked[i as usize] = 0;
            }
            lists.touched.clear();
            lists.asked.clear();
            lists.queue.clear();
            lists.events.clear();
            lists.wall_impulse = DVec3::ZERO;
        }
        per_slot.shift.resize(slots, DVec3::ZERO);
        per_slot.met.resize(slots, 0);
        per_slot.last.resize(slots, 0.0);
        per_slot.start_velocity.resize(slots, DVec3::ZERO);
        per_slot.stacked.resize(slots, 0);
    }
}

/// What the impacts stage reads of the world, apart from the balls.
struct Setting {
    dt: f64,
    gravity: DVec3,
    /// Gravity's acceleration (m/s^2).
    fall: f64,
    /// Below this approach speed an impact is left to the contact solver.
    threshold: f64,
    /// The scene's bounce threshold, by which a ball is judged stacked.
    bounce_threshold: f64,
    event_threshold: f64,
    ball_restitution: f64,
    ball_friction: f64,
    wall_restitution: f64,
    wall_friction: f64,
}

/// The grid layer at which the impacts due, `found` band by band, are
/// halved: the first layer of the second of two runs side by side (see
/// [`SIDE_BY_SIDE`]), if they are many and the room has layers enough.
fn halving_layer(found: &[Vec<Candidate>]) -> Option<usize> {
    let total: usize = found.iter().map(Vec::len).sum();
    if total < SIDE_BY_SIDE || found.len() < 3 {
        return None;
    }
    let mut before = 0;
    let bands_before = found[..found.len() - 2]
        .iter()
        .take_while(|band| {
            before += band.len();
            2 * before < total
        })
        .count();
    Some(bands_before + 1)
}

impl World {
    /// Resolves the step's impacts in the order they happen (see the module
    /// above), on the step-average velocities.
    pub(super) fn resolve_impacts(&mut self, dt: f64, gravity: DVec3) {
        let mut impacts = std::mem::take(&mut self.scratch.impacts);
        impacts.clear(self.balls.len());
        let setting = Setting {
            dt,
            gravity,
            fall: self.config.gravity,
            threshold: impact_threshold(&self.config),
            bounce_threshold: self.config.solver.bounce_threshold,
            event_threshold: self.config.solver.event_threshold,
            ball_restitution: self.config.balls.restitution,
            ball_friction: self.config.balls.friction,
            wall_restitution: self.config.room.restitution,
            wall_friction: self.config.room.friction,
        };
        let partners = &self.scratch.ball_partners;
        // Gravity may speed a ball towards a wall by at most this within the step.
        let fall = self.config.gravity * dt;
        let wall_due = |c: &&WallContact| {
            let reaches = c.gap + c.approach.min(0.0) * dt - 0.5 * fall * dt <= 0.0;
            let fast = c.approach - fall < -setting.threshold;
            partners[c.ball as usize] > 0 && reaches && fast
        };
        let any_due = impacts.any_due();
        if any_due || self.contacts.walls.iter().any(|c| wall_due(&c)) {
            impacts
                .neighbours
                .list(&self.contacts.pair_slots, &self.contacts.layers, partners);
            let walls = self.contacts.walls.iter().filter(wall_due);
            let Balls {
                position,
                velocity,
                spin,
                radius,
                mass,
                inv_mass,
                tint,
                ..
            } = &mut self.balls;
            let Impacts {
                per_slot,
                lists,
                due,
                neighbours,
                found,
                waiting,
                border,
                ..
            } = &mut impacts;
            let mut stage = Stage {
                fixed: Fixed {
                    position,
                    radius,
                    mass,
                    inv_mass,
                    partners,
                    neighbours,
                    room: &self.room,
                    setting: &setting,
                },
                changing: Changing {
                    velocity,
                    spin,
                    tint,
                    per_slot,
                },
                lists,
                events: &mut self.events,
            };
            find_due_impacts(&stage.changing.all(), &stage.fixed, due, found);
            match halving_layer(found) {
                None => stage.in_one_run(found, walls),
                Some(h) => {
                    let layers = &self.contacts.layers;
                    let line = layers[h];
                    border.mark(neighbours, layers[h - 1]..layers[h + 1], line);
                    stage.in_two_runs(line, border, found, waiting, walls);
                }
            }
        }
        impacts.pairs_changed = impacts.any_met() || any_due;
        self.impulses.surfaces += impacts.wall_impulse();
        if impacts.any_met() {
            self.hand_walls_to_contacts(&impacts, &setting);
        }
        self.scratch.impacts = impacts;
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
                c.gap += impacts.per_slot.shift[i].dot(n);
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
        let given = solve_predict(&mut self.step_context(warm_start), &hand);
        self.impulses += given;
        self.scratch.impacts = impacts;
        self.scratch.ball_partners = partners;
    }
}

/// What impacts change: the balls' motion, and the stage's own record of
/// each slot.
struct Changing<'a> {
    velocity: &'a mut [DVec3],
    spin: &'a mut [DVec3],
    tint: &'a mut [Tint],
    per_slot: &'a mut PerSlot,
}

impl Changing<'_> {
    /// All of it, for all slots.
    fn all(&mut self) -> Moving<'_> {
        let per_slot = &mut *self.per_slot;
        Moving {
            first: 0,
            velocity: self.velocity,
            spin: self.spin,
            tint: self.tint,
            shift: &mut per_slot.shift,
            met: &mut per_slot.met,
            last: &mut per_slot.last,
            start_velocity: &mut per_slot.start_velocity,
            stacked: &mut per_slot.stacked,
        }
    }
}

/// The impacts stage at work: what it reads, what it changes, its runs'
/// lists, and where its events go.
struct Stage<'a> {
    fixed: Fixed<'a>,
    changing: Changing<'a>,
    lists: &'a mut [Lists; 2],
    events: &'a mut Vec<Event>,
}

impl Stage<'_> {
    /// Resolves the impacts `found` due and those of the balls reaching
    /// `walls`, and all they lead to, in one run over all slots.
    fn in_one_run<'w>(
        &mut self,
        found: &[Vec<Candidate>],
        walls: impl Iterator<Item = &'w WallContact>,
    ) {
        let [first, _] = &mut *self.lists;
        heap(&mut first.queue, found.iter().flatten(), |_| true);
        let mut run = Run {
            fixed: &self.fixed,
            moving: self.changing.all(),
            lists: first,
            border: None,
        };
        walls.for_each(|c| run.queue_wall(c.ball as usize, c.surface, 0.0));
        run.resolve();
        self.events.append(&mut first.events);
    }

    /// Resolves the same in two runs side by side, the slots before `line`
    /// and those from it on, but for those of `border`; then, in a run over
    /// all slots, the impacts of the border's slots and all they lead to.
    /// `waiting` keeps the impacts due that wait for that run.
    fn in_two_runs<'w>(
        &mut self,
        line: usize,
        border: &Border,
        found: &[Vec<Candidate>],
        waiting: &mut Vec<Candidate>,
        walls: impl Iterator<Item = &'w WallContact> + Clone,
    ) {
        let waits = |c: &Candidate| {
            let j = match c.struck {
                Struck::Ball(j) => j as usize,
                Struck::Wall(_) => c.ball as usize,
            };
            border.holds(c.ball as usize) || border.holds(j)
        };
        let before = |c: &Candidate| (c.ball as usize) < line;
        let [first, second] = &mut *self.lists;
        heap(&mut first.queue, found.iter().flatten(), |c| {
            !waits(c) && before(c)
        });
        heap(&mut second.queue, found.iter().flatten(), |c| {
            !waits(c) && !before(c)
        });
        waiting.clear();
        waiting.extend(found.iter().flatten().filter(|c| waits(c)));
        let (lower, upper) = self.changing.all().split_at(line);
        let mut runs = [
            Run {
                fixed: &self.fixed,
                moving: lower,
                lists: &mut *first,
                border: Some(border),
            },
            Run {
                fixed: &self.fixed,
                moving: upper,
                lists: &mut *second,
                border: Some(border),
            },
        ];
        for c in walls.clone() {
            let i = c.ball as usize;
            runs[usize::from(i >= line)].queue_wall(i, c.surface, 0.0);
        }
        let [lower, upper] = &mut runs;
        rayon::join(|| lower.resolve(), || upper.resolve());
        self.events.append(&mut first.events);
        self.events.append(&mut second.events);
        // Then the slots by the line, and what they set moving.
        let mut run = Run {
            fixed: &self.fixed,
            moving: self.changing.all(),
            lists: first,
            border: None,
        };
        heap(&mut run.lists.queue, waiting.iter(), |_| true);
        for i in border.slots() {
            for &j in self.fixed.neighbours.of(i) {
                run.queue_pair(i, j as usize, 0.0);
            }
        }
        walls
            .filter(|c| border.holds(c.ball as usize))
            .for_each(|c| run.queue_wall(c.ball as usize, c.surface, 0.0));
        run.resolve();
        self.events.append(&mut first.events);
    }
}

/// Finds the impacts of the due pairs, band by band on all threads: before
/// any impact, each is the same wherever it is found.
fn find_due_impacts(
    all: &Moving,
    fixed: &Fixed,
    due: &[Vec<PairSlots>],
    found: &mut Vec<Vec<Candidate>>,
) {
    found.resize_with(due.len(), Vec::new);
    let partners = fixed.partners;
    let find = |(band, found): (&Vec<PairSlots>, &mut Vec<Candidate>)| {
        found.clear();
        for &[i, j] in band {
            let (i, j) = (i as usize, j as usize);
            if packed(partners, i) || packed(partners, j) {
                continue;
            }
            if let Some(c) = all.pair_impact(fixed, i, j, 0.0)
                && !all.rests_on_another(fixed, i)
                && !all.rests_on_another(fixed, j)
            {
                found.push(c);
            }
        }
    };
    if due.iter().map(Vec::len).sum::<usize>() >= PARALLEL_PAIRS {
        due.par_iter().zip(found).for_each(find);
    } else {
        due.iter().zip(found).for_each(find);
    }
}

/// Makes `queue` the impacts of `from` that `take` chooses, heaped all at
/// once: no one's place is sought more than once.
fn heap<'a>(
    queue: &mut BinaryHeap<Candidate>,
    from: impl Iterator<Item = &'a Candidate>,
    take: impl Fn(&Candidate) -> bool,
) {
    let mut all = std::mem::take(queue).into_vec();
    all.clear();
    all.extend(from.filter(|c| take(c)));
    *queue = BinaryHeap::from(all);
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
    let per_slot = &impacts.per_slot;
    let from = per_slot.last[i].max(per_slot.last[j]);
    let v = balls.velocity[i] - balls.velocity[j];
    let start = (balls.position[i] + per_slot.shift[i]) - (balls.position[j] + per_slot.shift[j]);
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

#[cfg(test)]
mod tests;
