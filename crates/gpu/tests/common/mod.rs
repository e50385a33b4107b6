//! What the GPU engine's tests share: a device, scenes, and measures.

#![allow(dead_code)]

use glam::DVec3;
use rolypoly_gpu::{BallState, Compute, GpuBalls};
use rolypoly_physics::{BallPlacement, World, WorldConfig};

/// The one device the tests open (lavapipe in CI); a missing adapter fails loudly.
/// The adapter is printed, so that a failure names where it ran. A
/// software Vulkan may take minutes over the steps a test queues before it
/// reads the balls back: the tests wait up to ten.
pub fn compute() -> Compute {
    rolypoly_gpu::set_program_gpu_timeout(std::time::Duration::from_secs(600));
    let compute = Compute::headless()
        .unwrap_or_else(|e| panic!("the GPU engine's tests need an adapter: {e}"));
    eprintln!("on {}", compute.adapter);
    compute
}

/// An empty room of `size`, no tumblers, no fireball, the given balls' count.
pub fn empty_room(size: DVec3, balls: usize) -> WorldConfig {
    let mut config = WorldConfig::default();
    config.tumblers.placements.clear();
    config.fireball.starts_active = false;
    config.room.size = size;
    config.balls.count = balls;
    config.balls.pour.rate = 0.0;
    config
}

/// A world of `config` with its balls on the GPU.
pub fn build(compute: &Compute, config: WorldConfig, seed: u64) -> (World, GpuBalls) {
    let mut world = World::new(config, seed).expect("the scene builds");
    let balls = GpuBalls::on_compute(compute, &mut world).expect("the engine starts");
    (world, balls)
}

/// One step of the world's tumblers and fireball, then its balls.
pub fn step(world: &mut World, balls: &mut GpuBalls) {
    world.step();
    balls.step(world).expect("a step");
}

/// A placed ball at `position` moving at `velocity`.
pub fn placed(position: DVec3, velocity: DVec3) -> BallPlacement {
    BallPlacement::new(position, velocity)
}

/// The deepest overlap between two live balls, or of a ball with a wall (m),
/// and how many balls are outside the room (the first of them printed).
pub fn overlap_and_escapes(state: &BallState, min: DVec3, max: DVec3) -> (f64, usize) {
    let live: Vec<usize> = (0..state.positions.len())
        .filter(|&i| state.alive[i])
        .collect();
    let mut deepest: f64 = 0.0;
    let mut escaped = 0;
    for &i in &live {
        let p = state.positions[i].as_dvec3();
        let r = f64::from(state.radii[i]);
        if !(p.cmpge(min).all() && p.cmple(max).all() && p.is_finite()) {
            if escaped == 0 {
                eprintln!(
                    "ball {i} out of the room: at {p}, moving at {}",
                    state.velocities[i]
                );
            }
            escaped += 1;
        }
        let wall = (p - min).min(max - p).min_element();
        deepest = deepest.max(r - wall);
    }
    // Sorted along x, so that only near neighbours are compared.
    let mut order = live.clone();
    order.sort_by(|&a, &b| state.positions[a].x.total_cmp(&state.positions[b].x));
    for (k, &i) in order.iter().enumerate() {
        let p = state.positions[i].as_dvec3();
        for &j in &order[k + 1..] {
            let q = state.positions[j].as_dvec3();
            let reach = f64::from(state.radii[i] + state.radii[j]);
            if q.x - p.x > reach {
                break;
            }
            deepest = deepest.max(reach - p.distance(q));
        }
    }
    (deepest, escaped)
}

/// The share of live balls slower than `speed` (m/s).
pub fn share_at_rest(state: &BallState, speed: f32) -> f64 {
    let live: Vec<usize> = (0..state.positions.len())
        .filter(|&i| state.alive[i])
        .collect();
    let resting = live
        .iter()
        .filter(|&&i| state.velocities[i].length() < speed)
        .count();
    resting as f64 / live.len().max(1) as f64
}
