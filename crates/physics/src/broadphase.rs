//! Uniform grid broadphase for the balls.
//!
//! Rebuilt every step with a counting sort into buffers that are kept between
//! steps, so its cost grows linearly with the ball count and it allocates
//! nothing once warm. Pairs come out in a fixed order (by cell, then index),
//! which keeps the solver deterministic.

use glam::DVec3;

#[derive(Clone, Debug, Default)]
pub(crate) struct Grid {
    origin: DVec3,
    cell: f64,
    dims: [usize; 3],
    /// `cell_start[c]..cell_start[c + 1]` indexes `sorted` for cell `c`.
    cell_start: Vec<u32>,
    sorted: Vec<u32>,
    ball_cell: Vec<u32>,
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
        self.cell_start.fill(0);
        self.ball_cell.clear();
        for (p, &live) in positions.iter().zip(alive) {
            let c = if live {
                self.index(self.coords(*p)) as u32
            } else {
                u32::MAX
            };
            self.ball_cell.push(c);
            if live {
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
        for (i, &c) in self.ball_cell.iter().enumerate() {
            if c != u32::MAX {
                let slot = &mut cursor[c as usize];
                self.sorted[*slot as usize] = i as u32;
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

    /// Calls `f(i, j)` once for every unordered pair of live balls in the same
    /// or neighbouring cells (so every pair closer than one cell size is seen).
    pub fn for_each_pair(&self, mut f: impl FnMut(usize, usize)) {
        let [nx, ny, nz] = self.dims;
        for cz in 0..nz {
            for cy in 0..ny {
                for cx in 0..nx {
                    let c = self.index([cx, cy, cz]);
                    let (s, e) = (self.cell_start[c] as usize, self.cell_start[c + 1] as usize);
                    if s == e {
                        continue;
                    }
                    let own = &self.sorted[s..e];
                    // Pairs within the cell.
                    for (k, &i) in own.iter().enumerate() {
                        for &j in &own[k + 1..] {
                            f(i as usize, j as usize);
                        }
                    }
                    // Half of the 26 neighbours, so that each pair is seen once.
                    for &(dx, dy, dz) in &FORWARD_NEIGHBOURS {
                        let (x, y, z) = (cx as isize + dx, cy as isize + dy, cz as isize + dz);
                        if x < 0
                            || y < 0
                            || z < 0
                            || x >= nx as isize
                            || y >= ny as isize
                            || z >= nz as isize
                        {
                            continue;
                        }
                        let n = self.index([x as usize, y as usize, z as usize]);
                        let other = &self.sorted
                            [self.cell_start[n] as usize..self.cell_start[n + 1] as usize];
                        for &i in own {
                            for &j in other {
                                f(i as usize, j as usize);
                            }
                        }
                    }
                }
            }
        }
    }

    /// Calls `f(i)` for every live ball whose cell touches the box `lo..hi`.
    pub fn for_each_in_box(&self, lo: DVec3, hi: DVec3, mut f: impl FnMut(usize)) {
        let a = self.coords(lo);
        let b = self.coords(hi);
        for z in a[2]..=b[2] {
            for y in a[1]..=b[1] {
                for x in a[0]..=b[0] {
                    let c = self.index([x, y, z]);
                    for &i in
                        &self.sorted[self.cell_start[c] as usize..self.cell_start[c + 1] as usize]
                    {
                        f(i as usize);
                    }
                }
            }
        }
    }
}

/// The 13 neighbour offsets that are "after" a cell in scan order.
const FORWARD_NEIGHBOURS: [(isize, isize, isize); 13] = [
    (1, 0, 0),
    (-1, 1, 0),
    (0, 1, 0),
    (1, 1, 0),
    (-1, -1, 1),
    (0, -1, 1),
    (1, -1, 1),
    (-1, 0, 1),
    (0, 0, 1),
    (1, 0, 1),
    (-1, 1, 1),
    (0, 1, 1),
    (1, 1, 1),
];

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
        grid.for_each_pair(|i, j| {
            if pos[i].distance(pos[j]) < reach {
                found.push((i.min(j), i.max(j)));
            }
        });
        let mut brute = Vec::new();
        for i in 0..n {
            for j in i + 1..n {
                if alive[i] && alive[j] && pos[i].distance(pos[j]) < reach {
                    brute.push((i, j));
                }
            }
        }
        found.sort();
        let before = found.len();
        found.dedup();
        assert_eq!(before, found.len(), "a pair was reported twice");
        assert_eq!(found, brute);
        assert!(!brute.is_empty());
    }
}
