//! A ball sliding over the floor starts to roll (P2): Coulomb friction at
//! the contact point slows it and spins it up until the point stops
//! slipping. A solid sphere launched without spin then rolls at 5/7 of its
//! speed, whatever the friction coefficient.
//!
//! Balls touching one another are held by the contact solver alone; a
//! lone ball also meets friction while it moves along its exact path. Both
//! must give the same result.

mod common;

use common::{empty_room, with_balls};
use glam::DVec3;
use rolypoly_physics::World;

/// `count` balls resting on the floor side by side along z, touching, all
/// sliding along +x at `speed` without spin.
fn sliding_balls(count: usize, speed: f64) -> World {
    let mut cfg = empty_room();
    cfg.room.rolling_resistance = 0.0;
    let r = cfg.balls.radius;
    let mut w = with_balls(cfg, count);
    for k in 0..count {
        let z = 2.0 * r * k as f64;
        w.balls_mut()
            .set(k, DVec3::new(-1.0, r, z), DVec3::new(speed, 0.0, 0.0));
    }
    w
}

fn assert_rolls_at_five_sevenths(mut w: World, speed: f64) {
    let r = w.config().balls.radius;
    // Sliding ends after 2 v / (7 mu g), under a tenth of a second here.
    for _ in 0..60 {
        w.step();
    }
    for (k, (v, spin)) in w
        .balls()
        .velocities()
        .iter()
        .zip(w.balls().spins())
        .enumerate()
    {
        let expected = 5.0 / 7.0 * speed;
        assert!(
            (v.x - expected).abs() < 1e-3 * speed,
            "ball {k}: speed {} m/s, expected 5/7 of {speed} = {expected}",
            v.x
        );
        assert!(
            v.y.abs() < 1e-6 && v.z.abs() < 1e-6,
            "ball {k}: velocity {v}"
        );
        // The contact point, r below the centre, stands still.
        let slip = *v + spin.cross(DVec3::new(0.0, -r, 0.0));
        assert!(slip.length() < 1e-6, "ball {k}: slips at {slip} m/s");
    }
}

#[test]
fn a_lone_sliding_ball_comes_to_roll_at_five_sevenths_of_its_speed() {
    assert_rolls_at_five_sevenths(sliding_balls(1, 1.5), 1.5);
}

#[test]
fn sliding_balls_touching_each_other_come_to_roll_alike() {
    // Touching, each is solved with its contacts, not moved on its own.
    assert_rolls_at_five_sevenths(sliding_balls(3, 1.5), 1.5);
}
