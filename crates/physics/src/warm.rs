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

use crate::contact::Pair;
use crate::room::Surface;

/// Last step's normal impulses of ball pairs and ball-wall contacts.
///
/// They are kept in last step's slot order (see [`crate::broadphase::Grid::order`]),
/// which is the order of space and changes little from one step to the next,
/// so that looking them up walks memory nearly in order. Each slot's
/// impulses lie packed one after the other: a lookup reads a few bytes, not
/// room for every partner a ball could have.
#[derive(Clone, Debug, Default)]
pub(crate) struct WarmStart {
    /// Per ball number: its slot last step (`NONE`: it had none).
    slot_of: Vec<u32>,
    /// Per slot: where its impulses lie in `partners` and `walls`.
    kept: Vec<Kept>,
    /// Per band of pairs, room for each of its pairs (see [`WarmPart`]).
    partners: Vec<Partner>,
    /// In slot order.
    walls: Vec<WallImpulse>,
    /// The share of each impulse that a lookup gives (see [`WarmStart::weaken`]).
    strength: f64,
}

/// Where one slot's impulses lie.
#[derive(Clone, Copy, Debug, Default)]
struct Kept {
    /// `partners[first..first + pairs]`: the balls of later slots it pushed.
    first: u32,
    pairs: u32,
    /// `walls[first_wall..first_wall + walls]`: the surfaces it pushed.
    first_wall: u32,
    walls: u32,
}

impl Kept {
    fn partner_range(&self) -> std::ops::Range<usize> {
        self.first as usize..(self.first + self.pairs) as usize
    }

    fn wall_range(&self) -> std::ops::Range<usize> {
        self.first_wall as usize..(self.first_wall + self.walls) as usize
    }
}

/// A ball of a later slot that a slot's ball pushed (by number), and how hard.
#[derive(Clone, Copy, Debug, Default)]
struct Partner {
    ball: u32,
    impulse: f32,
}

#[derive(Clone, Copy, Debug)]
struct WallImpulse {
    surface: Surface,
    impulse: f32,
}

/// Which slot keeps the impulse between the balls in slots `i` and `j`
/// (the earlier), and the other ball's number.
pub(crate) fn pair_owner(i: usize, j: usize, ids: &[u32]) -> (usize, u32) {
    if i < j { (i, ids[j]) } else { (j, ids[i]) }
}

impl WarmStart {
    const NONE: u32 = u32::MAX;

    /// Forgets everything, ready to record a step whose ball number `b`
    /// lies in slot `slot_of[b]` (`NONE` for none) of `slots`, with `pairs`
    /// ball pairs.
    pub fn begin(&mut self, slot_of: &[u32], slots: usize, pairs: usize) {
        self.slot_of.clear();
        self.slot_of.extend_from_slice(slot_of);
        self.kept.clear();
        self.kept.resize(slots, Kept::default());
        // Room past a slot's count is never read: it need not be cleared.
        if self.partners.len() < pairs {
            self.partners.resize(pairs, Partner::default());
        }
        self.walls.clear();
        self.strength = 1.0;
    }

    /// The whole recording, to be split between bands of pairs (see
    /// [`WarmPart::split`]).
    pub fn recorder(&mut self) -> WarmPart<'_> {
        WarmPart {
            first_slot: 0,
            kept: &mut self.kept,
            first_pair: 0,
            partners: &mut self.partners,
        }
    }

    /// Records the impulse between the ball in slot `i` and surface `s`;
    /// called in slot order.
    pub fn record_wall(&mut self, i: usize, s: Surface, impulse: f64) {
        if impulse <= 0.0 {
            return;
        }
        let kept = &mut self.kept[i];
        if kept.walls == 0 {
            kept.first_wall = self.walls.len() as u32;
        }
        debug_assert_eq!(
            (kept.first_wall + kept.walls) as usize,
            self.walls.len(),
            "walls recorded out of slot order"
        );
        kept.walls += 1;
        self.walls.push(WallImpulse {
            surface: s,
            impulse: impulse as f32,
        });
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
        let mut kept = self.partners[self.kept[owner].partner_range()].iter();
        self.share(kept.find(|p| p.ball == partner).map(|p| p.impulse))
    }

    /// Last step's impulse between ball number `ball` and surface `s`.
    pub fn wall(&self, ball: u32, s: Surface) -> f64 {
        let Some(slot) = self.slot(ball) else {
            return 0.0;
        };
        let mut kept = self.walls[self.kept[slot].wall_range()].iter();
        self.share(kept.find(|w| w.surface == s).map(|w| w.impulse))
    }

    /// The share of a kept impulse that a lookup gives, 0 for none.
    fn share(&self, impulse: Option<f32>) -> f64 {
        impulse.map_or(0.0, |impulse| self.strength * impulse as f64)
    }
}

/// The part of a recording that one or more bands of pairs write: the slots
/// of their grid layers, which keep their pairs (see [`pair_owner`]), and
/// room for their pairs. Parts apart are recorded side by side.
pub(crate) struct WarmPart<'a> {
    first_slot: usize,
    kept: &'a mut [Kept],
    first_pair: usize,
    partners: &'a mut [Partner],
}

impl<'a> WarmPart<'a> {
    /// The number of the first pair this part has room for.
    pub fn first_pair(&self) -> usize {
        self.first_pair
    }

    /// Splits the part before slot `slot` and before the room for pair
    /// number `pair` (both counted over the whole recording).
    pub fn split(self, slot: usize, pair: usize) -> (WarmPart<'a>, WarmPart<'a>) {
        let (kept, later_kept) = self.kept.split_at_mut(slot - self.first_slot);
        let (partners, later_partners) = self.partners.split_at_mut(pair - self.first_pair);
        (
            WarmPart {
                first_slot: self.first_slot,
                kept,
                first_pair: self.first_pair,
                partners,
            },
            WarmPart {
                first_slot: slot,
                kept: later_kept,
                first_pair: pair,
                partners: later_partners,
            },
        )
    }

    /// Records the pairs of `band` (slots of this part, `ids` each slot's
    /// ball number) that pushed, `impulses` giving each pair's impulse in
    /// turn, into room for the band's pairs.
    pub fn record_pairs<I>(&mut self, band: &[Pair], impulses: I, ids: &[u32])
    where
        I: Iterator<Item = f64> + Clone,
    {
        let first = self.first_slot;
        let owner = |p: &Pair| pair_owner(p.i as usize, p.j as usize, ids);
        let pushed = || band.iter().zip(impulses.clone()).filter(|(_, f)| *f > 0.0);
        for (p, _) in pushed() {
            self.kept[owner(p).0 - first].pairs += 1;
        }
        // Each slot's room follows the last one's, then fills from its start.
        let mut next = self.first_pair as u32;
        for kept in self.kept.iter_mut() {
            kept.first = next;
            next += kept.pairs;
            kept.pairs = 0;
        }
        for (p, impulse) in pushed() {
            let (slot, partner) = owner(p);
            let kept = &mut self.kept[slot - first];
            self.partners[(kept.first + kept.pairs) as usize - self.first_pair] = Partner {
                ball: partner,
                impulse: impulse as f32,
            };
            kept.pairs += 1;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    /// Pairs `(i, j, impulse)` by slot.
    fn to_pairs(pairs: &[(usize, usize, f64)]) -> Vec<Pair> {
        pairs
            .iter()
            .map(|&(i, j, _)| Pair::new(i, j, DVec3::Y, 0.0, 0.0))
            .collect()
    }

    impl WarmStart {
        /// Records one band of pairs `(i, j, impulse)` by slot, whose slot `k`
        /// holds ball number `ids[k]`, out of `balls` numbers.
        fn record(&mut self, ids: &[u32], balls: usize, pairs: &[(usize, usize, f64)]) {
            let mut slot_of = vec![WarmStart::NONE; balls];
            for (slot, &id) in ids.iter().enumerate() {
                slot_of[id as usize] = slot as u32;
            }
            self.begin(&slot_of, ids.len(), pairs.len());
            let band = to_pairs(pairs);
            let impulses = pairs.iter().map(|p| p.2);
            self.recorder().record_pairs(&band, impulses, ids);
        }
    }

    #[test]
    fn impulses_are_found_by_ball_number_after_the_balls_change_slots() {
        let mut w = WarmStart::default();
        // Slots 0..4 hold balls 3, 1, 0, 2; ball 4 is gone.
        let ids = [3, 1, 0, 2];
        w.record(&ids, 5, &[(0, 1, 2.5), (3, 2, 1.5), (1, 2, 0.0)]);
        w.record_wall(1, Surface::Back, 0.5);
        w.record_wall(3, Surface::Floor, 4.0);
        w.record_wall(3, Surface::Left, 3.0);
        assert_eq!(w.pair(3, 1), 2.5);
        assert_eq!(w.pair(1, 3), 2.5);
        assert_eq!(w.pair(0, 2), 1.5);
        assert_eq!(w.pair(1, 0), 0.0);
        assert_eq!(w.pair(4, 0), 0.0);
        assert_eq!(w.wall(1, Surface::Back), 0.5);
        assert_eq!(w.wall(2, Surface::Floor), 4.0);
        assert_eq!(w.wall(2, Surface::Left), 3.0);
        assert_eq!(w.wall(2, Surface::Ceiling), 0.0);
        assert_eq!(w.wall(3, Surface::Floor), 0.0);
        assert_eq!(w.wall(4, Surface::Floor), 0.0);
        w.weaken(0.5);
        assert_eq!(w.pair(3, 1), 1.25);
        assert_eq!(w.wall(2, Surface::Floor), 2.0);
        w.record(&ids, 5, &[]);
        assert_eq!(w.pair(3, 1), 0.0);
        assert_eq!(w.wall(2, Surface::Floor), 0.0);
    }

    #[test]
    fn a_ball_keeps_every_partner_it_pushed_and_no_other() {
        let mut w = WarmStart::default();
        let ids: Vec<u32> = (0..20).collect();
        // Slot 0 pushed every later slot but 7, slot 2 pushed 3.
        let mut pairs: Vec<(usize, usize, f64)> = (1..20).map(|b| (0, b, b as f64)).collect();
        pairs[6].2 = 0.0;
        pairs.insert(3, (3, 2, 0.25));
        w.record(&ids, 20, &pairs);
        assert_eq!(w.pair(0, 1), 1.0);
        assert_eq!(w.pair(0, 19), 19.0);
        assert_eq!(w.pair(19, 0), 19.0);
        assert_eq!(w.pair(0, 7), 0.0);
        assert_eq!(w.pair(2, 3), 0.25);
        assert_eq!(w.pair(1, 2), 0.0);
    }

    #[test]
    fn parts_split_between_bands_record_what_the_whole_would() {
        // Slots 0..6 hold balls in reverse; bands: slots 0..2 with pairs
        // (0, 1), (1, 3); slots 2..6 with pairs (2, 5), (4, 5), (2, 3).
        let ids: Vec<u32> = (0..6).rev().collect();
        let bands = [
            vec![(0, 1, 1.0), (1, 3, 2.0)],
            vec![(2, 5, 3.0), (4, 5, 4.0), (2, 3, 5.0)],
        ];
        let all: Vec<_> = bands.concat();
        let mut whole = WarmStart::default();
        whole.record(&ids, 6, &all);
        // The same pairs recorded in two parts, the second first.
        let mut split = WarmStart::default();
        let slot_of: Vec<u32> = (0..6).rev().collect();
        split.begin(&slot_of, 6, all.len());
        let impulses = |band: &[(usize, usize, f64)]| band.iter().map(|p| p.2).collect::<Vec<_>>();
        let (mut first, mut second) = split.recorder().split(2, bands[0].len());
        let later = impulses(&bands[1]);
        second.record_pairs(&to_pairs(&bands[1]), later.into_iter(), &ids);
        let earlier = impulses(&bands[0]);
        first.record_pairs(&to_pairs(&bands[0]), earlier.into_iter(), &ids);
        for a in 0..6 {
            for b in 0..6 {
                assert_eq!(split.pair(a, b), whole.pair(a, b), "balls {a} and {b}");
            }
        }
        assert_eq!(split.pair(ids[1], ids[3]), 2.0);
        assert_eq!(split.pair(ids[3], ids[2]), 5.0);
    }
}
