//! The GPU engine's impacts, as the CPU engine reports them: where, how
//! fast, with what and when; and as many a second on the default scene.

mod common;

use common::*;
use glam::DVec3;
use rolypoly_physics::{Event, EventKind, Surface, World, WorldConfig};

/// The impacts a listening engine reported over `steps` steps.
fn gpu_impacts(config: WorldConfig, seed: u64, steps: u32) -> Vec<Event> {
    let compute = compute();
    let (mut world, mut balls) = build(&compute, config, seed);
    balls.listen(true);
    let mut events = Vec::new();
    for _ in 0..steps {
        step(&mut world, &mut balls);
        balls.take_events(&mut events);
    }
    balls.take_events_in_flight().unwrap();
    balls.take_events(&mut events);
    assert_eq!(balls.impacts_dropped(), 0);
    events.retain(|e| is_impact(&e.kind));
    events
}

fn is_impact(kind: &EventKind) -> bool {
    matches!(
        kind,
        EventKind::BallSurface { .. } | EventKind::BallBall { .. } | EventKind::BallTumbler { .. }
    )
}

#[test]
fn a_dropped_ball_reports_each_bounce_on_the_floor_at_its_speed() {
    for (drop, e) in [(1.0, 0.8), (0.5, 0.6)] {
        let mut config = empty_room(DVec3::new(2.0, 3.0, 2.0), 0);
        config.room.restitution = e;
        let r = config.balls.radius;
        config.balls.placements = vec![placed(DVec3::new(0.0, r + drop, 0.0), DVec3::ZERO)];
        let dt = config.solver.dt;
        let g = config.gravity;
        let events = gpu_impacts(config, 1, 240);
        assert!(events.len() >= 2, "{drop} m: {events:?}");
        // The first lands at the speed of its fall, the next at e times it.
        let fall = (2.0 * g * drop).sqrt();
        for (k, event) in events.iter().take(2).enumerate() {
            assert!(
                matches!(
                    event.kind,
                    EventKind::BallSurface {
                        ball: 0,
                        surface: Surface::Floor
                    }
                ),
                "{event:?}"
            );
            let expected = fall * e.powi(k as i32);
            assert!(
                (event.speed - expected).abs() < 0.02 * expected,
                "{drop} m, bounce {k}: {} m/s against {expected}",
                event.speed
            );
            assert!((event.normal - DVec3::Y).length() < 1e-6, "{event:?}");
            assert!(event.point.y.abs() < 1e-3, "on the floor: {event:?}");
            assert!((0.0..=dt).contains(&event.within_step), "{event:?}");
        }
    }
}

#[test]
fn two_balls_meeting_head_on_report_one_impact_at_their_closing_speed() {
    for speed in [1.0, 3.0] {
        let mut config = empty_room(DVec3::new(4.0, 4.0, 4.0), 0);
        config.gravity = 0.0;
        config.balls.restitution = 1.0;
        let y = 2.0;
        config.balls.placements = vec![
            placed(DVec3::new(-0.5, y, 0.0), DVec3::new(speed, 0.0, 0.0)),
            placed(DVec3::new(0.5, y, 0.0), DVec3::new(-speed, 0.0, 0.0)),
        ];
        let events = gpu_impacts(config, 1, 60);
        let pairs: Vec<&Event> = events
            .iter()
            .filter(|e| matches!(e.kind, EventKind::BallBall { .. }))
            .collect();
        assert_eq!(pairs.len(), 1, "{speed} m/s: {events:?}");
        let hit = pairs[0];
        assert!(
            matches!(hit.kind, EventKind::BallBall { a: 0, b: 1 }),
            "{hit:?}"
        );
        assert!((hit.speed - 2.0 * speed).abs() < 0.01 * speed, "{hit:?}");
        // From ball 1 towards ball 0, at the middle.
        assert!((hit.normal + DVec3::X).length() < 1e-3, "{hit:?}");
        assert!(hit.point.x.abs() < 0.01, "{hit:?}");
    }
}

/// Impacts a second of the CPU engine on `config`, over `steps` steps.
fn cpu_impacts(config: WorldConfig, seed: u64, steps: u32) -> usize {
    let mut world = World::new(config, seed).expect("the scene builds");
    let (mut events, mut impacts) = (Vec::new(), 0);
    for _ in 0..steps {
        world.step();
        world.take_events(&mut events);
        impacts += events.iter().filter(|e| is_impact(&e.kind)).count();
    }
    impacts
}

#[test]
fn a_rerun_reports_the_same_impacts_in_the_same_order() {
    // Five tumblers and the fireball among 300 balls: many impacts at one
    // moment, appended by the atomics in any order.
    let mut config = WorldConfig::default();
    config.balls.count = 300;
    config.fireball.starts_active = true;
    for seed in [1, 4] {
        let first = gpu_impacts(config.clone(), seed, 240);
        assert!(first.len() > 100, "seed {seed}: {} impacts", first.len());
        let again = gpu_impacts(config.clone(), seed, 240);
        let differ = first.iter().zip(&again).position(|(a, b)| a != b);
        assert!(
            first.len() == again.len() && differ.is_none(),
            "seed {seed}: {} then {} impacts, first differing {differ:?}: {:?} against {:?}",
            first.len(),
            again.len(),
            differ.map(|k| first[k]),
            differ.map(|k| again[k])
        );
    }
}

#[test]
fn the_default_scene_sounds_as_often_as_on_the_cpu_engine() {
    let steps = 600; // 5 s
    for seed in [1, 2, 3] {
        let gpu = gpu_impacts(WorldConfig::default(), seed, steps).len();
        let cpu = cpu_impacts(WorldConfig::default(), seed, steps);
        let seconds = f64::from(steps) * WorldConfig::default().solver.dt;
        eprintln!(
            "seed {seed}: {:.1} impacts a second on the GPU engine, {:.1} on the CPU engine",
            gpu as f64 / seconds,
            cpu as f64 / seconds
        );
        assert!(cpu > 50, "seed {seed}: {cpu} on the CPU");
        let off = (gpu as f64 - cpu as f64).abs() / cpu as f64;
        assert!(off < 0.15, "seed {seed}: {gpu} against {cpu}");
    }
}
