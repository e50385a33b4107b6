//! The world: all bodies, and the fixed step that moves them.
//!
//! One step of `dt`, in order (each part in the file named; in Box2D's
//! words, prepare, restitution, warm start and solve, integrate, relax and
//! store):
//! 1. find contacts at the current positions, with the grid broadphase for
//!    balls (`find_contacts`);
//! 2. half a step of gravity on the balls' velocities (the step-average
//!    velocity);
//! 3. resolve the step's impacts one by one in the order they happen, each
//!    between its two bodies (`impacts`);
//! 4. solve contacts on those velocities (predict stage, speculative and
//!    warm-started; see [`crate::contact`], which gets a [`StepContext`]),
//!    each pair handed the impacts' outcome as its row is built;
//! 5. move: balls along exact parabolas with exact wall impacts, tumblers by
//!    integrating their grounded rolling/sliding equations (`flight`);
//! 6. end the contacts that pushed at rest, bounce what impacts were left
//!    to the solver, and record the impulses for the next warm start
//!    (project stage); emit events, take on colours (`report`);
//! 7. separate any remaining overlaps (`overlaps`), then move the fireball
//!    (`fireball_flight`).
//!
//! Around the step: where balls start (`spawn`), the hand that holds a
//! tumbler (`hand`), and what a player changes while it runs (`live`).
//!
//! Everything runs in a fixed order on `f64`, so the same configuration,
//! seed and inputs give bit-identical states (P10).

use crate::balls::{Balls, PARALLEL_BALLS, PARALLEL_LIGHT_PASSES, Tint};
use crate::broadphase::Grid;
use crate::config::{Rgb, WorldConfig};
use crate::contact::WarmStart;
use crate::contact::{
    Bodies, Contacts, Crowd, PARALLEL_PAIRS, Pair, PairMaterial, StepContext, WallContact,
    solve_project,
};
use crate::events::Event;
use crate::fireball::Fireball;
use crate::impulses::BallImpulses;
use crate::rng::Rng;
use crate::room::Room;
use crate::threads::with_workers_awake;
use crate::tumbler::{Tumbler, TumblerShape};
use glam::{DMat3, DVec3, Vec4};
use rayon::prelude::*;
use std::sync::Arc;
use std::time::Instant;

mod elsewhere;
mod find_contacts;
mod fireball_flight;
mod flight;
mod hand;
mod impacts;
mod inspect;
mod live;
mod overlaps;
mod pour;
mod profile;
mod report;
mod spawn;
mod state;

pub use hand::{BallPick, Pick};
pub use inspect::{ContactKind, ContactProbe};
pub use profile::{Stage, StepTimes};
pub use spawn::placement_problem;
pub use state::{StateError, WorldState};

/// A ball this close to a wall is touching it (metres).
const TOUCH_SLOP: f64 = 1e-6;

/// Why a world could not be built from a configuration.
#[derive(Clone, Debug, PartialEq)]
pub struct BuildError(pub String);

impl std::fmt::Display for BuildError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for BuildError {}

/// Kinetic and potential energy (potential measured from the floor).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Energy {
    /// Energy of motion, moving and turning (J).
    pub kinetic: f64,
    /// Energy of height above the floor (J).
    pub potential: f64,
}

impl Energy {
    /// Kinetic plus potential (J).
    pub fn total(&self) -> f64 {
        self.kinetic + self.potential
    }
}

impl std::ops::Add for Energy {
    type Output = Energy;

    fn add(self, other: Energy) -> Energy {
        Energy {
            kinetic: self.kinetic + other.kinetic,
            potential: self.potential + other.potential,
        }
    }
}

/// Calls `f(item, with)` for each ball's `items[i]` and `with[i]`, on all
/// threads for many balls: each ball's own, so the result is the same.
fn per_ball<A, B, F>(items: &mut [A], with: &[B], f: F)
where
    A: Send,
    B: Sync,
    F: Fn(&mut A, &B) + Sync,
{
    if items.len() >= PARALLEL_LIGHT_PASSES {
        items.par_iter_mut().zip(with).for_each(|(a, b)| f(a, b));
    } else {
        items.iter_mut().zip(with).for_each(|(a, b)| f(a, b));
    }
}

/// Adds up `part(range)` over the balls `0..count` in runs of a fixed
/// length, in order: the same sum on any number of threads, worked out on
/// all of them for many balls. The runs' sums are kept on the stack, a
/// batch at a time, so that a step allocates nothing.
fn sum_in_runs<T, P>(count: usize, part: P) -> T
where
    T: Copy + Default + Send + std::ops::Add<Output = T>,
    P: Fn(std::ops::Range<usize>) -> T + Sync,
{
    const RUN: usize = 4096;
    const BATCH: usize = 64;
    let run = |r: usize| part(r * RUN..((r + 1) * RUN).min(count));
    let runs = count.div_ceil(RUN);
    if count < PARALLEL_LIGHT_PASSES {
        return (0..runs).map(run).fold(T::default(), |a, b| a + b);
    }
    let mut sums = [T::default(); BATCH];
    let mut total = T::default();
    for first in (0..runs).step_by(BATCH) {
        let batch = &mut sums[..BATCH.min(runs - first)];
        batch
            .par_iter_mut()
            .enumerate()
            .for_each(|(r, sum)| *sum = run(first + r));
        total = batch.iter().fold(total, |a, &b| a + b);
    }
    total
}

/// Everything in the room, and the fixed step that moves it.
pub struct World {
    config: WorldConfig,
    room: Room,
    /// Shared, so that a step may hold it while it changes the world.
    shape: Arc<TumblerShape>,
    balls: Balls,
    tumblers: Vec<Tumbler>,
    fireball: Option<Fireball>,
    rng: Rng,
    time: f64,
    steps: u64,
    events: Vec<Event>,
    grid: Grid,
    contacts: Contacts,
    /// Last step's impulses of both solver stages, by ball number (see
    /// [`crate::contact::warm`]), and this step's, which take their place once the
    /// step is done.
    warm: WarmStart,
    warm_next: WarmStart,
    retakes: u64,
    /// The random balls still to pour, if the scene pours them.
    pour: pour::Pour,
    /// The ball the hand holds, if it holds one.
    ball_hold: Option<hand::BallHold>,
    /// How long the last step's stages took.
    times: StepTimes,
    /// What the room's surfaces and the tumblers gave the balls in the
    /// last step, and the momentum its poured balls brought in.
    impulses: BallImpulses,
    poured: DVec3,
    scratch: StepScratch,
}

/// A copy of the world that steps on exactly as the world would: every
/// body, the random sequence, the warm start, the pours and the hand. What
/// a step builds afresh is not copied (its working storage, the contacts
/// and the record it writes its impulses into), so that a copy kept to go
/// back to (the sandbox's rewind) holds only the state; until it steps, a
/// copy shows no contacts to the debug views.
impl Clone for World {
    fn clone(&self) -> World {
        World {
            config: self.config.clone(),
            room: self.room,
            shape: Arc::clone(&self.shape),
            balls: self.balls.clone(),
            tumblers: self.tumblers.clone(),
            fireball: self.fireball.clone(),
            rng: self.rng.clone(),
            time: self.time,
            steps: self.steps,
            events: self.events.clone(),
            grid: self.grid.clone(),
            contacts: Contacts::default(),
            warm: self.warm.clone(),
            warm_next: WarmStart::default(),
            retakes: self.retakes,
            pour: self.pour.clone(),
            ball_hold: self.ball_hold,
            times: self.times,
            impulses: self.impulses,
            poured: self.poured,
            scratch: StepScratch::sized_for(self.scratch.hit_wall.len(), self.tumblers.len()),
        }
    }
}

/// What a step works in and forgets: kept between steps only so that a
/// step allocates nothing.
#[derive(Default)]
struct StepScratch {
    /// The live balls in the grid's cell order, which the step works on so
    /// that neighbours in space are neighbours in memory (see `step`).
    sorted: Balls,
    /// Per tumbler: inverse inertia about its floor contact (world axes).
    contact_inv: Vec<DMat3>,
    /// Per ball: bounced off a wall while moving this step (see `solve_project`).
    hit_wall: Vec<bool>,
    /// Per ball: where it is and how far it looks for other balls this step
    /// (see `collect_contacts`).
    pair_spheres: Vec<Vec4>,
    /// Per ball: its speed at the start of the step.
    speed: Vec<f64>,
    /// Per ball: how many other balls it may touch this step (saturating).
    ball_partners: Vec<u8>,
    /// The few pairs a pass after the solver picks out of them all (see
    /// [`Contacts::copy_pairs_where`]).
    picked_pairs: Vec<Pair>,
    /// Per ball: where it was before sunk balls were pushed apart.
    unpushed: Vec<DVec3>,
    /// Per grid layer: the contacts of its balls with the walls.
    wall_contacts_by_layer: Vec<Vec<WallContact>>,
    crowd: Crowd,
    impacts: impacts::Impacts,
    /// The state before a step, to retake it if its warm start made energy.
    before_step: (Balls, Vec<Tumbler>),
}

impl StepScratch {
    /// Fresh storage for a world of `balls` ball numbers and `tumblers`
    /// tumblers: the parts a step indexes by number before it fills them.
    fn sized_for(balls: usize, tumblers: usize) -> StepScratch {
        StepScratch {
            contact_inv: vec![DMat3::IDENTITY; tumblers],
            hit_wall: vec![false; balls],
            ..StepScratch::default()
        }
    }
}

impl World {
    /// Builds the scene: tumblers at their placements, balls at random
    /// positions with random velocities drawn from `seed`.
    pub fn new(config: WorldConfig, seed: u64) -> Result<World, BuildError> {
        let room = Room::new(config.room.size);
        if config.tumblers.spheres.is_empty() {
            return Err(BuildError("the tumbler shape has no spheres".into()));
        }
        let shape = TumblerShape::new(&config.tumblers.spheres);
        let tumblers: Vec<Tumbler> = config
            .tumblers
            .placements
            .iter()
            .map(|p| Tumbler::new(&shape, p, room.min.y))
            .collect();
        for (i, t) in tumblers.iter().enumerate() {
            for s in 0..shape.spheres.len() {
                let c = t.sphere_center(&shape, s);
                if !room.contains_sphere(c, shape.spheres[s].radius, 1e-9) {
                    return Err(BuildError(format!(
                        "tumbler {i} at x = {}, z = {} does not fit in the room (sphere {s} sticks out)",
                        t.center.x, t.center.z
                    )));
                }
            }
            for (j, u) in tumblers.iter().enumerate().take(i) {
                if t.center.distance(u.center) < 2.0 * shape.bottom_radius {
                    return Err(BuildError(format!("tumblers {j} and {i} overlap")));
                }
            }
        }
        let b = &config.balls;
        for k in 0..b.placements.len() {
            if let Some(problem) = spawn::placement_problem(&config, &room, &shape, k) {
                return Err(BuildError(format!(
                    "ball {k} (balls.placement[{k}]) {problem}"
                )));
            }
        }
        // Two balls can touch within a step only if their centres are closer
        // than two radii plus the speculative reach of one radius (see
        // `collect_contacts`): a cell that wide finds every pair. Balls
        // spread thin through the room get cells about as wide as the space
        // between them, so that walking the empty cells costs no more than
        // the balls. The fireball and tumblers look for balls by box,
        // whatever the cell size.
        let touch = 3.0 * b.largest_radius() + 4.0 * TOUCH_SLOP;
        let spacing = (room.size().element_product() / b.total().max(1) as f64).cbrt();
        let grid = Grid::new(room.min, room.max, touch.max(spacing));
        let scratch = StepScratch::sized_for(b.total(), tumblers.len());
        let mut world = World {
            balls: Balls::with_uniform(b.total(), b.radius, b.mass),
            tumblers,
            fireball: None,
            rng: Rng::new(seed),
            time: 0.0,
            steps: 0,
            events: Vec::new(),
            grid,
            contacts: Contacts::default(),
            warm: Default::default(),
            warm_next: Default::default(),
            retakes: 0,
            pour: pour::Pour::default(),
            ball_hold: None,
            times: StepTimes::default(),
            impulses: BallImpulses::default(),
            poured: DVec3::ZERO,
            scratch,
            room,
            shape: Arc::new(shape),
            config,
        };
        world.spawn_balls()?;
        if world.config.fireball.starts_active {
            world.launch_fireball(None);
        }
        Ok(world)
    }

    /// The configuration it was built from, with the live settings taken since.
    pub fn config(&self) -> &WorldConfig {
        &self.config
    }

    /// The room.
    pub fn room(&self) -> &Room {
        &self.room
    }

    /// Simulated time (s).
    pub fn time(&self) -> f64 {
        self.time
    }

    /// Steps taken.
    pub fn step_count(&self) -> u64 {
        self.steps
    }

    /// The balls.
    pub fn balls(&self) -> &Balls {
        &self.balls
    }

    /// Mutable access to the balls, for building scenarios.
    pub fn balls_mut(&mut self) -> &mut Balls {
        &mut self.balls
    }

    /// The tumblers.
    pub fn tumblers(&self) -> &[Tumbler] {
        &self.tumblers
    }

    /// The shape all tumblers share.
    pub fn tumbler_shape(&self) -> &TumblerShape {
        &self.shape
    }

    /// The fireball, while it flies.
    pub fn fireball(&self) -> Option<&Fireball> {
        self.fireball.as_ref()
    }

    /// The colour a tint stands for.
    pub fn tint_color(&self, tint: Tint) -> Rgb {
        match tint {
            Tint::White => self.config.balls.color,
            Tint::Placed(k) => {
                let placed = self.config.balls.placements.get(k);
                placed
                    .and_then(|p| p.color)
                    .unwrap_or(self.config.balls.color)
            }
            Tint::Surface(s) => self.config.room.colors[s.index()],
            Tint::Tumbler(t) => {
                let colors = &self.config.tumblers.colors;
                if colors.is_empty() {
                    [1.0; 3]
                } else {
                    colors[t % colors.len()]
                }
            }
        }
    }

    /// Events since the last call (P9).
    pub fn drain_events(&mut self) -> std::vec::Drain<'_, Event> {
        self.events.drain(..)
    }

    /// Moves the events since the last call into `into` (emptied first),
    /// keeping both buffers' storage: no allocation once warm.
    pub fn take_events(&mut self, into: &mut Vec<Event>) {
        into.clear();
        std::mem::swap(&mut self.events, into);
    }

    /// Re-initialises the balls (I6): the placed balls back where their
    /// scene put them, the others at new random positions and velocities
    /// from the world's random sequence, every ball alive and of its
    /// starting colour again. Thrown balls are taken away.
    pub fn reset_balls(&mut self) -> Result<(), BuildError> {
        let total = self.config.balls.total();
        self.balls.truncate(total);
        self.ball_hold = None;
        self.scratch.hit_wall.truncate(total);
        // New balls under old numbers: last step's impulses mean nothing now.
        for w in [&mut self.warm, &mut self.warm_next] {
            w.begin(&[], 0, 0);
        }
        self.spawn_balls()
    }

    /// Launches the fireball from `from = (position, direction)`, or from the
    /// scene's spawn point. The start is pulled inside the room if needed.
    pub fn launch_fireball(&mut self, from: Option<(DVec3, DVec3)>) {
        let cfg = &self.config.fireball;
        let (pos, dir) = from.unwrap_or((cfg.spawn, cfg.direction));
        let fallback = cfg.direction.try_normalize().unwrap_or(DVec3::NEG_Z);
        let dir = dir.try_normalize().unwrap_or(fallback);
        self.fireball = Some(Fireball {
            position: self.room.clamp_sphere(pos, cfg.radius),
            velocity: dir * cfg.speed,
            radius: cfg.radius,
            mass: self.config.balls.mass,
            speed: cfg.speed,
        });
    }

    /// Removes the fireball: it no longer exists nor collides.
    pub fn remove_fireball(&mut self) {
        self.fireball = None;
    }

    /// Total kinetic and potential energy of every body.
    pub fn energy(&self) -> Energy {
        let g = self.config.gravity;
        let floor = self.room.min.y;
        let balls = &self.balls;
        let mut e = sum_in_runs(balls.len(), |run| {
            let mut e = Energy::default();
            for i in run {
                if balls.alive[i] {
                    e.kinetic += balls.kinetic_energy(i);
                    e.potential += balls.mass[i] * g * (balls.position[i].y - floor);
                }
            }
            e
        });
        for t in &self.tumblers {
            e.kinetic += t.kinetic_energy(&self.shape);
            e.potential += self.shape.mass * g * (t.center_of_mass().y - floor);
        }
        if let Some(f) = &self.fireball {
            e.kinetic += f.kinetic_energy();
        }
        e
    }

    /// Advances the world by one fixed time step.
    ///
    /// The contact solver starts from last step's impulses (see
    /// the `warm` module). Should that make energy (only the hand may feed
    /// some in), the excess is taken from the balls' motion, all slowed
    /// alike; if they have too little, the balls' motion of the step is
    /// shortened (see `shorten_ball_motion`); if even that cannot pay, the
    /// step is retaken from its start with half the warm start, and then
    /// without. Either way energy never grows.
    pub fn step(&mut self) {
        // A crowded world's step runs on a worker thread, the others kept
        // awake: its dozens of parallel stages then start on all threads at
        // once (see `threads`), instead of waking a sleeping one each time.
        if self.balls.len() >= PARALLEL_BALLS || self.contacts.pair_count() >= PARALLEL_PAIRS {
            with_workers_awake(|| self.step_here());
        } else {
            self.step_here();
        }
    }

    /// [`World::step`], on the current thread.
    fn step_here(&mut self) {
        let started = Instant::now();
        let mut clock = started;
        self.times = StepTimes::default();
        let events_before = self.events.len();
        let dt = self.config.solver.dt;
        self.poured = DVec3::ZERO;
        self.pour_due_balls();
        // The hand feeds energy in: a held step is not held to the world's.
        self.pull_held_ball(dt);
        self.times.lap(Stage::Setup, &mut clock);
        if self.grabbed().is_some() || self.ball_hold.is_some() {
            self.advance(dt, true, None, &mut clock);
        } else {
            let before = self.energy().total();
            self.scratch.before_step.0.clone_from(&self.balls);
            self.scratch.before_step.1.clone_from(&self.tumblers);
            let first_event = self.events.len();
            self.advance(dt, true, Some(before), &mut clock);
            // Retaken with half the warm start, then none: a cold step alone
            // would let a deep pile sag, and the next warm start overshoot.
            for share in [0.5, 0.0] {
                let after = self.energy().total();
                if after <= before
                    || self.take_kinetic_energy(after - before, before)
                    || self.shorten_ball_motion(before)
                {
                    break;
                }
                self.balls.clone_from(&self.scratch.before_step.0);
                self.tumblers.clone_from(&self.scratch.before_step.1);
                self.events.truncate(first_event);
                self.warm.weaken(share);
                self.retakes += 1;
                self.advance(dt, share > 0.0, Some(before), &mut clock);
            }
        }
        std::mem::swap(&mut self.warm, &mut self.warm_next);
        self.move_fireball(dt);
        self.steps += 1;
        self.time = self.steps as f64 * dt;
        self.times.impacts = self.events.len().saturating_sub(events_before);
        self.times.pairs = self.contacts.pair_count();
        self.times.other_contacts =
            self.contacts.walls.len() + self.contacts.tumbler_contacts.len();
        self.times.lap(Stage::Finish, &mut clock);
        self.times.total = started.elapsed();
    }

    /// How long the last step took, stage by stage, and what it worked on.
    pub fn step_times(&self) -> &StepTimes {
        &self.times
    }

    /// The impulses the room's surfaces and the tumblers gave the balls
    /// in the last step (see [`BallImpulses`] for what they leave out).
    pub fn ball_impulses(&self) -> BallImpulses {
        self.impulses
    }

    /// Takes `excess` joules from the balls' motion, all slowed alike, if
    /// they have it and the world then holds no more than `limit`.
    fn take_kinetic_energy(&mut self, excess: f64, limit: f64) -> bool {
        let live = || (0..self.balls.len()).filter(|&i| self.balls.alive[i]);
        let kinetic: f64 = live().map(|i| self.balls.kinetic_energy(i)).sum();
        if kinetic <= excess {
            return false;
        }
        let keep = ((kinetic - excess) / kinetic).sqrt();
        self.impulses.guard += (keep - 1.0) * self.balls.momentum();
        for i in 0..self.balls.len() {
            self.balls.velocity[i] *= keep;
            self.balls.spin[i] *= keep;
        }
        self.energy().total() <= limit
    }

    /// Shortens the balls' motion of this step alike, their positions back
    /// towards where the step began and their velocities with them, until
    /// the world holds no more than `limit`; if it can.
    ///
    /// This is for a pile at rest, which a warm start may lift by a hair:
    /// the lift is potential energy, and the balls have too little motion
    /// to pay for it. Retaking such a step with a weaker warm start lets the
    /// pile sag, and the next warm start overshoot again.
    fn shorten_ball_motion(&mut self, limit: f64) -> bool {
        let g = self.config.gravity;
        let start = &self.scratch.before_step.0;
        let live = || (0..self.balls.len()).filter(|&i| self.balls.alive[i]);
        let kinetic: f64 = live().map(|i| self.balls.kinetic_energy(i)).sum();
        let rise: f64 = live()
            .map(|i| self.balls.mass[i] * g * (self.balls.position[i].y - start.position[i].y))
            .sum();
        // The energy with the motion shortened to a share k is
        // kinetic k^2 + rise k + rest, everything else held.
        let rest = self.energy().total() - kinetic - rise;
        // A hair under the limit, for the rounding of the sums; at share 0
        // the balls stand where they began, at rest, which never exceeds it.
        let over = rest - (limit - 1e-13 * limit.abs());
        let share = if over >= 0.0 {
            0.0
        } else if kinetic > 0.0 {
            (-rise + (rise * rise - 4.0 * kinetic * over).sqrt()) / (2.0 * kinetic)
        } else if rise > 0.0 {
            -over / rise
        } else {
            1.0
        };
        let share = share.clamp(0.0, 1.0);
        self.impulses.guard += (share - 1.0) * self.balls.momentum();
        for i in 0..self.balls.len() {
            if self.balls.alive[i] {
                let from = start.position[i];
                self.balls.position[i] = from + (self.balls.position[i] - from) * share;
                self.balls.velocity[i] *= share;
                self.balls.spin[i] *= share;
            }
        }
        self.energy().total() <= limit
    }

    /// How many times a step was retaken with less of its warm start (see
    /// [`World::step`]).
    pub fn retakes(&self) -> u64 {
        self.retakes
    }

    /// One step of the balls and tumblers, with or without a warm start.
    /// With `start_energy`, the world's energy now, no part of the step may
    /// make energy; without, the hand feeds some in anyway.
    fn advance(
        &mut self,
        dt: f64,
        warm_start: bool,
        start_energy: Option<f64>,
        clock: &mut Instant,
    ) {
        let g = DVec3::new(0.0, -self.config.gravity, 0.0);
        // What came before this advance (an energy check, a retake's
        // restore) is the finish's.
        self.times.lap(Stage::Finish, clock);
        // A retaken step counts its impulses afresh.
        let live = (0..self.balls.len()).filter(|&i| self.balls.alive[i]);
        let mass: f64 = live.map(|i| self.balls.mass[i]).sum();
        self.impulses = BallImpulses {
            gravity: mass * g * dt,
            poured: self.poured,
            ..BallImpulses::default()
        };
        self.grid.rebuild(&self.balls.position, &self.balls.alive);
        let first_event = self.events.len();
        self.enter_sorted_order();
        self.times.lap(Stage::Grid, clock);
        self.collect_contacts(dt);
        self.times.lap(Stage::Contacts, clock);

        // Step-average velocities: half a step of gravity now, half after moving.
        per_ball(&mut self.balls.velocity, &self.balls.alive, |v, &alive| {
            if alive {
                *v += 0.5 * dt * g;
            }
        });
        self.resolve_impacts(dt, g);
        self.times.lap(Stage::Impacts, clock);
        self.update_contact_inertia();
        self.predict_after_impacts(warm_start);
        self.apply_rolling_resistance();
        self.times.lap(Stage::Solve, clock);

        self.move_balls(dt, g);
        self.move_tumblers(dt);
        self.times.lap(Stage::Move, clock);

        self.update_contact_inertia();
        self.begin_recording();
        let given = solve_project(&mut self.step_context(warm_start));
        self.impulses += given;
        self.times.lap(Stage::Project, clock);
        self.report_contacts();
        // Pushing sunk balls apart lifts them: it may spend what the step
        // has lost, no more.
        let budget = start_energy.map_or(f64::INFINITY, |start| {
            let rounding = 1e-10 * start.abs();
            start - self.energy().total() - rounding
        });
        self.push_apart_sunk_balls(budget);
        self.separate_overlaps();
        self.leave_sorted_order(first_event);
        self.times.lap(Stage::Report, clock);
    }

    /// Makes `self.balls` the live balls in the grid's cell order for the
    /// rest of the step: contacts, solving and moving then walk memory in
    /// the order of space. Ball numbers in this order are slots.
    fn enter_sorted_order(&mut self) {
        let order = self.grid.order();
        let (from, to) = (&self.balls, &mut self.scratch.sorted);
        fn gather<T: Copy + Send + Sync>(to: &mut Vec<T>, from: &[T], order: &[u32]) {
            to.clear();
            if order.len() >= PARALLEL_LIGHT_PASSES {
                to.par_extend(order.par_iter().map(|&id| from[id as usize]));
            } else {
                to.extend(order.iter().map(|&id| from[id as usize]));
            }
        }
        gather(&mut to.position, &from.position, order);
        gather(&mut to.velocity, &from.velocity, order);
        gather(&mut to.spin, &from.spin, order);
        gather(&mut to.radius, &from.radius, order);
        gather(&mut to.mass, &from.mass, order);
        gather(&mut to.inv_mass, &from.inv_mass, order);
        gather(&mut to.tint, &from.tint, order);
        to.alive.clear();
        to.alive.resize(order.len(), true);
        std::mem::swap(&mut self.balls, &mut self.scratch.sorted);
    }

    /// Writes the sorted balls back to their own numbers, and renumbers the
    /// balls named by the events of this step (from `first_event` on).
    fn leave_sorted_order(&mut self, first_event: usize) {
        std::mem::swap(&mut self.balls, &mut self.scratch.sorted);
        let (from, to) = (&self.scratch.sorted, &mut self.balls);
        let slots = self.grid.ball_slots();
        fn scatter<T: Copy + Send + Sync>(to: &mut [T], from: &[T], slots: &[u32]) {
            let put = |(id, x): (usize, &mut T)| {
                if let Some(&slot) = slots.get(id).filter(|&&s| s != Grid::NO_SLOT) {
                    *x = from[slot as usize];
                }
            };
            if to.len() >= PARALLEL_LIGHT_PASSES {
                to.par_iter_mut().enumerate().for_each(put);
            } else {
                to.iter_mut().enumerate().for_each(put);
            }
        }
        scatter(&mut to.position, &from.position, slots);
        scatter(&mut to.velocity, &from.velocity, slots);
        scatter(&mut to.spin, &from.spin, slots);
        scatter(&mut to.tint, &from.tint, slots);
        let order = self.grid.order();
        for e in &mut self.events[first_event..] {
            e.kind = e.kind.renumber_balls(|slot| order[slot] as usize);
        }
    }

    /// Forgets what the next step's warm start held, ready to record this
    /// step's impulses in this step's slots.
    fn begin_recording(&mut self) {
        let (slot_of, slots) = (self.grid.ball_slots(), self.grid.order().len());
        let pairs = self.contacts.pair_count();
        self.warm_next.begin(slot_of, slots, pairs);
    }

    /// What the solver stages work on, borrowed apart, with last step's
    /// impulses if the step is warm started, and where to record this step's.
    fn step_context(&mut self, warm_start: bool) -> StepContext<'_> {
        let bodies = Bodies {
            balls: &mut self.balls,
            tumblers: &mut self.tumblers,
            shape: &self.shape,
            contact_inv: &self.scratch.contact_inv,
            floor_friction: self.config.tumblers.floor_friction,
            wall_restitution: self.config.room.restitution,
            wall_friction: self.config.room.friction,
        };
        let solver = &self.config.solver;
        StepContext {
            dt: solver.dt,
            iterations: solver.iterations,
            bounce_threshold: solver.bounce_threshold,
            ball_restitution: self.config.balls.restitution,
            ball_material: PairMaterial {
                friction: self.config.balls.friction,
                rolling_resistance: self.config.balls.rolling_resistance,
            },
            bodies,
            contacts: &mut self.contacts,
            crowd: &mut self.scratch.crowd,
            hit_wall: &self.scratch.hit_wall,
            warm: warm_start.then(|| (&self.warm, self.grid.order())),
            record: &mut self.warm_next,
            ids: self.grid.order(),
        }
    }

    fn update_contact_inertia(&mut self) {
        for (inv, t) in self.scratch.contact_inv.iter_mut().zip(&self.tumblers) {
            *inv = t.contact_inertia_inverse(&self.shape);
        }
    }
}
