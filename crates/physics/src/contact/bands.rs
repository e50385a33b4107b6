//! Sweeping the ball pairs band by band, the even bands side by side and
//! then the odd ones, so that a sweep is the same on any number of threads.

use super::warm::WarmPart;

use super::{Pair, PairSlots, RowBand};

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
pub(super) fn sweep_bands<B, S, F>(bands: &mut [B], layers: &[usize], velocity: &mut [S], solve: &F)
where
    B: Band,
    S: Send,
    F: Fn(&mut B, &mut [S], usize) + Sync,
{
    // A slice of nothing, as long as the slots, for the second quantity.
    let mut nothing = vec![(); velocity.len()];
    let solve =
        |band: &mut B, velocity: &mut [S], _: &mut [()], first: usize| solve(band, velocity, first);
    sweep_bands_of_two(bands, layers, (velocity, &mut nothing), &solve);
}

/// As [`sweep_bands`] on two per-slot quantities at once, such as the
/// balls' velocities and spins: `solve(pair, velocity, spin, first)`.
pub(super) fn sweep_bands_of_two<B, S, T, F>(
    bands: &mut [B],
    layers: &[usize],
    (velocity, spin): (&mut [S], &mut [T]),
    solve: &F,
) where
    B: Band,
    S: Send,
    T: Send,
    F: Fn(&mut B, &mut [S], &mut [T], usize) + Sync,
{
    let parallel = bands.iter().map(Band::items).sum::<usize>() >= PARALLEL_PAIRS;
    for parity in 0..2 {
        if parity >= bands.len() {
            break;
        }
        let count = (bands.len() - parity).div_ceil(2);
        let first = layers[parity];
        let window = (&mut velocity[first..], &mut spin[first..]);
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
fn sweep_alternate<B, S, T, F>(
    bands: &mut [B],
    layers: &[usize],
    (velocity, spin): (&mut [S], &mut [T]),
    count: usize,
    parallel: bool,
    solve: &F,
) where
    B: Band,
    S: Send,
    T: Send,
    F: Fn(&mut B, &mut [S], &mut [T], usize) + Sync,
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
        let at = layers[split] - layers[0];
        let (left_v, right_v) = velocity.split_at_mut(at);
        let (left_s, right_s) = spin.split_at_mut(at);
        rayon::join(
            || sweep_alternate(left_bands, layers, (left_v, left_s), half, parallel, solve),
            || {
                let right_layers = &layers[split..];
                sweep_alternate(
                    right_bands,
                    right_layers,
                    (right_v, right_s),
                    count - half,
                    parallel,
                    solve,
                )
            },
        );
        return;
    }
    for k in 0..count {
        solve(&mut bands[2 * k], velocity, spin, layers[0]);
    }
}

/// What [`sweep_bands`] sweeps: bands of items, each a contact between two
/// balls, split between threads by their counts.
pub(super) trait Band: Send {
    fn items(&self) -> usize;
}

impl Band for Vec<Pair> {
    fn items(&self) -> usize {
        self.len()
    }
}

impl Band for Vec<PairSlots> {
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
#[inline(always)]
pub(super) fn in_four_streams<F: FnMut(usize)>(count: usize, mut visit: F) {
    let quarter = count / 4;
    for k in 0..quarter {
        visit(k);
        visit(k + quarter);
        visit(k + 2 * quarter);
        visit(k + 3 * quarter);
    }
    (4 * quarter..count).for_each(visit);
}

/// Calls `f(z, band, part)` for the bands `bands`, numbered from
/// `first_band` on, side by side: `part` is the part of a warm start's
/// recording that band `z` writes (see [`WarmPart`]). A band's pairs are
/// kept by slots of its own grid layer (see [`super::warm::pair_owner`]),
/// so no two bands write one place.
pub(super) fn by_band_with_own_part<F>(
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
