//! Impacts in the order they happen (E1, E2): simultaneous impacts give the
//! textbook answers, and a room of perfectly elastic balls keeps its energy
//! at any ball count, with gravity and without.

mod common;

use common::{build, elastic_room, empty_room};
use glam::DVec3;
use rolypoly_physics::World;

/// A weightless room so big that walls play no part, with balls of
/// restitution `e` and no friction anywhere.
fn open_space(e: f64, n: usize) -> World {
    let mut cfg = empty_room();
    cfg.gravity = 0.0;
    cfg.room.size = DVec3::splat(40.0);
    cfg.balls.count = n;
    cfg.balls.restitution = e;
    cfg.room.friction = 0.0;
    cfg.balls.friction = 0.0;
    cfg.balls.rolling_resistance = 0.0;
    cfg.solver.bounce_threshold = 0.0;
    build(cfg, 1)
}

/// The floor of the default room, frictionless, with `n` balls of
/// restitution `e`.
fn frictionless_floor(e: f64, n: usize) -> World {
    let mut cfg = empty_room();
    cfg.balls.count = n;
    cfg.balls.restitution = e;
    cfg.room.friction = 0.0;
    cfg.balls.friction = 0.0;
    cfg.balls.rolling_resistance = 0.0;
    cfg.room.rolling_resistance = 0.0;
    build(cfg, 1)
}

fn momentum(w: &World) -> DVec3 {
    let b = w.balls();
    (0..b.len())
        .filter(|&i| b.alive()[i])
        .map(|i| b.masses()[i] * b.velocities()[i])
        .sum()
}

fn run(w: &mut World, seconds: f64) {
    for _ in 0..(seconds / w.config().solver.dt).round() as usize {
        w.step();
    }
}

/// A row of `n` touching balls along x starting at `start`, the first
/// `moving` of them (touching each other too) sent in at `speed` from a
/// gap of a few centimetres: returns each ball's x velocity afterwards.
fn row_after_impact(w: &mut World, start: DVec3, moving: usize, speed: f64) -> Vec<f64> {
    let n = w.balls().len();
    let r = w.config().balls.radius;
    let gap = 0.037;
    for k in 0..n {
        let behind = if k < moving { gap } else { 0.0 };
        let x = start.x + 2.0 * r * k as f64 - behind;
        let v = if k < moving { speed } else { 0.0 };
        w.balls_mut()
            .set(k, DVec3::new(x, start.y, start.z), DVec3::X * v);
    }
    run(w, 0.25);
    w.balls().velocities().iter().map(|v| v.x).collect()
}

/// Newton's cradle passes the impulse down the row: the last `moving` balls
/// leave at the speed that came in, every other ball stays.
fn assert_cradle(speeds: &[f64], moving: usize, speed: f64, scene: &str) {
    let n = speeds.len();
    for (k, &v) in speeds.iter().enumerate() {
        if k >= n - moving {
            assert!(
                v >= 0.98 * speed,
                "{scene}: ball {k} of {n} leaves at {v:.4} m/s, not {speed}: {speeds:?}"
            );
        } else {
            assert!(
                v.abs() <= 0.02 * speed,
                "{scene}: ball {k} of {n} moves at {v:.4} m/s: {speeds:?}"
            );
        }
    }
}

#[test]
fn newtons_cradle_in_weightless_space_passes_the_impulse_to_the_far_ball() {
    for n in [2, 3, 5, 8] {
        for speed in [0.3, 1.0, 4.0] {
            let mut w = open_space(1.0, n);
            let speeds = row_after_impact(&mut w, DVec3::new(-1.0, 20.0, 0.0), 1, speed);
            assert_cradle(&speeds, 1, speed, &format!("{n} balls at {speed} m/s"));
        }
    }
}

#[test]
fn newtons_cradle_on_the_floor_passes_the_impulse_to_the_far_ball() {
    for n in [3, 5, 7] {
        let mut w = frictionless_floor(1.0, n);
        let r = w.config().balls.radius;
        let speeds = row_after_impact(&mut w, DVec3::new(-1.0, r, 0.5), 1, 1.0);
        assert_cradle(&speeds, 1, 1.0, &format!("{n} balls on the floor"));
    }
}

#[test]
fn two_in_two_out_and_three_in_three_out() {
    for (n, moving) in [(5, 2), (5, 3), (6, 2)] {
        let mut w = open_space(1.0, n);
        let speeds = row_after_impact(&mut w, DVec3::new(-1.0, 20.0, 0.0), moving, 1.0);
        assert_cradle(&speeds, moving, 1.0, &format!("{moving} into {n}"));
    }
}

/// A cue ball sent at `speed` into a touching triangle of ten, slightly off
/// centre by `offset`.
fn billiards_break(w: &mut World, speed: f64, offset: f64) {
    let r = w.config().balls.radius;
    let centre = DVec3::new(0.0, 20.0, 0.0);
    // Rows of 1, 2, 3 and 4 balls, each touching its neighbours.
    let row_step = 3.0_f64.sqrt() * r;
    let mut k = 0;
    for row in 0..4 {
        for col in 0..=row {
            let z = (col as f64 - 0.5 * row as f64) * 2.0 * r;
            let p = centre + DVec3::new(row as f64 * row_step, 0.0, z);
            w.balls_mut().set(k, p, DVec3::ZERO);
            k += 1;
        }
    }
    let cue = centre + DVec3::new(-0.6, 0.0, offset);
    w.balls_mut().set(k, cue, DVec3::X * speed);
}

#[test]
fn a_cue_ball_breaks_a_touching_triangle_keeping_momentum_and_energy() {
    for (speed, offset) in [(3.0, 0.0), (5.0, 0.013), (1.5, -0.04)] {
        let mut w = open_space(1.0, 11);
        billiards_break(&mut w, speed, offset);
        let (p0, e0) = (momentum(&w), w.energy().total());
        run(&mut w, 0.5);
        let (p1, e1) = (momentum(&w), w.energy().total());
        let scale = p0.length();
        assert!(
            (p1 - p0).length() <= 1e-9 * scale,
            "cue at {speed} m/s: momentum changed by {:e} of itself",
            (p1 - p0).length() / scale
        );
        assert!(
            ((e1 - e0) / e0).abs() <= 1e-3,
            "cue at {speed} m/s: energy changed by {:.4} %",
            100.0 * (e1 - e0) / e0
        );
        // The break did happen: the triangle's balls fly apart, each
        // leaving the cue's line.
        let moving = w.balls().velocities()[..10]
            .iter()
            .filter(|v| v.length() > 0.05 * speed)
            .count();
        assert!(moving >= 5, "cue at {speed} m/s: only {moving} balls move");
    }
}

#[test]
fn unequal_masses_head_on_give_the_one_dimensional_velocities() {
    for (m1, m2, v1, v2, e) in [
        (0.25, 1.0, 2.0, -0.5, 1.0),
        (3.0, 0.1, 1.0, 0.0, 1.0),
        (0.5, 0.5, 1.5, -1.5, 0.6),
        (1.0, 7.0, 0.8, 0.3, 0.85),
    ] {
        let mut w = open_space(e, 2);
        let r = w.config().balls.radius;
        let dt = w.config().solver.dt;
        // They touch 0.37 steps into the fourth step.
        let meet = 3.37 * dt;
        let x1 = -r - (v1 * meet);
        let x2 = r - (v2 * meet);
        w.balls_mut()
            .set(0, DVec3::new(x1, 20.0, 0.0), DVec3::X * v1);
        w.balls_mut()
            .set(1, DVec3::new(x2, 20.0, 0.0), DVec3::X * v2);
        w.balls_mut().set_mass(0, m1);
        w.balls_mut().set_mass(1, m2);
        run(&mut w, 0.1);
        let total = m1 + m2;
        let expected1 = (m1 * v1 + m2 * v2 - m2 * e * (v1 - v2)) / total;
        let expected2 = (m1 * v1 + m2 * v2 + m1 * e * (v1 - v2)) / total;
        let v = w.balls().velocities();
        assert!(
            (v[0].x - expected1).abs() < 1e-6 && (v[1].x - expected2).abs() < 1e-6,
            "m {m1}, {m2}, v {v1}, {v2}, e {e}: got {:.9}, {:.9}, expected {expected1:.9}, {expected2:.9}",
            v[0].x,
            v[1].x
        );
        assert!(v[0].y.abs() < 1e-12 && v[1].z.abs() < 1e-12);
    }
}

#[test]
fn an_elastic_room_keeps_its_energy_at_any_ball_count() {
    for (gravity, allowed) in [(0.0, 1e-3), (9.81, 5e-3)] {
        for n in [100, 400, 1000] {
            for seed in [21, 22] {
                let mut w = build(elastic_room(n, gravity), seed);
                let start = w.energy().total();
                let mut before = start;
                let mut worst_growth = f64::NEG_INFINITY;
                for _ in 0..(10.0 / w.config().solver.dt) as usize {
                    w.step();
                    let after = w.energy().total();
                    worst_growth = worst_growth.max((after - before) / before);
                    before = after;
                }
                let change = (before - start) / start;
                let scene = format!("{n} balls, gravity {gravity}, seed {seed}");
                assert!(
                    change.abs() <= allowed,
                    "{scene}: energy changed by {:.4} % over 10 s",
                    100.0 * change
                );
                assert!(
                    worst_growth <= 1e-6,
                    "{scene}: energy grew by {worst_growth:e} of itself in one step"
                );
                let balls = w.balls();
                assert!(balls.alive().iter().all(|&a| a));
            }
        }
    }
}

#[test]
fn a_weightless_crowd_far_from_the_walls_keeps_its_momentum() {
    // Balls in a cube in the middle of a huge room, flying at each other
    // for less time than any needs to reach a wall.
    for (n, seed) in [(200, 3_u64), (500, 4)] {
        let mut cfg = elastic_room(n, 0.0);
        cfg.room.size = DVec3::new(60.0, 60.0, 60.0);
        cfg.balls.speed_max = 2.0;
        let mut w = build(cfg, seed);
        let mut rng = rolypoly_physics::Rng::new(seed);
        let side = (n as f64).cbrt().ceil() as usize;
        let r = w.config().balls.radius;
        for k in 0..n {
            let cell = DVec3::new(
                (k % side) as f64,
                (k / side % side) as f64,
                (k / side / side) as f64,
            );
            let p = DVec3::new(0.0, 30.0, 0.0) + (cell - 0.5 * side as f64) * 3.0 * r;
            let v = rng.direction() * rng.range(0.5, 2.0);
            w.balls_mut().set(k, p, v);
        }
        let (p0, e0) = (momentum(&w), w.energy().total());
        let mut collisions = 0;
        for _ in 0..240 {
            w.step();
            collisions += w.drain_events().count();
        }
        let (p1, e1) = (momentum(&w), w.energy().total());
        let scale: f64 = (0..n)
            .map(|i| w.balls().masses()[i] * w.balls().velocities()[i].length())
            .sum();
        assert!(
            collisions > n / 2,
            "{n} balls: only {collisions} collisions"
        );
        assert!(
            (p1 - p0).length() <= 1e-9 * scale,
            "{n} balls: momentum changed by {:e} of the sum of |m v|",
            (p1 - p0).length() / scale
        );
        assert!(
            ((e1 - e0) / e0).abs() <= 1e-3,
            "{n} balls: energy {e0} -> {e1}"
        );
    }
}
