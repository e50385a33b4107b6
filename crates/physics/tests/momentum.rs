//! Newton's second law over each step: what changes the balls' momentum is
//! what the room's surfaces and the tumblers gave them, and gravity's
//! `M g dt`; the balls' impacts on one another pass momentum between them
//! and keep its sum. The impulses are the step's own count
//! ([`World::ball_impulses`]), the momentum the balls' own.

mod common;

use common::build;
use glam::DVec3;
use rolypoly_physics::{World, WorldConfig};

/// The balls' momentum (kg m/s), their mass (kg), and the sum of each
/// ball's momentum's length: the scale a rounding error is measured on.
fn momentum(w: &World) -> (DVec3, f64, f64) {
    let b = w.balls();
    let live = (0..b.len()).filter(|&i| b.alive()[i]);
    live.fold((DVec3::ZERO, 0.0, 0.0), |(p, m, scale), i| {
        let (mi, v) = (b.masses()[i], b.velocities()[i]);
        (p + mi * v, m + mi, scale + mi * v.length())
    })
}

/// What a run's steps showed of the balance.
#[derive(Debug, Default)]
struct Balance {
    /// The worst step's gap between the change of the balls' momentum and
    /// what its impulses and gravity give.
    gap: f64,
    /// The largest impulse a step's surfaces, tumblers and guard gave.
    surfaces: f64,
    tumblers: f64,
    guard: f64,
}

/// Steps `w` for `seconds`, each step's figures as shares of the balls'
/// momentum's scale as the step began.
fn balance(w: &mut World, seconds: f64) -> Balance {
    let dt = w.config().solver.dt;
    let g = DVec3::new(0.0, -w.config().gravity, 0.0);
    let mut seen = Balance::default();
    let steps = (seconds / dt).round() as usize;
    for _ in 0..steps {
        let (before, mass_before, scale) = momentum(w);
        w.step();
        // Gravity pulls on the balls poured at the step's start too.
        let (after, mass, _) = momentum(w);
        let given = w.ball_impulses();
        assert_eq!(given.poured != DVec3::ZERO, mass > mass_before);
        if scale == 0.0 {
            continue;
        }
        let gravity = mass * g * dt;
        let expected = given.surfaces + given.tumblers + given.guard + gravity + given.poured;
        assert!((given.gravity - gravity).length() <= 1e-12 * gravity.length());
        assert!((given.total() - expected).length() <= 1e-12 * scale);
        seen.gap = seen.gap.max((after - before - expected).length() / scale);
        seen.surfaces = seen.surfaces.max(given.surfaces.length() / scale);
        seen.tumblers = seen.tumblers.max(given.tumblers.length() / scale);
        seen.guard = seen.guard.max(given.guard.length() / scale);
    }
    seen
}

/// The law's tolerance, as a share of the momentum's scale: rounding.
const ROUNDING: f64 = 1e-9;

/// An elastic gas of `balls` balls, seed `seed`, under `gravity`: what its
/// steps showed, the balance held and the walls having turned it.
fn elastic_gas(balls: usize, seed: u64, gravity: f64) -> Balance {
    let seen = balance(&mut build(common::elastic_room(balls, gravity), seed), 4.0);
    println!("{balls} balls, seed {seed}, g {gravity}: {seen:?}");
    assert!(seen.gap <= ROUNDING, "{balls} balls, seed {seed}: {seen:?}");
    assert!(seen.surfaces > 1e-3, "{balls} balls, seed {seed}: {seen:?}");
    assert_eq!(seen.tumblers, 0.0);
    seen
}

#[test]
fn in_a_weightless_elastic_gas_only_the_walls_change_the_momentum() {
    for (balls, seed) in [(150, 2), (400, 5), (1500, 9)] {
        let seen = elastic_gas(balls, seed, 0.0);
        // The walls turned it, and nothing else did: the guard never
        // slows an elastic gas beyond rounding.
        assert!(seen.guard <= 1e-12, "{balls} balls, seed {seed}: {seen:?}");
    }
}

#[test]
fn with_gravity_the_change_also_holds_m_g_dt() {
    // 400 balls of seed 3 hold one bouncing ever faster on the floor, its
    // bounces left unfinished at the step's end: the floor holds it up.
    for (balls, seed) in [(120, 3), (400, 3), (600, 8)] {
        elastic_gas(balls, seed, 9.81);
    }
}

#[test]
fn tumblers_friction_settling_piles_and_a_pour_keep_the_balance() {
    let mut bouncing = common::elastic_room(200, 9.81);
    bouncing.tumblers = WorldConfig::default().tumblers;
    bouncing.tumblers.restitution = 1.0;
    bouncing.tumblers.damping = 0.0;
    let mut pit = common::crowded_pit();
    pit.balls.count = 2500;
    let mut pour = common::empty_room();
    pour.balls.count = 300;
    pour.balls.pour.rate = 200.0;
    for (name, cfg, seconds) in [
        ("elastic tumblers", bouncing, 4.0),
        ("default", WorldConfig::default(), 6.0),
        ("crowded pit", pit, 1.5),
        ("pour", pour, 2.5),
    ] {
        for seed in [2, 7] {
            let seen = balance(&mut build(cfg.clone(), seed), seconds);
            println!("{name}, seed {seed}: {seen:?}");
            assert!(seen.gap <= ROUNDING, "{name}, seed {seed}: {seen:?}");
            assert!(seen.surfaces > 1e-3, "{name}, seed {seed}: {seen:?}");
            if !["crowded pit", "pour"].contains(&name) {
                assert!(seen.tumblers > 1e-4, "{name}, seed {seed}: {seen:?}");
            }
        }
    }
}
