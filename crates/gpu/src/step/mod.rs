//! One step of the balls, stage by stage. Each stage is a module here with
//! its WGSL file beside it: the module makes the stage's pipelines from
//! `common.wgsl` and its file, and records the stage's dispatches into one
//! compute pass (stamped by the stage timer where there is one). They run
//! in the order of [`Stage::ALL`].

mod contacts;
mod flight;
mod grid;
mod impacts;
mod report;
mod scan;
mod solve;

pub use solve::SweepCounts;

use crate::bindings::Buffers;
use crate::layout::{BRICK, SLOTS, groups};
use crate::profile::{Stage, StageTimer};

/// What the stages build their pipelines from: the device, the layout of
/// the balls' one bind group, and the WGSL every stage shares.
pub struct Shaders<'a> {
    device: &'a wgpu::Device,
    layout: wgpu::PipelineLayout,
    common: String,
}

impl<'a> Shaders<'a> {
    fn new(device: &'a wgpu::Device, balls: &wgpu::BindGroupLayout) -> Shaders<'a> {
        Shaders {
            device,
            layout: device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some("balls"),
                bind_group_layouts: &[Some(balls)],
                immediate_size: 0,
            }),
            common: format!(
                "const SLOTS: u32 = {SLOTS}u;\nconst BRICK = vec3<u32>({}u, {}u, {}u);\n{}",
                BRICK[0],
                BRICK[1],
                BRICK[2],
                include_str!("common.wgsl")
            ),
        }
    }

    /// A stage's WGSL `source` after the shared file, with `constants`
    /// (name, value) declared above both.
    fn module(&self, label: &str, constants: &[(&str, u32)], source: &str) -> wgpu::ShaderModule {
        let declared: String = constants
            .iter()
            .map(|(name, value)| format!("const {name}: u32 = {value}u;\n"))
            .collect();
        self.device
            .create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(label),
                source: wgpu::ShaderSource::Wgsl(
                    format!("{declared}{}\n{source}", self.common).into(),
                ),
            })
    }

    /// The pipeline of `entry` in `module`, on the balls' bind group.
    fn pipeline(&self, module: &wgpu::ShaderModule, entry: &str) -> wgpu::ComputePipeline {
        self.pipeline_in(&self.layout, module, entry, &[])
    }

    /// The pipeline of `entry` in `module` on `layout`, its overridable
    /// constants set to `overrides`.
    fn pipeline_in(
        &self,
        layout: &wgpu::PipelineLayout,
        module: &wgpu::ShaderModule,
        entry: &str,
        overrides: &[(&str, f64)],
    ) -> wgpu::ComputePipeline {
        self.device
            .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(entry),
                layout: Some(layout),
                module,
                entry_point: Some(entry),
                compilation_options: wgpu::PipelineCompilationOptions {
                    constants: overrides,
                    ..Default::default()
                },
                cache: None,
            })
    }
}

/// Which of a stage's stamps a compute pass writes: a stage recorded as
/// two passes (the grid, around its scan) stamps its start in the first
/// and its end in the second.
#[derive(Clone, Copy)]
enum Stamps {
    Both,
    Start,
    End,
}

/// A step being recorded: the encoder, what every pass binds, and the
/// dispatches so far.
pub struct Recorder<'a> {
    encoder: &'a mut wgpu::CommandEncoder,
    bind_group: &'a wgpu::BindGroup,
    timer: Option<&'a StageTimer>,
    /// Balls in use.
    balls: u64,
    /// Whether the sweeping stages run in one workgroup each.
    small: bool,
    dispatches: u32,
}

impl Recorder<'_> {
    /// Records `work` as stage `stage`'s compute pass.
    fn stage(&mut self, stage: Stage, work: impl FnOnce(&mut Pass)) {
        self.pass(stage, Stamps::Both, work);
    }

    fn pass(&mut self, stage: Stage, stamps: Stamps, work: impl FnOnce(&mut Pass)) {
        let timestamp_writes = self.timer.map(|t| {
            let both = t.writes(stage);
            match stamps {
                Stamps::Both => both,
                Stamps::Start => wgpu::ComputePassTimestampWrites {
                    end_of_pass_write_index: None,
                    ..both
                },
                Stamps::End => wgpu::ComputePassTimestampWrites {
                    beginning_of_pass_write_index: None,
                    ..both
                },
            }
        });
        let mut pass = self
            .encoder
            .begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some(stage.name()),
                timestamp_writes,
            });
        pass.set_bind_group(0, self.bind_group, &[]);
        work(&mut Pass {
            pass,
            balls: self.balls,
            dispatches: &mut self.dispatches,
        });
    }
}

/// One stage's compute pass, counting what it dispatches.
pub struct Pass<'a, 'p> {
    pass: wgpu::ComputePass<'p>,
    balls: u64,
    dispatches: &'a mut u32,
}

impl Pass<'_, '_> {
    /// A thread for each of `items`.
    fn over(&mut self, pipeline: &wgpu::ComputePipeline, items: u64) {
        let (x, y) = groups(items);
        self.workgroups(pipeline, x, y);
    }

    /// The balls in use.
    fn balls(&self) -> u64 {
        self.balls
    }

    /// A thread for each ball in use.
    fn over_balls(&mut self, pipeline: &wgpu::ComputePipeline) {
        self.over(pipeline, self.balls);
    }

    fn workgroups(&mut self, pipeline: &wgpu::ComputePipeline, x: u32, y: u32) {
        self.pass.set_pipeline(pipeline);
        self.pass.dispatch_workgroups(x, y, 1);
        *self.dispatches += 1;
    }
}

/// Every stage's pipelines.
pub struct Stages {
    grid: grid::Grid,
    contacts: contacts::Contacts,
    impacts: impacts::Impacts,
    solve: solve::Solve,
    report: report::Report,
    flight: flight::Flight,
}

impl Stages {
    /// The stages for `buffers` (bound by `bind_group`, of `layout`), whose
    /// grid has `cells` cells, sweeping `counts` times.
    pub fn new(
        device: &wgpu::Device,
        buffers: &Buffers,
        layout: &wgpu::BindGroupLayout,
        cells: u64,
        counts: &SweepCounts,
    ) -> Stages {
        let shaders = Shaders::new(device, layout);
        Stages {
            grid: grid::Grid::new(&shaders, buffers, cells),
            contacts: contacts::Contacts::new(&shaders),
            impacts: impacts::Impacts::new(&shaders),
            solve: solve::Solve::new(&shaders, counts),
            report: report::Report::new(&shaders),
            flight: flight::Flight::new(&shaders),
        }
    }

    /// Records one step of `balls` balls and `tumblers` tumblers into
    /// `encoder`, a compute pass a stage, each stamped by `timer` if given;
    /// a small world's sweeping stages each in one workgroup. Returns the
    /// dispatches recorded.
    #[allow(clippy::too_many_arguments)]
    pub fn record(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        bind_group: &wgpu::BindGroup,
        timer: Option<&StageTimer>,
        balls: u64,
        tumblers: u32,
        small: bool,
    ) -> u32 {
        let mut step = Recorder {
            encoder,
            bind_group,
            timer,
            balls,
            small,
            dispatches: 0,
        };
        self.grid.record(&mut step);
        self.contacts.record(&mut step);
        self.impacts.record(&mut step);
        self.solve.record(&mut step);
        self.report.record_pushes(&mut step, tumblers);
        self.flight.record(&mut step);
        step.dispatches
    }

    /// Writes the renderer's instances of `balls` balls from the state as it
    /// is, without a step.
    pub fn write_instances(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        bind_group: &wgpu::BindGroup,
        balls: u64,
    ) {
        let mut recorder = Recorder {
            encoder,
            bind_group,
            timer: None,
            balls,
            small: false,
            dispatches: 0,
        };
        self.flight.record_instances(&mut recorder);
    }
}
