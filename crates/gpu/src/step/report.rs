//! What leaves a step (`report.wgsl`): stage 5, each tumbler's push from
//! the balls, summed in a fixed order; and last, the instances the
//! renderer draws.

use super::{Recorder, Shaders};
use crate::profile::Stage;

pub struct Report {
    sum_tumbler_push: wgpu::ComputePipeline,
    write_instances: wgpu::ComputePipeline,
}

impl Report {
    pub fn new(shaders: &Shaders) -> Report {
        let module = shaders.module("report", &[], include_str!("report.wgsl"));
        Report {
            sum_tumbler_push: shaders.pipeline(&module, "sum_tumbler_push"),
            write_instances: shaders.pipeline(&module, "write_instances"),
        }
    }

    /// One workgroup a tumbler.
    pub fn record_pushes(&self, step: &mut Recorder, tumblers: u32) {
        step.stage(Stage::Push, |pass| {
            if tumblers > 0 {
                pass.workgroups(&self.sum_tumbler_push, tumblers, 1);
            }
        });
    }

    pub fn record_instances(&self, step: &mut Recorder) {
        step.stage(Stage::Instances, |pass| {
            pass.over_balls(&self.write_instances)
        });
    }
}
