//! Stage 3, the impacts (`impacts.wgsl`): rounds in which each ball
//! meets the contact it touches first, if that contact's other side meets
//! it first too, so that impacts come one after another in time order and
//! a blow passes from ball to ball within the step. Each round first finds
//! the first contacts and lists the balls that have one, sizing the
//! round's bounces to the list, on the GPU: a round in which nothing
//! bounces dispatches no workgroups.

use super::{Recorder, Shaders};
use crate::bindings::{Buffers, READ_WRITE, compute_buffer};
use crate::layout::{IMPACT_DISPATCH_START, IMPACT_ROUNDS};
use crate::profile::Stage;

const ROUNDS: usize = IMPACT_ROUNDS as usize;

pub struct Impacts {
    /// Each round's: first contacts found and the list made, which also
    /// sizes the round's bounces.
    find_first: [wgpu::ComputePipeline; ROUNDS],
    /// Each round's bounces.
    bounce: [wgpu::ComputePipeline; ROUNDS],
    in_one_group: wgpu::ComputePipeline,
    /// The rounds' dispatches, and the group that binds them to the
    /// passes that size them (and to no other: a buffer a dispatch reads
    /// its size from may not be bound for writing in it).
    dispatches: wgpu::Buffer,
    sizing: wgpu::BindGroup,
}

impl Impacts {
    pub fn new(shaders: &Shaders, buffers: &Buffers, balls: &wgpu::BindGroupLayout) -> Impacts {
        let device = shaders.device;
        let sizing_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("impact dispatches"),
            entries: &[compute_buffer(0, READ_WRITE)],
        });
        let sizing = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("impact dispatches"),
            layout: &sizing_layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: buffers.impact_dispatch.as_entire_binding(),
            }],
        });
        let sizing_pipelines = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("balls, sizing the impact rounds"),
            bind_group_layouts: &[Some(balls), Some(&sizing_layout)],
            immediate_size: 0,
        });
        let module = shaders.module(
            "impacts",
            &[("IMPACT_ROUNDS", IMPACT_ROUNDS)],
            include_str!("impacts.wgsl"),
        );
        let in_round = |round: usize, layout: &wgpu::PipelineLayout, entry: &str| {
            shaders.pipeline_in(layout, &module, entry, &[("IMPACT_ROUND", round as f64)])
        };
        Impacts {
            find_first: std::array::from_fn(|round| {
                in_round(round, &sizing_pipelines, "find_first_contacts")
            }),
            bounce: std::array::from_fn(|round| {
                in_round(round, &shaders.layout, "bounce_first_contacts")
            }),
            in_one_group: shaders.pipeline(&module, "impacts_in_one_group"),
            dispatches: buffers.impact_dispatch.clone(),
            sizing,
        }
    }

    pub fn record(&self, step: &mut Recorder) {
        let small = step.small;
        step.stage(Stage::Impacts, |pass| {
            if small {
                return pass.workgroups(&self.in_one_group, 1, 1);
            }
            pass.pass.set_bind_group(1, &self.sizing, &[]);
            for round in 0..ROUNDS {
                pass.over_balls(&self.find_first[round]);
                let sizes = (std::mem::size_of_val(&IMPACT_DISPATCH_START) * round) as u64;
                pass.sized_by_gpu(&self.bounce[round], &self.dispatches, sizes);
            }
        });
    }
}
