//! Energy never grows (P1, P4): contacts, bounces, friction and damping can
//! only take energy out. The fireball and the hand feed energy in by design,
//! so they stay out of these scenes.

mod common;

use common::build;
use rolypoly_physics::{World, WorldConfig};

/// Steps `w` for `seconds` and returns the largest relative growth of the
/// total energy over a single step.
fn worst_step_growth(w: &mut World, seconds: f64) -> f64 {
    let mut worst = f64::NEG_INFINITY;
    let mut before = w.energy().total();
    let steps = (seconds / w.config().solver.dt) as usize;
    for _ in 0..steps {
        w.step();
        let after = w.energy().total();
        assert!(after.is_finite());
        worst = worst.max((after - before) / before.abs().max(1e-12));
        before = after;
    }
    worst
}

#[test]
fn default_scene_never_gains_energy() {
    for seed in [1, 2, 3] {
        let mut w = build(WorldConfig::default(), seed);
        let growth = worst_step_growth(&mut w, 20.0);
        assert!(
            growth <= 1e-9,
            "seed {seed}: energy grew by {growth:e} in one step"
        );
    }
}

#[test]
fn perfectly_elastic_scene_with_gravity_never_gains_energy() {
    for seed in [4, 5, 6] {
        let mut cfg = WorldConfig::default();
        cfg.balls.count = 120;
        cfg.balls.restitution = 1.0;
        cfg.room.restitution = 1.0;
        cfg.tumblers.restitution = 1.0;
        cfg.tumblers.damping = 0.0;
        let mut w = build(cfg, seed);
        let growth = worst_step_growth(&mut w, 10.0);
        assert!(
            growth <= 1e-9,
            "seed {seed}: energy grew by {growth:e} in one step"
        );
    }
}

#[test]
fn a_settling_heap_never_gains_energy() {
    // Many balls in a small room pile up on the floor and on the tumblers:
    // stacks, clusters and resting contacts.
    let mut cfg = WorldConfig::default();
    cfg.room.size = glam::DVec3::new(3.0, 3.0, 3.0);
    cfg.tumblers.placements.truncate(1);
    cfg.tumblers.placements[0].x = 0.0;
    cfg.tumblers.placements[0].z = 0.0;
    cfg.balls.count = 400;
    cfg.balls.speed_max = 3.0;
    for seed in [7, 8] {
        let mut w = build(cfg.clone(), seed);
        let growth = worst_step_growth(&mut w, 8.0);
        assert!(
            growth <= 1e-9,
            "seed {seed}: energy grew by {growth:e} in one step"
        );
    }
}

#[test]
fn elastic_weightless_frictionless_scene_keeps_its_energy() {
    // Tumblers are defined by gravity (it is what rights them), so this scene
    // is the balls alone.
    let mut cfg = common::elastic_room(WorldConfig::default().balls.count, 0.0);
    // As the default's: a slow impact rests.
    cfg.solver.bounce_threshold = WorldConfig::default().solver.bounce_threshold;
    let mut w = build(cfg, 5);
    let e0 = w.energy().total();
    let growth = worst_step_growth(&mut w, 10.0);
    let e1 = w.energy().total();
    assert!(growth <= 1e-9, "energy grew by {growth:e} in one step");
    let change = (e1 - e0).abs() / e0;
    println!("energy changed by {:.2e} of itself over 10 s", change);
    assert!(
        change < 1e-3,
        "energy changed by {:.4}% over 10 s",
        100.0 * change
    );
}
