use super::*;
use crate::config::WorldConfig;
use crate::rng::Rng;

/// A weightless, lossless crowd of `n` balls on a lattice in the middle of
/// a room too large for any to reach a wall in the test, flying at each
/// other, slowly enough that none lies packed in the crowd: enough impacts
/// a step that they are resolved side by side.
fn crowd(n: usize, seed: u64) -> World {
    let mut cfg = WorldConfig::default();
    cfg.tumblers.placements.clear();
    cfg.gravity = 0.0;
    cfg.balls.count = n;
    cfg.balls.restitution = 1.0;
    cfg.room.restitution = 1.0;
    cfg.room.friction = 0.0;
    cfg.room.rolling_resistance = 0.0;
    cfg.solver.bounce_threshold = 0.0;
    cfg.room.size = DVec3::new(60.0, 60.0, 60.0);
    let mut w = World::new(cfg, seed).expect("the crowd builds");
    let mut rng = Rng::new(seed);
    let side = (n as f64).cbrt().ceil() as usize;
    let r = w.config().balls.radius;
    for k in 0..n {
        let cell = DVec3::new(
            (k % side) as f64,
            (k / side % side) as f64,
            (k / side / side) as f64,
        );
        let p = DVec3::new(0.0, 30.0, 0.0) + (cell - 0.5 * side as f64) * 2.4 * r;
        let v = rng.direction() * rng.range(0.5, 1.0);
        w.balls_mut().set(k, p, v);
    }
    w
}

fn momentum(w: &World) -> (DVec3, f64) {
    let b = w.balls();
    (0..b.len()).fold((DVec3::ZERO, 0.0), |(p, scale), i| {
        let mv = b.mass[i] * b.velocity[i];
        (p + mv, scale + mv.length())
    })
}

#[test]
fn impacts_resolved_side_by_side_keep_momentum_and_energy() {
    for (n, seed) in [(4500, 5_u64), (6000, 6)] {
        let mut w = crowd(n, seed);
        let (p0, scale) = momentum(&w);
        let e0 = w.energy().total();
        let mut before = e0;
        let mut side_by_side = 0;
        for _ in 0..30 {
            w.step();
            if halving_layer(&w.scratch.impacts.found).is_some() {
                side_by_side += 1;
            }
            let after = w.energy().total();
            assert!(
                after <= before * (1.0 + 1e-6),
                "{n} balls: energy grew from {before} to {after} in one step"
            );
            before = after;
        }
        assert!(side_by_side > 0, "{n} balls: never side by side");
        let (p1, _) = momentum(&w);
        assert!(
            (p1 - p0).length() <= 1e-9 * scale,
            "{n} balls: momentum changed by {:e} of the sum of |m v|",
            (p1 - p0).length() / scale
        );
        assert!(
            ((before - e0) / e0).abs() <= 1e-3,
            "{n} balls: energy {e0} -> {before}"
        );
    }
}

#[test]
fn impacts_resolved_side_by_side_are_the_same_on_one_thread_and_two() {
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("a thread pool");
        pool.install(|| {
            let mut w = crowd(4500, 9);
            for _ in 0..10 {
                w.step();
            }
            let b = w.balls();
            let bits = |v: &[DVec3]| -> Vec<u64> {
                v.iter()
                    .flat_map(|x| x.to_array().map(f64::to_bits))
                    .collect()
            };
            (bits(&b.position), bits(&b.velocity), bits(&b.spin))
        })
    };
    assert!(run(1) == run(2), "one thread and two disagree");
}
