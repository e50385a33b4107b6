//! Balls placed by hand (E3): they start exactly where and how the scene
//! says, the random balls keep clear of them, a restart puts them back, and
//! a placement that cannot be built is refused with the ball named.

mod common;

use common::{build, tumbler_at};
use glam::DVec3;
use rolypoly_physics::{BallPlacement, Tint, World, WorldConfig};

fn placed(position: [f64; 3], velocity: [f64; 3]) -> BallPlacement {
    BallPlacement::new(DVec3::from_array(position), DVec3::from_array(velocity))
}

fn scene_with(placements: Vec<BallPlacement>, random: usize) -> WorldConfig {
    let mut cfg = WorldConfig::default();
    cfg.balls.count = random;
    cfg.balls.placements = placements;
    cfg
}

fn build_error(cfg: WorldConfig) -> String {
    match World::new(cfg, 1) {
        Ok(_) => panic!("the scene built"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn placed_balls_start_exactly_as_written_with_their_own_size_mass_spin_and_colour() {
    let mut big = placed([1.0, 0.5, -1.0], [0.0, 2.0, 0.0]);
    big.radius = Some(0.3);
    big.mass = Some(4.0);
    big.spin = DVec3::new(0.0, 0.0, -5.0);
    big.color = Some([0.1, 0.2, 0.9]);
    let plain = placed([-1.0, 2.0, 0.5], [1.0, 0.0, 0.0]);
    let w = build(scene_with(vec![big.clone(), plain.clone()], 0), 3);
    let b = w.balls();
    assert_eq!(b.len(), 2);
    assert_eq!(b.positions()[0], big.position);
    assert_eq!(b.velocities()[0], big.velocity);
    assert_eq!(b.spins()[0], big.spin);
    assert_eq!((b.radii()[0], b.masses()[0]), (0.3, 4.0));
    assert_eq!(w.tint_color(b.tints()[0]), [0.1, 0.2, 0.9]);
    let defaults = &w.config().balls;
    assert_eq!(
        (b.radii()[1], b.masses()[1]),
        (defaults.radius, defaults.mass)
    );
    assert_eq!(b.tints()[1], Tint::White);
    assert_eq!(b.positions()[1], plain.position);
}

#[test]
fn random_balls_come_in_addition_and_keep_clear_of_the_placed_ones() {
    for seed in [1, 2, 3] {
        let mut heavy = placed([0.0, 1.0, 0.0], [0.0; 3]);
        heavy.radius = Some(0.8);
        let cfg = scene_with(vec![heavy, placed([3.0, 3.0, 3.0], [0.0; 3])], 200);
        let w = build(cfg, seed);
        let b = w.balls();
        assert_eq!(b.len(), 202);
        for i in 2..b.len() {
            for k in 0..2 {
                let apart = b.positions()[i].distance(b.positions()[k]);
                assert!(
                    apart >= b.radii()[i] + b.radii()[k],
                    "seed {seed}: random ball {i} overlaps placed ball {k}"
                );
            }
        }
    }
}

#[test]
fn a_restart_puts_the_placed_balls_back_exactly() {
    let mut ball = placed([0.0, 1.5, 0.0], [2.0, 1.0, -3.0]);
    ball.color = Some([1.0, 0.0, 0.0]);
    let cfg = scene_with(vec![ball.clone(), placed([1.0, 1.5, 0.0], [0.0; 3])], 20);
    let mut w = build(cfg, 9);
    let start: Vec<_> = w.balls().positions().to_vec();
    for _ in 0..240 {
        w.step();
    }
    assert_ne!(w.balls().positions()[0], ball.position);
    w.reset_balls().unwrap();
    let b = w.balls();
    assert_eq!(b.positions()[..2], start[..2]);
    assert_eq!(b.velocities()[0], ball.velocity);
    assert_eq!(b.tints()[0], Tint::Placed(0));
    // The random ones are drawn anew.
    assert_ne!(b.positions()[2..], start[2..]);
}

#[test]
fn a_ball_out_of_the_room_or_in_another_body_is_refused_by_number() {
    let cfg = scene_with(
        vec![
            placed([0.0, 1.0, 0.0], [0.0; 3]),
            placed([0.0, 0.05, 0.0], [0.0; 3]),
        ],
        0,
    );
    let e = build_error(cfg);
    assert!(e.contains("ball 1") && e.contains("inside the room"), "{e}");

    let cfg = scene_with(
        vec![
            placed([0.0, 1.0, 0.0], [0.0; 3]),
            placed([0.1, 1.0, 0.0], [0.0; 3]),
        ],
        0,
    );
    let e = build_error(cfg);
    assert!(e.contains("ball 1") && e.contains("overlaps ball 0"), "{e}");

    let mut cfg = scene_with(vec![placed([0.0, 0.3, 0.0], [0.0; 3])], 0);
    cfg.tumblers.placements = vec![tumbler_at(0.2, 0.0, DVec3::X, 0.0)];
    let e = build_error(cfg);
    assert!(e.contains("ball 0") && e.contains("tumbler 0"), "{e}");

    // Touching is not overlapping: a row at twice the radius apart builds.
    let r = WorldConfig::default().balls.radius;
    let row = (0..5)
        .map(|k| placed([k as f64 * 2.0 * r, r, 0.0], [0.0; 3]))
        .collect();
    let mut cfg = scene_with(row, 0);
    cfg.tumblers.placements.clear();
    build(cfg, 1);
}
