//! What the sound costs: the synthesis' time per second of audio made, on
//! one core, beside the physics' own time for the same steps.
//!
//! Run with `cargo bench -p rolypoly-sound --bench synthesis`. Prints one
//! row per scene: the seconds of audio, the synthesis' time, its share of
//! one core (time per second of audio), the physics' time for the same
//! steps, the strikes voiced and merged into the crowd's bed, and the
//! loudest sample before the limiter.

use std::time::{Duration, Instant};

use glam::DVec3;
use rolypoly_physics::{World, WorldConfig};
use rolypoly_sound::{Listener, SoundConfig, Soundtrack};

struct Case {
    name: &'static str,
    config: WorldConfig,
    fireball_at: Option<f64>,
    seconds: f64,
}

/// The ball pit of scenes/ballpit-10k.toml: 10 000 balls dropped around
/// the tumblers.
fn pit() -> WorldConfig {
    let mut config = WorldConfig::default();
    config.room.size = DVec3::new(10.0, 5.0, 10.0);
    config.room.restitution = 0.8;
    config.balls.count = 10_000;
    config.balls.radius = 0.1;
    config.balls.mass = 1.0;
    config.balls.restitution = 0.8;
    config.balls.speed_min = 0.0;
    config.balls.speed_max = 1.0;
    config.balls.start_fill = 0.4;
    config
}

fn main() {
    let cases = [
        Case {
            name: "default scene, fireball at 2 s",
            config: WorldConfig::default(),
            fireball_at: Some(2.0),
            seconds: 10.0,
        },
        Case {
            name: "10k pit, its landing",
            config: pit(),
            fireball_at: None,
            seconds: 2.0,
        },
    ];
    println!(
        "{:<32} {:>7} {:>10} {:>8} {:>10} {:>8} {:>8} {:>8}",
        "scene", "audio s", "sound ms", "of core", "physics ms", "voiced", "bedded", "peak"
    );
    for case in cases {
        let mut world = World::new(case.config, 1).unwrap();
        let size = world.room().size();
        let ear = Listener {
            position: DVec3::new(0.0, 1.6, 0.45 * size.z),
            forward: -DVec3::Z,
        };
        let mut sound = Soundtrack::new(&SoundConfig::default(), &world);
        let mut events = Vec::new();
        let (mut synthesis, mut physics) = (Duration::ZERO, Duration::ZERO);
        let steps = (case.seconds / world.config().solver.dt).round() as usize;
        for _ in 0..steps {
            if case
                .fireball_at
                .is_some_and(|t| (world.time() - t).abs() < 1e-9)
            {
                world.launch_fireball(None);
            }
            let started = Instant::now();
            world.step();
            physics += started.elapsed();
            world.take_events(&mut events);
            let started = Instant::now();
            sound.hear_step(&world, &events, &ear);
            synthesis += started.elapsed();
            sound.take_frames();
        }
        let (voiced, bedded) = sound.strikes();
        println!(
            "{:<32} {:>7.1} {:>10.1} {:>7.1}% {:>10.1} {:>8} {:>8} {:>8.3}",
            case.name,
            case.seconds,
            synthesis.as_secs_f64() * 1e3,
            100.0 * synthesis.as_secs_f64() / case.seconds,
            physics.as_secs_f64() * 1e3,
            voiced,
            bedded,
            sound.loudest,
        );
    }
}
