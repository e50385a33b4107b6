//! Stage 6, the flight (`flight.wgsl`): balls a contact held move at their
//! solved velocity; others fly their exact parabola, bouncing exactly off
//! the walls; each from where the solver shifted it, its impacts
//! reported (the pairs' in a pass before, as the flight moves the other
//! ball). A last pass writes what the renderer draws (in one, the flight
//! would bind more buffers than WebGPU promises).

use super::{Kernel, Recorder, Shaders};
use crate::profile::Stage;

pub struct Flight {
    report_pairs: Kernel,
    fly: Kernel,
    write_instances: Kernel,
}

impl Flight {
    pub fn new(shaders: &Shaders) -> Flight {
        let module = shaders.module("flight", &[], include_str!("flight.wgsl"));
        Flight {
            report_pairs: shaders.pipeline(&module, "report_pairs"),
            fly: shaders.pipeline(&module, "fly"),
            write_instances: shaders.pipeline(&module, "write_instances"),
        }
    }

    pub fn record(&self, step: &mut Recorder) {
        step.stage(Stage::Flight, |pass| {
            pass.over_balls(&self.report_pairs);
            pass.over_balls(&self.fly);
            pass.over_balls(&self.write_instances);
        });
    }

    /// The renderer's instances of the balls as they stand, without a step.
    pub fn record_instances(&self, step: &mut Recorder) {
        step.stage(Stage::Flight, |pass| pass.over_balls(&self.write_instances));
    }
}
