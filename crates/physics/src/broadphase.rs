//! Uniform grid broadphase for the balls.
//!
//! Rebuilt every step with a counting sort into buffers that are kept between
//! steps, so its cost grows linearly with the ball count and it allocates
//! nothing once warm. Pairs come out in a fixed order (by cell, then index),
//! which keeps the solver deterministic.

use crate::balls::PARALLEL_LIGHT_PASSES;
use glam::{DVec3, Vec4};
use rayon::prelude::*;

#[derive(Clone, Debug, Default)]
pub(crate) struct Grid {
    origin: DVec3,
    cell: f64,
    dims: [usize; 3],
    /// `cell_start[c]..cell_start[c + 1]` indexes `sorted` for cell `c`.
    cell_start: Vec<u32>,
    sorted: Vec<u32>,
    ball_cell: Vec<u32>,
    /// Per ball: its slot in `sorted` (`NO_SLOT` if it is not alive).
    ball_slot: Vec<u32>,
}

impl Grid {
    pub const NO_SLOT: u32 = u32::MAX;
}

/// Cells are never made so small that the grid would dwarf the balls.
const MAX_CELLS: usize = 1 << 22;

impl Grid {
    /// A grid over the box `min..max` with cells of at least `cell` metres.
    pub fn new(min: DVec3, max: DVec3, cell: f64) -> Grid {
        let size = max - min;
        let mut cell = cell.max(1e-6);
        let dims = loop {
            let d = [
                ((size.x / cell).ceil() as usize).max(1),
                ((size.y / cell).ceil() as usize).max(1),
                ((size.z / cell).ceil() as usize).max(1),
            ];
            if d[0] * d[1] * d[2] <= MAX_CELLS {
                break d;
            }
            cell *= 1.25;
        };
        Grid {
            origin: min,
            cell,
            dims,
            cell_start: vec![0; dims[0] * dims[1] * dims[2] + 1],
            sorted: Vec::new(),
            ball_cell: Vec::new(),
            ball_slot: Vec::new(),
        }
    }

    fn coords(&self, p: DVec3) -> [usize; 3] {
        let q = (p - self.origin) / self.cell;
        [
            (q.x.max(0.0) as usize).min(self.dims[0] - 1),
            (q.y.max(0.0) as usize).min(self.dims[1] - 1),
            (q.z.max(0.0) as usize).min(self.dims[2] - 1),
        ]
    }

    fn index(&self, c: [usize; 3]) -> usize {
        (c[2] * self.dims[1] + c[1]) * self.dims[0] + c[0]
    }

    /// Sorts the live balls into cells.
    pub fn rebuild(&mut self, positions: &[DVec3], alive: &[bool]) {
        // Each ball's cell, on all threads for many balls.
        let mut ball_cell = std::mem::take(&mut self.ball_cell);
        ball_cell.clear();
        let cell_of = |(p, &live): (&DVec3, &bool)| {
            if live {
                self.index(self.coords(*p)) as u32
            } else {
                u32::MAX
            }
        };
        if positions.len() >= PARALLEL_LIGHT_PASSES {
            ball_cell.par_extend(positions.par_iter().zip(alive).map(cell_of));
        } else {
            ball_cell.extend(positions.iter().zip(alive).map(cell_of));
        }
        self.ball_cell = ball_cell;
        self.cell_start.fill(0);
        for &c in &self.ball_cell {
            if c != u32::MAX {
                self.cell_start[c as usize + 1] += 1;
            }
        }
        for c in 1..self.cell_start.len() {
            self.cell_start[c] += self.cell_start[c - 1];
        }
        let total = *self.cell_start.last().unwrap_or(&0) as usize;
        self.sorted.clear();
        self.sorted.resize(total, 0);
        // Fill each cell in ball-index order, using the next cell's start as a cursor
        // and restoring it afterwards.
        let n_cells = self.cell_start.len() - 1;
        let mut cursor = std::mem::take(&mut self.cell_start);
        self.ball_slot.clear();
        for (i, &c) in self.ball_cell.iter().enumerate() {
            if c == u32::MAX {
                self.ball_slot.push(Grid::NO_SLOT);
            } else {
                let slot = &mut cursor[c as usize];
                self.sorted[*slot as usize] = i as u32;
                self.ball_slot.push(*slot);
                *slot += 1;
            }
        }
        // cursor[c] now holds the end of cell c, i.e. the start of cell c + 1.
        for c in (1..=n_cells).rev() {
            cursor[c] = cursor[c - 1];
        }
        cursor[0] = 0;
        self.cell_start = cursor;
    }

    /// The live balls in cell order: slot `k` of the sorted order holds ball
    /// `order()[k]`. Cells are contiguous runs of slots.
    pub fn order(&self) -> &[u32] {
        &self.sorted
    }

    /// The cells that hold a ball, each once, by its lowest corner, and
    /// the cells' edge: the sorted balls run cell by cell.
    pub fn occupied_cells(&self) -> (Vec<DVec3>, f64) {
        let mut cells: Vec<u32> = self
            .sorted
            .iter()
            .map(|&b| self.ball_cell[b as usize])
            .collect();
        cells.dedup();
        let [nx, ny, _] = self.dims;
        let corner = |c: u32| {
            let c = c as usize;
            let (x, y, z) = (c % nx, (c / nx) % ny, c / (nx * ny));
            self.origin + DVec3::new(x as f64, y as f64, z as f64) * self.cell
        };
        (cells.into_iter().map(corner).collect(), self.cell)
    }

    /// The inverse of [`Grid::order`]: per ball, its slot (`NO_SLOT` if it
    /// is not alive).
    pub fn ball_slots(&self) -> &[u32] {
        &self.ball_slot
    }

    fn slots(&self, cell: usize) -> std::ops::Range<usize> {
        self.cell_start[cell] as usize..self.cell_start[cell + 1] as usize
    }

    /// Number of cell layers along z.
    pub fn layer_count(&self) -> usize {
        self.dims[2]
    }

    /// The first slot of every layer along z, then one past the last slot:
    /// layer `z` holds slots `layer_slots()[z]..layer_slots()[z + 1]`.
    pub fn layer_slots(&self, into: &mut Vec<usize>) {
        into.clear();
        let per_layer = self.dims[0] * self.dims[1];
        into.extend((0..=self.dims[2]).map(|z| self.cell_start[z * per_layer] as usize));
    }

    /// Calls `f(k, l)` once for every unordered pair of slots (see
    /// [`Grid::order`]) with `k` in a cell of layer `z` whose spheres
    /// `spheres` (in slot order: centre in x, y, z and radius in w) overlap.
    /// `l` lies in layer `z` or `z + 1`; `k < l` within a cell. Over all
    /// layers, every overlapping pair whose centres are closer than the cell
    /// size is seen once (pairs farther apart may be missed).
    ///
    /// The spheres are `f32`, half the memory of the positions to stream:
    /// callers widen them by the rounding error and test the pairs found
    /// exactly.
    pub fn for_each_close_pair_in_layer(
        &self,
        spheres: &[Vec4],
        cz: usize,
        mut f: impl FnMut(usize, usize),
    ) {
        let [nx, ny, nz] = self.dims;
        let mut close = |own: std::ops::Range<usize>, other: std::ops::Range<usize>| {
            for k in own {
                let p = spheres[k];
                for (l, q) in spheres[other.clone()].iter().enumerate() {
                    let reach = p.w + q.w;
                    if (*q - p).truncate().length_squared() < reach * reach {
                        f(k, other.start + l);
                    }
                }
            }
        };
        for cy in 0..ny {
            let row = self.index([0, cy, cz]);
            for cx in 0..nx {
                let own = self.slots(row + cx);
                if own.is_empty() {
                    continue;
                }
                // Within the cell, and with the next cell along x.
                for k in own.clone() {
                    close(k..k + 1, k + 1..own.end);
                }
                if cx + 1 < nx {
                    close(own.clone(), self.slots(row + cx + 1));
                }
                // The four rows ahead in (y, z), three cells each: a row's
                // cells are contiguous slots, so each row is one range.
                let (x0, x1) = (cx.saturating_sub(1), (cx + 1).min(nx - 1));
                for (dy, dz) in FORWARD_ROWS {
                    let (y, z) = (cy as isize + dy, cz + dz);
                    if y < 0 || y >= ny as isize || z >= nz {
                        continue;
                    }
                    let other_row = self.index([0, y as usize, z]);
                    let start = self.cell_start[other_row + x0] as usize;
                    let end = self.cell_start[other_row + x1 + 1] as usize;
                    close(own.clone(), start..end);
                }
            }
        }
    }

    /// Calls `f(k)` for every slot (see [`Grid::order`]) whose cell touches
    /// the box `lo..hi`.
    pub fn for_each_in_box(&self, lo: DVec3, hi: DVec3, mut f: impl FnMut(usize)) {
        let a = self.coords(lo);
        let b = self.coords(hi);
        for z in a[2]..=b[2] {
            for y in a[1]..=b[1] {
                for x in a[0]..=b[0] {
                    self.slots(self.index([x, y, z])).for_each(&mut f);
                }
            }
        }
    }
}

/// The rows of cells (dy, dz) that come after a cell's own row in scan
/// order and touch it: with the next cell in its own row, these hold the 13
/// of its 26 neighbours that see each pair once.
const FORWARD_ROWS: [(isize, usize); 4] = [(1, 0), (-1, 1), (0, 1), (1, 1)];

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Rng;

    #[test]
    fn finds_exactly_the_close_pairs_that_brute_force_finds() {
        let mut rng = Rng::new(3);
        let min = DVec3::new(-2.0, 0.0, -2.0);
        let max = DVec3::new(2.0, 3.0, 2.0);
        let n = 600;
        let pos: Vec<DVec3> = (0..n)
            .map(|_| {
                DVec3::new(
                    rng.range(-2.0, 2.0),
                    rng.range(0.0, 3.0),
                    rng.range(-2.0, 2.0),
                )
            })
            .collect();
        let mut alive = vec![true; n];
        alive[5] = false;
        let reach = 0.3;
        let mut grid = Grid::new(min, max, reach);
        grid.rebuild(&pos, &alive);
        let mut found = Vec::new();
        let order = grid.order();
        // Every ball reaches a quarter of the way, ball 7 three quarters.
        let reach_of = |i: usize| if i == 7 { 0.75 * reach } else { 0.25 * reach };
        let spheres: Vec<Vec4> = order
            .iter()
            .map(|&i| {
                pos[i as usize]
                    .as_vec3()
                    .extend(reach_of(i as usize) as f32)
            })
            .collect();
        for z in 0..grid.layer_count() {
            grid.for_each_close_pair_in_layer(&spheres, z, |k, l| {
                let (i, j) = (order[k] as usize, order[l] as usize);
                found.push((i.min(j), i.max(j)));
            });
        }
        let mut brute = Vec::new();
        for i in 0..n {
            for j in i + 1..n {
                let within = if i == 7 || j == 7 { reach } else { 0.5 * reach };
                if alive[i] && alive[j] && pos[i].distance(pos[j]) < within {
                    brute.push((i, j));
                }
            }
        }
        found.sort();
        let before = found.len();
        found.dedup();
        assert_eq!(before, found.len(), "a pair was reported twice");
        assert_eq!(found, brute);
        assert!(brute.iter().any(|&(i, j)| i == 7 || j == 7));
        assert!(brute.iter().any(|&(i, j)| i != 7 && j != 7));
    }
}
