//! One step of the balls, stage by stage. Each stage is a module here with
//! its WGSL file beside it: the module makes the stage's pipelines from
//! `common.wgsl` and its file, and records the stage's dispatches into one
//! compute pass (stamped by the stage timer where there is one). They run
//! in the order of [`Stage::ALL`].

mod contacts;
mod flight;
mod grid;
mod impacts;
mod reflect;
mod report;
mod scan;
mod solve;

pub use solve::SweepCounts;

use std::cell::RefCell;

use crate::bindings::{Buffers, compute_buffer};
use crate::layout::{BRICK, HIT_BALL, HIT_BODY, HIT_WALL, IMPACT_CAPACITY, SLOTS, groups};
use crate::profile::{Stage, StageTimer};

/// What one pipeline of the engine binds: the numbers an adapter's limits
/// are held against.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PassLayout {
    /// The WGSL entry point.
    pub entry: String,
    /// Storage buffers it binds (a shader stage's count: it has one stage).
    pub storage_buffers: u32,
    /// Uniform buffers it binds.
    pub uniform_buffers: u32,
    /// Bind groups it sets.
    pub bind_groups: u32,
    /// Its largest binding, in bytes.
    pub largest_binding: u64,
    /// The bindings it uses, by number (see `common.wgsl`).
    pub bindings: Vec<u32>,
}

/// A stage's WGSL, compiled, and its text (to read which buffers each
/// entry point uses).
pub struct Module {
    shader: wgpu::ShaderModule,
    source: String,
}

/// A pipeline and the bind group of exactly the buffers its entry point
/// uses.
pub struct Kernel {
    pipeline: wgpu::ComputePipeline,
    bind_group: wgpu::BindGroup,
}

/// What the stages build their pipelines from: the device, the buffers,
/// the WGSL every stage shares, and the layouts made so far.
pub struct Shaders<'a> {
    device: &'a wgpu::Device,
    buffers: &'a Buffers,
    common: String,
    layouts: RefCell<Vec<PassLayout>>,
}

impl<'a> Shaders<'a> {
    fn new(device: &'a wgpu::Device, buffers: &'a Buffers) -> Shaders<'a> {
        Shaders {
            device,
            buffers,
            layouts: RefCell::new(Vec::new()),
            common: format!(
                "const SLOTS: u32 = {SLOTS}u;\nconst BRICK = vec3<u32>({}u, {}u, {}u);\n\
                 const IMPACT_CAPACITY: u32 = {IMPACT_CAPACITY}u;\n\
                 const HIT_WALL: u32 = {HIT_WALL}u;\nconst HIT_BALL: u32 = {HIT_BALL}u;\n\
                 const HIT_BODY: u32 = {HIT_BODY}u;\n{}{}",
                BRICK[0],
                BRICK[1],
                BRICK[2],
                buffers.wgsl_sections(),
                include_str!("common.wgsl")
            ),
        }
    }

    /// A stage's WGSL `source` after the shared file, with `constants`
    /// (name, value) declared above both.
    fn module(&self, label: &str, constants: &[(&str, u32)], source: &str) -> Module {
        let declared: String = constants
            .iter()
            .map(|(name, value)| format!("const {name}: u32 = {value}u;\n"))
            .collect();
        let source = format!("{declared}{}\n{source}", self.common);
        Module {
            shader: self
                .device
                .create_shader_module(wgpu::ShaderModuleDescriptor {
                    label: Some(label),
                    source: wgpu::ShaderSource::Wgsl(source.as_str().into()),
                }),
            source,
        }
    }

    /// The kernel of `entry` in `module`.
    fn pipeline(&self, module: &Module, entry: &str) -> Kernel {
        self.pipeline_with(module, entry, &[])
    }

    /// The kernel of `entry` in `module`, its overridable constants set to
    /// `overrides`, binding only the buffers the entry point uses.
    fn pipeline_with(&self, module: &Module, entry: &str, overrides: &[(&str, f64)]) -> Kernel {
        let uses = reflect::uses(&module.source, entry);
        let entries: Vec<wgpu::BindGroupLayoutEntry> = uses
            .iter()
            .map(|u| compute_buffer(u.binding, u.ty))
            .collect();
        let layout = self
            .device
            .create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some(entry),
                entries: &entries,
            });
        let bound: Vec<wgpu::BindGroupEntry> = uses
            .iter()
            .map(|u| wgpu::BindGroupEntry {
                binding: u.binding,
                resource: self.buffers.at(u.binding).as_entire_binding(),
            })
            .collect();
        let bind_group = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(entry),
            layout: &layout,
            entries: &bound,
        });
        let pipeline_layout = self
            .device
            .create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some(entry),
                bind_group_layouts: &[Some(&layout)],
                immediate_size: 0,
            });
        let pipeline = self
            .device
            .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(entry),
                layout: Some(&pipeline_layout),
                module: &module.shader,
                entry_point: Some(entry),
                compilation_options: wgpu::PipelineCompilationOptions {
                    constants: overrides,
                    ..Default::default()
                },
                cache: None,
            });
        let storage = uses.iter().filter(|u| u.is_storage());
        let layout = PassLayout {
            entry: entry.to_owned(),
            storage_buffers: storage.clone().count() as u32,
            uniform_buffers: (uses.len() - storage.clone().count()) as u32,
            bind_groups: 1,
            largest_binding: uses
                .iter()
                .map(|u| self.buffers.at(u.binding).size())
                .max()
                .unwrap_or(0),
            bindings: uses.iter().map(|u| u.binding).collect(),
        };
        let mut layouts = self.layouts.borrow_mut();
        if !layouts.contains(&layout) {
            layouts.push(layout);
        }
        Kernel {
            pipeline,
            bind_group,
        }
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

/// A step being recorded: the encoder and the dispatches so far.
pub struct Recorder<'a> {
    encoder: &'a mut wgpu::CommandEncoder,
    timer: Option<&'a StageTimer>,
    /// Balls in use.
    balls: u64,
    /// Whether the sweeping stages run in one workgroup each.
    small: bool,
    /// Whether a fireball takes the balls it reaches.
    catching: bool,
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
        let pass = self
            .encoder
            .begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some(stage.name()),
                timestamp_writes,
            });
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
    fn over(&mut self, kernel: &Kernel, items: u64) {
        let (x, y) = groups(items);
        self.workgroups(kernel, x, y);
    }

    /// The balls in use.
    fn balls(&self) -> u64 {
        self.balls
    }

    /// A thread for each ball in use.
    fn over_balls(&mut self, kernel: &Kernel) {
        self.over(kernel, self.balls);
    }

    fn workgroups(&mut self, kernel: &Kernel, x: u32, y: u32) {
        self.pass.set_pipeline(&kernel.pipeline);
        self.pass.set_bind_group(0, &kernel.bind_group, &[]);
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
    layouts: Vec<PassLayout>,
}

impl Stages {
    /// The stages for `buffers`, whose grid has `cells` cells, sweeping
    /// `counts` times.
    pub fn new(
        device: &wgpu::Device,
        buffers: &Buffers,
        cells: u64,
        counts: &SweepCounts,
    ) -> Stages {
        let shaders = Shaders::new(device, buffers);
        let grid = grid::Grid::new(&shaders, buffers, cells);
        let contacts = contacts::Contacts::new(&shaders);
        let impacts = impacts::Impacts::new(&shaders);
        let solve = solve::Solve::new(&shaders, counts);
        let report = report::Report::new(&shaders);
        let flight = flight::Flight::new(&shaders);
        let mut layouts = shaders.layouts.into_inner();
        layouts.extend(grid.scan_layouts());
        Stages {
            grid,
            contacts,
            impacts,
            solve,
            report,
            flight,
            layouts,
        }
    }

    /// What each pipeline binds, an entry point a row.
    pub fn layouts(&self) -> &[PassLayout] {
        &self.layouts
    }

    /// Records one step of `balls` balls and `tumblers` tumblers into
    /// `encoder`, a compute pass a stage, each stamped by `timer` if given;
    /// a small world's sweeping stages each in one workgroup; the balls a
    /// fireball reaches taken if `catching`. Returns the dispatches
    /// recorded.
    #[allow(clippy::too_many_arguments)]
    pub fn record(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        timer: Option<&StageTimer>,
        balls: u64,
        tumblers: u32,
        small: bool,
        catching: bool,
    ) -> u32 {
        let mut step = Recorder {
            encoder,
            timer,
            balls,
            small,
            catching,
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
    pub fn write_instances(&self, encoder: &mut wgpu::CommandEncoder, balls: u64) {
        let mut recorder = Recorder {
            encoder,
            timer: None,
            balls,
            small: false,
            catching: false,
            dispatches: 0,
        };
        self.flight.record_instances(&mut recorder);
    }
}
