//! The same ball pit in Rapier (rapier3d 0.36, f32), for the side-by-side
//! benchmark against the rolypoly engine.
//!
//! Rapier gives a contact the friction of its two colliders combined by a
//! rule each collider names; where the two name different rules, the one
//! of higher priority wins (in rapier3d 0.36, from highest: `GeometricMean`,
//! `ClampedSum`, `Max`, `Multiply`, `Min`, `Average`). So that every pair
//! gets exactly the pit's coefficient, with no arithmetic to round:
//!
//! - balls have friction `ball_friction` and the rule `Average`: two balls
//!   average `ball_friction` with itself, which is `ball_friction`;
//! - walls have friction `wall_friction` and the rule `Max` where
//!   `wall_friction >= ball_friction`, `Min` where it is less: either
//!   outranks the balls' `Average`, and the larger (or smaller) of the two
//!   coefficients is then `wall_friction`.
//!
//! Restitution is the same on every collider, so the default `Average`
//! gives every pair the pit's. Rapier has no rolling resistance.

use glam::DVec3;
use rapier3d::prelude::*;

use crate::pit::{Pit, PitEngine};

/// Wall thickness: thick enough that no ball tunnels through at the pit's speeds.
const WALL: f32 = 1.0;

/// Converts to rapier's f32 vector component by component (rapier's glam may
/// be a different version from ours).
fn to_rapier(v: DVec3) -> Vector {
    Vector::new(v.x as f32, v.y as f32, v.z as f32)
}

fn from_rapier(v: Vector) -> DVec3 {
    DVec3::new(f64::from(v.x), f64::from(v.y), f64::from(v.z))
}

/// A Rapier world holding one pit.
pub struct RapierPit {
    pipeline: PhysicsPipeline,
    gravity: Vector,
    params: IntegrationParameters,
    islands: IslandManager,
    broad_phase: DefaultBroadPhase,
    narrow_phase: NarrowPhase,
    bodies: RigidBodySet,
    colliders: ColliderSet,
    impulse_joints: ImpulseJointSet,
    multibody_joints: MultibodyJointSet,
    soft_bodies: SoftBodySet,
    ccd: CCDSolver,
    /// The balls, in `Pit::start` order.
    balls: Vec<RigidBodyHandle>,
}

impl RapierPit {
    /// The pit as a Rapier world.
    pub fn new(pit: &Pit) -> RapierPit {
        let mut bodies = RigidBodySet::new();
        let mut colliders = ColliderSet::new();

        let half = to_rapier(pit.size * 0.5);
        let height = pit.size.y as f32;
        // Each slab extends WALL past the inner corners so the edges overlap.
        let slabs = [
            // Floor and ceiling.
            (
                Vector::new(half.x + WALL, WALL * 0.5, half.z + WALL),
                Vector::new(0.0, -WALL * 0.5, 0.0),
            ),
            (
                Vector::new(half.x + WALL, WALL * 0.5, half.z + WALL),
                Vector::new(0.0, height + WALL * 0.5, 0.0),
            ),
            // x = ±size.x / 2.
            (
                Vector::new(WALL * 0.5, half.y + WALL, half.z + WALL),
                Vector::new(-(half.x + WALL * 0.5), half.y, 0.0),
            ),
            (
                Vector::new(WALL * 0.5, half.y + WALL, half.z + WALL),
                Vector::new(half.x + WALL * 0.5, half.y, 0.0),
            ),
            // z = ±size.z / 2.
            (
                Vector::new(half.x + WALL, half.y + WALL, WALL * 0.5),
                Vector::new(0.0, half.y, -(half.z + WALL * 0.5)),
            ),
            (
                Vector::new(half.x + WALL, half.y + WALL, WALL * 0.5),
                Vector::new(0.0, half.y, half.z + WALL * 0.5),
            ),
        ];
        // See the module's documentation for how the rules give each pair its
        // coefficient.
        let wall_rule = if pit.wall_friction >= pit.ball_friction {
            CoefficientCombineRule::Max
        } else {
            CoefficientCombineRule::Min
        };
        for (half_extents, centre) in slabs {
            colliders.insert(
                ColliderBuilder::cuboid(half_extents.x, half_extents.y, half_extents.z)
                    .translation(centre)
                    .restitution(pit.restitution as f32)
                    .friction(pit.wall_friction as f32)
                    .friction_combine_rule(wall_rule),
            );
        }

        let balls = pit
            .start
            .iter()
            .map(|start| {
                let body = bodies.insert(
                    RigidBodyBuilder::dynamic()
                        .translation(to_rapier(start.position))
                        .linvel(to_rapier(start.velocity)),
                );
                colliders.insert_with_parent(
                    ColliderBuilder::ball(pit.radius as f32)
                        .mass(pit.mass as f32)
                        .restitution(pit.restitution as f32)
                        .friction(pit.ball_friction as f32)
                        .friction_combine_rule(CoefficientCombineRule::Average),
                    body,
                    &mut bodies,
                );
                body
            })
            .collect();

        RapierPit {
            pipeline: PhysicsPipeline::new(),
            gravity: Vector::new(0.0, -pit.gravity as f32, 0.0),
            params: IntegrationParameters {
                dt: pit.dt as f32,
                ..IntegrationParameters::default()
            },
            islands: IslandManager::new(),
            broad_phase: DefaultBroadPhase::new(),
            narrow_phase: NarrowPhase::new(),
            bodies,
            colliders,
            impulse_joints: ImpulseJointSet::new(),
            multibody_joints: MultibodyJointSet::new(),
            soft_bodies: SoftBodySet::new(),
            ccd: CCDSolver::new(),
            balls,
        }
    }
}

impl RapierPit {
    /// The engine's name, as the table prints it.
    pub const NAME: &'static str = "rapier3d 0.36";
}

impl PitEngine for RapierPit {
    fn name(&self) -> String {
        Self::NAME.to_string()
    }

    fn step(&mut self) {
        self.pipeline.step(
            self.gravity,
            &self.params,
            &mut self.islands,
            &mut self.broad_phase,
            &mut self.narrow_phase,
            &mut self.bodies,
            &mut self.colliders,
            &mut self.impulse_joints,
            &mut self.multibody_joints,
            &mut self.soft_bodies,
            &mut self.ccd,
            &(),
            &(),
        );
    }

    fn read(&self, positions: &mut Vec<DVec3>, velocities: &mut Vec<DVec3>) {
        positions.clear();
        velocities.clear();
        for &handle in &self.balls {
            let body = &self.bodies[handle];
            positions.push(from_rapier(body.translation()));
            velocities.push(from_rapier(body.linvel()));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pit::Start;

    /// The friction Rapier gave each contact pair after a step of two
    /// touching balls resting on the floor: (ball-ball, ball-wall).
    fn pair_frictions(ball_friction: f64, wall_friction: f64) -> (Vec<f32>, Vec<f32>) {
        let still = |x| Start {
            position: DVec3::new(x, 0.1, 0.0),
            velocity: DVec3::ZERO,
        };
        let pit = Pit {
            radius: 0.1,
            mass: 1.0,
            restitution: 0.5,
            wall_friction,
            ball_friction,
            gravity: 9.81,
            dt: 1.0 / 60.0,
            size: DVec3::new(1.0, 1.0, 1.0),
            start: vec![still(-0.1), still(0.1)],
        };
        let mut engine = RapierPit::new(&pit);
        engine.step();
        let is_ball = |h: ColliderHandle| engine.colliders[h].parent().is_some();
        let (mut between_balls, mut on_walls) = (Vec::new(), Vec::new());
        for pair in engine.narrow_phase.contact_pairs() {
            for manifold in pair
                .solver_manifolds()
                .iter()
                .filter(|m| !m.points.is_empty())
            {
                match (is_ball(pair.collider1), is_ball(pair.collider2)) {
                    (true, true) => between_balls.push(manifold.data.friction),
                    (false, false) => {}
                    _ => on_walls.push(manifold.data.friction),
                }
            }
        }
        (between_balls, on_walls)
    }

    #[test]
    fn every_pair_gets_the_pits_friction() {
        for (ball, wall) in [(0.0, 0.5), (0.5, 0.5), (0.3, 0.5), (0.9, 0.5), (0.5, 0.0)] {
            let (between_balls, on_walls) = pair_frictions(ball, wall);
            assert_eq!(between_balls, [ball as f32], "ball {ball}, wall {wall}");
            assert_eq!(on_walls, [wall as f32; 2], "ball {ball}, wall {wall}");
        }
    }

    #[test]
    fn ball_falls_freely_then_rests_on_floor() {
        let pit = Pit {
            radius: 0.1,
            mass: 1.0,
            restitution: 0.5,
            wall_friction: 0.5,
            ball_friction: 0.0,
            gravity: 9.81,
            dt: 1.0 / 60.0,
            size: DVec3::new(1.0, 2.0, 1.0),
            start: vec![Start {
                position: DVec3::new(0.0, 1.0, 0.0),
                velocity: DVec3::ZERO,
            }],
        };
        let mut engine = RapierPit::new(&pit);
        let (mut positions, mut velocities) = (Vec::new(), Vec::new());

        for _ in 0..18 {
            engine.step();
        }
        engine.read(&mut positions, &mut velocities);
        let free_fall = 1.0 - 0.5 * 9.81 * 0.3 * 0.3;
        assert!(
            (positions[0].y - free_fall).abs() < 0.02,
            "y after 0.3 s: {}, free fall: {free_fall}",
            positions[0].y
        );

        for _ in 18..180 {
            engine.step();
        }
        engine.read(&mut positions, &mut velocities);
        assert_eq!(positions.len(), 1);
        assert_eq!(velocities.len(), 1);
        assert!(
            (positions[0].y - 0.1).abs() < 0.01,
            "y after 3 s: {}",
            positions[0].y
        );
    }
}
