//! Step-time benchmark: the default scene, and the same room with many balls.
//!
//! Run with `cargo bench -p rolypoly-physics --bench step`. Prints one row
//! per scene: the mean wall time of a step after a warm-up, steps per
//! second, and ball-steps per second (how many ball updates the engine does
//! per second).

use glam::DVec3;
use rolypoly_physics::{World, WorldConfig};
use std::time::Instant;

struct Case {
    name: &'static str,
    config: WorldConfig,
    fireball: bool,
    seconds: f64,
}

fn case(name: &'static str, balls: usize, room: DVec3, fireball: bool, seconds: f64) -> Case {
    let mut config = WorldConfig::default();
    config.balls.count = balls;
    config.room.size = room;
    Case {
        name,
        config,
        fireball,
        seconds,
    }
}

fn main() {
    let default_room = WorldConfig::default().room.size;
    let cases = [
        case(
            "default scene (30 balls, 5 tumblers)",
            30,
            default_room,
            false,
            10.0,
        ),
        case("default scene + fireball", 30, default_room, true, 10.0),
        case("1k balls, default room", 1_000, default_room, false, 3.0),
        case(
            "10k balls, 16 x 6 x 16 m room",
            10_000,
            DVec3::new(16.0, 6.0, 16.0),
            false,
            1.0,
        ),
    ];
    println!(
        "{:<40} {:>8} {:>12} {:>12} {:>16}",
        "scene", "steps", "us/step", "steps/s", "ball-steps/s"
    );
    for c in cases {
        let balls = c.config.balls.count;
        let dt = c.config.solver.dt;
        let mut world = match World::new(c.config, 1) {
            Ok(w) => w,
            Err(e) => {
                eprintln!("{}: {e}", c.name);
                std::process::exit(1);
            }
        };
        if c.fireball {
            world.launch_fireball(None);
        }
        // Warm up: let the balls spread and the buffers reach their size.
        for _ in 0..60 {
            world.step();
            world.drain_events().for_each(drop);
        }
        let steps = (c.seconds / dt) as usize;
        let start = Instant::now();
        for _ in 0..steps {
            world.step();
            world.drain_events().for_each(drop);
        }
        let elapsed = start.elapsed().as_secs_f64();
        let per_step = elapsed / steps as f64;
        println!(
            "{:<40} {:>8} {:>12.1} {:>12.0} {:>16.3e}",
            c.name,
            steps,
            per_step * 1e6,
            1.0 / per_step,
            balls as f64 / per_step
        );
    }
}
