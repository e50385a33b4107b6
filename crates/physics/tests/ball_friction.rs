//! Friction between two balls (F1, F2) against rigid-body impulse theory:
//! an oblique impact sticks or slides, sidespin throws the struck ball, a
//! cut shot throws as tan(throw) = min(mu, 2 tan(cut) / (7 (1 + e))), and
//! every impact keeps momentum and never makes energy.

mod common;

use common::{empty_room, with_balls};
use glam::DVec3;
use rolypoly_physics::World;

const RADIUS: f64 = 0.1;
const MASS: f64 = 0.25;

/// Two balls in weightless open space with restitution `e` and friction
/// `mu`: ball 0 at the origin moving at `v` with spin `w`, ball 1 at rest
/// `offset` sideways (along z) on its path, `gap` ahead of touching along x.
fn strike(e: f64, mu: f64, v: DVec3, w: DVec3, offset: f64) -> World {
    let mut cfg = empty_room();
    cfg.gravity = 0.0;
    cfg.room.size = DVec3::splat(40.0);
    cfg.balls.radius = RADIUS;
    cfg.balls.mass = MASS;
    cfg.balls.restitution = e;
    cfg.balls.friction = mu;
    cfg.balls.rolling_resistance = 0.0;
    // Every approach, however slow, is an impact of the formulas.
    cfg.solver.bounce_threshold = 0.0;
    let mut world = with_balls(cfg, 2);
    let centre = DVec3::new(0.0, 20.0, 0.0);
    // Ball 1 sits where ball 0's line of flight meets it `offset` sideways.
    let along = ((2.0 * RADIUS).powi(2) - offset * offset).sqrt();
    let dt = world.config().solver.dt;
    let start = centre - DVec3::X * (along + v.x * 5.3 * dt);
    world.balls_mut().set(0, start, v);
    world.balls_mut().set_spin(0, w);
    world
        .balls_mut()
        .set(1, centre + DVec3::Z * offset, DVec3::ZERO);
    world
}

/// Runs the world a third of a second, long past the impact.
fn run(world: &mut World) {
    for _ in 0..40 {
        world.step();
    }
}

fn momentum(world: &World) -> DVec3 {
    let b = world.balls();
    (0..2).map(|k| b.velocities()[k] * b.masses()[k]).sum()
}

fn energy(world: &World) -> f64 {
    world.energy().kinetic
}

/// The two balls' velocities and spins after the impact, from the impulse
/// formulas: the normal impulse (1 + e) m v_n / 2 along the line of centres
/// `n` (from ball 1 to ball 0), and friction against the contact point's
/// sliding `u`, stopping it if mu times the normal impulse suffices (it
/// takes m |u| / 7 for two equal solid spheres), else mu times it.
fn expected(e: f64, mu: f64, v: DVec3, w: DVec3, n: DVec3) -> [DVec3; 4] {
    let approach = -v.dot(n);
    let normal = (1.0 + e) * MASS * approach / 2.0;
    let slip = v - (RADIUS * w).cross(n);
    let slip = slip - slip.dot(n) * n;
    let stop = MASS * slip / 7.0;
    let friction = if stop.length() <= mu * normal {
        -stop
    } else {
        -slip.normalize_or_zero() * mu * normal
    };
    let impulse = n * normal + friction;
    let inertia = 0.4 * MASS * RADIUS * RADIUS;
    let turn = n.cross(friction) * (RADIUS / inertia);
    [v + impulse / MASS, w - turn, -impulse / MASS, -turn]
}

/// Ball 0 struck ball 1 `offset` sideways: the line of centres at contact.
fn line_of_centres(offset: f64) -> DVec3 {
    let along = ((2.0 * RADIUS).powi(2) - offset * offset).sqrt();
    DVec3::new(-along, 0.0, -offset).normalize()
}

fn check(e: f64, mu: f64, v: DVec3, w: DVec3, offset: f64) {
    let mut world = strike(e, mu, v, w, offset);
    let (p0, e0) = (momentum(&world), energy(&world));
    run(&mut world);
    let b = world.balls();
    let got = [
        b.velocities()[0],
        b.spins()[0],
        b.velocities()[1],
        b.spins()[1],
    ];
    let want = expected(e, mu, v, w, line_of_centres(offset));
    for (k, (g, x)) in got.iter().zip(&want).enumerate() {
        assert!(
            (*g - *x).length() < 1e-6 * (1.0 + x.length()),
            "e {e} mu {mu} v {v} w {w} offset {offset}: quantity {k} is {g}, theory {x}"
        );
    }
    let p1 = momentum(&world);
    assert!((p1 - p0).length() < 1e-9, "momentum {p0} -> {p1}");
    assert!(energy(&world) <= e0 * (1.0 + 1e-12), "energy grew");
}

#[test]
fn oblique_impacts_stick_or_slide_as_impulse_theory_says() {
    // Sliding speed against 3.5 mu (1 + e) times the approach: a thin cut
    // slides, a full one sticks; both at several speeds and coefficients.
    for &(mu, e) in &[(0.05, 0.9), (0.2, 0.5), (0.5, 0.85), (1.0, 0.2)] {
        for &speed in &[0.5, 2.0, 6.0] {
            for &cut in &[0.1, 0.5, 0.9, 0.99] {
                check(e, mu, DVec3::X * speed, DVec3::ZERO, cut * 2.0 * RADIUS);
            }
        }
    }
}

#[test]
fn spin_carries_into_the_struck_ball() {
    // Head on with sidespin (about y): the contact point slides along z,
    // friction throws the struck ball sideways and spins it.
    for &(mu, spin) in &[(0.1, 20.0), (0.4, 20.0), (0.4, -60.0), (1.0, 5.0)] {
        let w = DVec3::Y * spin;
        check(0.8, mu, DVec3::X * 3.0, w, 0.0);
        let mut world = strike(0.8, mu, DVec3::X * 3.0, w, 0.0);
        run(&mut world);
        let struck = world.balls().velocities()[1];
        assert!(
            struck.z.abs() > 1e-3,
            "mu {mu}: no throw from sidespin ({struck})"
        );
    }
    // Spin about the line of centres slides nothing at the contact point
    // (there is no twisting friction at a point): both keep their own.
    let w = DVec3::X * 30.0;
    check(0.8, 0.5, DVec3::X * 3.0, w, 0.0);
    let mut world = strike(0.8, 0.5, DVec3::X * 3.0, w, 0.0);
    run(&mut world);
    assert_eq!(world.balls().spins()[1], DVec3::ZERO);
}

#[test]
fn a_cut_shot_throws_the_object_ball_off_the_line_of_centres() {
    for &(mu, e) in &[(0.06, 0.95), (0.2, 0.9), (0.5, 0.5)] {
        for &cut_deg in &[5.0_f64, 15.0, 30.0, 45.0, 60.0] {
            let cut = cut_deg.to_radians();
            let offset = 2.0 * RADIUS * cut.sin();
            let mut world = strike(e, mu, DVec3::X * 2.0, DVec3::ZERO, offset);
            run(&mut world);
            let object = world.balls().velocities()[1];
            let n = -line_of_centres(offset);
            let throw = object.cross(n).length().atan2(object.dot(n));
            let theory = mu.min(2.0 * cut.tan() / (7.0 * (1.0 + e))).atan();
            assert!(
                (throw - theory).abs() < 1e-6,
                "mu {mu} e {e} cut {cut_deg}: thrown {:.4} deg, theory {:.4} deg",
                throw.to_degrees(),
                theory.to_degrees()
            );
            assert!(throw > 0.0);
        }
    }
}

/// A ball dropped on a standing tumbler's top knot, spinning about x at 30
/// rad/s, with friction `mu` between them: its velocity along z and the
/// knot's, just after the impact.
fn spinning_ball_on_a_tumbler(mu: f64) -> (f64, f64) {
    let mut cfg = empty_room();
    cfg.tumblers.placements = vec![common::tumbler_at(0.0, 0.0, DVec3::X, 0.0)];
    cfg.balls.friction = mu;
    let mut world = with_balls(cfg, 1);
    let shape = world.tumbler_shape().clone();
    let knot = world.tumblers()[0].sphere_center(&shape, 5);
    let top = knot.y + shape.spheres[5].radius + world.config().balls.radius;
    world
        .balls_mut()
        .set(0, DVec3::new(knot.x, top + 0.3, knot.z), DVec3::ZERO);
    world.balls_mut().set_spin(0, DVec3::X * 30.0);
    // The fall takes a quarter of a second; the bounce is over in a step.
    for _ in 0..(0.3 / world.config().solver.dt) as usize {
        world.step();
    }
    let ball = world.balls().velocities()[0].z;
    let knot_now = world.tumblers()[0].sphere_center(&shape, 5);
    (ball, world.tumblers()[0].point_velocity(knot_now).z)
}

#[test]
fn a_spinning_ball_throws_a_tumbler_and_is_thrown_off_it() {
    // The contact point of the ball slides along -z: friction sends the
    // ball along +z and the tumbler's top along -z, more with more friction.
    let (ball_0, top_0) = spinning_ball_on_a_tumbler(0.0);
    assert!(
        ball_0.abs() < 1e-9 && top_0.abs() < 1e-9,
        "{ball_0} {top_0}"
    );
    let mut last = 0.0;
    for mu in [0.1, 0.4] {
        let (ball, top) = spinning_ball_on_a_tumbler(mu);
        println!("mu {mu}: ball {ball:.3} m/s, tumbler's top {top:.3} m/s");
        assert!(
            ball > last + 0.05,
            "mu {mu}: the ball is thrown at {ball} m/s"
        );
        assert!(top < -0.01, "mu {mu}: the tumbler's top moves at {top} m/s");
        last = ball;
    }
}
