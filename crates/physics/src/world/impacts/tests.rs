use super::*;
use crate::config::WorldConfig;

/// A weightless, lossless crowd of `n` balls in an 8 x 4 x 8 m room, flying in all
/// directions, slowly enough that few lie packed in the crowd: enough
/// impacts a step that they are resolved side by side.
fn crowd(n: usize, seed: u64) -> World {
    let mut cfg = WorldConfig::default();
    cfg.tumblers.placements.clear();
    cfg.gravity = 0.0;
    cfg.balls.count = n;
    cfg.balls.speed_max = 1.0;
    cfg.balls.restitution = 1.0;
    cfg.room.restitution = 1.0;
    cfg.room.friction = 0.0;
    cfg.room.rolling_resistance = 0.0;
    cfg.balls.friction = 0.0;
    cfg.balls.rolling_resistance = 0.0;
    cfg.solver.bounce_threshold = 0.0;
    cfg.room.size = DVec3::new(8.0, 4.0, 8.0);
    World::new(cfg, seed).expect("the crowd builds")
}

#[test]
fn impacts_resolved_side_by_side_keep_the_energy() {
    for (n, seed) in [(6000, 5_u64), (8000, 6)] {
        let mut w = crowd(n, seed);
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
            let mut w = crowd(6000, 9);
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
