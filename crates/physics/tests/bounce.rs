//! Free fall and bouncing against analytic results (P4).

mod common;

use common::{empty_room, with_balls};
use glam::DVec3;

#[test]
fn free_fall_follows_the_exact_parabola() {
    let mut cfg = empty_room();
    cfg.room.size = DVec3::new(4.0, 60.0, 4.0);
    let g = cfg.gravity;
    let dt = cfg.solver.dt;
    let mut w = with_balls(cfg, 1);
    let (y0, vy0, vx0) = (50.0, 3.0, 0.5);
    w.balls_mut()
        .set(0, DVec3::new(-1.0, y0, 0.0), DVec3::new(vx0, vy0, 0.0));
    for n in 1..=300 {
        w.step();
        let t = n as f64 * dt;
        let p = w.balls().positions()[0];
        let v = w.balls().velocities()[0];
        let y = y0 + vy0 * t - 0.5 * g * t * t;
        assert!((p.y - y).abs() < 1e-9, "step {n}: y = {} expected {y}", p.y);
        assert!((p.x - (-1.0 + vx0 * t)).abs() < 1e-9);
        assert!((v.y - (vy0 - g * t)).abs() < 1e-9);
    }
}

/// Drops a ball from `h` (bottom of the ball above the floor) and returns the
/// highest the bottom reaches after the first bounce.
fn rebound_height(restitution: f64, h: f64) -> f64 {
    let mut cfg = empty_room();
    cfg.room.restitution = restitution;
    cfg.room.size.y = 2.0 * h + 1.0;
    let r = cfg.balls.radius;
    let dt = cfg.solver.dt;
    let mut w = with_balls(cfg, 1);
    w.balls_mut()
        .set(0, DVec3::new(0.0, h + r, 0.0), DVec3::ZERO);
    let mut bounced = false;
    let mut top: f64 = 0.0;
    for _ in 0..(4.0 / dt) as usize {
        w.step();
        let events = w.drain_events().count();
        let p = w.balls().positions()[0];
        let v = w.balls().velocities()[0];
        if events > 0 && !bounced {
            bounced = true;
            continue;
        }
        if bounced {
            top = top.max(p.y - r);
            if v.y < 0.0 {
                break;
            }
        }
    }
    // The sampled maximum can miss the true apex by up to g dt^2 / 8.
    top
}

#[test]
fn a_dropped_ball_rebounds_to_e_squared_of_its_height() {
    let h = 1.5;
    for e in [0.3, 0.6, 0.9] {
        let top = rebound_height(e, h);
        let expected = e * e * h;
        let err = (top - expected).abs() / expected;
        assert!(
            err < 0.02,
            "e = {e}: rebound {top:.5} m, expected {expected:.5} m ({:.2}%)",
            100.0 * err
        );
    }
}

#[test]
fn with_zero_restitution_a_ball_does_not_bounce() {
    let top = rebound_height(0.0, 1.5);
    assert!(top < 1e-9, "rose {top} m");
}
