//! The pit in the rolypoly GPU engine.

use glam::DVec3;
use rolypoly_gpu::{Compute, GpuBalls, GpuError};
use rolypoly_physics::World;

use crate::ours::world_for;
use crate::pit::{Pit, PitEngine};

/// The pit's balls on the GPU; the world keeps nothing else.
pub struct GpuPit {
    world: World,
    balls: GpuBalls,
}

impl GpuPit {
    /// The pit as the CPU engine starts it, its balls moved to `compute`.
    pub fn new(pit: &Pit, compute: &Compute) -> Result<GpuPit, String> {
        let mut world = world_for(pit)?;
        let balls = GpuBalls::on_compute(compute, &mut world).map_err(|e| e.to_string())?;
        Ok(GpuPit { world, balls })
    }

    /// Dispatches the engine's last step recorded.
    pub fn dispatches_per_step(&self) -> u32 {
        self.balls.dispatches_per_step()
    }

    /// Each stage's mean GPU seconds over `steps` more steps, where the
    /// adapter writes timestamps.
    pub fn profile(&mut self, steps: u32) -> Result<Option<[f64; rolypoly_gpu::STAGES]>, GpuError> {
        self.balls.profile(&mut self.world, steps)
    }
}

impl PitEngine for GpuPit {
    fn name(&self) -> String {
        "rolypoly-gpu".into()
    }

    fn step(&mut self) {
        self.world.step();
        if let Err(e) = self.balls.step(&mut self.world) {
            panic!("the GPU engine stopped: {e}");
        }
    }

    fn finish(&mut self) {
        if let Err(e) = self.balls.finish() {
            panic!("the GPU engine stopped: {e}");
        }
    }

    fn read(&self, positions: &mut Vec<DVec3>, velocities: &mut Vec<DVec3>) {
        let state = match self.balls.read() {
            Ok(state) => state,
            Err(e) => panic!("the GPU engine's balls could not be read: {e}"),
        };
        positions.clear();
        positions.extend(state.positions.iter().map(|p| p.as_dvec3()));
        velocities.clear();
        velocities.extend(state.velocities.iter().map(|v| v.as_dvec3()));
    }
}
