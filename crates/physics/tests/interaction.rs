//! The API the window drives: picking, grabbing and dragging a tumbler,
//! the fireball and re-initialising the balls (I3, I5, I6, P8).

mod common;

use common::{build, empty_room, tumbler_at};
use glam::DVec3;
use rolypoly_physics::{EventKind, Tint, World, WorldConfig};

fn lone_tumbler() -> World {
    let mut cfg = empty_room();
    cfg.tumblers.placements = vec![tumbler_at(0.0, 0.0, DVec3::X, 0.0)];
    build(cfg, 1)
}

#[test]
fn a_ray_picks_the_nearest_tumbler_sphere() {
    let w = lone_tumbler();
    let shape = w.tumbler_shape();
    let head = w.tumblers()[0].sphere_center(shape, 4);
    let pick = w
        .pick(DVec3::new(0.0, head.y, 3.0), DVec3::NEG_Z)
        .expect("hit");
    assert_eq!(pick.tumbler, 0);
    assert!(
        (pick.point.z - shape.spheres[4].radius).abs() < 1e-9,
        "{:?}",
        pick.point
    );
    assert!(w.pick(DVec3::new(2.0, 0.5, 3.0), DVec3::NEG_Z).is_none());
}

/// What a drag did to the tumbler.
struct Drag {
    /// How far the bottom moved along the drag (+x).
    moved: f64,
    /// Largest lean of the axis towards the hand (+x), degrees.
    lean_forward: f64,
    /// Share of the steps during which the bottom slid over the floor.
    sliding: f64,
}

/// Holds the tumbler at `height` above the bottom sphere's centre and walks
/// the hand 1 m along +x in one second, then holds it there for another.
fn drag_at(height: f64) -> Drag {
    let mut w = lone_tumbler();
    let start = w.tumblers()[0].bottom_center();
    let grip = start + DVec3::new(0.0, height, 0.0);
    w.grab(0, grip);
    assert_eq!(w.grabbed(), Some(0));
    let (mut fwd, mut slid) = (0.0f64, 0);
    let steps = 240;
    for step in 0..steps {
        let x = (step as f64 / 120.0).min(1.0);
        w.drag_to(grip + DVec3::new(x, 0.0, 0.0));
        w.step();
        let t = &w.tumblers()[0];
        let lean = t.axis().x.asin().to_degrees();
        fwd = fwd.max(lean);
        slid += t.sliding() as usize;
    }
    w.release();
    assert_eq!(w.grabbed(), None);
    Drag {
        moved: (w.tumblers()[0].bottom_center() - start).x,
        lean_forward: fwd,
        sliding: slid as f64 / steps as f64,
    }
}

#[test]
fn grabbed_high_it_tilts_and_swings_grabbed_low_it_slides() {
    // The same hand, two grab points: the difference comes only from where
    // the force acts, against the floor's friction at the contact point.
    let high = drag_at(0.6);
    let low = drag_at(-0.27);
    assert!(
        high.lean_forward > 20.0,
        "a high grab should tip it towards the hand ({} deg)",
        high.lean_forward
    );
    assert!(
        low.moved > high.moved + 0.2,
        "a low grab should slide it along further: {} vs {} m",
        low.moved,
        high.moved
    );
    assert!(
        low.sliding > 1.5 * high.sliding,
        "low slides {:.2}, high {:.2}",
        low.sliding,
        high.sliding
    );
    assert!(low.moved > 0.7 && high.moved > 0.3);
}

#[test]
fn released_tumbler_keeps_its_motion_and_rights_itself() {
    let mut w = lone_tumbler();
    let grip = w.tumblers()[0].sphere_center(w.tumbler_shape(), 4);
    w.grab(0, grip);
    for step in 0..60 {
        w.drag_to(grip + DVec3::new(step as f64 * 0.01, 0.0, 0.0));
        w.step();
    }
    let (v, w_before) = (
        w.tumblers()[0].linear_velocity(),
        w.tumblers()[0].angular_velocity(),
    );
    w.release();
    // Letting go changes nothing by itself ...
    assert_eq!(w.tumblers()[0].linear_velocity(), v);
    assert_eq!(w.tumblers()[0].angular_velocity(), w_before);
    // ... and it carries on the way it was going.
    let x0 = w.tumblers()[0].bottom_center().x;
    assert!(v.x > 0.1, "it was not moving with the hand: {v}");
    for _ in 0..6 {
        w.step();
    }
    assert!(w.tumblers()[0].bottom_center().x > x0);
    for _ in 0..(30.0 / w.config().solver.dt) as usize {
        w.step();
    }
    assert!(w.tumblers()[0].tilt().to_degrees() < 1.0);
}

#[test]
fn fireball_keeps_its_speed_ignores_gravity_and_reports_hits() {
    let mut w = build(WorldConfig::default(), 3);
    assert!(w.fireball().is_none());
    // Straight down onto ball 0 from just above it, so that it meets a ball
    // early; from then on it bounces about the room.
    let below = w.balls().positions()[0];
    let room = *w.room();
    let start = room.clamp_sphere(below + DVec3::new(0.0, 0.6, 0.0), 0.3);
    w.launch_fireball(Some((start, below - start)));
    let speed = w.fireball().unwrap().speed;
    let (mut walls, mut balls, mut tumblers) = (0, 0, 0);
    for _ in 0..(20.0 / w.config().solver.dt) as usize {
        w.step();
        for e in w.drain_events() {
            match e.kind {
                EventKind::FireballSurface { .. } => walls += 1,
                EventKind::FireballBall { .. } => balls += 1,
                EventKind::FireballTumbler { .. } => tumblers += 1,
                _ => {}
            }
        }
        let f = w.fireball().unwrap();
        assert!((f.velocity.length() - speed).abs() < 1e-9 * speed);
    }
    assert!(
        walls > 5 && balls > 0,
        "walls {walls} balls {balls} tumblers {tumblers}"
    );
    w.remove_fireball();
    assert!(w.fireball().is_none());
    w.step();
    assert!(!w.drain_events().any(|e| matches!(
        e.kind,
        EventKind::FireballSurface { .. }
            | EventKind::FireballBall { .. }
            | EventKind::FireballTumbler { .. }
    )));
}

#[test]
fn fireball_knocks_a_ball_away_with_momentum_to_match() {
    let mut cfg = empty_room();
    cfg.gravity = 0.0;
    cfg.fireball.consumes_balls = false;
    let mut w = build(
        WorldConfig {
            balls: rolypoly_physics::BallsConfig {
                count: 1,
                ..cfg.balls.clone()
            },
            ..cfg
        },
        1,
    );
    w.balls_mut().set(0, DVec3::new(0.0, 2.0, 0.0), DVec3::ZERO);
    w.launch_fireball(Some((DVec3::new(-1.0, 2.0, 0.0), DVec3::X)));
    let f0 = w.fireball().unwrap().clone();
    for _ in 0..60 {
        w.step();
        if w.drain_events()
            .any(|e| matches!(e.kind, EventKind::FireballBall { ball: 0 }))
        {
            break;
        }
    }
    let ball_v = w.balls().velocities()[0];
    // Head-on, equal masses, elastic: the ball takes the fireball's velocity.
    assert!((ball_v - f0.velocity).length() < 1e-9, "{ball_v}");
    let f = w.fireball().unwrap();
    assert!((f.velocity.length() - f0.speed).abs() < 1e-9);
}

#[test]
fn reset_brings_back_fresh_white_balls() {
    let mut w = build(WorldConfig::default(), 5);
    for _ in 0..600 {
        w.step();
    }
    assert!(w.balls().tints().iter().any(|t| *t != Tint::White));
    let before: Vec<DVec3> = w.balls().positions().to_vec();
    w.reset_balls().expect("balls fit");
    let b = w.balls();
    assert!(b.tints().iter().all(|t| *t == Tint::White));
    assert!(b.alive().iter().all(|a| *a));
    assert!(b.positions().iter().zip(&before).all(|(p, q)| p != q));
    assert!(
        b.velocities()
            .iter()
            .all(|v| v.length() >= w.config().balls.speed_min)
    );
}

#[test]
fn a_consuming_fireball_catches_the_ball_and_flies_on() {
    let mut cfg = empty_room();
    cfg.gravity = 0.0;
    cfg.balls.count = 1;
    assert!(cfg.fireball.consumes_balls, "catching is the default");
    let mut w = build(cfg, 1);
    w.balls_mut().set(0, DVec3::new(0.0, 2.0, 0.0), DVec3::ZERO);
    w.launch_fireball(Some((DVec3::new(-1.0, 2.0, 0.0), DVec3::X)));
    let mut events = Vec::new();
    let mut hit = None;
    for _ in 0..60 {
        w.step();
        w.take_events(&mut events);
        hit = hit.or(events
            .iter()
            .find(|e| matches!(e.kind, EventKind::FireballBall { ball: 0 }))
            .copied());
    }
    let hit = hit.expect("the fireball reached the ball");
    assert!(!w.balls().alive()[0], "the ball is caught");
    // The event says where the ball was: its surface point and the normal towards the fireball.
    assert!(
        (hit.point - hit.normal * w.balls().radii()[0] - DVec3::new(0.0, 2.0, 0.0)).length() < 1e-9
    );
    assert_eq!(w.fireball().unwrap().velocity.normalize(), DVec3::X);
    w.reset_balls().expect("balls fit");
    assert!(w.balls().alive()[0], "re-initialising brings it back");
}
