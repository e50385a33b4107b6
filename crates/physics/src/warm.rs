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
//! add energy; [`crate::World::step`] takes such excess back out of the
//! step's motion.

use crate::room::Surface;
use rayon::prelude::*;

/// Last step's normal impulses of ball pairs and ball-wall contacts.
///
/// They are kept in last step's slot order (see [`crate::broadphase::Grid::order`]),
/// which is the order of space and changes little from one step to the next,
/// so that looking them up walks memory nearly in order.
#[derive(Clone, Debug, Default)]
pub(crate) struct WarmStart {
    /// Per ball number: its slot last step (`NONE`: it had none).
    slot_of: Vec<u32>,
    slots: Vec<WarmSlot>,
    /// The share of each impulse that a lookup gives (see [`WarmStart::weaken`]).
    strength: f64,
}

/// What the ball in one slot pushed last step: together, so that a lookup
/// reads one place.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct WarmSlot {
    count: u8,
    /// The balls of later slots it pushed (by number), and how hard.
    partners: [u32; WarmSlot::PARTNERS],
    impulses: [f32; WarmSlot::PARTNERS],
    /// Per surface (in [`Surface::ALL`] order).
    walls: [f32; 6],
}

impl WarmSlot {
    /// Equal spheres touch at most twelve others; a pair beyond that (only in
    /// a crushed pile) starts cold.
    const PARTNERS: usize = 12;

    /// Records that this slot's ball pushed ball number `partner`, of a
    /// later slot (see [`pair_owner`]).
    pub fn record_partner(&mut self, partner: u32, impulse: f64) {
        let n = self.count as usize;
        if impulse > 0.0 && n < WarmSlot::PARTNERS {
            self.partners[n] = partner;
            self.impulses[n] = impulse as f32;
            self.count += 1;
        }
    }

    fn partner(&self, partner: u32) -> Option<f32> {
        let n = self.count as usize;
        let k = self.partners[..n].iter().position(|&p| p == partner)?;
        Some(self.impulses[k])
    }
}

/// Which slot keeps the impulse between the balls in slots `i` and `j`
/// (the earlier), and the other ball's number.
pub(crate) fn pair_owner(i: usize, j: usize, ids: &[u32]) -> (usize, u32) {
    if i < j { (i, ids[j]) } else { (j, ids[i]) }
}

impl WarmStart {
    const NONE: u32 = u32::MAX;

    /// Forgets everything, ready to record a step whose slot `k` holds ball
    /// number `ids[k]`, out of `balls` numbers.
    pub fn begin(&mut self, ids: &[u32], balls: usize) {
        self.slot_of.clear();
        self.slot_of.resize(balls, WarmStart::NONE);
        for (slot, &id) in ids.iter().enumerate() {
            self.slot_of[id as usize] = slot as u32;
        }
        // Partners past a slot's count are never read: only counts restart.
        self.slots.resize(ids.len(), WarmSlot::default());
        let forget = |s: &mut WarmSlot| {
            s.count = 0;
            s.walls = [0.0; 6];
        };
        if ids.len() >= PARALLEL_SLOTS {
            self.slots.par_iter_mut().for_each(forget);
        } else {
            self.slots.iter_mut().for_each(forget);
        }
        self.strength = 1.0;
    }

    /// Every slot, to record the pairs' impulses in (see
    /// [`WarmSlot::record_partner`]).
    pub fn slots_mut(&mut self) -> &mut [WarmSlot] {
        &mut self.slots
    }

    /// From now on, lookups give `share` of each impulse kept: a step that
    /// a full warm start made overshoot is retaken with less of it.
    pub fn weaken(&mut self, share: f64) {
        self.strength = share;
    }

    fn slot(&self, ball: u32) -> Option<usize> {
        match self.slot_of.get(ball as usize) {
            Some(&slot) if slot != WarmStart::NONE => Some(slot as usize),
            _ => None,
        }
    }

    /// Last step's impulse between balls number `a` and `b` (0 if none).
    pub fn pair(&self, a: u32, b: u32) -> f64 {
        let (Some(sa), Some(sb)) = (self.slot(a), self.slot(b)) else {
            return 0.0;
        };
        let (owner, partner) = if sa < sb { (sa, b) } else { (sb, a) };
        self.slots[owner]
            .partner(partner)
            .map_or(0.0, |impulse| self.strength * impulse as f64)
    }

    /// Last step's impulse between ball number `ball` and surface `s`.
    pub fn wall(&self, ball: u32, s: Surface) -> f64 {
        self.slot(ball).map_or(0.0, |slot| {
            self.strength * self.slots[slot].walls[s.index()] as f64
        })
    }

    /// Records the impulse between the ball in slot `i` and surface `s`.
    pub fn record_wall(&mut self, i: usize, s: Surface, impulse: f64) {
        self.slots[i].walls[s.index()] = impulse.max(0.0) as f32;
    }
}

/// Below this many slots a warm start is begun on one thread.
const PARALLEL_SLOTS: usize = 4096;

#[cfg(test)]
mod tests {
    use super::*;

    impl WarmStart {
        fn record_pair(&mut self, i: usize, j: usize, ids: &[u32], impulse: f64) {
            let (owner, partner) = pair_owner(i, j, ids);
            self.slots[owner].record_partner(partner, impulse);
        }
    }

    #[test]
    fn impulses_are_found_by_ball_number_after_the_balls_change_slots() {
        let mut w = WarmStart::default();
        // Slots 0..4 hold balls 3, 1, 0, 2; ball 4 is gone.
        let ids = [3, 1, 0, 2];
        w.begin(&ids, 5);
        w.record_pair(0, 1, &ids, 2.5);
        w.record_pair(3, 2, &ids, 1.5);
        w.record_pair(1, 2, &ids, 0.0);
        w.record_wall(3, Surface::Floor, 4.0);
        assert_eq!(w.pair(3, 1), 2.5);
        assert_eq!(w.pair(1, 3), 2.5);
        assert_eq!(w.pair(0, 2), 1.5);
        assert_eq!(w.pair(1, 0), 0.0);
        assert_eq!(w.pair(4, 0), 0.0);
        assert_eq!(w.wall(2, Surface::Floor), 4.0);
        assert_eq!(w.wall(2, Surface::Ceiling), 0.0);
        assert_eq!(w.wall(4, Surface::Floor), 0.0);
        w.weaken(0.5);
        assert_eq!(w.pair(3, 1), 1.25);
        assert_eq!(w.wall(2, Surface::Floor), 2.0);
        w.begin(&ids, 5);
        assert_eq!(w.pair(3, 1), 0.0);
        assert_eq!(w.wall(2, Surface::Floor), 0.0);
    }

    #[test]
    fn a_ball_keeps_at_most_twelve_partners() {
        let mut w = WarmStart::default();
        let ids: Vec<u32> = (0..20).collect();
        w.begin(&ids, 20);
        for b in 1..20 {
            w.record_pair(0, b, &ids, b as f64);
        }
        assert_eq!(w.pair(0, 12), 12.0);
        assert_eq!(w.pair(0, 13), 0.0);
    }
}
