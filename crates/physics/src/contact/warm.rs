//! Warm starting: the normal impulses that held contacts last step, kept by
//! ball number, so that this step's solver starts from them. Both solver
//! stages' impulses of a contact are kept together: one lookup finds both,
//! and one recording, as the step ends, keeps both.
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

#[cfg(doc)]
use super::stages::Stage;
use super::{FrictionImpulse, Pair};
use crate::room::Surface;
use glam::Vec3;
use serde::{Deserialize, Serialize};

/// Last step's normal impulses of ball pairs and ball-wall contacts, of
/// both solver stages.
///
/// They are kept in last step's slot order (see [`crate::broadphase::Grid::order`]),
/// which is the order of space and changes little from one step to the next,
/// so that looking them up walks memory nearly in order. Each slot's
/// impulses lie packed one after the other: a lookup reads a few bytes, not
/// room for every partner a ball could have.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
pub(crate) struct WarmStart {
    /// Per ball number: its slot last step (`NONE`: it had none).
    slot_of: Vec<u32>,
    /// Per slot: where its impulses lie in `partners` and `walls`.
    kept: Vec<Kept>,
    /// Per band of pairs, room for each of its pairs (see [`WarmPart`]).
    partners: Vec<Partner>,
    /// Beside `partners`, each pair's friction impulses in each stage,
    /// where the step that recorded them solved friction between balls
    /// (else empty).
    friction: Vec<[HeldFriction; 2]>,
    /// In slot order.
    walls: Vec<WallImpulse>,
    /// The share of each impulse that a lookup gives (see [`WarmStart::weaken`]).
    strength: f64,
}

/// Where one slot's impulses lie.
#[derive(Clone, Copy, Debug, Default, Serialize, Deserialize)]
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

/// A contact's impulses in each solver stage, indexed by [`Stage`], as kept:
/// single precision is plenty for a starting guess, and half the bytes.
pub(crate) type Held = [f32; 2];

/// A contact's impulses in each solver stage, indexed by [`Stage`].
pub(crate) type StageImpulses = [f64; 2];

/// A pair's friction impulses in each solver stage, indexed by [`Stage`].
pub(crate) type StageFriction = [FrictionImpulse; 2];

/// Whether a contact pushed in either stage, and so is worth keeping.
fn pushed(impulses: StageImpulses) -> bool {
    impulses.iter().any(|&f| f > 0.0)
}

fn held(impulses: StageImpulses) -> Held {
    impulses.map(|f| f as f32)
}

/// A pair's friction impulses as kept (see [`Held`]), as they act on the
/// ball of the lower number: a pair's slots may come in either order.
#[derive(Clone, Copy, Debug, Default, Serialize, Deserialize)]
struct HeldFriction {
    tangent: Vec3,
    rolling: Vec3,
}

impl HeldFriction {
    fn of(f: &FrictionImpulse) -> HeldFriction {
        HeldFriction {
            tangent: f.tangent.as_vec3(),
            rolling: f.rolling.as_vec3(),
        }
    }

    fn share(&self, share: f64) -> FrictionImpulse {
        FrictionImpulse {
            tangent: self.tangent.as_dvec3() * share,
            rolling: self.rolling.as_dvec3() * share,
        }
    }

    /// As it acts on the other ball.
    fn reversed(self) -> HeldFriction {
        HeldFriction {
            tangent: -self.tangent,
            rolling: -self.rolling,
        }
    }
}

/// A ball of a later slot that a slot's ball pushed (by number), and how hard.
#[derive(Clone, Copy, Debug, Default, Serialize, Deserialize)]
struct Partner {
    ball: u32,
    impulses: Held,
}

#[derive(Clone, Copy, Debug, Serialize, Deserialize)]
struct WallImpulse {
    surface: Surface,
    impulses: Held,
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
        self.friction.clear();
        self.walls.clear();
        self.strength = 1.0;
    }

    /// The whole recording, to be split between bands of pairs (see
    /// [`WarmPart::split`]).
    ///
    /// With `friction`, the pairs' friction impulses are kept too.
    pub fn recorder(&mut self, friction: bool) -> WarmPart<'_> {
        if friction {
            self.friction
                .resize(self.partners.len(), Default::default());
        }
        WarmPart {
            first_slot: 0,
            kept: &mut self.kept,
            first_pair: 0,
            partners: &mut self.partners,
            friction: &mut self.friction,
        }
    }

    /// Records the impulses between the ball in slot `i` and surface `s`;
    /// called in slot order.
    pub fn record_wall(&mut self, i: usize, s: Surface, impulses: StageImpulses) {
        if !pushed(impulses) {
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
            impulses: held(impulses),
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

    /// Last step's impulses between balls number `a` and `b` (0 if none),
    /// as kept: [`WarmStart::share`] tells what of each to start from.
    pub fn pair(&self, a: u32, b: u32) -> Held {
        self.find_pair(a, b)
            .map_or(Held::default(), |k| self.partners[k].impulses)
    }

    /// As [`WarmStart::pair`], with the pair's friction impulses on ball
    /// `a`, as a start (their share; zero where none were kept).
    pub fn pair_with_friction(&self, a: u32, b: u32) -> (Held, StageFriction) {
        match self.find_pair(a, b) {
            Some(k) => {
                let on_a = |f: HeldFriction| if a < b { f } else { f.reversed() };
                let share = |held: &[HeldFriction; 2]| held.map(|f| on_a(f).share(self.strength));
                let friction = self.friction.get(k).map(share);
                (self.partners[k].impulses, friction.unwrap_or_default())
            }
            None => (Held::default(), StageFriction::default()),
        }
    }

    /// Where the impulses between balls number `a` and `b` lie in `partners`.
    fn find_pair(&self, a: u32, b: u32) -> Option<usize> {
        let (sa, sb) = (self.slot(a)?, self.slot(b)?);
        let (owner, partner) = if sa < sb { (sa, b) } else { (sb, a) };
        let range = self.kept[owner].partner_range();
        let first = range.start;
        let mut kept = self.partners[range].iter();
        kept.position(|p| p.ball == partner).map(|k| first + k)
    }

    /// Last step's impulses between ball number `ball` and surface `s`, as
    /// kept (see [`WarmStart::pair`]).
    pub fn wall(&self, ball: u32, s: Surface) -> Held {
        let Some(slot) = self.slot(ball) else {
            return Held::default();
        };
        let mut kept = self.walls[self.kept[slot].wall_range()].iter();
        kept.find(|w| w.surface == s)
            .map_or(Held::default(), |w| w.impulses)
    }

    /// Each ball number recorded, with the slot its impulses are kept under.
    fn recorded_balls(&self) -> impl Iterator<Item = (u32, usize)> + '_ {
        (0..self.slot_of.len() as u32).filter_map(|ball| Some((ball, self.slot(ball)?)))
    }

    /// Every pair of balls recorded as pushing: the lower ball number, the
    /// higher, both stages' normal impulses, and both stages' friction
    /// impulses summed as they act on the lower-numbered ball (zero where
    /// none were kept). For the debug views.
    pub fn recorded_pairs(&self) -> impl Iterator<Item = (u32, u32, Held, Vec3)> + '_ {
        self.recorded_balls().flat_map(move |(ball, slot)| {
            let range = self.kept[slot].partner_range();
            range.map(move |k| {
                let partner = self.partners[k];
                let friction = self
                    .friction
                    .get(k)
                    .map_or(Vec3::ZERO, |[a, b]| a.tangent + b.tangent);
                let (lo, hi) = (ball.min(partner.ball), ball.max(partner.ball));
                (lo, hi, partner.impulses, friction)
            })
        })
    }

    /// Every ball and surface recorded as pushing, with both stages'
    /// impulses. For the debug views.
    pub fn recorded_walls(&self) -> impl Iterator<Item = (u32, Surface, Held)> + '_ {
        self.recorded_balls().flat_map(move |(ball, slot)| {
            self.walls[self.kept[slot].wall_range()]
                .iter()
                .map(move |w| (ball, w.surface, w.impulses))
        })
    }

    /// The impulse to start from, given one kept: its share (see
    /// [`WarmStart::weaken`]).
    pub fn share(&self, impulse: f32) -> f64 {
        self.strength * impulse as f64
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
    /// Beside `partners`, or empty where friction is not kept.
    friction: &'a mut [[HeldFriction; 2]],
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
        let at = (pair - self.first_pair).min(self.friction.len());
        let (friction, later_friction) = self.friction.split_at_mut(at);
        (
            WarmPart {
                first_slot: self.first_slot,
                kept,
                first_pair: self.first_pair,
                partners,
                friction,
            },
            WarmPart {
                first_slot: slot,
                kept: later_kept,
                first_pair: pair,
                partners: later_partners,
                friction: later_friction,
            },
        )
    }

    /// Records the pairs of `band` (slots of this part, `ids` each slot's
    /// ball number) that pushed, `impulses` giving each pair's impulses in
    /// turn, into room for the band's pairs; with them, where this part
    /// keeps friction, each pair's `friction` (one per pair, or none).
    pub fn record_pairs<I>(
        &mut self,
        band: &[Pair],
        impulses: I,
        friction: &[StageFriction],
        ids: &[u32],
    ) where
        I: Iterator<Item = StageImpulses> + Clone,
    {
        let first = self.first_slot;
        let owner = |p: &Pair| pair_owner(p.i as usize, p.j as usize, ids);
        let kept_pairs = || {
            band.iter()
                .zip(impulses.clone())
                .enumerate()
                .filter(|(_, (_, f))| pushed(*f))
        };
        for (_, (p, _)) in kept_pairs() {
            self.kept[owner(p).0 - first].pairs += 1;
        }
        // Each slot's room follows the last one's, then fills from its start.
        let mut next = self.first_pair as u32;
        for kept in self.kept.iter_mut() {
            kept.first = next;
            next += kept.pairs;
            kept.pairs = 0;
        }
        let keeps_friction = !self.friction.is_empty() && !friction.is_empty();
        for (k, (p, impulses)) in kept_pairs() {
            let (slot, partner) = owner(p);
            let kept = &mut self.kept[slot - first];
            let room = (kept.first + kept.pairs) as usize - self.first_pair;
            self.partners[room] = Partner {
                ball: partner,
                impulses: held(impulses),
            };
            if keeps_friction {
                let on_lower = ids[p.i as usize] < ids[p.j as usize];
                let held = |f: FrictionImpulse| {
                    let held = HeldFriction::of(&f);
                    if on_lower { held } else { held.reversed() }
                };
                self.friction[room] = friction[k].map(held);
            }
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

    /// The impulses a test records for a contact: `f` in the predict stage,
    /// `2 f` in the project stage.
    fn both(f: f64) -> StageImpulses {
        [f, 2.0 * f]
    }

    impl WarmStart {
        /// What a lookup of the pair of balls `a` and `b` starts each stage from.
        fn pair_start(&self, a: u32, b: u32) -> StageImpulses {
            self.pair(a, b).map(|f| self.share(f))
        }

        /// What a lookup of ball `ball` on surface `s` starts each stage from.
        fn wall_start(&self, ball: u32, s: Surface) -> StageImpulses {
            self.wall(ball, s).map(|f| self.share(f))
        }

        /// Records one band of pairs `(i, j, impulse)` by slot, whose slot `k`
        /// holds ball number `ids[k]`, out of `balls` numbers (see [`both`]).
        fn record(&mut self, ids: &[u32], balls: usize, pairs: &[(usize, usize, f64)]) {
            let mut slot_of = vec![WarmStart::NONE; balls];
            for (slot, &id) in ids.iter().enumerate() {
                slot_of[id as usize] = slot as u32;
            }
            self.begin(&slot_of, ids.len(), pairs.len());
            let band = to_pairs(pairs);
            let impulses = pairs.iter().map(|p| both(p.2));
            self.recorder(false).record_pairs(&band, impulses, &[], ids);
        }
    }

    #[test]
    fn impulses_are_found_by_ball_number_after_the_balls_change_slots() {
        let mut w = WarmStart::default();
        // Slots 0..4 hold balls 3, 1, 0, 2; ball 4 is gone.
        let ids = [3, 1, 0, 2];
        w.record(&ids, 5, &[(0, 1, 2.5), (3, 2, 1.5), (1, 2, 0.0)]);
        w.record_wall(1, Surface::Back, both(0.5));
        w.record_wall(3, Surface::Floor, both(4.0));
        w.record_wall(3, Surface::Left, both(3.0));
        assert_eq!(w.pair_start(3, 1), both(2.5));
        assert_eq!(w.pair_start(1, 3), both(2.5));
        assert_eq!(w.pair_start(0, 2), both(1.5));
        assert_eq!(w.pair_start(1, 0), both(0.0));
        assert_eq!(w.pair_start(4, 0), both(0.0));
        assert_eq!(w.wall_start(1, Surface::Back), both(0.5));
        assert_eq!(w.wall_start(2, Surface::Floor), both(4.0));
        assert_eq!(w.wall_start(2, Surface::Left), both(3.0));
        assert_eq!(w.wall_start(2, Surface::Ceiling), both(0.0));
        assert_eq!(w.wall_start(3, Surface::Floor), both(0.0));
        // Listed whole, by ball number, the pair that did not push left out.
        let mut pairs: Vec<_> = w.recorded_pairs().map(|(a, b, f, _)| (a, b, f)).collect();
        pairs.sort_by_key(|p| (p.0, p.1));
        assert_eq!(pairs, [(0, 2, [1.5, 3.0]), (1, 3, [2.5, 5.0])]);
        let mut walls: Vec<_> = w.recorded_walls().collect();
        walls.sort_by_key(|w| w.0);
        assert_eq!(walls.len(), 3);
        assert_eq!(walls[0], (1, Surface::Back, [0.5, 1.0]));
        assert!(walls[1..].iter().all(|w| w.0 == 2));
        assert_eq!(w.wall_start(4, Surface::Floor), both(0.0));
        w.weaken(0.5);
        assert_eq!(w.pair_start(3, 1), both(1.25));
        assert_eq!(w.wall_start(2, Surface::Floor), both(2.0));
        w.record(&ids, 5, &[]);
        assert_eq!(w.pair_start(3, 1), both(0.0));
        assert_eq!(w.wall_start(2, Surface::Floor), both(0.0));
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
        assert_eq!(w.pair_start(0, 1), both(1.0));
        assert_eq!(w.pair_start(0, 19), both(19.0));
        assert_eq!(w.pair_start(19, 0), both(19.0));
        assert_eq!(w.pair_start(0, 7), both(0.0));
        assert_eq!(w.pair_start(2, 3), both(0.25));
        assert_eq!(w.pair_start(1, 2), both(0.0));
    }

    #[test]
    fn a_contact_that_pushed_in_either_stage_keeps_both_impulses() {
        let mut w = WarmStart::default();
        let ids = [0, 1, 2];
        w.begin(&ids, 3, 2);
        let band = to_pairs(&[(0, 1, 0.0), (1, 2, 0.0)]);
        let impulses = [[1.5, 0.0], [0.0, 0.0]];
        w.recorder(false)
            .record_pairs(&band, impulses.into_iter(), &[], &ids);
        w.record_wall(0, Surface::Floor, [0.0, 0.75]);
        w.record_wall(2, Surface::Floor, [0.0, 0.0]);
        assert_eq!(w.pair_start(0, 1), [1.5, 0.0]);
        assert_eq!(w.pair_start(1, 2), [0.0, 0.0]);
        assert_eq!(w.wall_start(0, Surface::Floor), [0.0, 0.75]);
        assert_eq!(w.wall_start(2, Surface::Floor), [0.0, 0.0]);
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
        let impulses =
            |band: &[(usize, usize, f64)]| band.iter().map(|p| both(p.2)).collect::<Vec<_>>();
        let (mut first, mut second) = split.recorder(false).split(2, bands[0].len());
        let later = impulses(&bands[1]);
        second.record_pairs(&to_pairs(&bands[1]), later.into_iter(), &[], &ids);
        let earlier = impulses(&bands[0]);
        first.record_pairs(&to_pairs(&bands[0]), earlier.into_iter(), &[], &ids);
        for a in 0..6 {
            for b in 0..6 {
                assert_eq!(split.pair(a, b), whole.pair(a, b), "balls {a} and {b}");
            }
        }
        assert_eq!(split.pair_start(ids[1], ids[3]), both(2.0));
        assert_eq!(split.pair_start(ids[3], ids[2]), both(5.0));
    }
}
