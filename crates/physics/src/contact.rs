//! Contacts and the sequential-impulse solver that resolves them.
//!
//! A contact joins a ball or tumbler (`a`) to a ball, tumbler or wall (`b`).
//! The two kinds that crowd a room, ball against ball ([`Pair`]) and ball
//! against wall ([`WallContact`]), have small types of their own, solved
//! as rows that hold only what an iteration reads ([`PairRow`], [`WallRow`]).
//! The solver runs in two stages per step:
//!
//! 1. **predict**, on the velocities that will carry the bodies through the
//!    step: no contact may close more than its gap (speculative contacts, so
//!    nothing tunnels into anything), and touching contacts may not approach;
//! 2. **project**, after the bodies have moved: contacts that pushed in stage 1
//!    end with the bounce their restitution asks for (measured from the
//!    approach speed before the step), or at rest.
//!
//! Only lone impacts bounce (see [`Crowd`]); contacts with a tumbler bounce
//! in stage 1 already (see [`solve_predict`]). Every other impulse stops an
//! approach and nothing more, so no stage can add energy.

use crate::balls::{Balls, sphere_inertia};
use crate::room::Surface;
use crate::tumbler::{Response, Tumbler, TumblerShape};
use crate::warm::{Held, WarmPart, WarmStart};
use glam::{DMat3, DVec3};
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};

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

/// Below this many ball pairs a stage runs on one thread: handing work to
/// other threads costs more than it saves. The result is the same either way.
pub(crate) const PARALLEL_PAIRS: usize = 4096;

/// One Gauss-Seidel sweep over every band of pairs, `solve(pair, velocity,
/// first)` for each, in an order fixed by the bands alone.
///
/// Band `z` moves only the balls of grid layers `z` and `z + 1`, so bands two
/// apart share no ball: the even bands are swept side by side, then the odd
/// ones. Each band's own pairs are solved in order, so the result is
/// bit-identical on any number of threads.
fn sweep_bands<B, S, F>(bands: &mut [B], layers: &[usize], velocity: &mut [S], solve: &F)
where
    B: Band,
    S: Send,
    F: Fn(&mut B, &mut [S], usize) + Sync,
{
    let parallel = bands.iter().map(Band::items).sum::<usize>() >= PARALLEL_PAIRS;
    for parity in 0..2 {
        if parity >= bands.len() {
            break;
        }
        let count = (bands.len() - parity).div_ceil(2);
        let first = layers[parity];
        let window = &mut velocity[first..];
        sweep_alternate(
            &mut bands[parity..],
            &layers[parity..],
            window,
            count,
            parallel,
            solve,
        );
    }
}

/// Sweeps `count` bands: `bands[0]`, `bands[2]`, ..., whose balls start at
/// slot `layers[0]` (the first slot of `velocity`), splitting the work in
/// halves across threads.
fn sweep_alternate<B, S, F>(
    bands: &mut [B],
    layers: &[usize],
    velocity: &mut [S],
    count: usize,
    parallel: bool,
    solve: &F,
) where
    B: Band,
    S: Send,
    F: Fn(&mut B, &mut [S], usize) + Sync,
{
    if count >= 2 && parallel {
        // Split where the pairs, not the bands, are halved: piles fill some
        // layers much more than others.
        let pairs = |k: usize| bands[2 * k].items();
        let total: usize = (0..count).map(pairs).sum();
        let mut half = 0;
        let mut left = 0;
        while half + 1 < count && 2 * (left + pairs(half)) <= total {
            left += pairs(half);
            half += 1;
        }
        let half = half.max(1);
        let split = 2 * half;
        let (left_bands, right_bands) = bands.split_at_mut(split);
        let (left_v, right_v) = velocity.split_at_mut(layers[split] - layers[0]);
        rayon::join(
            || sweep_alternate(left_bands, layers, left_v, half, parallel, solve),
            || {
                let right_layers = &layers[split..];
                sweep_alternate(
                    right_bands,
                    right_layers,
                    right_v,
                    count - half,
                    parallel,
                    solve,
                )
            },
        );
        return;
    }
    for k in 0..count {
        solve(&mut bands[2 * k], velocity, layers[0]);
    }
}

/// What [`sweep_bands`] sweeps: bands of items, each a contact between two
/// balls, split between threads by their counts.
trait Band: Send {
    fn items(&self) -> usize;
}

impl Band for Vec<Pair> {
    fn items(&self) -> usize {
        self.len()
    }
}

impl Band for RowBand {
    fn items(&self) -> usize {
        self.rows.len()
    }
}

/// Calls `visit` on the items `0..count` of a band, its four quarters taken
/// in turn. Items next to each other in a band mostly share a ball, and
/// each would wait for the last one's write to it; the quarters lie apart
/// in space, so the processor works on four at once.
#[inline]
fn in_four_streams<F: FnMut(usize)>(count: usize, mut visit: F) {
    let quarter = count / 4;
    for k in 0..quarter {
        visit(k);
        visit(k + quarter);
        visit(k + 2 * quarter);
        visit(k + 3 * quarter);
    }
    (4 * quarter..count).for_each(visit);
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
    /// First slot of each grid layer, and one past the last slot.
    pub layers: Vec<usize>,
    /// Pairs in all bands, counted once they are filled.
    pair_count: usize,
    /// Balls against walls, in slot order.
    pub walls: Vec<WallContact>,
    /// Every other contact: each involves a tumbler.
    pub others: Vec<Contact>,
    /// Per band, the pairs a solver stage iterates on (see [`PairRow`]).
    rows: Vec<RowBand>,
    /// The ball-wall contacts a solver stage iterates on (see [`WallRow`]).
    wall_rows: WallRows,
    /// Per band, the pairs picked by [`Contacts::copy_pairs_where`].
    picked: Vec<Vec<Pair>>,
}

impl Contacts {
    /// Ready for `layers` grid layers: every band emptied, storage kept.
    pub fn reset(&mut self, layers: usize) {
        self.bands.resize_with(layers, Vec::new);
        self.bands.iter_mut().for_each(Vec::clear);
        self.pair_count = 0;
        self.walls.clear();
        self.others.clear();
    }

    /// Counts the pairs once the bands are filled.
    pub fn count_pairs(&mut self) {
        self.pair_count = self.bands.iter().map(Vec::len).sum();
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

    /// Fills the wall rows from the ball-wall contacts that `row` chooses,
    /// in order, with the target and friction coefficient it gives them;
    /// each starts from its contact's impulse, applied already.
    fn start_wall_rows<F>(&mut self, balls: &Balls, row: F)
    where
        F: Fn(&WallContact) -> Option<(f64, f64)> + Sync,
    {
        let walls = &self.walls;
        let build = |c: &WallContact| {
            let (target, friction) = row(c)?;
            let row = WallRow::new(c.ball as usize, c.surface, balls, target, friction);
            Some((row, WallImpulse::starting(c.impulse)))
        };
        // On one thread: a parallel filter gathers its pieces in lists,
        // which costs more than the rows.
        let WallRows {
            rows,
            impulses,
            frames,
        } = &mut self.wall_rows;
        *frames = Surface::ALL.map(WallFrame::of);
        let mut built = (std::mem::take(rows), std::mem::take(impulses));
        built.0.clear();
        built.1.clear();
        built.extend(walls.iter().filter_map(build));
        (*rows, *impulses) = built;
    }

    /// One Gauss-Seidel sweep over the wall rows.
    ///
    /// A ball-wall contact moves its ball alone, so different balls' rows
    /// are solved side by side; each ball's own in their order, which keeps
    /// the result the same on any number of threads.
    fn sweep_wall_rows(&mut self, balls: &mut Balls) {
        let parallel =
            self.wall_rows.rows.len() >= PARALLEL_BALL_WALLS && self.pair_count() >= PARALLEL_PAIRS;
        let WallRows {
            rows,
            impulses,
            frames,
        } = &mut self.wall_rows;
        let view = BallSlices {
            velocity: &mut balls.velocity,
            spin: &mut balls.spin,
            first: 0,
        };
        sweep_wall_rows(rows, impulses, view, frames, parallel);
    }

    /// Hands each ball-wall contact its row's normal impulse, 0 for the
    /// contacts without a row; `chosen` tells them as in
    /// [`Contacts::start_wall_rows`].
    fn keep_wall_impulses<F>(&mut self, chosen: F)
    where
        F: Fn(&WallContact) -> bool,
    {
        let mut impulses = self.wall_rows.impulses.iter();
        for c in &mut self.walls {
            c.impulse = if chosen(c) {
                impulses.next().map_or(0.0, |k| k.normal)
            } else {
                0.0
            };
        }
    }

    /// Calls `solve(contact, bodies)` for every contact with a tumbler.
    fn sweep_tumblers<G>(&mut self, bodies: &mut Bodies, mut solve: G)
    where
        G: FnMut(&mut Contact, &mut Bodies),
    {
        for c in &mut self.others {
            solve(c, bodies);
        }
    }

    /// One sweep of `solve(pair, slots, first)` over every pair, on a
    /// per-slot quantity such as the balls' positions (see
    /// [`sweep_bands`]).
    pub fn sweep_slots<S, F>(&mut self, slots: &mut [S], solve: &F)
    where
        S: Send,
        F: Fn(&mut Pair, &mut [S], usize) + Sync,
    {
        let band = |band: &mut Vec<Pair>, slots: &mut [S], first: usize| {
            band.iter_mut().for_each(|p| solve(p, slots, first));
        };
        sweep_bands(&mut self.bands, &self.layers, slots, &band);
    }

    /// Fills the rows from the pairs that `row` chooses, band by band and in
    /// order, with the target and starting impulse it gives them, and
    /// applies the starting impulses to the balls.
    fn start_rows<F>(&mut self, balls: &mut Balls, row: F)
    where
        F: Fn(&mut Pair) -> Option<(f64, f64)> + Sync,
    {
        self.rows.resize_with(self.bands.len(), RowBand::default);
        let inv_mass = &balls.inv_mass;
        let build = |(band, rows): (&mut Vec<Pair>, &mut RowBand)| {
            rows.rows.clear();
            rows.impulses.clear();
            for p in band {
                if let Some((target, impulse)) = row(p) {
                    rows.rows.push(PairRow::new(p, inv_mass, target));
                    rows.impulses.push(impulse);
                }
            }
        };
        if self.pair_count() >= PARALLEL_PAIRS {
            self.bands
                .par_iter_mut()
                .zip(&mut self.rows)
                .for_each(build);
        } else {
            self.bands.iter_mut().zip(&mut self.rows).for_each(build);
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
    fn sweep_rows(&mut self, balls: &mut Balls) {
        let inv_mass = &balls.inv_mass;
        let solve = |band: &mut RowBand, velocity: &mut [DVec3], first: usize| {
            let (rows, impulses) = (&band.rows, &mut band.impulses[..]);
            in_four_streams(rows.len(), |k| {
                rows[k].solve(&mut impulses[k], velocity, first, inv_mass)
            });
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
        let rows = &self.rows;
        let hand = |z: usize, band: &mut Vec<Pair>, part: &mut WarmPart| {
            let mut project = rows[z].impulses.iter();
            let impulses = band
                .iter()
                .zip(&rows[z].predicted)
                .map(move |(p, &predicted)| [predicted, next_impulse(p.pushed, &mut project)]);
            part.record_pairs(band, impulses, ids);
        };
        let parallel = self.pair_count() >= PARALLEL_PAIRS;
        let part = warm.recorder();
        by_band_with_own_part(&mut self.bands, 0, &self.layers, part, parallel, &hand);
    }
}

/// The impulse of a band's next pair: its row's, the next of `rows`, if
/// it has one.
fn next_impulse(has_row: bool, rows: &mut std::slice::Iter<f64>) -> f64 {
    if has_row {
        rows.next().copied().unwrap_or(0.0)
    } else {
        0.0
    }
}

/// Calls `f(z, band, part)` for the bands `bands`, numbered from
/// `first_band` on, side by side: `part` is the part of a warm start's
/// recording that band `z` writes (see [`WarmPart`]). A band's pairs are
/// kept by slots of its own grid layer (see [`crate::warm::pair_owner`]),
/// so no two bands write one place.
fn by_band_with_own_part<F>(
    bands: &mut [Vec<Pair>],
    first_band: usize,
    layers: &[usize],
    part: WarmPart,
    parallel: bool,
    f: &F,
) where
    F: Fn(usize, &mut Vec<Pair>, &mut WarmPart) + Sync,
{
    if bands.len() >= 2 && parallel {
        let half = bands.len() / 2;
        let pairs: usize = bands[..half].iter().map(Vec::len).sum();
        let (left, right) = bands.split_at_mut(half);
        let pair_half = part.first_pair() + pairs;
        let (left_part, right_part) = part.split(layers[half], pair_half);
        rayon::join(
            || by_band_with_own_part(left, first_band, layers, left_part, parallel, f),
            || {
                let right_layers = &layers[half..];
                let right_first = first_band + half;
                by_band_with_own_part(right, right_first, right_layers, right_part, parallel, f)
            },
        );
        return;
    }
    let mut rest = part;
    for (k, band) in bands.iter_mut().enumerate() {
        let pair_end = rest.first_pair() + band.len();
        let (mut own, later) = rest.split(layers[k + 1], pair_end);
        f(first_band + k, band, &mut own);
        rest = later;
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

/// A ball-wall contact as a solver stage iterates on it: as [`PairRow`],
/// only what the iterations read, with its ball's build worked out once
/// (divisions are slow).
#[derive(Clone, Copy, Debug)]
struct WallRow {
    slot: u32,
    surface: Surface,
    /// The ball's mass and its inverse: the wall does not move.
    mass: f64,
    inv_mass: f64,
    /// The normal velocity the stage drives the ball to, at least.
    target: f64,
    /// Coulomb friction coefficient (0: the stage solves no friction).
    friction: f64,
    radius: f64,
    inv_inertia: f64,
    /// Mass along a tangent at the contact point: 2m/7 for a solid sphere.
    tangent_mass: f64,
}

/// A wall row's accumulated impulses: along the normal and the two tangents.
#[derive(Clone, Copy, Debug, Default)]
struct WallImpulse {
    normal: f64,
    friction: [f64; 2],
}

impl WallImpulse {
    fn starting(normal: f64) -> WallImpulse {
        WallImpulse {
            normal,
            friction: [0.0; 2],
        }
    }
}

/// The wall rows of a stage, and the impulses each has accumulated (apart,
/// as in [`RowBand`]).
#[derive(Clone, Debug, Default)]
struct WallRows {
    rows: Vec<WallRow>,
    impulses: Vec<WallImpulse>,
    /// Each surface's frame, by surface index: worked out once a stage.
    frames: [WallFrame; 6],
}

/// A surface's inward normal, the two tangents friction acts along, and
/// the axes about which friction along each turns a ball (normal x tangent).
#[derive(Clone, Copy, Debug, Default)]
struct WallFrame {
    normal: DVec3,
    tangents: [DVec3; 2],
    turns: [DVec3; 2],
}

impl WallFrame {
    fn of(surface: Surface) -> WallFrame {
        let normal = surface.inward_normal();
        let (t1, t2) = normal.any_orthonormal_pair();
        WallFrame {
            normal,
            tangents: [t1, t2],
            turns: [normal.cross(t1), normal.cross(t2)],
        }
    }
}

impl WallRow {
    fn new(slot: usize, surface: Surface, balls: &Balls, target: f64, friction: f64) -> WallRow {
        let (mass, inv_mass, radius) = (balls.mass[slot], balls.inv_mass[slot], balls.radius[slot]);
        let inv_inertia = 1.0 / sphere_inertia(mass, radius);
        WallRow {
            slot: slot as u32,
            surface,
            mass: if inv_mass > 0.0 { 1.0 / inv_mass } else { 0.0 },
            inv_mass,
            target,
            friction,
            radius,
            inv_inertia,
            tangent_mass: 1.0 / (inv_mass + radius * radius * inv_inertia),
        }
    }

    /// One Gauss-Seidel update of the row, as [`Bodies::solve_normal`] for a
    /// ball on a wall, then Coulomb friction at the contact point, so that
    /// a sliding ball starts to roll.
    #[inline]
    fn solve(
        &self,
        impulse: &mut WallImpulse,
        velocity: &mut DVec3,
        spin: &mut DVec3,
        frame: &WallFrame,
    ) {
        let n = frame.normal;
        let delta = accumulate(&mut impulse.normal, self.mass, velocity.dot(n), self.target);
        *velocity += n * (delta * self.inv_mass);
        let limit = self.friction * impulse.normal;
        if limit == 0.0 && impulse.friction == [0.0; 2] {
            // Nothing to hold and nothing held: most speculative contacts.
            return;
        }
        // The contact point lies at -radius n: its slip along t is
        // v.t + (spin x -rn).t = v.t - r spin.(n x t), and an impulse along
        // t there turns the ball about -(n x t).
        let r = self.radius;
        for k in 0..2 {
            let (t, turn) = (frame.tangents[k], frame.turns[k]);
            let held = &mut impulse.friction[k];
            let slip = velocity.dot(t) - r * spin.dot(turn);
            let total = (*held - self.tangent_mass * slip).clamp(-limit, limit);
            let delta = total - *held;
            *held = total;
            *velocity += t * (delta * self.inv_mass);
            *spin -= turn * (r * delta * self.inv_inertia);
        }
    }
}

/// Below this many ball-wall contacts, or [`PARALLEL_PAIRS`] pairs, they are
/// solved on one thread (the crowded pit of the thread test has more).
const PARALLEL_BALL_WALLS: usize = 512;

/// The velocities and spins of the balls from slot `first` on.
struct BallSlices<'a> {
    velocity: &'a mut [DVec3],
    spin: &'a mut [DVec3],
    first: usize,
}

/// Solves wall rows (in slot order) whose balls lie in `balls`, halving the
/// work across threads between two balls.
fn sweep_wall_rows(
    rows: &[WallRow],
    impulses: &mut [WallImpulse],
    balls: BallSlices,
    frames: &[WallFrame; 6],
    parallel: bool,
) {
    if parallel && rows.len() >= PARALLEL_BALL_WALLS / 2 {
        let mut half = rows.len() / 2;
        while half < rows.len() && rows[half].slot == rows[half - 1].slot {
            half += 1;
        }
        if let Some(split) = rows.get(half).map(|r| r.slot as usize) {
            let (left, right) = rows.split_at(half);
            let (left_impulses, right_impulses) = impulses.split_at_mut(half);
            let (lv, rv) = balls.velocity.split_at_mut(split - balls.first);
            let (ls, rs) = balls.spin.split_at_mut(split - balls.first);
            let (left_balls, right_balls) = (
                BallSlices {
                    velocity: lv,
                    spin: ls,
                    first: balls.first,
                },
                BallSlices {
                    velocity: rv,
                    spin: rs,
                    first: split,
                },
            );
            rayon::join(
                || sweep_wall_rows(left, left_impulses, left_balls, frames, parallel),
                || sweep_wall_rows(right, right_impulses, right_balls, frames, parallel),
            );
            return;
        }
    }
    for (row, impulse) in rows.iter().zip(impulses) {
        let k = row.slot as usize - balls.first;
        let frame = &frames[row.surface.index()];
        row.solve(impulse, &mut balls.velocity[k], &mut balls.spin[k], frame);
    }
}

/// Which contacts act on each body in a stage, so that a lone impact, which
/// may bounce, can be told from a crowded one, which may not.
///
/// Bouncing each of several coupled contacts to the speed its own approach
/// asks for can create energy (think of a ball pressed between two others);
/// stopping them cannot. Two contacts on one ball are coupled unless their
/// normals are perpendicular, so a ball rolling on the floor still bounces
/// off another one sideways. On a tumbler every pair of contacts is coupled.
///
/// The project stage asks only about balls in a fast impact, which are few
/// in a pile: it gathers the contacts of those balls alone (see
/// [`Crowd::will_ask`]).
#[derive(Debug, Default)]
pub(crate) struct Crowd {
    balls: Vec<BallCrowd>,
    tumbler_count: Vec<u8>,
    /// Per ball: whether the project stage may ask about it. Set on any
    /// thread, and read only after the threads have joined.
    asked: Vec<AtomicBool>,
}

/// The contacts on one ball: how many, and the first few, each by the body
/// on its other side (see [`other_side`]) and its normal.
#[derive(Clone, Copy, Debug, Default)]
struct BallCrowd {
    count: u8,
    other: [u32; BallCrowd::KEPT],
    normal: [DVec3; BallCrowd::KEPT],
}

impl BallCrowd {
    /// A ball with more contacts than this is crowded whatever their normals.
    const KEPT: usize = 6;

    fn add(&mut self, other: u32, normal: DVec3) {
        let n = self.count as usize;
        if n < BallCrowd::KEPT {
            self.other[n] = other;
            self.normal[n] = normal;
        }
        self.count = self.count.saturating_add(1);
    }

    /// Whether the contact with `other`, along `normal`, is the only one
    /// coupled to this ball.
    fn lone(&self, other: u32, normal: DVec3) -> bool {
        let n = self.count as usize;
        n <= BallCrowd::KEPT
            && (0..n).all(|k| self.other[k] == other || self.normal[k].dot(normal).abs() < 1e-9)
    }
}

/// A ball's contacts told apart by the body on their other side: another
/// ball by its slot, a wall, or one sphere of a tumbler.
fn other_side(body: BodyRef) -> u32 {
    const WALL: u32 = 1 << 31;
    const TUMBLER: u32 = 3 << 30;
    match body {
        BodyRef::Ball(j) => j as u32,
        BodyRef::Wall(s) => WALL | s.index() as u32,
        BodyRef::Tumbler(t, sphere) => TUMBLER | ((t as u32) << 4) | sphere as u32,
    }
}

impl Crowd {
    /// From this many balls on, a reset runs on all threads.
    const PARALLEL_RESET: usize = 16384;

    /// Forgets which balls the project stage will ask about.
    fn forget_asked(&mut self, balls: usize) {
        self.asked.resize_with(balls, AtomicBool::default);
        self.asked.iter_mut().for_each(|a| *a.get_mut() = false);
    }

    /// Notes that the project stage may ask about ball `i`.
    fn will_ask(&self, i: u32) {
        self.asked[i as usize].store(true, Ordering::Relaxed);
    }

    fn asked(&self, i: usize) -> bool {
        self.asked[i].load(Ordering::Relaxed)
    }

    /// Restarts the crowds of every ball, or with `only_asked` of the balls
    /// noted by [`Crowd::will_ask`], and gathers their pairs that `counts`
    /// picks, on all threads: a ball's list is a set, so the order in which
    /// pairs join it does not matter. Restarts the tumblers' counts too.
    /// Balls left out keep a stale crowd.
    fn gather<F>(&mut self, contacts: &mut Contacts, tumblers: usize, only_asked: bool, counts: F)
    where
        F: Fn(&Pair) -> bool + Sync,
    {
        let asked = &self.asked;
        let wanted = |i: usize| !only_asked || asked[i].load(Ordering::Relaxed);
        // Entries past a ball's count are never read: only counts restart.
        // Each count lies on a line of its own, so a crowded room's are
        // restarted on all threads.
        let restart = |(i, b): (usize, &mut BallCrowd)| {
            if wanted(i) {
                b.count = 0;
            }
        };
        self.balls.resize(asked.len(), BallCrowd::default());
        if self.balls.len() >= Crowd::PARALLEL_RESET {
            self.balls.par_iter_mut().enumerate().for_each(restart);
        } else {
            self.balls.iter_mut().enumerate().for_each(restart);
        }
        self.tumbler_count.clear();
        self.tumbler_count.resize(tumblers, 0);
        if only_asked && !asked.iter().any(|a| a.load(Ordering::Relaxed)) {
            return;
        }
        contacts.sweep_slots(&mut self.balls, &|p, balls, first| {
            if counts(p) {
                if wanted(p.i as usize) {
                    balls[p.i as usize - first].add(p.j, p.normal);
                }
                if wanted(p.j as usize) {
                    balls[p.j as usize - first].add(p.i, p.normal);
                }
            }
        });
    }

    fn add(&mut self, c: &Contact) {
        self.add_to(c, false);
    }

    /// As [`Crowd::add`], for the balls noted by [`Crowd::will_ask`].
    fn add_if_asked(&mut self, c: &Contact) {
        self.add_to(c, true);
    }

    fn add_to(&mut self, c: &Contact, asked_only: bool) {
        for (body, other) in [(c.a, c.b), (c.b, c.a)] {
            match body {
                BodyRef::Ball(i) if asked_only && !self.asked(i) => {}
                BodyRef::Ball(i) => self.balls[i].add(other_side(other), c.normal),
                BodyRef::Tumbler(t, _) => {
                    self.tumbler_count[t] = self.tumbler_count[t].saturating_add(1)
                }
                BodyRef::Wall(_) => {}
            }
        }
    }

    fn add_wall(&mut self, c: &WallContact) {
        let wall = other_side(BodyRef::Wall(c.surface));
        self.balls[c.ball as usize].add(wall, c.normal());
    }

    /// Whether wall contact `c` is the only contact coupled to its ball.
    fn lone_wall(&self, c: &WallContact) -> bool {
        debug_assert!(self.asked(c.ball as usize));
        let wall = other_side(BodyRef::Wall(c.surface));
        self.balls[c.ball as usize].lone(wall, c.normal())
    }

    /// Whether pair `p` is the only contact coupled to its two balls.
    fn lone_pair(&self, p: &Pair) -> bool {
        debug_assert!(self.asked(p.i as usize) && self.asked(p.j as usize));
        self.balls[p.i as usize].lone(p.j, p.normal) && self.balls[p.j as usize].lone(p.i, p.normal)
    }

    /// Whether contact `c` is the only one coupled to its bodies.
    fn lone(&self, c: &Contact) -> bool {
        [(c.a, c.b), (c.b, c.a)]
            .into_iter()
            .all(|(body, other)| match body {
                BodyRef::Ball(i) => self.balls[i].lone(other_side(other), c.normal),
                BodyRef::Tumbler(t, _) => self.tumbler_count[t] == 1,
                BodyRef::Wall(_) => true,
            })
    }
}

/// Stage 1: speculative, non-penetrating velocities for the coming step.
///
/// A lone impact on a tumbler due within the step bounces here already, at
/// its full approach speed: a tumbler's response to an impulse changes as it
/// turns, and splitting one impact over two configurations could create
/// energy.
///
/// With `warm` (last step's impulses and each slot's ball number) pairs and
/// ball-wall contacts start from the impulse that held them last step; the
/// impulses they end with are kept for [`solve_project`] to record.
#[allow(clippy::too_many_arguments)]
pub(crate) fn solve_predict(
    bodies: &mut Bodies,
    contacts: &mut Contacts,
    crowd: &mut Crowd,
    iterations: usize,
    dt: f64,
    bounce_threshold: f64,
    warm: Option<(&WarmStart, &[u32])>,
) {
    // Every ball within reach counts against a bounce, touching or not: a
    // ball sent back by a tumbler may meet a neighbour it was leaving, and
    // pressing it would make the bounce pump energy. Other contacts count
    // once they touch within the step.
    let touching =
        |gap: f64, approach: f64, kick: f64| gap + (approach + kick).min(0.0) * dt <= TOUCHING;
    // Only a tumbler's contacts may bounce here, so only they ask the crowd.
    let may_bounce = !contacts.others.is_empty();
    crowd.forget_asked(bodies.balls.len());
    if may_bounce {
        crowd.gather(contacts, bodies.tumblers.len(), false, |_| true);
    }
    for c in contacts.walls.iter_mut() {
        c.impulse = 0.0;
        if may_bounce {
            // Gravity's half step, which the wall does not share.
            let kick = bodies.balls.velocity[c.ball as usize].dot(c.normal()) - c.approach;
            if touching(c.gap, c.approach, kick) {
                crowd.add_wall(c);
            }
        }
    }
    for c in contacts.others.iter_mut() {
        bodies.prepare(c);
        c.impulse = 0.0;
        // Gravity's half step, which the contact's two sides may not share.
        c.kick = bodies.normal_velocity(c) - c.approach;
        if touching(c.gap, c.approach, c.kick) {
            crowd.add(c);
        }
    }
    for c in contacts.others.iter_mut() {
        c.bounce =
            c.approach < -bounce_threshold && c.gap + c.approach * dt <= 0.0 && crowd.lone(c);
    }
    // Pairs never bounce here, so all start warm. One lookup finds the
    // project stage's start too.
    contacts.start_rows(bodies.balls, |p| {
        let target = if p.gap > 0.0 { -p.gap / dt } else { 0.0 };
        let held = warm_pair(warm, p);
        p.project_start = held[Stage::Project as usize];
        Some((target, share(warm, held[Stage::Predict as usize])))
    });
    if let Some((warm, ids)) = warm {
        warm_start_walls(bodies.balls, contacts, warm, ids, Stage::Predict);
    }
    let closing = |gap: f64| if gap > 0.0 { -gap / dt } else { 0.0 };
    let target = |c: &Contact| {
        if c.bounce {
            c.kick - c.restitution * c.approach
        } else {
            closing(c.gap)
        }
    };
    let friction = bodies.wall_friction;
    contacts.start_wall_rows(bodies.balls, |c| Some((closing(c.gap), friction)));
    for _ in 0..iterations {
        contacts.sweep_wall_rows(bodies.balls);
        contacts.sweep_rows(bodies.balls);
        contacts.sweep_tumblers(bodies, |c, bodies| bodies.solve_normal(c, target(c)));
    }
    contacts.keep_wall_impulses(|_| true);
    // The project stage asks about the balls of contacts that pushed
    // against a fast approach: only those may bounce.
    let fast = |pushed: f64, approach: f64| pushed > 0.0 && approach < -bounce_threshold;
    let crowd = &*crowd;
    contacts.keep_predicted_impulses(|p: &mut Pair, impulse: f64| {
        p.pushed = impulse > 0.0;
        if fast(impulse, p.approach) {
            crowd.will_ask(p.i);
            crowd.will_ask(p.j);
        }
    });
    for c in contacts.others.iter_mut() {
        c.pushed = c.impulse;
    }
    for c in contacts.walls.iter_mut() {
        c.pushed = c.impulse;
        if fast(c.pushed, c.approach) {
            crowd.will_ask(c.ball);
        }
    }
}

/// The two solver stages, each warm-started from its own impulses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Stage {
    Predict,
    Project,
}

impl Stage {
    /// Whether the stage solves contact `pushed`/`bounce`; bouncing contacts
    /// start cold, their impulse is of this impact alone.
    fn warm_starts(self, pushed: f64, bounce: bool) -> bool {
        !bounce && (self == Stage::Predict || pushed > 0.0)
    }
}

/// Last step's impulses of pair `p` as kept, if there is a warm start.
fn warm_pair(warm: Option<(&WarmStart, &[u32])>, p: &Pair) -> Held {
    warm.map_or(Held::default(), |(warm, ids)| {
        warm.pair(ids[p.i as usize], ids[p.j as usize])
    })
}

/// The impulse to start from, given one kept (0 without a warm start).
fn share(warm: Option<(&WarmStart, &[u32])>, impulse: f32) -> f64 {
    warm.map_or(0.0, |(warm, _)| warm.share(impulse))
}

/// Starts ball-wall contacts from last step's impulses.
fn warm_start_walls(
    balls: &mut Balls,
    contacts: &mut Contacts,
    warm: &WarmStart,
    ids: &[u32],
    stage: Stage,
) {
    for c in contacts.walls.iter_mut() {
        if !stage.warm_starts(c.pushed, c.bounce) {
            continue;
        }
        let i = c.ball as usize;
        let impulse = warm.share(warm.wall(ids[i], c.surface)[stage as usize]);
        if impulse > 0.0 {
            c.impulse = impulse;
            balls.velocity[i] += c.normal() * (impulse * balls.inv_mass[i]);
        }
    }
}

/// Stage 2: contacts that pushed end bouncing or resting.
///
/// A lone impact between balls, or of a ball on a wall, bounces to the speed
/// its restitution gives the approach measured before the step (so a pair
/// obeys the 1-D formulas exactly); every other contact that pushed ends at
/// rest. A ball that bounced off a wall while moving has spent its approach
/// already: `hit_wall` marks those, and their contacts only stop.
///
/// Warm started from `warm` as the predict stage. The impulses of both
/// stages are recorded into `record` for the next step's warm start.
#[allow(clippy::too_many_arguments)]
pub(crate) fn solve_project(
    bodies: &mut Bodies,
    contacts: &mut Contacts,
    crowd: &mut Crowd,
    iterations: usize,
    bounce_threshold: f64,
    ball_restitution: f64,
    hit_wall: &[bool],
    warm: Option<(&WarmStart, &[u32])>,
    record: (&mut WarmStart, &[u32]),
) {
    crowd.gather(contacts, bodies.tumblers.len(), true, |p| p.pushed);
    for c in contacts.others.iter().filter(|c| c.pushed > 0.0) {
        crowd.add_if_asked(c);
    }
    for c in contacts.walls.iter().filter(|c| c.pushed > 0.0) {
        if crowd.asked(c.ball as usize) {
            crowd.add_wall(c);
        }
    }
    // A tumbler's contacts bounced in the predict stage already.
    for c in contacts.others.iter_mut() {
        c.bounce = false;
        c.impulse = 0.0;
        if c.pushed > 0.0 {
            bodies.prepare(c);
        }
    }
    for c in contacts.walls.iter_mut() {
        c.bounce = c.pushed > 0.0
            && c.approach < -bounce_threshold
            && !hit_wall[c.ball as usize]
            && crowd.lone_wall(c);
        c.impulse = 0.0;
    }
    // Only the pairs that pushed take part.
    // A bouncing pair starts cold: its impulse is of this impact alone.
    let crowd = &*crowd;
    contacts.start_rows(bodies.balls, |p| {
        p.pushed.then(|| {
            let bounce = p.approach < -bounce_threshold
                && !hit_wall[p.i as usize]
                && !hit_wall[p.j as usize]
                && crowd.lone_pair(p);
            if bounce {
                (-ball_restitution * p.approach, 0.0)
            } else {
                (0.0, share(warm, p.project_start))
            }
        })
    });
    if let Some((warm, ids)) = warm {
        warm_start_walls(bodies.balls, contacts, warm, ids, Stage::Project);
    }
    // Friction acted in the predict stage; here contacts only end bouncing
    // or at rest.
    let restitution = bodies.wall_restitution;
    contacts.start_wall_rows(bodies.balls, |c| {
        let target = if c.bounce {
            -restitution * c.approach
        } else {
            0.0
        };
        (c.pushed > 0.0).then_some((target, 0.0))
    });
    for _ in 0..iterations {
        contacts.sweep_wall_rows(bodies.balls);
        contacts.sweep_rows(bodies.balls);
        contacts.sweep_tumblers(bodies, |c, bodies| {
            if c.pushed > 0.0 {
                bodies.solve_normal(c, 0.0);
            }
        });
    }
    let (warm_next, ids) = record;
    contacts.record_row_impulses((&mut *warm_next, ids));
    contacts.keep_wall_impulses(|c| c.pushed > 0.0);
    for c in &contacts.walls {
        warm_next.record_wall(c.ball as usize, c.surface, [c.pushed, c.impulse]);
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
