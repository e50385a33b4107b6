//! Stage 7, the overlaps (`overlaps.wgsl`): what the velocities left of
//! overlap pushed out by position, in Jacobi sweeps, one dispatch each.

use super::{JacobiSweeps, Recorder, Shaders};
use crate::profile::Stage;

pub struct Overlaps {
    sweeps: JacobiSweeps,
    in_one_group: wgpu::ComputePipeline,
}

impl Overlaps {
    pub fn new(shaders: &Shaders, sweeps: u32) -> Overlaps {
        let module = shaders.module(
            "overlaps",
            &[("SHIFT_SWEEPS", sweeps)],
            include_str!("overlaps.wgsl"),
        );
        let pipeline = |entry: &str| shaders.pipeline(&module, entry);
        Overlaps {
            sweeps: JacobiSweeps::new(sweeps, pipeline, ["overlaps_forth", "overlaps_back"]),
            in_one_group: pipeline("overlaps_in_one_group"),
        }
    }

    pub fn record(&self, step: &mut Recorder) {
        let small = step.small;
        step.stage(Stage::Overlaps, |pass| {
            if small {
                return pass.workgroups(&self.in_one_group, 1, 1);
            }
            self.sweeps.record(pass);
        });
    }
}
