//! A run's state as bytes: a simulation made elsewhere from the same scene
//! takes them on and steps on to the same bits; bytes that are not such a
//! state are refused by name.

use rolypoly_core::scene::{Scene, load_scene};
use rolypoly_core::simulation::Simulation;
use rolypoly_core::snapshot::{SimulationState, SnapshotError, decode, encode};
use rolypoly_physics::World;

fn simulation(scene: &Scene, seed: u64) -> Simulation {
    let world = World::new(scene.world.clone(), seed).expect("the scene builds");
    Simulation::new(world, scene.effects.clone(), seed)
}

fn ticks(sim: &mut Simulation, n: usize) {
    for _ in 0..n {
        sim.tick();
    }
}

/// The default scene with `balls` balls.
fn scene_with(balls: usize) -> Scene {
    let mut scene = load_scene(None).expect("the built-in scene");
    scene.world.balls.count = balls;
    scene
}

#[test]
fn a_simulation_made_elsewhere_takes_on_the_bytes_and_steps_on_to_the_same_bits() {
    for (balls, seed, fireball, before) in
        [(30, 1, true, 150), (30, 8, false, 40), (600, 3, true, 240)]
    {
        let scene = scene_with(balls);
        let mut here = simulation(&scene, seed);
        if fireball {
            // Its trail and hits fill the effects' state.
            here.world.launch_fireball(None);
        }
        ticks(&mut here, before);
        let bytes = encode(&here.state());

        let mut there = simulation(&scene, seed);
        let state: SimulationState = decode(&bytes).expect("bytes just written");
        there.set_state(state).expect("a state of the same scene");
        assert_eq!(encode(&there.state()), bytes, "{balls} balls, seed {seed}");
        assert_eq!(there.fx.stats(), here.fx.stats());

        ticks(&mut here, 90);
        ticks(&mut there, 90);
        assert_eq!(
            encode(&there.state()),
            encode(&here.state()),
            "{balls} balls, seed {seed}: stepped on from the bytes"
        );
        assert_eq!(there.world.time().to_bits(), here.world.time().to_bits());
    }
}

#[test]
fn bytes_that_are_no_state_of_this_program_are_refused_by_name() {
    let scene = scene_with(30);
    let mut sim = simulation(&scene, 2);
    ticks(&mut sim, 10);
    let bytes = encode(&sim.state());

    let not = decode::<SimulationState>(b"PK\x03\x04 a zip file").unwrap_err();
    assert!(matches!(not, SnapshotError::NotASnapshot), "{not}");

    for cut in [20, 25, bytes.len() / 2, bytes.len() - 1] {
        let short = decode::<SimulationState>(&bytes[..cut]).unwrap_err();
        assert!(
            matches!(
                short,
                SnapshotError::Damaged(_) | SnapshotError::Version { .. }
            ),
            "cut at {cut}: {short}"
        );
    }
    let mut longer = bytes.clone();
    longer.push(0);
    let long = decode::<SimulationState>(&longer).unwrap_err();
    assert!(long.to_string().contains("1 bytes follow"), "{long}");

    // Another version of the program: its header names it.
    let header = b"rolypoly snapshot\n".len() + 4;
    let mut other = bytes[..header].to_vec();
    other.push(5);
    other.extend_from_slice(b"9.9.9");
    other.extend_from_slice(&bytes[header + 1 + usize::from(bytes[header])..]);
    let version = decode::<SimulationState>(&other).unwrap_err();
    assert!(
        matches!(&version, SnapshotError::Version { version, format: 1 } if version == "9.9.9"),
        "{version}"
    );
    assert!(version.to_string().contains("rolypoly 9.9.9"), "{version}");
}

#[test]
fn a_state_of_another_scene_is_refused_and_the_simulation_is_unchanged() {
    let mut tumblers = simulation(&scene_with(30), 4);
    ticks(&mut tumblers, 10);
    let mut no_tumblers = {
        let mut scene = scene_with(30);
        scene.world.tumblers.placements.clear();
        simulation(&scene, 4)
    };
    ticks(&mut no_tumblers, 10);
    let before = encode(&no_tumblers.state());
    let refused = no_tumblers.set_state(tumblers.state()).unwrap_err();
    assert!(refused.to_string().contains("another scene"), "{refused}");
    assert_eq!(encode(&no_tumblers.state()), before);
}
