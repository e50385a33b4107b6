//! Stage 3, the impacts (`impacts.wgsl`): rounds of Jacobi sweeps of
//! bounces, so that a blow passes from ball to ball within the step. Each
//! round first lists the balls with a contact that bounces and sizes its
//! sweeps' dispatches to the list, on the GPU: a round in which nothing
//! bounces dispatches no workgroups.

use super::{JacobiSweeps, Recorder, Shaders};
use crate::bindings::{Buffers, READ_WRITE, compute_buffer};
use crate::layout::{IMPACT_DISPATCH_START, IMPACT_ROUNDS};
use crate::profile::Stage;

const ROUNDS: usize = IMPACT_ROUNDS as usize;

pub struct Impacts {
    /// Each round's: goals raised and the list made, which also sizes
    /// the round's sweeps.
    raise_goals: [wgpu::ComputePipeline; ROUNDS],
    /// Each round's sweeps.
    sweeps: [JacobiSweeps; ROUNDS],
    in_one_group: wgpu::ComputePipeline,
    /// The rounds' dispatches, and the group that binds them to the
    /// passes that size them (and to no other: a buffer a dispatch reads
    /// its size from may not be bound for writing in it).
    dispatches: wgpu::Buffer,
    sizing: wgpu::BindGroup,
}

impl Impacts {
    pub fn new(
        shaders: &Shaders,
        buffers: &Buffers,
        balls: &wgpu::BindGroupLayout,
        sweeps: u32,
    ) -> Impacts {
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
            label: Some("balls, sizing the impact sweeps"),
            bind_group_layouts: &[Some(balls), Some(&sizing_layout)],
            immediate_size: 0,
        });
        let module = shaders.module(
            "impacts",
            &[("IMPACT_ROUNDS", IMPACT_ROUNDS), ("IMPACT_SWEEPS", sweeps)],
            include_str!("impacts.wgsl"),
        );
        let in_round = |round: usize, layout: &wgpu::PipelineLayout, entry: &str| {
            shaders.pipeline_in(layout, &module, entry, &[("IMPACT_ROUND", round as f64)])
        };
        Impacts {
            raise_goals: std::array::from_fn(|round| {
                in_round(round, &sizing_pipelines, "raise_impact_goals")
            }),
            sweeps: std::array::from_fn(|round| {
                JacobiSweeps::new(
                    sweeps,
                    |entry| in_round(round, &shaders.layout, entry),
                    ["impacts_forth", "impacts_back"],
                )
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
                pass.over_balls(&self.raise_goals[round]);
                let sizes = (std::mem::size_of_val(&IMPACT_DISPATCH_START) * round) as u64;
                self.sweeps[round].record_sized(pass, &self.dispatches, sizes);
            }
        });
    }
}
