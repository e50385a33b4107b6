//! Every scene shipped in `scenes/` loads, and shows what its header says
//! it shows (E3): each claim checked as physics, over more than one seed
//! where the scene has random balls.

use std::path::{Path, PathBuf};

use glam::DVec3;
use rolypoly::scene::load_scene;
use rolypoly_physics::{EventKind, World, WorldConfig, angle_of_repose};

fn scene_path(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../scenes")
        .join(name)
}

fn config(name: &str) -> WorldConfig {
    match load_scene(Some(&scene_path(name))) {
        Ok(scene) => scene.world,
        Err(e) => panic!("{name} does not load: {e}"),
    }
}

fn world(name: &str, seed: u64) -> World {
    match World::new(config(name), seed) {
        Ok(w) => w,
        Err(e) => panic!("{name} does not build: {e}"),
    }
}

fn run(w: &mut World, seconds: f64) {
    for _ in 0..(seconds / w.config().solver.dt).round() as usize {
        w.step();
    }
}

fn momentum(w: &World) -> DVec3 {
    let b = w.balls();
    (0..b.len())
        .map(|i| b.masses()[i] * b.velocities()[i])
        .sum()
}

#[test]
fn every_shipped_scene_loads_builds_and_says_how_to_run_it() {
    let mut names: Vec<String> = std::fs::read_dir(scene_path(""))
        .expect("the scenes folder")
        .map(|entry| {
            entry
                .expect("a scene")
                .file_name()
                .to_string_lossy()
                .into_owned()
        })
        .filter(|name| name.ends_with(".toml"))
        .collect();
    names.sort();
    for wanted in [
        "newtons-cradle.toml",
        "billiards-break.toml",
        "elastic-gas.toml",
        "unequal-masses.toml",
        "tumbler-crowd.toml",
        "heap.toml",
        "ballpit-10k.toml",
        "ballpit-100k.toml",
        "ballpit-1m.toml",
    ] {
        assert!(names.iter().any(|n| n == wanted), "{wanted} is missing");
    }
    for name in &names {
        let text = std::fs::read_to_string(scene_path(name)).expect("readable");
        assert!(text.starts_with("# "), "{name} has no header comment");
        // The default scene's file documents the format instead.
        let runnable = name == "default.toml" || text.contains("cargo run --release -- --scene");
        assert!(runnable, "{name} does not say how to run it");
        world(name, 1);
    }
}

#[test]
fn newtons_cradle_sends_off_as_many_balls_as_came_in_and_keeps_its_energy() {
    let mut w = world("newtons-cradle.toml", 1);
    let e0 = w.energy().total();
    // Placed in rows of five at rest, each followed by the balls coming in.
    let rows = [(0, 1), (6, 2), (13, 3)];
    let speed = w.balls().velocities()[5].x;
    run(&mut w, 1.6);
    for (first, moving) in rows {
        let v: Vec<f64> = (first..first + 5 + moving)
            .map(|i| w.balls().velocities()[i].x)
            .collect();
        for (k, &vx) in v.iter().enumerate() {
            let leaves = (5 - moving..5).contains(&k);
            if leaves {
                assert!(
                    vx >= 0.98 * speed,
                    "{moving} in: ball {k} leaves at {vx}: {v:?}"
                );
            } else {
                assert!(
                    vx.abs() <= 0.02 * speed,
                    "{moving} in: ball {k} moves at {vx}: {v:?}"
                );
            }
        }
    }
    // Back and forth off the walls for a while: nothing lost.
    run(&mut w, 18.4);
    let e1 = w.energy().total();
    assert!(((e1 - e0) / e0).abs() < 5e-3, "energy {e0} J became {e1} J");
}

#[test]
fn the_billiards_break_spreads_the_rack_and_shares_the_cue_balls_momentum() {
    let mut w = world("billiards-break.toml", 1);
    let cue = w.balls().len() - 1;
    // Roll up to the rack, and note the momentum of the last step before it.
    let mut before = momentum(&w);
    let mut hit = false;
    for _ in 0..240 {
        before = momentum(&w);
        w.step();
        if w.drain_events()
            .any(|e| matches!(e.kind, EventKind::BallBall { .. }))
        {
            hit = true;
            break;
        }
    }
    assert!(hit, "the cue ball never reached the rack");
    let dt = w.config().solver.dt;
    run(&mut w, 2.0 * dt);
    let after = momentum(&w);
    assert!(
        (after - before).length() <= 0.02 * before.length(),
        "momentum {before} before the break, {after} after"
    );
    assert!(w.balls().velocities()[cue].x < 0.5 * before.x / w.balls().masses()[cue]);
    run(&mut w, 0.5);
    // A perfectly tight rack keeps a ball or two of its middle in place.
    let moving = (0..cue)
        .filter(|&i| w.balls().velocities()[i].length() > 0.05)
        .count();
    assert!(moving >= 10, "only {moving} of the rack's 15 balls move");
}

#[test]
fn the_elastic_gas_keeps_its_energy() {
    for seed in [1, 2, 3] {
        let mut w = world("elastic-gas.toml", seed);
        assert_eq!(w.balls().len(), 400);
        let e0 = w.energy().total();
        run(&mut w, 10.0);
        let e1 = w.energy().total();
        assert!(
            ((e1 - e0) / e0).abs() < 1e-3,
            "seed {seed}: energy {e0} J became {e1} J"
        );
    }
}

#[test]
fn unequal_masses_leave_with_the_one_dimensional_velocities() {
    let mut w = world("unequal-masses.toml", 1);
    let b = w.balls();
    let pairs: Vec<_> = (0..b.len() / 2)
        .map(|k| {
            let (i, j) = (2 * k, 2 * k + 1);
            let (m1, m2) = (b.masses()[i], b.masses()[j]);
            let (v1, v2) = (b.velocities()[i].x, b.velocities()[j].x);
            let total = m1 + m2;
            let e = w.config().balls.restitution;
            let after1 = (m1 * v1 + m2 * v2 - m2 * e * (v1 - v2)) / total;
            let after2 = (m1 * v1 + m2 * v2 + m1 * e * (v1 - v2)) / total;
            (i, j, after1, after2)
        })
        .collect();
    assert_eq!(pairs.len(), 3);
    run(&mut w, 2.0);
    for (i, j, after1, after2) in pairs {
        let v = w.balls().velocities();
        assert!(
            (v[i].x - after1).abs() < 1e-6 && (v[j].x - after2).abs() < 1e-6,
            "balls {i} and {j}: {} and {}, expected {after1} and {after2}",
            v[i].x,
            v[j].x
        );
    }
}

#[test]
fn the_tumbler_crowd_stands_upright_again_after_the_rain() {
    for seed in [1, 2] {
        let mut w = world("tumbler-crowd.toml", seed);
        assert!(w.tumblers().len() >= 20);
        run(&mut w, 30.0);
        for (t, tumbler) in w.tumblers().iter().enumerate() {
            let axis = tumbler.orientation() * DVec3::Y;
            let tilt = axis.angle_between(DVec3::Y).to_degrees();
            assert!(
                tilt < 5.0,
                "seed {seed}: tumbler {t} leans {tilt:.1} degrees"
            );
        }
        let room = *w.room();
        let b = w.balls();
        for i in 0..b.len() {
            assert!(
                room.contains_sphere(b.positions()[i], b.radii()[i], 1e-6),
                "seed {seed}: ball {i} left the room"
            );
        }
    }
}

#[test]
fn the_poured_heap_comes_to_rest_at_an_angle_of_repose() {
    for seed in [1, 2] {
        let mut w = world("heap.toml", seed);
        let c = w.config().balls.clone();
        assert!(c.pour.rate > 0.0 && c.count >= 2000);
        // The pour at its rate (and a moment more), then time to settle.
        run(&mut w, c.count as f64 / c.pour.rate + 0.5);
        assert_eq!(w.balls_to_pour(), 0, "seed {seed}: the pour is behind");
        run(&mut w, 4.0);
        let b = w.balls();
        assert_eq!(b.len(), c.count, "seed {seed}");
        assert!(b.alive().iter().all(|&a| a), "seed {seed}");
        let room = *w.room();
        for i in 0..b.len() {
            assert!(
                room.contains_sphere(b.positions()[i], b.radii()[i], 1e-6),
                "seed {seed}: ball {i} left the room"
            );
        }
        let resting = (0..b.len())
            .filter(|&i| b.velocities()[i].length() < 0.05)
            .count();
        assert!(
            resting * 100 >= 95 * b.len(),
            "seed {seed}: only {resting} of {} balls rest",
            b.len()
        );
        let axis = [c.pour.spout.x, c.pour.spout.z];
        let angle = angle_of_repose(b.positions(), c.radius, axis);
        println!("seed {seed}: {resting} balls at rest, the flank at {angle:?} degrees");
        assert!(
            angle.is_some_and(|a| (15.0..=30.0).contains(&a)),
            "seed {seed}: the heap's flank stands at {angle:?} degrees"
        );
    }
}

#[test]
fn the_ten_thousand_ball_pit_settles_without_sinking() {
    let mut w = world("ballpit-10k.toml", 1);
    assert_eq!(w.balls().len(), 10_000);
    run(&mut w, 5.0);
    let b = w.balls();
    let room = *w.room();
    let resting = (0..b.len())
        .filter(|&i| b.velocities()[i].length() < 0.05)
        .count();
    assert!(resting >= 9_000, "only {resting} of 10 000 balls rest");
    for i in 0..b.len() {
        assert!(
            room.contains_sphere(b.positions()[i], b.radii()[i], 1e-6),
            "ball {i} left the room"
        );
    }
    // Nowhere does one ball sink into another by more than a centimetre.
    let r = b.radii()[0];
    let mut order: Vec<usize> = (0..b.len()).collect();
    order.sort_by(|&i, &j| b.positions()[i].x.total_cmp(&b.positions()[j].x));
    for (k, &i) in order.iter().enumerate() {
        for &j in &order[k + 1..] {
            if b.positions()[j].x - b.positions()[i].x > 2.0 * r {
                break;
            }
            let overlap = 2.0 * r - b.positions()[i].distance(b.positions()[j]);
            assert!(overlap < 0.01, "balls {i} and {j} overlap by {overlap} m");
        }
    }
}
