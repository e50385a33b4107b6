//! Stage 7, the overlaps (`overlaps.wgsl`): what the velocities left of
//! overlap pushed out by position, in Jacobi sweeps, one dispatch each.

use super::{Recorder, Shaders};
use crate::profile::Stage;

pub struct Overlaps {
    /// A sweep each way (see `pos_in` in `common.wgsl`).
    sweep: [wgpu::ComputePipeline; 2],
    sweeps: u32,
    in_one_group: wgpu::ComputePipeline,
}

impl Overlaps {
    pub fn new(shaders: &Shaders, sweeps: u32) -> Overlaps {
        let module = shaders.module(
            "overlaps",
            &[("SHIFT_SWEEPS", sweeps)],
            include_str!("overlaps.wgsl"),
        );
        Overlaps {
            sweep: [
                shaders.pipeline(&module, "overlaps_forth"),
                shaders.pipeline(&module, "overlaps_back"),
            ],
            sweeps,
            in_one_group: shaders.pipeline(&module, "overlaps_in_one_group"),
        }
    }

    pub fn record(&self, step: &mut Recorder) {
        let small = step.small;
        step.stage(Stage::Overlaps, |pass| {
            if small {
                return pass.workgroups(&self.in_one_group, 1, 1);
            }
            for sweep in 0..self.sweeps as usize {
                pass.over_balls(&self.sweep[sweep % 2]);
            }
        });
    }
}
