//! The pit in the rolypoly engine.

use glam::DVec3;
use rolypoly_physics::{World, WorldConfig};

use crate::pit::{Pit, PitEngine};

/// The pit as a rolypoly world.
pub struct OurPit {
    world: World,
}

impl OurPit {
    /// The pit as a rolypoly world (see [`world_for`]).
    pub fn new(pit: &Pit) -> Result<OurPit, String> {
        Ok(OurPit {
            world: world_for(pit)?,
        })
    }

    /// The world, to measure its quality.
    pub fn world(&self) -> &World {
        &self.world
    }
}

/// Builds the pit as a rolypoly scene: no tumblers, no fireball, no
/// rolling resistance (Rapier has none), the pit's materials and step,
/// every ball where the pit starts it. Both of our engines start from it.
pub fn world_for(pit: &Pit) -> Result<World, String> {
    let mut config = WorldConfig::default();
    config.tumblers.placements.clear();
    config.fireball.starts_active = false;
    config.gravity = pit.gravity;
    config.solver.dt = pit.dt;
    config.room.size = pit.size;
    config.room.restitution = pit.restitution;
    config.room.friction = pit.wall_friction;
    config.room.rolling_resistance = 0.0;
    config.balls.count = pit.start.len();
    config.balls.radius = pit.radius;
    config.balls.mass = pit.mass;
    config.balls.restitution = pit.restitution;
    config.balls.friction = pit.ball_friction;
    // Rapier has no rolling resistance, so neither pit has any: not
    // between balls, not on the walls.
    config.balls.rolling_resistance = 0.0;
    // Every ball starts at once, where the pit puts it: none is poured.
    config.balls.pour.rate = 0.0;
    let mut world = World::new(config, 1).map_err(|e| e.to_string())?;
    for (i, s) in pit.start.iter().enumerate() {
        world.balls_mut().set(i, s.position, s.velocity);
    }
    Ok(world)
}

impl PitEngine for OurPit {
    fn name(&self) -> String {
        "rolypoly".into()
    }

    fn step(&mut self) {
        self.world.step();
        // Events are the product's business; the pit does not read them.
        self.world.drain_events().for_each(drop);
    }

    fn read(&self, positions: &mut Vec<DVec3>, velocities: &mut Vec<DVec3>) {
        positions.clear();
        positions.extend_from_slice(self.world.balls().positions());
        velocities.clear();
        velocities.extend_from_slice(self.world.balls().velocities());
    }
}
