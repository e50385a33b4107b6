//! Warm starting: the normal impulses that held contacts last step, kept by
//! ball number, so that this step's solver starts from them.
//!
//! A pile's weight has to reach the floor through every layer of balls.
//! Gauss-Seidel carries it down one layer or so per iteration, so a solver
//! starting from nothing each step leaves the lower layers approaching one
//! another, and the pile creeps into itself. Started from last step's
//! impulses, which change little while the pile rests, the few iterations of
//! a step only have to correct the change.
//!
//! A warm start can push apart contacts that no longer need it, which would
//! add energy; [`crate::World::step`] guards against that by retaking such a
//! step cold.

use crate::room::Surface;

/// Last step's normal impulses of ball pairs and ball-wall contacts.
#[derive(Clone, Debug, Default)]
pub(crate) struct WarmStart {
    /// Per ball number: the higher-numbered partners it pushed, and how hard.
    partners: Vec<[u32; WarmStart::PARTNERS]>,
    impulses: Vec<[f32; WarmStart::PARTNERS]>,
    count: Vec<u8>,
    /// Per ball number and surface (in [`Surface::ALL`] order).
    walls: Vec<[f32; 6]>,
}

impl WarmStart {
    /// Equal spheres touch at most twelve others; a pair beyond that (only in
    /// a crushed pile) starts cold.
    const PARTNERS: usize = 12;

    /// Forgets everything and makes room for `balls` ball numbers.
    pub fn clear(&mut self, balls: usize) {
        self.partners.resize(balls, [0; WarmStart::PARTNERS]);
        self.impulses.resize(balls, [0.0; WarmStart::PARTNERS]);
        self.count.clear();
        self.count.resize(balls, 0);
        self.walls.clear();
        self.walls.resize(balls, [0.0; 6]);
    }

    /// Last step's impulse between balls number `a` and `b` (0 if none).
    pub fn pair(&self, a: u32, b: u32) -> f64 {
        let (low, high) = if a < b { (a, b) } else { (b, a) };
        let Some(&n) = self.count.get(low as usize) else {
            return 0.0;
        };
        let low = low as usize;
        self.partners[low][..n as usize]
            .iter()
            .position(|&p| p == high)
            .map_or(0.0, |k| self.impulses[low][k] as f64)
    }

    /// Last step's impulse between ball number `ball` and surface `s`.
    pub fn wall(&self, ball: u32, s: Surface) -> f64 {
        self.walls
            .get(ball as usize)
            .map_or(0.0, |w| w[s.index()] as f64)
    }

    pub fn record_pair(&mut self, a: u32, b: u32, impulse: f64) {
        if impulse <= 0.0 {
            return;
        }
        let (low, high) = if a < b { (a, b) } else { (b, a) };
        let low = low as usize;
        let n = self.count[low] as usize;
        if n < WarmStart::PARTNERS {
            self.partners[low][n] = high;
            self.impulses[low][n] = impulse as f32;
            self.count[low] += 1;
        }
    }

    pub fn record_wall(&mut self, ball: u32, s: Surface, impulse: f64) {
        self.walls[ball as usize][s.index()] = impulse.max(0.0) as f32;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn impulses_are_found_by_either_ball_and_forgotten_on_clear() {
        let mut w = WarmStart::default();
        w.clear(4);
        w.record_pair(3, 1, 2.5);
        w.record_pair(1, 2, 0.0);
        w.record_wall(2, Surface::Floor, 4.0);
        assert_eq!(w.pair(1, 3), 2.5);
        assert_eq!(w.pair(3, 1), 2.5);
        assert_eq!(w.pair(1, 2), 0.0);
        assert_eq!(w.wall(2, Surface::Floor), 4.0);
        assert_eq!(w.wall(2, Surface::Ceiling), 0.0);
        w.clear(4);
        assert_eq!(w.pair(1, 3), 0.0);
        assert_eq!(w.wall(2, Surface::Floor), 0.0);
    }

    #[test]
    fn a_ball_keeps_at_most_twelve_partners() {
        let mut w = WarmStart::default();
        w.clear(20);
        for b in 1..20 {
            w.record_pair(0, b, b as f64);
        }
        assert_eq!(w.pair(0, 12), 12.0);
        assert_eq!(w.pair(0, 13), 0.0);
    }
}
