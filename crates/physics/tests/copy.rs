//! A copy of the world steps on to the same bits as the world: what the
//! sandbox's rewind keeps to go back to.

mod common;

use common::{build, crowded_pit, state_bits};
use glam::DVec3;
use rolypoly_physics::{World, WorldConfig};

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
