//! Scene builders shared by the scenario tests.
#![allow(dead_code)]

use glam::DVec3;
use rolypoly_physics::{TumblerPlacement, World, WorldConfig};

/// The default scene with nothing in it: no balls, no tumblers.
pub fn empty_room() -> WorldConfig {
    let mut cfg = WorldConfig::default();
    cfg.balls.count = 0;
    cfg.tumblers.placements.clear();
    cfg
}

/// The default room with every loss switched off and `n` balls in it:
/// restitution 1 for balls and room, no friction or rolling resistance,
/// every impact bouncing.
pub fn elastic_room(n: usize, gravity: f64) -> WorldConfig {
    let mut cfg = empty_room();
    cfg.gravity = gravity;
    cfg.balls.count = n;
    cfg.balls.restitution = 1.0;
    cfg.room.restitution = 1.0;
    cfg.room.friction = 0.0;
    cfg.balls.friction = 0.0;
    cfg.balls.rolling_resistance = 0.0;
    cfg.room.rolling_resistance = 0.0;
    cfg.solver.bounce_threshold = 0.0;
    cfg
}

/// Enough balls in a small room that contacts are found and solved on
/// several threads (both solver stages switch at a few thousand).
pub fn crowded_pit() -> WorldConfig {
    let mut cfg = WorldConfig::default();
    cfg.room.size = DVec3::new(4.0, 3.0, 4.0);
    cfg.tumblers.placements.clear();
    cfg.balls.count = 3000;
    cfg.balls.radius = 0.08;
    cfg
}

pub fn tumbler_at(x: f64, z: f64, tilt_axis: DVec3, tilt_deg: f64) -> TumblerPlacement {
    TumblerPlacement {
        x,
        z,
        tilt_axis,
        tilt_deg,
    }
}

pub fn build(cfg: WorldConfig, seed: u64) -> World {
    match World::new(cfg, seed) {
        Ok(w) => w,
        Err(e) => panic!("scene does not build: {e}"),
    }
}

/// A world with `n` balls, all placed by the caller.
pub fn with_balls(mut cfg: WorldConfig, n: usize) -> World {
    cfg.balls.count = n;
    build(cfg, 1)
}

/// Every number that describes the world's state, for bit-exact comparison.
pub fn state_bits(w: &World) -> Vec<u64> {
    let mut out = Vec::new();
    let b = w.balls();
    for i in 0..b.len() {
        for v in [b.positions()[i], b.velocities()[i], b.spins()[i]] {
            out.extend(v.to_array().map(f64::to_bits));
        }
        out.push(b.alive()[i] as u64);
    }
    for t in w.tumblers() {
        out.extend(t.center_of_mass().to_array().map(f64::to_bits));
        out.extend(t.orientation().to_array().map(f64::to_bits));
        out.extend(t.angular_velocity().to_array().map(f64::to_bits));
        out.extend(t.linear_velocity().to_array().map(f64::to_bits));
    }
    if let Some(f) = w.fireball() {
        out.extend(f.position.to_array().map(f64::to_bits));
        out.extend(f.velocity.to_array().map(f64::to_bits));
    }
    out
}
