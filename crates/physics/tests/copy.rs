//! A copy of the world steps on to the same bits as the world: what the
//! sandbox's rewind keeps to go back to.

mod common;

use common::{build, crowded_pit, state_bits};
use glam::DVec3;
use rolypoly_physics::{StateError, World, WorldConfig};

fn run(world: &mut World, steps: usize) {
    for _ in 0..steps {
        world.step();
    }
}

#[test]
fn a_copy_taken_mid_run_steps_on_to_the_same_bits() {
    let mut pit = crowded_pit();
    pit.balls.count = 1500;
    let scenes: [(WorldConfig, u64, bool); 3] = [
        (WorldConfig::default(), 1, true),
        (WorldConfig::default(), 7, false),
        (pit, 3, false),
    ];
    for (cfg, seed, fireball) in scenes {
        let mut world = build(cfg, seed);
        if fireball {
            world.launch_fireball(None);
        }
        run(&mut world, 90);
        // Held by the hand too, where there are balls.
        world.hold_ball(0);
        world.drag_to(DVec3::new(0.5, 1.5, 0.5));
        run(&mut world, 10);
        let mut copy = world.clone();
        assert_eq!(state_bits(&copy), state_bits(&world));
        run(&mut world, 150);
        run(&mut copy, 150);
        assert_eq!(state_bits(&copy), state_bits(&world), "seed {seed}");
        assert_eq!(copy.held_ball(), world.held_ball());
    }
}

/// A pit that pours its balls from a spout, so that a state is taken while
/// some are still to come.
fn pouring_pit(count: usize) -> WorldConfig {
    let mut cfg = crowded_pit();
    cfg.balls.count = count;
    cfg.balls.pour.rate = 400.0;
    cfg.balls.pour.spout = DVec3::new(0.0, 2.5, 0.0);
    cfg.balls.pour.radius = 0.5;
    cfg
}

#[test]
fn a_world_of_the_same_scene_takes_on_a_state_and_steps_on_to_the_same_bits() {
    let mut settled = crowded_pit();
    settled.balls.count = 800;
    // Lying in a heap by then, held by the warm start.
    let scenes: [(WorldConfig, u64, bool, usize); 5] = [
        (WorldConfig::default(), 1, true, 60),
        (WorldConfig::default(), 11, false, 200),
        (pouring_pit(600), 5, false, 45),
        (pouring_pit(2000), 9, true, 120),
        (settled, 4, false, 400),
    ];
    for (cfg, seed, fireball, before) in scenes {
        let mut world = build(cfg.clone(), seed);
        if fireball {
            world.launch_fireball(None);
        }
        run(&mut world, before);
        world.hold_ball(0);
        world.drag_to(DVec3::new(0.3, 1.2, -0.4));
        run(&mut world, 5);
        let state = world.state();
        // Another world of the scene, made from another seed and stepped
        // elsewhere: everything that differs is the state's to set.
        let mut other = build(cfg, seed + 100);
        run(&mut other, 3);
        other.set_state(state).expect("a state of the same scene");
        assert_eq!(state_bits(&other), state_bits(&world), "seed {seed}");
        run(&mut world, 120);
        run(&mut other, 120);
        assert_eq!(state_bits(&other), state_bits(&world), "seed {seed}");
        assert_eq!(other.held_ball(), world.held_ball());
        assert_eq!(other.time().to_bits(), world.time().to_bits());
        assert_eq!(other.step_count(), world.step_count());
    }
}

#[test]
fn a_state_of_another_scene_is_refused_and_changes_nothing() {
    let mut tumblers = build(WorldConfig::default(), 2);
    run(&mut tumblers, 20);
    let mut empty = build(common::empty_room(), 2);
    run(&mut empty, 20);
    let before = state_bits(&empty);
    let refused = empty.set_state(tumblers.state());
    assert!(
        matches!(refused, Err(StateError::Tumblers { state: 5, scene: 0 })),
        "{refused:?}"
    );
    assert!(refused.unwrap_err().to_string().contains("another scene"));
    assert_eq!(state_bits(&empty), before);
}
