//! Ball-ball collisions against the classic 1-D formulas for balls along
//! the line of centres (P2, P3) and
//! momentum conservation (P1).

mod common;

use common::{empty_room, with_balls};
use glam::DVec3;
use rolypoly_physics::{EventKind, World};

/// A weightless room big enough that walls play no part.
fn open_space(restitution: f64, n: usize) -> World {
    let mut cfg = empty_room();
    cfg.gravity = 0.0;
    cfg.room.size = DVec3::splat(40.0);
    cfg.balls.restitution = restitution;
    // The classic 1-D formulas hold for balls that slide on each other.
    cfg.balls.friction = 0.0;
    with_balls(cfg, n)
}

/// Velocities along the line of centres after an impact, by the classic
/// 1-D formulas:
/// v1' = ((m1 - m2) v1 + 2 m2 v2) / (m1 + m2), and symmetrically, with the
/// relative velocity scaled by the restitution so momentum is kept.
fn expected_normal_speeds(m1: f64, m2: f64, v1: f64, v2: f64, e: f64) -> (f64, f64) {
    let total = m1 + m2;
    let v1f = (m1 * v1 + m2 * v2 - m2 * e * (v1 - v2)) / total;
    let v2f = (m1 * v1 + m2 * v2 + m1 * e * (v1 - v2)) / total;
    (v1f, v2f)
}

#[test]
fn elastic_formula_is_the_restitution_formula_at_e_one() {
    let (m1, m2, v1, v2) = (0.3, 0.7, 2.0, -1.0);
    let (a, b) = expected_normal_speeds(m1, m2, v1, v2, 1.0);
    assert!((a - ((m1 - m2) * v1 + 2.0 * m2 * v2) / (m1 + m2)).abs() < 1e-15);
    assert!((b - ((m2 - m1) * v2 + 2.0 * m1 * v1) / (m1 + m2)).abs() < 1e-15);
}

fn collide(m1: f64, m2: f64, v1: DVec3, v2: DVec3, offset: f64, e: f64) {
    let mut w = open_space(e, 2);
    let r = w.config().balls.radius;
    let dt = w.config().solver.dt;
    // Ball 1 at the left, ball 2 at the right, offset sideways for an oblique hit.
    let p1 = DVec3::new(-1.0, 20.0, 0.0);
    let p2 = DVec3::new(-1.0 + 0.5, 20.0 + offset, 0.0);
    // Run them backwards so that they meet mid-step, then start them there.
    let back = 7.3 * dt;
    w.balls_mut().set(0, p1 - v1 * back, v1);
    w.balls_mut().set(1, p2 - v2 * back, v2);
    w.balls_mut().set_mass(0, m1);
    w.balls_mut().set_mass(1, m2);
    let p_before = m1 * v1 + m2 * v2;
    let mut hit = None;
    for _ in 0..400 {
        w.step();
        for ev in w.drain_events() {
            if let EventKind::BallBall { .. } = ev.kind {
                hit = Some(ev);
            }
        }
        if hit.is_some() {
            break;
        }
    }
    let hit = hit.expect("the balls never met");
    // The analytic line of centres at first touch: |d + (v1 - v2) t| = 2r.
    let (d0, dv) = ((p1 - v1 * back) - (p2 - v2 * back), v1 - v2);
    let (a, b, c) = (
        dv.length_squared(),
        d0.dot(dv),
        d0.length_squared() - 4.0 * r * r,
    );
    let t_touch = (-b - (b * b - a * c).sqrt()) / a;
    let n_touch = (d0 + dv * t_touch).normalize();
    let pos = w.balls().positions();
    // The line of centres at the moment of impact, pointing at ball 1.
    let n = match hit.kind {
        EventKind::BallBall { a: 0, .. } => hit.normal,
        _ => -hit.normal,
    };
    assert!(
        (n - n_touch).length() < 1e-9,
        "impact normal {n} vs analytic {n_touch}"
    );
    let (u1, u2) = (w.balls().velocities()[0], w.balls().velocities()[1]);
    let (a, b) = expected_normal_speeds(m1, m2, v1.dot(n), v2.dot(n), e);
    assert!(
        (u1.dot(n) - a).abs() < 1e-9,
        "ball 1 normal speed {} expected {a}",
        u1.dot(n)
    );
    assert!(
        (u2.dot(n) - b).abs() < 1e-9,
        "ball 2 normal speed {} expected {b}",
        u2.dot(n)
    );
    // Tangential components are untouched (no friction between balls).
    assert!(((u1 - u1.dot(n) * n) - (v1 - v1.dot(n) * n)).length() < 1e-9);
    assert!(((u2 - u2.dot(n) * n) - (v2 - v2.dot(n) * n)).length() < 1e-9);
    let p_after = m1 * u1 + m2 * u2;
    assert!((p_after - p_before).length() <= 1e-12 * p_before.length().max(1.0));
    // They touch and separate: no overlap is left.
    assert!(pos[0].distance(pos[1]) >= 2.0 * r - 1e-9);
}

#[test]
fn head_on_and_oblique_impacts_match_the_formulas() {
    let x = |v: f64| DVec3::new(v, 0.0, 0.0);
    // (m1, m2, v1, v2, sideways offset, restitution)
    let cases = [
        (0.25, 0.25, x(3.0), x(-1.0), 0.0, 1.0),
        (0.25, 0.25, x(3.0), x(-1.0), 0.0, 0.6),
        (0.1, 0.9, x(4.0), DVec3::ZERO, 0.0, 1.0),
        (2.0, 0.5, x(1.0), x(-2.5), 0.0, 0.85),
        (0.25, 0.25, x(3.0), DVec3::ZERO, 0.13, 1.0),
        (
            0.4,
            0.15,
            DVec3::new(2.0, 0.5, 0.3),
            DVec3::new(-1.0, 0.0, -0.2),
            -0.09,
            0.7,
        ),
    ];
    for (m1, m2, v1, v2, offset, e) in cases {
        collide(m1, m2, v1, v2, offset, e);
    }
}

#[test]
fn separating_or_distant_balls_do_not_interact() {
    let mut w = open_space(1.0, 2);
    let r = w.config().balls.radius;
    // Overlapping slightly but moving apart: no impulse, only separation.
    w.balls_mut()
        .set(0, DVec3::new(0.0, 20.0, 0.0), DVec3::new(-1.0, 0.0, 0.0));
    w.balls_mut().set(
        1,
        DVec3::new(2.0 * r - 0.001, 20.0, 0.0),
        DVec3::new(1.0, 0.0, 0.0),
    );
    w.step();
    assert_eq!(w.balls().velocities()[0], DVec3::new(-1.0, 0.0, 0.0));
    assert_eq!(w.balls().velocities()[1], DVec3::new(1.0, 0.0, 0.0));
    assert_eq!(w.drain_events().count(), 0);
}

#[test]
fn momentum_is_conserved_in_a_crowd_away_from_walls() {
    let n = 200;
    let mut w = open_space(0.8, n);
    let mut rng = 12345u64;
    let mut next = || {
        rng = rng
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (rng >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    // A dense cloud in the middle of a 40 m room; every ball has its own mass.
    for i in 0..n {
        let p = DVec3::new(next(), next(), next()) * 2.5 + DVec3::new(0.0, 20.0, 0.0);
        let v = DVec3::new(next(), next(), next()) * 4.0;
        w.balls_mut().set(i, p, v);
        w.balls_mut().set_mass(i, 0.1 + next().abs());
    }
    let momentum = |w: &World| -> DVec3 {
        let b = w.balls();
        (0..b.len())
            .map(|i| b.masses()[i] * b.velocities()[i])
            .sum()
    };
    let scale: f64 = {
        let b = w.balls();
        (0..b.len())
            .map(|i| b.masses()[i] * b.velocities()[i].length())
            .sum()
    };
    let p0 = momentum(&w);
    let mut impacts = 0;
    for _ in 0..240 {
        w.step();
        impacts += w
            .drain_events()
            .filter(|e| matches!(e.kind, EventKind::BallBall { .. }))
            .count();
        let b = w.balls();
        assert!(
            b.positions()
                .iter()
                .all(|p| p.x.abs() < 19.0 && (p.y - 20.0).abs() < 19.0)
        );
    }
    assert!(impacts > 50, "only {impacts} impacts");
    let drift = (momentum(&w) - p0).length();
    assert!(
        drift <= 1e-9 * scale,
        "momentum changed by {drift} (scale {scale})"
    );
}

#[test]
fn ball_takes_the_colour_of_what_it_hits() {
    use rolypoly_physics::{Surface, Tint};
    let mut cfg = empty_room();
    cfg.gravity = 0.0;
    let mut w = with_balls(cfg, 1);
    assert_eq!(w.balls().tints()[0], Tint::White);
    w.balls_mut()
        .set(0, DVec3::new(0.0, 2.0, 0.0), DVec3::new(-5.0, 0.0, 0.0));
    for _ in 0..200 {
        w.step();
        if w.balls().tints()[0] != Tint::White {
            break;
        }
    }
    assert_eq!(w.balls().tints()[0], Tint::Surface(Surface::Left));
}

#[test]
fn a_ball_hitting_a_tumbler_takes_its_colour_and_rocks_it() {
    use rolypoly_physics::{EventKind, Tint};
    let mut cfg = empty_room();
    cfg.tumblers.placements = vec![common::tumbler_at(0.0, 0.0, DVec3::X, 0.0)];
    let mut w = with_balls(cfg, 1);
    // Thrown level at the tumbler's head, from the side.
    let head = w.tumblers()[0].sphere_center(w.tumbler_shape(), 4);
    w.balls_mut().set(
        0,
        head + DVec3::new(-1.5, 0.0, 0.0),
        DVec3::new(6.0, 0.0, 0.0),
    );
    let mut hit = false;
    for _ in 0..120 {
        w.step();
        if w.drain_events().any(|e| {
            matches!(
                e.kind,
                EventKind::BallTumbler {
                    ball: 0,
                    tumbler: 0,
                    ..
                }
            )
        }) {
            hit = true;
            break;
        }
    }
    assert!(hit, "the ball never reached the tumbler");
    assert_eq!(w.balls().tints()[0], Tint::Tumbler(0));
    // The impulse at the contact point turns it about its floor contact.
    assert!(
        w.tumblers()[0].angular_velocity().length() > 0.01,
        "the tumbler did not rock"
    );
    assert!(
        w.balls().velocities()[0].x < 0.0,
        "the ball did not bounce back"
    );
}
