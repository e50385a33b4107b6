//! Contacts and the sequential-impulse solver that resolves them.
//!
//! A contact joins a ball or tumbler (`a`) to a ball, tumbler or wall (`b`).
//! The two kinds that crowd a room, ball against ball ([`Pair`]) and ball
//! against wall ([`WallContact`]), have small types of their own, solved
//! as rows that hold only what an iteration reads ([`PairRow`], and the
//! wall rows of [`wall_rows`]).
//! Most impacts between balls, and of balls on walls, are over before the
//! solver runs: the world resolves them one by one in the order they happen
//! (see the world's `impacts`), and hands the solver the contacts with their
//! new approach speeds. The solver then runs in two stages per step, each
//! given the step's [`StepContext`]:
//!
//! 1. **predict**, on the velocities that will carry the bodies through the
//!    step: no contact may close more than its gap (speculative contacts, so
//!    nothing tunnels into anything), and touching contacts may not approach;
//! 2. **project**, after the bodies have moved: contacts that pushed in stage 1
//!    end with the bounce their restitution asks for (measured from the
//!    approach speed before the step), or at rest.
//!
//! Of the impacts left to the solver (those of balls packed in a crowd, and
//! every contact with a tumbler), only lone ones bounce (see [`Crowd`]);
//! contacts with a tumbler bounce in stage 1 already (see [`solve_predict`]).
//! Every other impulse stops an approach and nothing more, so no stage can
//! add energy.
//!
//! The parts, a file each: [`stages`], the two stages read top to bottom;
//! [`warm`], last step's impulses to start from;
//! [`bands`], how a sweep over the ball pairs runs on any number of
//! threads with the same result; [`wall_rows`], ball-wall contacts with
//! friction; [`crowd`], which impacts are lone. This file holds the
//! contacts themselves, the pair rows and the bodies they push.

use crate::balls::Balls;
use crate::room::Surface;
use crate::tumbler::{Response, Tumbler, TumblerShape};
use glam::{DMat3, DVec3};
use rayon::prelude::*;

mod bands;
mod crowd;
mod pair_friction;
pub(crate) mod stages;
mod tumbler_friction;
mod wall_rows;
pub(crate) mod warm;

pub(crate) use bands::PARALLEL_PAIRS;
use bands::{by_band_with_own_part, in_four_streams, sweep_bands, sweep_bands_of_two};
pub(crate) use crowd::Crowd;
use pair_friction::{BallBuild, Levers, Motion, RollingRow};
pub(crate) use pair_friction::{FrictionImpulse, PairMaterial};
pub(crate) use stages::{StepContext, solve_predict, solve_project};
pub(crate) use tumbler_friction::TangentRows;
use wall_rows::WallRows;
use warm::WarmPart;
pub(crate) use warm::{StageFriction, WarmStart};

/// Surfaces closer than this (metres) at the end of a step count as touching.
const TOUCHING: f64 = 1e-6;

#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum BodyRef {
    Ball(usize),
    /// A tumbler and which of its six spheres touches.
    Tumbler(usize, usize),
    Wall(Surface),
}

#[derive(Clone, Debug)]
pub(crate) struct Contact {
    pub a: BodyRef,
    pub b: BodyRef,
    /// Unit normal from `b` towards `a`.
    pub normal: DVec3,
    /// World contact point (where impulses act on tumblers).
    pub point: DVec3,
    /// Distance between the surfaces at the start of the step (negative: overlap).
    pub gap: f64,
    pub restitution: f64,
    /// Relative normal velocity before the step (negative: approaching).
    pub approach: f64,
    /// How much gravity's half step changed the relative normal velocity.
    pub kick: f64,
    /// Effective mass along the normal.
    pub mass: f64,
    /// How a tumbler's velocities change per unit impulse along `normal`.
    pub response_a: Response,
    pub response_b: Response,
    /// Accumulated normal impulse of the current stage.
    pub impulse: f64,
    /// Normal impulse of the predict stage (> 0: the contact pushed).
    pub pushed: f64,
    /// Whether the project stage bounces this contact.
    pub bounce: bool,
    /// Coulomb friction at the contact (see [`tumbler_friction`]): a
    /// ball's against a tumbler; 0 for the other contacts.
    pub friction: f64,
    pub slide: TangentRows,
}

impl Contact {
    pub fn new(
        a: BodyRef,
        b: BodyRef,
        normal: DVec3,
        point: DVec3,
        gap: f64,
        restitution: f64,
    ) -> Contact {
        Contact {
            a,
            b,
            normal,
            point,
            gap,
            restitution,
            approach: 0.0,
            kick: 0.0,
            mass: 0.0,
            response_a: Response::default(),
            response_b: Response::default(),
            impulse: 0.0,
            pushed: 0.0,
            bounce: false,
            friction: 0.0,
            slide: TangentRows::default(),
        }
    }
}

/// A contact between two balls: most contacts in a crowded room, so it is
/// kept small and solved without asking which kind of body it touches.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Pair {
    pub i: u32,
    pub j: u32,
    /// Unit normal from `j` towards `i`.
    pub normal: DVec3,
    /// Distance between the surfaces at the start of the step (negative: overlap).
    pub gap: f64,
    /// Relative normal velocity before the step (negative: approaching).
    /// Gravity's half step moves both balls alike, so it stays the same.
    pub approach: f64,
    /// Whether the pair pushed in the predict stage. Its impulses live in
    /// its rows (see [`RowBand`]), so that the pair stays small.
    pub pushed: bool,
    /// Last step's impulse of the project stage, as kept (see
    /// [`WarmStart::pair`]): looked up with the predict stage's.
    pub project_start: f32,
}

impl Pair {
    pub fn new(i: usize, j: usize, normal: DVec3, gap: f64, approach: f64) -> Pair {
        Pair {
            i: i as u32,
            j: j as u32,
            normal,
            gap,
            approach,
            pushed: false,
            project_start: 0.0,
        }
    }
}

/// The slots of a pair's two balls, `[i, j]`: all that a sweep over the
/// balls' positions reads, a seventh of a [`Pair`] to stream from memory.
pub(crate) type PairSlots = [u32; 2];

/// A ball touching one of the room's walls, or about to: the second most
/// common contact in a crowded room, so it is kept small; the normal,
/// restitution and friction are the wall's.
#[derive(Clone, Copy, Debug)]
pub(crate) struct WallContact {
    pub ball: u32,
    pub surface: Surface,
    /// Whether the project stage bounces this contact.
    pub bounce: bool,
    /// Distance between the ball and the wall at the start of the step
    /// (negative: overlap).
    pub gap: f64,
    /// The ball's normal velocity before the step (negative: approaching).
    pub approach: f64,
    /// Accumulated normal impulse of the current stage.
    pub impulse: f64,
    /// Normal impulse of the predict stage (> 0: the contact pushed).
    pub pushed: f64,
}

impl WallContact {
    pub fn new(ball: usize, surface: Surface, gap: f64, approach: f64) -> WallContact {
        WallContact {
            ball: ball as u32,
            surface,
            bounce: false,
            gap,
            approach,
            impulse: 0.0,
            pushed: 0.0,
        }
    }

    /// Unit normal from the wall towards the ball.
    pub fn normal(&self) -> DVec3 {
        self.surface.inward_normal()
    }
}

/// A pair as a solver stage iterates on it: only what the iterations read.
/// A crowd's rows are streamed from memory once per iteration, and in a
/// large pile that stream is much of the work.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PairRow {
    i: u32,
    j: u32,
    normal: DVec3,
    /// Effective mass along the normal.
    mass: f64,
    /// The relative normal velocity the stage drives the pair to, at least.
    target: f64,
}

impl PairRow {
    fn new(p: &Pair, inv_mass: &[f64], target: f64) -> PairRow {
        let w = inv_mass[p.i as usize] + inv_mass[p.j as usize];
        PairRow {
            i: p.i,
            j: p.j,
            normal: p.normal,
            mass: if w > 0.0 { 1.0 / w } else { 0.0 },
            target,
        }
    }

    /// Applies `impulse` to the two balls.
    #[inline]
    fn push(&self, velocity: &mut [DVec3], first: usize, inv_mass: &[f64], impulse: f64) {
        let (i, j) = (self.i as usize, self.j as usize);
        velocity[i - first] += self.normal * (impulse * inv_mass[i]);
        velocity[j - first] -= self.normal * (impulse * inv_mass[j]);
    }

    /// One Gauss-Seidel update of the row's accumulated `impulse`, as
    /// [`Bodies::solve_normal`] for two balls. `velocity` holds the slots
    /// from `first` on; `inv_mass` all of them.
    #[inline]
    fn solve(&self, impulse: &mut f64, velocity: &mut [DVec3], first: usize, inv_mass: &[f64]) {
        let (i, j) = (self.i as usize, self.j as usize);
        let vn = (velocity[i - first] - velocity[j - first]).dot(self.normal);
        let delta = accumulate(impulse, self.mass, vn, self.target);
        // Applied even when zero: whether it is cannot be foreseen, and a
        // branch that guesses wrong costs more than the arithmetic.
        self.push(velocity, first, inv_mass, delta);
    }
}

/// The rows of one band, and the impulse each has accumulated: apart, so
/// that the rows are only read and their memory never written back.
#[derive(Clone, Debug, Default)]
struct RowBand {
    rows: Vec<PairRow>,
    impulses: Vec<f64>,
    /// The impulses the predict stage ended with, one per pair of the band,
    /// kept for the recording as the step ends.
    predicted: Vec<f64>,
    /// Where the pairs have friction, what each row's friction has
    /// accumulated (see [`pair_friction`]), else none; and where they have
    /// rolling resistance, each row's rolling row, else none.
    friction_impulses: Vec<FrictionImpulse>,
    rolling: Vec<RollingRow>,
    /// The friction impulses the predict stage ended with, kept as
    /// `predicted`.
    friction_predicted: Vec<FrictionImpulse>,
    /// Both stages' friction impulses per pair, gathered for the recording.
    friction_recorded: Vec<StageFriction>,
}

/// How a stage starts a pair's row: the relative normal velocity it drives
/// the pair to, at least, the normal impulse it starts from, and, if the
/// stage solves friction, the friction impulses it starts from.
pub(crate) struct RowStart {
    pub target: f64,
    pub impulse: f64,
    pub friction: Option<FrictionImpulse>,
}

/// The Gauss-Seidel update of every normal contact: the impulse that drives
/// the relative normal velocity `vn` to at least `target`, added to the
/// contact's `impulse` so far and kept non-negative (contacts only push).
/// Returns the change, which the caller applies to the bodies.
#[inline]
fn accumulate(impulse: &mut f64, mass: f64, vn: f64, target: f64) -> f64 {
    let total = (*impulse + mass * (target - vn)).max(0.0);
    let delta = total - *impulse;
    *impulse = total;
    delta
}

/// All contacts of a step: ball pairs in bands, balls against walls, and
/// every contact with a tumbler.
///
/// Band `z` holds the pairs found from the cells of grid layer `z` (see
/// [`crate::broadphase::Grid::layer_slots`]): they join balls of layers `z`
/// and `z + 1`, the slots `layers[z]..layers[z + 2]`.
#[derive(Clone, Debug, Default)]
pub(crate) struct Contacts {
    pub bands: Vec<Vec<Pair>>,
    /// Per band, the slots of its pairs, in the same order.
    pub pair_slots: Vec<Vec<PairSlots>>,
    /// First slot of each grid layer, and one past the last slot.
    pub layers: Vec<usize>,
    /// Pairs in all bands, counted once they are filled.
    pair_count: usize,
    /// Balls against walls, in slot order.
    pub walls: Vec<WallContact>,
    /// Every contact with a tumbler: of a ball, another tumbler or a wall.
    pub tumbler_contacts: Vec<Contact>,
    /// Per band, the pairs a solver stage iterates on (see [`PairRow`]).
    rows: Vec<RowBand>,
    /// The ball-wall contacts a solver stage iterates on (see [`wall_rows`]).
    wall_rows: WallRows,
    /// Per band, the pairs picked by [`Contacts::copy_pairs_where`].
    picked: Vec<Vec<Pair>>,
    /// What the pairs' friction rows read of each ball (see [`Levers`]).
    levers: Levers,
}

impl Contacts {
    /// Ready for `layers` grid layers: every band emptied, storage kept.
    pub fn reset(&mut self, layers: usize) {
        self.bands.resize_with(layers, Vec::new);
        self.bands.iter_mut().for_each(Vec::clear);
        self.pair_slots.resize_with(layers, Vec::new);
        self.pair_slots.iter_mut().for_each(Vec::clear);
        self.pair_count = 0;
        self.walls.clear();
        self.tumbler_contacts.clear();
    }

    /// Counts the pairs once the bands are filled.
    pub fn count_pairs(&mut self) {
        self.pair_count = self.bands.iter().map(Vec::len).sum();
        debug_assert_eq!(
            self.pair_count,
            self.pair_slots.iter().map(Vec::len).sum::<usize>(),
            "a pair without its slots"
        );
    }

    pub fn pair_count(&self) -> usize {
        self.pair_count
    }

    pub fn pairs(&self) -> impl Iterator<Item = &Pair> {
        self.bands.iter().flatten()
    }

    /// Fills `into` with the pairs that `choose` picks, in band order: a
    /// search through every pair, on all threads, for the few that need
    /// more than the solver gives them. Each band picks into storage of its
    /// own, kept between steps, so that the search allocates nothing.
    pub fn copy_pairs_where<F>(&mut self, choose: F, into: &mut Vec<Pair>)
    where
        F: Fn(&Pair) -> bool + Sync,
    {
        into.clear();
        if self.pair_count() < PARALLEL_PAIRS {
            into.extend(self.pairs().filter(|p| choose(p)).copied());
            return;
        }
        self.picked.resize_with(self.bands.len(), Vec::new);
        let pick = |(band, picked): (&Vec<Pair>, &mut Vec<Pair>)| {
            picked.clear();
            picked.extend(band.iter().filter(|p| choose(p)).copied());
        };
        self.bands.par_iter().zip(&mut self.picked).for_each(pick);
        for picked in &self.picked[..self.bands.len()] {
            into.extend_from_slice(picked);
        }
    }

    /// Calls `solve(contact, bodies)` for every contact with a tumbler.
    fn sweep_tumblers<G>(&mut self, bodies: &mut Bodies, mut solve: G)
    where
        G: FnMut(&mut Contact, &mut Bodies),
    {
        for c in &mut self.tumbler_contacts {
            solve(c, bodies);
        }
    }

    /// One sweep of `solve(pair, slots, first)` over every pair, on a
    /// per-slot quantity such as the balls' crowds (see [`sweep_bands`]).
    pub fn sweep_pairs<S, F>(&mut self, slots: &mut [S], solve: &F)
    where
        S: Send,
        F: Fn(&Pair, &mut [S], usize) + Sync,
    {
        let band = |band: &mut Vec<Pair>, slots: &mut [S], first: usize| {
            band.iter().for_each(|p| solve(p, slots, first));
        };
        sweep_bands(&mut self.bands, &self.layers, slots, &band);
    }

    /// As [`Contacts::sweep_pairs`] for a sweep that needs only each
    /// pair's two slots, such as one over the balls' positions.
    pub fn sweep_pair_slots<S, F>(&mut self, slots: &mut [S], solve: &F)
    where
        S: Send,
        F: Fn(PairSlots, &mut [S], usize) + Sync,
    {
        let band = |band: &mut Vec<PairSlots>, slots: &mut [S], first: usize| {
            band.iter().for_each(|&p| solve(p, slots, first));
        };
        sweep_bands(&mut self.pair_slots, &self.layers, slots, &band);
    }

    /// Fills the rows from the pairs that `row` chooses, band by band and in
    /// order, with the start it gives them (applied by
    /// [`Contacts::start_rows`]); a pair given a friction start gets
    /// friction rows of `material`.
    fn build_rows<F>(&mut self, balls: &Balls, material: PairMaterial, row: F)
    where
        F: Fn(&mut Pair) -> Option<RowStart> + Sync,
    {
        self.rows.resize_with(self.bands.len(), RowBand::default);
        if material.any() {
            self.levers.update(balls, material);
        }
        let inv_mass = &balls.inv_mass;
        let rolls = material.rolling_resistance > 0.0;
        let build = |(band, rows): (&mut Vec<Pair>, &mut RowBand)| {
            rows.rows.clear();
            rows.impulses.clear();
            rows.friction_impulses.clear();
            rows.rolling.clear();
            for p in band {
                let Some(start) = row(p) else {
                    continue;
                };
                if let Some(kept) = start.friction {
                    let (i, j) = (p.i as usize, p.j as usize);
                    let rolling = rolls.then(|| RollingRow::new(i, j, balls, material));
                    rows.friction_impulses.push(FrictionImpulse::starting(
                        kept,
                        p.normal,
                        start.impulse,
                        material.friction,
                        rolling.as_ref(),
                    ));
                    rows.rolling.extend(rolling);
                }
                rows.rows.push(PairRow::new(p, inv_mass, start.target));
                rows.impulses.push(start.impulse);
            }
            debug_assert!(
                rows.friction_impulses.is_empty()
                    || rows.friction_impulses.len() == rows.rows.len()
            );
        };
        if self.pair_count() >= PARALLEL_PAIRS {
            self.bands
                .par_iter_mut()
                .zip(&mut self.rows)
                .for_each(build);
        } else {
            self.bands.iter_mut().zip(&mut self.rows).for_each(build);
        }
    }

    /// Whether any band's rows have friction rows.
    fn rows_have_friction(&self) -> bool {
        self.rows
            .iter()
            .any(|band| !band.friction_impulses.is_empty())
    }

    /// Applies the rows' starting impulses to the balls.
    fn start_rows(&mut self, balls: &mut Balls) {
        let inv_mass = &balls.inv_mass;
        if self.rows_have_friction() {
            let build = BallBuild::new(inv_mass, &balls.radius, &self.levers);
            let start = |band: &mut RowBand, velocity: &mut [DVec3], spin: &mut [DVec3], first| {
                let mut motion = Motion {
                    velocity,
                    spin,
                    first,
                    build,
                };
                for (k, (r, &impulse)) in band.rows.iter().zip(&band.impulses).enumerate() {
                    if impulse > 0.0 {
                        r.push(motion.velocity, first, inv_mass, impulse);
                        let rolling = band.rolling.get(k);
                        motion.push(r, &band.friction_impulses[k], rolling);
                    }
                }
            };
            let slots = (&mut balls.velocity[..], &mut balls.spin[..]);
            sweep_bands_of_two(&mut self.rows, &self.layers, slots, &start);
            return;
        }
        let start = |band: &mut RowBand, velocity: &mut [DVec3], first: usize| {
            for (r, &impulse) in band.rows.iter().zip(&band.impulses) {
                if impulse > 0.0 {
                    r.push(velocity, first, inv_mass, impulse);
                }
            }
        };
        sweep_bands(&mut self.rows, &self.layers, &mut balls.velocity, &start);
    }

    /// One Gauss-Seidel sweep over the rows (see [`sweep_bands`]).
    /// The rows' friction rows are solved too if `friction`.
    fn sweep_rows(&mut self, balls: &mut Balls, friction: bool) {
        let inv_mass = &balls.inv_mass;
        if friction && self.rows_have_friction() {
            let build = BallBuild::new(inv_mass, &balls.radius, &self.levers);
            let solve = |band: &mut RowBand, velocity: &mut [DVec3], spin: &mut [DVec3], first| {
                let RowBand {
                    rows,
                    impulses,
                    friction_impulses,
                    rolling,
                    ..
                } = band;
                let mut motion = Motion {
                    velocity,
                    spin,
                    first,
                    build,
                };
                in_four_streams(
                    rows.len(),
                    #[inline(always)]
                    |k| {
                        let r = &rows[k];
                        r.solve(&mut impulses[k], motion.velocity, first, inv_mass);
                        motion.solve(r, impulses[k], &mut friction_impulses[k], rolling.get(k));
                    },
                );
            };
            let slots = (&mut balls.velocity[..], &mut balls.spin[..]);
            sweep_bands_of_two(&mut self.rows, &self.layers, slots, &solve);
            return;
        }
        let solve = |band: &mut RowBand, velocity: &mut [DVec3], first: usize| {
            let (rows, impulses) = (&band.rows, &mut band.impulses[..]);
            // Inlined by force: left to the compiler, a change elsewhere in
            // the crate may make each row a call, a fifth slower a sweep.
            in_four_streams(
                rows.len(),
                #[inline(always)]
                |k| rows[k].solve(&mut impulses[k], velocity, first, inv_mass),
            );
        };
        sweep_bands(&mut self.rows, &self.layers, &mut balls.velocity, &solve);
    }

    /// Hands each pair its row's impulse, `keep(pair, impulse)`, and keeps
    /// the impulses for [`Contacts::record_row_impulses`]: every pair has a
    /// row in the predict stage.
    fn keep_predicted_impulses<G>(&mut self, keep: G)
    where
        G: Fn(&mut Pair, f64) + Sync,
    {
        let hand = |(band, rows): (&mut Vec<Pair>, &mut RowBand)| {
            debug_assert_eq!(band.len(), rows.impulses.len(), "a pair without a row");
            for (p, &impulse) in band.iter_mut().zip(&rows.impulses) {
                keep(p, impulse);
            }
            std::mem::swap(&mut rows.predicted, &mut rows.impulses);
            std::mem::swap(&mut rows.friction_predicted, &mut rows.friction_impulses);
        };
        if self.pair_count() >= PARALLEL_PAIRS {
            self.bands.par_iter_mut().zip(&mut self.rows).for_each(hand);
        } else {
            self.bands.iter_mut().zip(&mut self.rows).for_each(hand);
        }
    }

    /// Records each pair's impulses of both stages for the next step's
    /// warm start in `record` (begun for this step's slots, with each
    /// slot's ball number): the predict stage's kept by
    /// [`Contacts::keep_predicted_impulses`], and the project stage's from
    /// the rows, which only the pairs that pushed have.
    fn record_row_impulses(&mut self, record: (&mut WarmStart, &[u32])) {
        let (warm, ids) = record;
        let friction = self
            .rows
            .iter()
            .any(|band| !band.friction_predicted.is_empty());
        if friction {
            // The project stage's, which only the pairs that pushed have.
            let gather = |(band, rows): (&Vec<Pair>, &mut RowBand)| {
                let RowBand {
                    friction_impulses,
                    friction_predicted,
                    friction_recorded,
                    ..
                } = rows;
                let mut project = friction_impulses.iter();
                let both = band.iter().zip(friction_predicted.iter());
                friction_recorded.clear();
                friction_recorded.extend(
                    both.map(|(p, &predicted)| [predicted, next_impulse(p.pushed, &mut project)]),
                );
            };
            if self.pair_count() >= PARALLEL_PAIRS {
                self.bands.par_iter().zip(&mut self.rows).for_each(gather);
            } else {
                self.bands.iter().zip(&mut self.rows).for_each(gather);
            }
        }
        let rows = &self.rows;
        let hand = |z: usize, band: &mut Vec<Pair>, part: &mut WarmPart| {
            let mut project = rows[z].impulses.iter();
            let impulses = band
                .iter()
                .zip(&rows[z].predicted)
                .map(move |(p, &predicted)| [predicted, next_impulse(p.pushed, &mut project)]);
            part.record_pairs(band, impulses, &rows[z].friction_recorded, ids);
        };
        let parallel = self.pair_count() >= PARALLEL_PAIRS;
        let part = warm.recorder(friction);
        by_band_with_own_part(&mut self.bands, 0, &self.layers, part, parallel, &hand);
    }
}

/// The impulse of a band's next pair: its row's, the next of `rows`, if
/// it has one.
fn next_impulse<T: Copy + Default>(has_row: bool, rows: &mut std::slice::Iter<T>) -> T {
    if has_row {
        rows.next().copied().unwrap_or_default()
    } else {
        T::default()
    }
}

/// Mutable views of everything a contact can push.
pub(crate) struct Bodies<'a> {
    pub balls: &'a mut Balls,
    pub tumblers: &'a mut [Tumbler],
    pub shape: &'a TumblerShape,
    /// Per tumbler: inverse inertia about its floor contact (world axes).
    pub contact_inv: &'a [DMat3],
    /// Between a tumbler's round bottom and the floor.
    pub floor_friction: f64,
    /// What every ball-wall contact is made of: the room's walls.
    pub wall_restitution: f64,
    pub wall_friction: f64,
}

impl Bodies<'_> {
    fn velocity(&self, body: BodyRef, point: DVec3) -> DVec3 {
        match body {
            BodyRef::Ball(i) => self.balls.velocity[i],
            BodyRef::Tumbler(t, _) => self.tumblers[t].point_velocity(point),
            BodyRef::Wall(_) => DVec3::ZERO,
        }
    }

    /// Inverse effective mass of `body` at `point` along `n`, and how a
    /// tumbler's velocities respond per unit impulse.
    fn response(&self, body: BodyRef, point: DVec3, n: DVec3) -> (f64, Response) {
        match body {
            BodyRef::Ball(i) => (self.balls.inv_mass[i], Response::default()),
            BodyRef::Tumbler(t, _) => {
                let tumbler = &self.tumblers[t];
                let r = tumbler.impulse_response(
                    self.shape,
                    &self.contact_inv[t],
                    self.floor_friction,
                    point,
                    n,
                );
                let dv =
                    r.center_velocity + r.angular_velocity.cross(point - tumbler.bottom_center());
                (dv.dot(n), r)
            }
            BodyRef::Wall(_) => (0.0, Response::default()),
        }
    }

    fn push(&mut self, body: BodyRef, n: DVec3, response: &Response, impulse: f64) {
        match body {
            BodyRef::Ball(i) => self.balls.velocity[i] += n * (impulse * self.balls.inv_mass[i]),
            BodyRef::Tumbler(t, _) => self.tumblers[t].apply_response(response, impulse),
            BodyRef::Wall(_) => {}
        }
    }

    /// Relative normal velocity of a contact (negative: approaching).
    pub fn normal_velocity(&self, c: &Contact) -> f64 {
        (self.velocity(c.a, c.point) - self.velocity(c.b, c.point)).dot(c.normal)
    }

    /// Computes the effective mass for the bodies' current configuration.
    pub fn prepare(&self, c: &mut Contact) {
        let (wa, sa) = self.response(c.a, c.point, c.normal);
        let (wb, sb) = self.response(c.b, c.point, c.normal);
        c.mass = if wa + wb > 0.0 { 1.0 / (wa + wb) } else { 0.0 };
        c.response_a = sa;
        c.response_b = sb;
        self.prepare_friction(c);
    }

    /// One Gauss-Seidel update: drive the relative normal velocity to at
    /// least `target`, keeping the accumulated impulse non-negative.
    fn solve_normal(&mut self, c: &mut Contact, target: f64) {
        let vn = self.normal_velocity(c);
        let delta = accumulate(&mut c.impulse, c.mass, vn, target);
        if delta != 0.0 {
            self.push(c.a, c.normal, &c.response_a, delta);
            self.push(c.b, c.normal, &c.response_b, -delta);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_contacts_that_crowd_a_room_stay_small() {
        // A pair is streamed from memory several times a step: the project
        // stage's warm start lives in what would be its padding.
        assert_eq!(std::mem::size_of::<Pair>(), 56);
        assert_eq!(std::mem::size_of::<PairRow>(), 48);
        assert_eq!(std::mem::size_of::<WallContact>(), 40);
    }
}
