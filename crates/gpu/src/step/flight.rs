//! Stage 6, the flight (`flight.wgsl`): balls a contact held move at their
//! solved velocity; others fly their exact parabola, bouncing exactly off
//! the walls.

use super::{Recorder, Shaders};
use crate::profile::Stage;

pub struct Flight {
    fly: wgpu::ComputePipeline,
}

impl Flight {
    pub fn new(shaders: &Shaders) -> Flight {
        let module = shaders.module("flight", &[], include_str!("flight.wgsl"));
        Flight {
            fly: shaders.pipeline(&module, "fly"),
        }
    }

    pub fn record(&self, step: &mut Recorder) {
        step.stage(Stage::Flight, |pass| pass.over_balls(&self.fly));
    }
}
