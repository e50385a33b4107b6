//! What the last step did inside, for the debug views: the contacts the
//! solver pushed at, with their impulses, and the broadphase's occupied
//! cells. Read-only, and built only when asked for: a step keeps what it
//! needs for its own warm start, and these are read from that.

use glam::DVec3;

use super::World;
use crate::contact::BodyRef;
use crate::room::Surface;

/// Which bodies a contact joins.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ContactKind {
    /// Two balls.
    BallBall,
    /// A ball and one of the room's surfaces.
    BallWall,
    /// A ball and a tumbler.
    BallTumbler,
    /// A tumbler on the floor (its rolling contact) or against a wall.
    TumblerFloor,
    /// Two tumblers.
    TumblerTumbler,
}

/// One contact the last step's solver pushed at.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactProbe {
    /// Which bodies it joins.
    pub kind: ContactKind,
    /// The balls it joins, by number (the second only for two balls).
    pub balls: [Option<usize>; 2],
    /// Whether it pushed in the step before too (the solver started from
    /// that impulse); if not, it is new.
    pub kept: bool,
    /// Where it acts: on the first body's surface (m).
    pub point: DVec3,
    /// Unit normal from the second body towards the first.
    pub normal: DVec3,
    /// The normal impulse over the step, both solver stages (N s).
    pub impulse: f64,
    /// The friction impulse over the step on the first body (N s), where
    /// friction was kept.
    pub friction: DVec3,
}

impl World {
    /// The contacts the last step's solver pushed at, in a fixed order:
    /// ball pairs by ball number, balls on walls, contacts of tumblers,
    /// then each tumbler's rolling contact with the floor. Impacts resolved
    /// one by one in time order before the solver are the step's events.
    pub fn contact_probes(&self) -> Vec<ContactProbe> {
        let balls = &self.balls;
        let total = |held: [f32; 2]| f64::from(held[0]) + f64::from(held[1]);
        let mut probes = Vec::new();
        for (a, b, held, friction) in self.warm.recorded_pairs() {
            let (i, j) = (a as usize, b as usize);
            let Some(normal) = (balls.position[i] - balls.position[j]).try_normalize() else {
                continue;
            };
            probes.push(ContactProbe {
                kind: ContactKind::BallBall,
                balls: [Some(i), Some(j)],
                kept: total(self.warm_next.pair(a, b)) > 0.0,
                point: balls.position[i] - normal * balls.radius[i],
                normal,
                impulse: total(held),
                friction: friction.as_dvec3(),
            });
        }
        for (a, surface, held) in self.warm.recorded_walls() {
            let i = a as usize;
            let normal = surface.inward_normal();
            probes.push(ContactProbe {
                kind: ContactKind::BallWall,
                balls: [Some(i), None],
                kept: total(self.warm_next.wall(a, surface)) > 0.0,
                point: balls.position[i] - normal * balls.radius[i],
                normal,
                impulse: total(held),
                friction: DVec3::ZERO,
            });
        }
        // Contacts with tumblers name balls by their slot in the step's
        // order of space.
        let order = self.grid.order();
        let ball_of = |slot: usize| order.get(slot).map(|&id| id as usize);
        for c in &self.contacts.tumbler_contacts {
            let impulse = c.pushed + c.impulse;
            if impulse <= 0.0 {
                continue;
            }
            let (kind, first) = match (c.a, c.b) {
                (BodyRef::Ball(slot), _) | (_, BodyRef::Ball(slot)) => {
                    (ContactKind::BallTumbler, ball_of(slot))
                }
                (BodyRef::Tumbler(..), BodyRef::Tumbler(..)) => (ContactKind::TumblerTumbler, None),
                _ => (ContactKind::TumblerFloor, None),
            };
            probes.push(ContactProbe {
                kind,
                balls: [first, None],
                kept: c.gap <= 0.0,
                point: c.point,
                normal: c.normal,
                impulse,
                friction: DVec3::ZERO,
            });
        }
        let weight_impulse = self.shape.mass * self.config.gravity * self.config.solver.dt;
        // A tumbler always stands on the floor, which carries its weight.
        for t in &self.tumblers {
            probes.push(ContactProbe {
                kind: ContactKind::TumblerFloor,
                balls: [None, None],
                kept: true,
                point: t.contact_point(),
                normal: Surface::Floor.inward_normal(),
                impulse: weight_impulse,
                friction: DVec3::ZERO,
            });
        }
        probes
    }

    /// The broadphase grid's cells that hold a ball, each by its lowest
    /// corner, and the cells' edge (m).
    pub fn occupied_cells(&self) -> (Vec<DVec3>, f64) {
        self.grid.occupied_cells()
    }
}
