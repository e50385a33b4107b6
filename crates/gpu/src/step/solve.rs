//! Stage 4, the contact solver (`solve.wgsl`): gravity and the warm start
//! given to the velocities, then Jacobi sweeps with mass splitting, one
//! dispatch each.

use super::{Recorder, Shaders};
use crate::profile::Stage;

pub struct Solve {
    warm_start: wgpu::ComputePipeline,
    /// A sweep each way (see `vel_in` in `common.wgsl`).
    sweep: [wgpu::ComputePipeline; 2],
    sweeps: u32,
    in_one_group: wgpu::ComputePipeline,
}

impl Solve {
    pub fn new(shaders: &Shaders, sweeps: u32) -> Solve {
        let module = shaders.module(
            "solve",
            &[("SOLVE_SWEEPS", sweeps)],
            include_str!("solve.wgsl"),
        );
        Solve {
            warm_start: shaders.pipeline(&module, "warm_start"),
            sweep: [
                shaders.pipeline(&module, "solve_forth"),
                shaders.pipeline(&module, "solve_back"),
            ],
            sweeps,
            in_one_group: shaders.pipeline(&module, "solve_in_one_group"),
        }
    }

    pub fn record(&self, step: &mut Recorder) {
        let small = step.small;
        step.stage(Stage::Solve, |pass| {
            pass.over_balls(&self.warm_start);
            if small {
                return pass.workgroups(&self.in_one_group, 1, 1);
            }
            for sweep in 0..self.sweeps as usize {
                pass.over_balls(&self.sweep[sweep % 2]);
            }
        });
    }
}
