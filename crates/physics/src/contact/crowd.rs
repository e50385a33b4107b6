//! Which contacts act on each body in a stage: a lone impact may bounce,
//! a crowded one may not.

use crate::balls::PARALLEL_LIGHT_PASSES;
use glam::DVec3;
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};

use super::{BodyRef, Contact, Contacts, Pair, WallContact};

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
    /// Forgets which balls the project stage will ask about.
    pub(super) fn forget_asked(&mut self, balls: usize) {
        self.asked.resize_with(balls, AtomicBool::default);
        self.asked.iter_mut().for_each(|a| *a.get_mut() = false);
    }

    /// Notes that the project stage may ask about ball `i`.
    pub(super) fn will_ask(&self, i: u32) {
        self.asked[i as usize].store(true, Ordering::Relaxed);
    }

    pub(super) fn asked(&self, i: usize) -> bool {
        self.asked[i].load(Ordering::Relaxed)
    }

    /// Restarts the crowds of every ball, or with `only_asked` of the balls
    /// noted by [`Crowd::will_ask`], and gathers their pairs that `counts`
    /// picks, on all threads: a ball's list is a set, so the order in which
    /// pairs join it does not matter. Restarts the tumblers' counts too.
    /// Balls left out keep a stale crowd.
    pub(super) fn gather<F>(
        &mut self,
        contacts: &mut Contacts,
        tumblers: usize,
        only_asked: bool,
        counts: F,
    ) where
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
        if self.balls.len() >= PARALLEL_LIGHT_PASSES {
            self.balls.par_iter_mut().enumerate().for_each(restart);
        } else {
            self.balls.iter_mut().enumerate().for_each(restart);
        }
        self.tumbler_count.clear();
        self.tumbler_count.resize(tumblers, 0);
        if only_asked && !asked.iter().any(|a| a.load(Ordering::Relaxed)) {
            return;
        }
        contacts.sweep_pairs(&mut self.balls, &|p, balls, first| {
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

    pub(super) fn add(&mut self, c: &Contact) {
        self.add_to(c, false);
    }

    /// As [`Crowd::add`], for the balls noted by [`Crowd::will_ask`].
    pub(super) fn add_if_asked(&mut self, c: &Contact) {
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

    pub(super) fn add_wall(&mut self, c: &WallContact) {
        let wall = other_side(BodyRef::Wall(c.surface));
        self.balls[c.ball as usize].add(wall, c.normal());
    }

    /// Whether wall contact `c` is the only contact coupled to its ball.
    pub(super) fn lone_wall(&self, c: &WallContact) -> bool {
        debug_assert!(self.asked(c.ball as usize));
        let wall = other_side(BodyRef::Wall(c.surface));
        self.balls[c.ball as usize].lone(wall, c.normal())
    }

    /// Whether pair `p` is the only contact coupled to its two balls.
    pub(super) fn lone_pair(&self, p: &Pair) -> bool {
        debug_assert!(self.asked(p.i as usize) && self.asked(p.j as usize));
        self.balls[p.i as usize].lone(p.j, p.normal) && self.balls[p.j as usize].lone(p.i, p.normal)
    }

    /// Whether contact `c` is the only one coupled to its bodies.
    pub(super) fn lone(&self, c: &Contact) -> bool {
        [(c.a, c.b), (c.b, c.a)]
            .into_iter()
            .all(|(body, other)| match body {
                BodyRef::Ball(i) => self.balls[i].lone(other_side(other), c.normal),
                BodyRef::Tumbler(t, _) => self.tumbler_count[t] == 1,
                BodyRef::Wall(_) => true,
            })
    }
}
