//! Stage 5, what the balls did to the tumblers (`report.wgsl`): each
//! tumbler's push from the balls, summed in a fixed order.

use super::{Kernel, Recorder, Shaders};
use crate::profile::Stage;

pub struct Report {
    sum_tumbler_push: Kernel,
}

impl Report {
    pub fn new(shaders: &Shaders) -> Report {
        let module = shaders.module("report", &[], include_str!("report.wgsl"));
        Report {
            sum_tumbler_push: shaders.pipeline(&module, "sum_tumbler_push"),
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
}
