//! Stage 4, the contact solver (`solve.wgsl`): gravity and the warm start
//! given to the velocities, then Jacobi sweeps with mass splitting, a few
//! a dispatch among each block of neighbouring balls (see `ball_at` in
//! `common.wgsl`).

use super::{JacobiSweeps, Recorder, Shaders, SweepCounts};
use crate::profile::Stage;

pub struct Solve {
    warm_start: wgpu::ComputePipeline,
    sweeps: JacobiSweeps,
    in_one_group: wgpu::ComputePipeline,
}

impl Solve {
    pub fn new(shaders: &Shaders, counts: &SweepCounts) -> Solve {
        let module = shaders.module(
            "solve",
            &[
                ("SOLVE_DISPATCHES", counts.solve_dispatches),
                ("BLOCK_SWEEPS", counts.solve_block_sweeps),
            ],
            include_str!("solve.wgsl"),
        );
        let pipeline = |entry: &str| shaders.pipeline(&module, entry);
        Solve {
            warm_start: pipeline("warm_start"),
            sweeps: JacobiSweeps::new(
                counts.solve_dispatches,
                pipeline,
                ["solve_forth", "solve_back"],
            ),
            in_one_group: pipeline("solve_in_one_group"),
        }
    }

    pub fn record(&self, step: &mut Recorder) {
        let small = step.small;
        step.stage(Stage::Solve, |pass| {
            pass.over_balls(&self.warm_start);
            if small {
                return pass.workgroups(&self.in_one_group, 1, 1);
            }
            self.sweeps.record(pass);
        });
    }
}
