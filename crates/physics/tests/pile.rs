//! A deep pile holds its weight (P3): balls resting under many layers of
//! others do not sink into one another, the pile does not creep, and it
//! comes to rest without jitter (P4).

mod common;

use common::{build, empty_room};
use glam::DVec3;
use rolypoly_physics::World;

/// The deepest overlap between two balls (metres), by brute force.
fn deepest_overlap(w: &World) -> f64 {
    let p = w.balls().positions();
    let r = w.balls().radii();
    let mut deepest: f64 = 0.0;
    for i in 0..p.len() {
        for j in i + 1..p.len() {
            deepest = deepest.max(r[i] + r[j] - p[i].distance(p[j]));
        }
    }
    deepest
}

/// `layers` loose layers of 6 x 6 balls dropped into a narrow shaft, the
/// ball at lattice site `k` numbered `number(k)`, with `friction` between
/// them. The numbering changes only the order in which the solver visits
/// contacts.
fn shaft(layers: usize, number: impl Fn(usize) -> usize, friction: f64) -> World {
    let mut cfg = empty_room();
    cfg.room.size = DVec3::new(1.3, 4.0, 1.3);
    cfg.balls.radius = 0.1;
    cfg.balls.restitution = 0.5;
    // With friction the shaft's weight also hangs on its walls, by
    // arches (Janssen's silo): those must hold still too.
    cfg.balls.friction = friction;
    let per_layer = 36;
    cfg.balls.count = layers * per_layer;
    let mut w = build(cfg, 1);
    for k in 0..layers * per_layer {
        let (layer, cell) = (k / per_layer, k % per_layer);
        // A slight stagger per layer, so the pile has to find its own packing.
        let shift = if layer % 2 == 0 { 0.0 } else { 0.03 };
        let x = -0.525 + 0.21 * (cell % 6) as f64 + shift;
        let z = -0.525 + 0.21 * (cell / 6) as f64 + shift;
        let y = 0.12 + 0.23 * layer as f64;
        w.balls_mut()
            .set(number(k), DVec3::new(x, y, z), DVec3::new(0.0, -0.5, 0.0));
    }
    w
}

#[test]
fn a_deep_pile_holds_its_weight_and_comes_to_rest() {
    // Whether a pile holds must not hang on the order of its contacts: an
    // unconverged solver can hold one order and let another creep.
    let count = 12 * 36;
    for friction in [0.0, 0.4] {
        settles(shaft(12, |k| k, friction));
        settles(shaft(12, |k| count - 1 - k, friction));
        settles(shaft(12, |k| (k * 7) % count, friction));
    }
}

fn settles(mut w: World) {
    assert!(deepest_overlap(&w) <= 0.0, "the pile starts with overlaps");
    let dt = w.config().solver.dt;
    let steps = |s: f64| (s / dt).round() as usize;
    for _ in 0..steps(2.0) {
        w.step();
    }
    let settled = deepest_overlap(&w);
    let energy = w.energy().total();
    for _ in 0..steps(2.0) {
        w.step();
    }
    let later = deepest_overlap(&w);
    let fastest = w
        .balls()
        .velocities()
        .iter()
        .map(|v| v.length())
        .fold(0.0, f64::max);
    // Creep would show as the pile sinking: potential energy lost.
    let sunk = (energy - w.energy().total()) / (w.balls().len() as f64 * 9.81);
    println!(
        "deepest overlap {:.2} mm at 2 s, {:.2} mm at 4 s; sank {:.3} mm on average; \
         fastest ball {:.2} mm/s; {} steps retaken",
        settled * 1e3,
        later * 1e3,
        sunk * 1e3,
        fastest * 1e3,
        w.retakes()
    );
    // A tenth of the radius: a pile that creeps reaches a third or more.
    assert!(settled < 0.01, "overlap {settled} m at 2 s");
    assert!(later < 0.01, "overlap {later} m at 4 s");
    assert!(sunk < 0.002, "the pile sank by {sunk} m in 2 s");
    // At rest, without jitter (P4): nothing in the shaft moves a millimetre a second.
    assert!(fastest < 0.001, "a ball still moves at {fastest} m/s");
}
