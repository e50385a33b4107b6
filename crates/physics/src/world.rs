//! The world: all bodies, and the fixed step that moves them.
//!
//! One step of `dt`, in order:
//! 1. find contacts at the current positions (grid broadphase for balls);
//! 2. half a step of gravity on the balls' velocities (the step-average velocity);
//! 3. solve contacts on those velocities (predict stage, speculative);
//! 4. move: balls along exact parabolas with exact wall impacts, tumblers by
//!    integrating their grounded rolling/sliding equations;
//! 5. resolve bounces and rests (project stage), emit events, take on colours;
//! 6. separate any remaining overlaps, then move the fireball.
//!
//! Everything runs in a fixed order on `f64`, so the same configuration,
//! seed and inputs give bit-identical states (P10).

use crate::balls::{Balls, PARALLEL_BALLS, Tint};
use crate::broadphase::Grid;
use crate::ccd::first_impact;
use crate::config::{Rgb, WorldConfig};
use crate::contact::{
    Bodies, BodyRef, Contact, Contacts, Crowd, PARALLEL_PAIRS, Pair, WallContact, solve_predict,
    solve_project,
};
use crate::events::{Event, EventKind};
use crate::fireball::Fireball;
use crate::rng::Rng;
use crate::room::{Room, Surface};
use crate::tumbler::{Grip, GroundedParams, Tumbler, TumblerShape};
use crate::warm::WarmStart;
use glam::{DMat3, DQuat, DVec3, Vec4};
use rayon::prelude::*;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

/// Overlaps smaller than this are left alone (metres).
const OVERLAP_SLOP: f64 = 1e-5;
/// A ball this close to a wall is touching it (metres).
const TOUCH_SLOP: f64 = 1e-6;
/// Balls sunk into each other deeper than this share of their radii's sum
/// are pushed apart down to it (see `push_apart_sunk_balls`).
const SUNK_SLOP: f64 = 0.005;
/// Sweeps over the pairs that push sunk balls apart, and the share of an
/// overlap that one push removes.
const PUSH_SWEEPS: usize = 4;
const PUSH_SHARE: f64 = 0.5;

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
    pub kinetic: f64,
    pub potential: f64,
}

impl Energy {
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
    if items.len() >= PARALLEL_BALLS {
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
    if count < PARALLEL_BALLS {
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

/// The world's parts that the contact solver reads and writes.
struct SolverParts<'a> {
    bodies: Bodies<'a>,
    contacts: &'a mut Contacts,
    crowd: &'a mut Crowd,
    hit_wall: &'a [bool],
    /// Last step's impulses, and each slot's ball number.
    warm: Option<(&'a WarmStart, &'a [u32])>,
    /// Where this step's impulses are recorded.
    record: &'a mut WarmStart,
    /// Each slot's ball number.
    ids: &'a [u32],
}

/// A tumbler hit by a pick ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pick {
    pub tumbler: usize,
    pub point: DVec3,
    /// Distance along the ray.
    pub distance: f64,
}

pub struct World {
    config: WorldConfig,
    room: Room,
    /// Shared, so that a step may hold it while it changes the world.
    shape: Arc<TumblerShape>,
    balls: Balls,
    /// The live balls in the grid's cell order, which the step works on so
    /// that neighbours in space are neighbours in memory (see `step`).
    sorted: Balls,
    tumblers: Vec<Tumbler>,
    fireball: Option<Fireball>,
    rng: Rng,
    time: f64,
    steps: u64,
    events: Vec<Event>,
    grid: Grid,
    contacts: Contacts,
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
    /// Last step's impulses of both solver stages, by ball number (see
    /// [`crate::warm`]), and this step's, which take their place once the
    /// step is done.
    warm: WarmStart,
    warm_next: WarmStart,
    /// The state before a step, to retake it if its warm start made energy.
    before_step: (Balls, Vec<Tumbler>),
    retakes: u64,
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
        // Two balls can touch within a step only if their centres are closer
        // than two radii plus the speculative reach of one radius (see
        // `collect_contacts`): a cell that wide finds every pair. Balls
        // spread thin through the room get cells about as wide as the space
        // between them, so that walking the empty cells costs no more than
        // the balls. The fireball and tumblers look for balls by box,
        // whatever the cell size.
        let touch = 3.0 * b.radius + 4.0 * TOUCH_SLOP;
        let spacing = (room.size().element_product() / b.count.max(1) as f64).cbrt();
        let grid = Grid::new(room.min, room.max, touch.max(spacing));
        let mut world = World {
            balls: Balls::with_uniform(b.count, b.radius, b.mass),
            sorted: Balls::default(),
            contact_inv: vec![DMat3::IDENTITY; tumblers.len()],
            tumblers,
            fireball: None,
            rng: Rng::new(seed),
            time: 0.0,
            steps: 0,
            events: Vec::new(),
            grid,
            contacts: Contacts::default(),
            hit_wall: vec![false; b.count],
            ball_partners: Vec::new(),
            picked_pairs: Vec::new(),
            unpushed: Vec::new(),
            wall_contacts_by_layer: Vec::new(),
            pair_spheres: Vec::new(),
            speed: Vec::new(),
            crowd: Crowd::default(),
            warm: Default::default(),
            warm_next: Default::default(),
            before_step: Default::default(),
            retakes: 0,
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

    pub fn config(&self) -> &WorldConfig {
        &self.config
    }

    pub fn room(&self) -> &Room {
        &self.room
    }

    pub fn time(&self) -> f64 {
        self.time
    }

    pub fn step_count(&self) -> u64 {
        self.steps
    }

    pub fn balls(&self) -> &Balls {
        &self.balls
    }

    /// Mutable access to the balls, for building scenarios.
    pub fn balls_mut(&mut self) -> &mut Balls {
        &mut self.balls
    }

    pub fn tumblers(&self) -> &[Tumbler] {
        &self.tumblers
    }

    pub fn tumbler_shape(&self) -> &TumblerShape {
        &self.shape
    }

    pub fn fireball(&self) -> Option<&Fireball> {
        self.fireball.as_ref()
    }

    /// The colour a tint stands for.
    pub fn tint_color(&self, tint: Tint) -> Rgb {
        match tint {
            Tint::White => self.config.balls.color,
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

    /// Re-initialises the balls (I6): new random positions and velocities
    /// from the world's random sequence, every ball alive and white again.
    pub fn reset_balls(&mut self) -> Result<(), BuildError> {
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

    /// The nearest tumbler sphere hit by the ray `origin + t dir`, t >= 0.
    pub fn pick(&self, origin: DVec3, dir: DVec3) -> Option<Pick> {
        let dir = dir.try_normalize()?;
        let mut best: Option<Pick> = None;
        for (ti, t) in self.tumblers.iter().enumerate() {
            for (si, s) in self.shape.spheres.iter().enumerate() {
                let c = t.sphere_center(&self.shape, si);
                let oc = origin - c;
                let b = oc.dot(dir);
                let disc = b * b - (oc.length_squared() - s.radius * s.radius);
                if disc < 0.0 {
                    continue;
                }
                let hit = -b - disc.sqrt();
                let hit = if hit >= 0.0 { hit } else { -b + disc.sqrt() };
                if hit >= 0.0 && best.is_none_or(|p| hit < p.distance) {
                    best = Some(Pick {
                        tumbler: ti,
                        point: origin + dir * hit,
                        distance: hit,
                    });
                }
            }
        }
        best
    }

    /// Takes hold of tumbler `tumbler` at world point `point` (I5).
    pub fn grab(&mut self, tumbler: usize, point: DVec3) {
        if let Some(t) = self.tumblers.get_mut(tumbler) {
            let anchor = t.orientation.inverse() * (point - t.center);
            t.grip = Some(Grip {
                anchor,
                target: point,
            });
        }
    }

    /// Moves the hand holding a tumbler; the tumbler follows through a
    /// spring-damper force at the grab point.
    pub fn drag_to(&mut self, target: DVec3) {
        for t in &mut self.tumblers {
            if let Some(g) = &mut t.grip {
                g.target = target;
            }
        }
    }

    /// Lets go: the tumbler keeps the motion it has.
    pub fn release(&mut self) {
        for t in &mut self.tumblers {
            t.grip = None;
        }
    }

    /// Index of the tumbler being held, if any.
    pub fn grabbed(&self) -> Option<usize> {
        self.tumblers.iter().position(|t| t.grip.is_some())
    }

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

    /// Places every ball at a random free spot with a random velocity.
    ///
    /// Spots come from a jittered lattice whose spacing leaves each ball
    /// room to move: shuffled lattice sites give random, non-overlapping
    /// positions in time linear in the ball count.
    fn spawn_balls(&mut self) -> Result<(), BuildError> {
        let n = self.balls.len();
        if n == 0 {
            return Ok(());
        }
        let r = self.config.balls.radius;
        let fill = self.config.balls.start_fill;
        if !(fill > 0.0 && fill <= 1.0) {
            return Err(BuildError(format!(
                "balls.start_fill = {fill} is out of range: allowed > 0 and <= 1"
            )));
        }
        let lo = self.room.min + DVec3::splat(r);
        let mut top = self.room.max;
        top.y = self.room.min.y + fill * (self.room.max.y - self.room.min.y);
        let hi = top - DVec3::splat(r);
        let span = hi - lo;
        let within = if fill < 1.0 {
            format!("the lowest {fill} of the room's height (balls.start_fill)")
        } else {
            "the room".to_string()
        };
        if span.min_element() < 0.0 {
            return Err(BuildError(format!(
                "balls of radius {r} do not fit in {within}"
            )));
        }
        // Aim for about four sites per ball, never closer than 2.1 radii.
        let volume = span.x.max(0.0) * span.y.max(0.0) * span.z.max(0.0);
        let spacing = (volume / (4.0 * n as f64)).cbrt().max(2.1 * r);
        let dims = [
            (span.x / spacing).floor() as usize + 1,
            (span.y / spacing).floor() as usize + 1,
            (span.z / spacing).floor() as usize + 1,
        ];
        let jitter = 0.5 * (spacing - 2.05 * r).max(0.0);
        let clearance = self.shape.bound_radius + r + 0.5 * spacing;
        let mut sites = Vec::with_capacity(dims[0] * dims[1] * dims[2]);
        for z in 0..dims[2] {
            for y in 0..dims[1] {
                for x in 0..dims[0] {
                    let p = lo + DVec3::new(x as f64, y as f64, z as f64) * spacing;
                    let clear = self.tumblers.iter().all(|t| {
                        let c = t.center
                            + t.orientation * DVec3::new(0.0, self.shape.bound_height, 0.0);
                        p.distance(c) > clearance
                    });
                    if clear && p.cmple(hi + DVec3::splat(1e-9)).all() {
                        sites.push(p);
                    }
                }
            }
        }
        if sites.len() < n {
            return Err(BuildError(format!(
                "{n} balls of radius {r} do not fit in {within} beside the tumblers (room for {})",
                sites.len()
            )));
        }
        let (min_speed, max_speed) = (self.config.balls.speed_min, self.config.balls.speed_max);
        for i in 0..n {
            // Partial Fisher-Yates: site i is a uniform pick among the rest.
            let k = i + (self.rng.next_u64() % (sites.len() - i) as u64) as usize;
            sites.swap(i, k);
            let offset = DVec3::new(
                self.rng.range(-jitter, jitter),
                self.rng.range(-jitter, jitter),
                self.rng.range(-jitter, jitter),
            );
            let p = (sites[i] + offset).clamp(lo, hi);
            let v = self.rng.direction() * self.rng.range(min_speed, max_speed);
            self.balls.set(i, p, v);
            self.balls.alive[i] = true;
            self.balls.tint[i] = Tint::White;
        }
        Ok(())
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
        // A crowded world's step runs on a worker thread: its forty-odd
        // parallel stages then hand work to the other workers, which are
        // awake, instead of waking the caller's thread after each one.
        if self.balls.len() >= PARALLEL_BALLS || self.contacts.pair_count() >= PARALLEL_PAIRS {
            rayon::scope(|_| self.step_here());
        } else {
            self.step_here();
        }
    }

    /// [`World::step`], on the current thread.
    fn step_here(&mut self) {
        let dt = self.config.solver.dt;
        if self.grabbed().is_some() {
            self.advance(dt, true, None);
        } else {
            let before = self.energy().total();
            self.before_step.0.clone_from(&self.balls);
            self.before_step.1.clone_from(&self.tumblers);
            let first_event = self.events.len();
            self.advance(dt, true, Some(before));
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
                self.balls.clone_from(&self.before_step.0);
                self.tumblers.clone_from(&self.before_step.1);
                self.events.truncate(first_event);
                self.warm.weaken(share);
                self.retakes += 1;
                self.advance(dt, share > 0.0, Some(before));
            }
        }
        std::mem::swap(&mut self.warm, &mut self.warm_next);
        self.move_fireball(dt);
        self.steps += 1;
        self.time = self.steps as f64 * dt;
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
        let start = &self.before_step.0;
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
    fn advance(&mut self, dt: f64, warm_start: bool, start_energy: Option<f64>) {
        let g = DVec3::new(0.0, -self.config.gravity, 0.0);
        self.grid.rebuild(&self.balls.position, &self.balls.alive);
        let first_event = self.events.len();
        self.enter_sorted_order();
        self.collect_contacts(dt);

        // Step-average velocities: half a step of gravity now, half after moving.
        per_ball(&mut self.balls.velocity, &self.balls.alive, |v, &alive| {
            if alive {
                *v += 0.5 * dt * g;
            }
        });
        self.update_contact_inertia();
        let (iterations, threshold) = (
            self.config.solver.iterations,
            self.config.solver.bounce_threshold,
        );
        let mut parts = self.solver_parts(warm_start);
        solve_predict(
            &mut parts.bodies,
            parts.contacts,
            parts.crowd,
            iterations,
            dt,
            threshold,
            parts.warm,
        );
        self.apply_rolling_resistance();

        self.move_balls(dt, g);
        self.move_tumblers(dt);

        self.update_contact_inertia();
        let restitution = self.config.balls.restitution;
        self.begin_recording();
        let mut parts = self.solver_parts(warm_start);
        solve_project(
            &mut parts.bodies,
            parts.contacts,
            parts.crowd,
            iterations,
            threshold,
            restitution,
            parts.hit_wall,
            parts.warm,
            (parts.record, parts.ids),
        );
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
    }

    /// Makes `self.balls` the live balls in the grid's cell order for the
    /// rest of the step: contacts, solving and moving then walk memory in
    /// the order of space. Ball numbers in this order are slots.
    fn enter_sorted_order(&mut self) {
        let order = self.grid.order();
        let (from, to) = (&self.balls, &mut self.sorted);
        fn gather<T: Copy + Send + Sync>(to: &mut Vec<T>, from: &[T], order: &[u32]) {
            to.clear();
            if order.len() >= PARALLEL_BALLS {
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
        std::mem::swap(&mut self.balls, &mut self.sorted);
    }

    /// Writes the sorted balls back to their own numbers, and renumbers the
    /// balls named by the events of this step (from `first_event` on).
    fn leave_sorted_order(&mut self, first_event: usize) {
        std::mem::swap(&mut self.balls, &mut self.sorted);
        let (from, to) = (&self.sorted, &mut self.balls);
        let slots = self.grid.ball_slots();
        fn scatter<T: Copy + Send + Sync>(to: &mut [T], from: &[T], slots: &[u32]) {
            let put = |(id, x): (usize, &mut T)| {
                if let Some(&slot) = slots.get(id).filter(|&&s| s != Grid::NO_SLOT) {
                    *x = from[slot as usize];
                }
            };
            if to.len() >= PARALLEL_BALLS {
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

    /// What the solver works on, borrowed apart, with last step's impulses
    /// if the step is warm started, and where to record this step's.
    fn solver_parts(&mut self, warm_start: bool) -> SolverParts<'_> {
        let bodies = Bodies {
            balls: &mut self.balls,
            tumblers: &mut self.tumblers,
            shape: &self.shape,
            contact_inv: &self.contact_inv,
            floor_friction: self.config.tumblers.floor_friction,
            wall_restitution: self.config.room.restitution,
            wall_friction: self.config.room.friction,
        };
        SolverParts {
            bodies,
            contacts: &mut self.contacts,
            crowd: &mut self.crowd,
            hit_wall: &self.hit_wall,
            warm: warm_start.then(|| (&self.warm, self.grid.order())),
            record: &mut self.warm_next,
            ids: self.grid.order(),
        }
    }

    fn update_contact_inertia(&mut self) {
        for (inv, t) in self.contact_inv.iter_mut().zip(&self.tumblers) {
            *inv = t.contact_inertia_inverse(&self.shape);
        }
    }

    /// All contacts that may act during the coming step.
    fn collect_contacts(&mut self, dt: f64) {
        let balls = &self.balls;
        let room = &self.room;
        let cfg = &self.config;
        // A contact is kept if its gap could close within the step; speculative
        // reach is capped at one ball radius (the grid's cell allows for that).
        let reach_cap = cfg.balls.radius;
        let contacts = &mut self.contacts;

        // Each ball's share of the pair test below: its radius and how far
        // it could fly, so that resting balls look no further than touching;
        // widened by more than `f32` rounds off in a room of any size.
        let (spheres, speed) = (&mut self.pair_spheres, &mut self.speed);
        speed.clear();
        speed.extend(balls.velocity.iter().map(|v| v.length()));
        spheres.clear();
        spheres.extend((0..balls.len()).map(|i| {
            let p = balls.position[i];
            let reach = balls.radius[i] + (2.0 * speed[i] * dt).min(reach_cap) + TOUCH_SLOP;
            let rounding = 1e-6 * (1.0 + p.abs().max_element());
            p.as_vec3().extend((reach + rounding) as f32)
        }));
        let (spheres, speed) = (&self.pair_spheres, &self.speed);
        let grid = &self.grid;
        contacts.reset(grid.layer_count());
        grid.layer_slots(&mut contacts.layers);
        let find_pairs = |(z, band): (usize, &mut Vec<Pair>)| {
            grid.for_each_close_pair_in_layer(spheres, z, |i, j| {
                let d = balls.position[i] - balls.position[j];
                let dist = d.length();
                let gap = dist - balls.radius[i] - balls.radius[j];
                let relative = balls.velocity[i] - balls.velocity[j];
                // Either ball may bounce off a wall within the step and come
                // back at up to its speed: allow for that (which covers their
                // relative speed too).
                let closing = 2.0 * (speed[i] + speed[j]) * dt;
                if gap < closing.min(reach_cap) + TOUCH_SLOP && dist > 0.0 {
                    // Gravity moves both alike, so within the step they close
                    // along a straight line: take the normal at the moment of impact.
                    let reach = balls.radius[i] + balls.radius[j];
                    let (n, gap) = impact_normal(d, relative, reach, dt).unwrap_or((d / dist, gap));
                    // Approach speed before anything moves: what restitution acts on.
                    band.push(Pair::new(i, j, n, gap, relative.dot(n)));
                }
            });
        };
        // Each layer fills its own band, so the pairs come out in the same
        // order on any number of threads.
        if balls.len() >= PARALLEL_BALLS {
            contacts
                .bands
                .par_iter_mut()
                .enumerate()
                .for_each(find_pairs);
        } else {
            contacts.bands.iter_mut().enumerate().for_each(find_pairs);
        }
        contacts.count_pairs();

        // Balls resting on or touching a wall. A lone ball's impacts are
        // found exactly while moving (see `move_balls`); a ball pressed by
        // others gets a speculative contact with every wall it could reach
        // in the step, so that it stops there with them instead of bouncing
        // back into them (which would sink balls into each other).
        let partners = &mut self.ball_partners;
        partners.clear();
        partners.resize(balls.len(), 0);
        contacts.sweep_slots(partners, &|p, partners, first| {
            for k in [p.i as usize - first, p.j as usize - first] {
                partners[k] = partners[k].saturating_add(1);
            }
        });
        let partners = &self.ball_partners;
        let touch_walls = |i: usize, into: &mut Vec<WallContact>| {
            let crowded = partners[i] > 0;
            for s in Surface::ALL {
                let gap = room.distance(s, balls.position[i]) - balls.radius[i];
                let n = s.inward_normal();
                // Others may push it as far as it could fly: allow for both.
                let reach = if crowded {
                    (-balls.velocity[i].dot(n) * dt).max(reach_cap)
                } else {
                    0.0
                };
                if gap <= reach + TOUCH_SLOP {
                    let gap = if gap > TOUCH_SLOP { gap } else { gap.min(0.0) };
                    // Its approach speed before anything moves: what
                    // restitution acts on.
                    let approach = balls.velocity[i].dot(n);
                    into.push(WallContact::new(i, s, gap, approach));
                }
            }
        };
        // Layer by layer, each into its own list, then in layer order: the
        // same contacts in the same order on any number of threads.
        let layers = &contacts.layers;
        let by_layer = &mut self.wall_contacts_by_layer;
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
                            contacts.others.push(Contact::new(
                                BodyRef::Ball(bi),
                                BodyRef::Tumbler(ti, si),
                                n,
                                c + n * s.radius,
                                gap,
                                cfg.tumblers.restitution,
                            ));
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
                            contacts.others.push(Contact::new(
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
                        contacts.others.push(Contact::new(
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

        // Approach speeds before anything moves: what restitution acts on
        // (pairs and walls have theirs from when they were found).
        let SolverParts {
            bodies, contacts, ..
        } = self.solver_parts(false);
        for c in contacts.others.iter_mut() {
            c.approach = bodies.normal_velocity(c);
        }
    }

    /// Rolling resistance: a ball pressed on a surface loses rolling speed
    /// in proportion to the normal impulse, until it stops.
    fn apply_rolling_resistance(&mut self) {
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
            self.balls.velocity[i] = v.dot(n) * n + tangential * keep;
            self.balls.spin[i] *= keep;
        }
    }

    /// Moves every ball along its parabola, bouncing exactly off the walls.
    fn move_balls(&mut self, dt: f64, gravity: DVec3) {
        let room = self.room;
        let solver = &self.config.solver;
        let (e, mu) = (self.config.room.restitution, self.config.room.friction);
        for i in 0..self.balls.len() {
            self.hit_wall[i] = false;
            if !self.balls.alive[i] {
                continue;
            }
            let r = self.balls.radius[i];
            if self.ball_partners[i] > 0 {
                // Its walls are in the solver already (see `collect_contacts`):
                // the step-average velocity carries it along its parabola.
                let v = self.balls.velocity[i];
                self.balls.position[i] = room.clamp_sphere(self.balls.position[i] + v * dt, r);
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
                    if let Some(t) = first_impact(d0, n.dot(u), n.dot(g), left) {
                        if first.is_none_or(|(best, _)| t < best) {
                            first = Some((t, s));
                        }
                    }
                }
                let Some((t, s)) = first else {
                    x += u * left + 0.5 * g * left * left;
                    u += g * left;
                    break;
                };
                x += u * t + 0.5 * g * t * t;
                u += g * t;
                left -= t;
                let n = s.inward_normal();
                // Sit exactly on the wall.
                x += n * (r - room.distance(s, x));
                let speed = -n.dot(u);
                self.hit_wall[i] = true;
                let normal_impulse = if speed > solver.bounce_threshold {
                    u += (1.0 + e) * speed * n;
                    m * (1.0 + e) * speed
                } else {
                    u += speed * n;
                    if n.dot(g) < 0.0 {
                        // Resting on it: the wall carries gravity from here on.
                        g -= n.dot(g) * n;
                    }
                    m * speed
                };
                // Coulomb friction at the contact point, at most enough to roll.
                let arm = -r * n;
                let slip = u + spin.cross(arm);
                let slip = slip - slip.dot(n) * n;
                let slip_speed = slip.length();
                if slip_speed > 0.0 {
                    let j = (mu * normal_impulse).min(slip_speed / (1.0 / m + r * r / inertia));
                    let impulse = -slip / slip_speed * j;
                    u += impulse / m;
                    spin += arm.cross(impulse) / inertia;
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
                    });
                }
            }
            self.balls.position[i] = room.clamp_sphere(x, r);
            self.balls.velocity[i] = u;
            self.balls.spin[i] = spin;
        }
    }

    fn move_tumblers(&mut self, dt: f64) {
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

    /// Events and colours from the contacts that pushed this step.
    fn report_contacts(&mut self) {
        let threshold = self.config.solver.event_threshold;
        let hits = &mut self.picked_pairs;
        let hit = |p: &Pair| p.pushed && -p.approach > threshold;
        self.contacts.copy_pairs_where(hit, hits);
        for p in hits.iter() {
            let (i, j) = (p.i as usize, p.j as usize);
            let gap = p.gap.max(0.0);
            self.events.push(Event {
                kind: EventKind::BallBall { a: i, b: j },
                point: self.balls.position[j] + p.normal * (self.balls.radius[j] + 0.5 * gap),
                normal: p.normal,
                speed: -p.approach,
            });
        }
        for c in &self.contacts.walls {
            if c.pushed <= 0.0 || -c.approach <= threshold {
                continue;
            }
            let (i, s) = (c.ball as usize, c.surface);
            self.balls.tint[i] = Tint::Surface(s);
            self.events.push(Event {
                kind: EventKind::BallSurface {
                    ball: i,
                    surface: s,
                },
                // Where the ball meets the wall.
                point: self.room.foot(s, self.balls.position[i]),
                normal: c.normal(),
                speed: -c.approach,
            });
        }
        for c in &self.contacts.others {
            if c.pushed <= 0.0 || -c.approach <= threshold {
                continue;
            }
            let kind = match (c.a, c.b) {
                (BodyRef::Ball(i), BodyRef::Tumbler(t, s)) => {
                    self.balls.tint[i] = Tint::Tumbler(t);
                    EventKind::BallTumbler {
                        ball: i,
                        tumbler: t,
                        sphere: s,
                    }
                }
                _ => continue,
            };
            self.events.push(Event {
                kind,
                point: c.point,
                normal: c.normal,
                speed: -c.approach,
            });
        }
    }

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
    fn push_apart_sunk_balls(&mut self, budget: f64) {
        let balls = &mut self.balls;
        self.unpushed.clone_from(&balls.position);
        let (radius, inv_mass) = (&balls.radius, &balls.inv_mass);
        let mut pushed = false;
        for _ in 0..PUSH_SWEEPS {
            let pushed_now = AtomicBool::new(false);
            let push = |p: &mut Pair, position: &mut [DVec3], first: usize| {
                let (i, j) = (p.i as usize, p.j as usize);
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
            self.contacts.sweep_slots(&mut balls.position, &push);
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
        let unpushed = &self.unpushed;
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
    fn separate_overlaps(&mut self) {
        let shape = Arc::clone(&self.shape);
        let shape = &*shape;
        let mut lone_pairs = std::mem::take(&mut self.picked_pairs);
        let partners = &self.ball_partners;
        let lone = |p: &Pair| partners[p.i as usize] == 1 && partners[p.j as usize] == 1;
        self.contacts.copy_pairs_where(lone, &mut lone_pairs);
        for p in &lone_pairs {
            self.separate_balls(p.i as usize, p.j as usize);
        }
        self.picked_pairs = lone_pairs;
        for k in 0..self.contacts.others.len() {
            let c = &self.contacts.others[k];
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
            self.balls.velocity[i] *= keep;
            self.balls.spin[i] *= keep;
        }
        part
    }

    /// Moves the fireball in substeps short enough that it cannot pass
    /// through a ball, bouncing off walls, tumblers and balls at constant speed.
    fn move_fireball(&mut self, dt: f64) {
        let Some(mut f) = self.fireball.take() else {
            return;
        };
        let min_radius = f.radius.min(self.config.balls.radius);
        let substeps = ((f.speed * dt) / (0.5 * min_radius)).ceil().max(1.0) as usize;
        let h = dt / substeps as f64;
        let shape = &self.shape;
        let friction = self.config.tumblers.floor_friction;
        for _ in 0..substeps {
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
                        });
                    }
                }
            }
            f.position = self.room.clamp_sphere(f.position, f.radius);
        }
        self.fireball = Some(f);
    }
}

/// For two spheres whose centres differ by `d + v t`, the line of centres at
/// first touch within `horizon`, and the gap left along it at t = 0.
fn impact_normal(d: DVec3, v: DVec3, reach: f64, horizon: f64) -> Option<(DVec3, f64)> {
    let a = v.length_squared();
    let b = d.dot(v);
    let c = d.length_squared() - reach * reach;
    if c <= 0.0 || b >= 0.0 || a == 0.0 {
        return None;
    }
    let disc = b * b - a * c;
    if disc < 0.0 {
        return None;
    }
    let t = c / (-b + disc.sqrt());
    if t > horizon {
        return None;
    }
    let n = (d + v * t).normalize();
    Some((n, -v.dot(n) * t))
}
