//! Each slot's neighbours, the balls it has a contact with this step: the
//! only balls an impact on it can set moving within the step.

use super::packed;
use crate::contact::PairSlots;

/// Below this many pairs, a run of bands lists its neighbours on one thread.
const LIST_ALONE: usize = 16_384;

/// Per slot, the other slots of its pairs: `of(i)`.
#[derive(Debug, Default)]
pub(super) struct Neighbours {
    /// Where each slot's neighbours begin, and one past the last's end.
    first: Vec<u32>,
    neighbours: Vec<u32>,
    /// Where the next neighbour of each slot goes while they are listed.
    cursor: Vec<u32>,
}

impl Neighbours {
    /// Lists each slot's neighbours from the contacts' pairs, by counting
    /// sort: in slot order, whatever the threads found them in. `partners`
    /// holds how many each slot has, counted while the pairs were found;
    /// `layers` the first slot of each grid layer (see
    /// [`crate::contact::Contacts`]). A slot packed in a crowd takes part in
    /// no impact, and gets none listed (its count may have saturated).
    pub(super) fn list(
        &mut self,
        pair_slots: &[Vec<PairSlots>],
        layers: &[usize],
        partners: &[u8],
    ) {
        let slots = partners.len();
        let first = &mut self.first;
        first.clear();
        first.push(0);
        first.extend((0..slots).map(|k| {
            if packed(partners, k) {
                0
            } else {
                u32::from(partners[k])
            }
        }));
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
            partners,
        };
        bands.scatter(0..pair_slots.len(), &mut self.cursor, &mut self.neighbours);
    }

    /// The neighbours of slot `i` (none listed if it is packed).
    pub(super) fn of(&self, i: usize) -> &[u32] {
        &self.neighbours[self.first[i] as usize..self.first[i + 1] as usize]
    }
}

/// The pairs' slots band by band, as [`Neighbours::list`] scatters them
/// into each slot's neighbours.
struct Bands<'a> {
    pair_slots: &'a [Vec<PairSlots>],
    layers: &'a [usize],
    /// Where each slot's neighbours begin.
    first: &'a [u32],
    partners: &'a [u8],
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
            // Split where half the pairs lie before, leaving a band on each
            // side: where the last band holds more than half, it goes alone
            // (a split at the run's end would hand the whole run on again).
            let mut before = 0;
            let mid = (run.start
                + 1
                + self.pair_slots[run.start..run.end - 1]
                    .iter()
                    .take_while(|band| {
                        before += band.len();
                        2 * before < pairs
                    })
                    .count())
            .min(run.end - 1);
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
        let partners = self.partners;
        let mut put = |a: u32, b: u32| {
            if packed(partners, a as usize) {
                return;
            }
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
