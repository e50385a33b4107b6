//! The ball passes' pipelines: each WGSL file after `common.wgsl`, one
//! pipeline for each of its entry points, all on the one layout of
//! `bindings.rs`.

use crate::colours::COLOURS;
use crate::layout::SLOTS;

/// The shader files, in the order a step runs them.
const SOURCES: [&str; 7] = [
    include_str!("shaders/grid.wgsl"),
    include_str!("shaders/contacts.wgsl"),
    include_str!("shaders/impacts.wgsl"),
    include_str!("shaders/solve.wgsl"),
    include_str!("shaders/flight.wgsl"),
    include_str!("shaders/project.wgsl"),
    include_str!("shaders/report.wgsl"),
];

/// A small world's sweeps in one workgroup each (see `small.wgsl`), built
/// on the files whose passes they stand for.
const SMALL: [&str; 4] = [
    include_str!("shaders/impacts.wgsl"),
    include_str!("shaders/solve.wgsl"),
    include_str!("shaders/project.wgsl"),
    include_str!("shaders/small.wgsl"),
];

/// How many sweeps each sweeping stage runs a step.
pub struct SweepCounts {
    /// Impact rounds, and Jacobi sweeps of each.
    pub impact_rounds: u32,
    pub impact_sweeps: u32,
    /// Gauss-Seidel sweeps of the resting contacts, each of every colour.
    pub solve_sweeps: u32,
    /// Jacobi sweeps pushing overlaps out.
    pub shift_sweeps: u32,
}

/// One pipeline for each entry point.
pub struct Passes {
    pub clear_cells: wgpu::ComputePipeline,
    pub count_cells: wgpu::ComputePipeline,
    pub place_in_cells: wgpu::ComputePipeline,
    pub sort_cells: wgpu::ComputePipeline,
    pub gauge_near_speed: wgpu::ComputePipeline,
    pub find_contacts: wgpu::ComputePipeline,
    pub find_mirrors: wgpu::ComputePipeline,
    pub warm_start: wgpu::ComputePipeline,
    pub raise_impact_goals: wgpu::ComputePipeline,
    pub solve_impacts: wgpu::ComputePipeline,
    pub solve_cell: wgpu::ComputePipeline,
    pub apply_deltas: wgpu::ComputePipeline,
    pub fly: wgpu::ComputePipeline,
    pub find_overlaps: wgpu::ComputePipeline,
    pub apply_shifts: wgpu::ComputePipeline,
    pub sum_tumbler_push: wgpu::ComputePipeline,
    pub write_instances: wgpu::ComputePipeline,
    pub impacts_in_one_group: wgpu::ComputePipeline,
    pub solve_in_one_group: wgpu::ComputePipeline,
    pub overlaps_in_one_group: wgpu::ComputePipeline,
}

impl Passes {
    pub fn new(
        device: &wgpu::Device,
        layout: &wgpu::BindGroupLayout,
        colour_layout: &wgpu::BindGroupLayout,
        counts: &SweepCounts,
    ) -> Passes {
        let common = format!(
            "const SLOTS: u32 = {SLOTS}u;\n{}",
            include_str!("shaders/common.wgsl")
        );
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("balls"),
            bind_group_layouts: &[Some(layout)],
            immediate_size: 0,
        });
        // The solver's sweeps also read which colour of cells they take.
        let coloured_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("balls by colour of cell"),
            bind_group_layouts: &[Some(layout), Some(colour_layout)],
            immediate_size: 0,
        });
        let modules: Vec<wgpu::ShaderModule> = SOURCES
            .iter()
            .map(|source| {
                device.create_shader_module(wgpu::ShaderModuleDescriptor {
                    label: Some("balls"),
                    source: wgpu::ShaderSource::Wgsl(format!("{common}\n{source}").into()),
                })
            })
            .collect();
        let pipeline_in = |layout: &wgpu::PipelineLayout, file: usize, entry: &str| {
            device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(entry),
                layout: Some(layout),
                module: &modules[file],
                entry_point: Some(entry),
                compilation_options: Default::default(),
                cache: None,
            })
        };
        let small = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("small world"),
            source: wgpu::ShaderSource::Wgsl(format!("{common}\n{}", SMALL.join("\n")).into()),
        });
        let constants = [
            ("IMPACT_ROUNDS", f64::from(counts.impact_rounds)),
            ("IMPACT_SWEEPS", f64::from(counts.impact_sweeps)),
            ("SOLVE_SWEEPS", f64::from(counts.solve_sweeps)),
            ("SHIFT_SWEEPS", f64::from(counts.shift_sweeps)),
            ("COLOURS", f64::from(COLOURS)),
        ];
        let in_one_group = |entry: &str| {
            device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(entry),
                layout: Some(&pipeline_layout),
                module: &small,
                entry_point: Some(entry),
                compilation_options: wgpu::PipelineCompilationOptions {
                    constants: &constants,
                    ..Default::default()
                },
                cache: None,
            })
        };
        let pipeline = |file: usize, entry: &str| pipeline_in(&pipeline_layout, file, entry);
        Passes {
            clear_cells: pipeline(0, "clear_cells"),
            count_cells: pipeline(0, "count_cells"),
            place_in_cells: pipeline(0, "place_in_cells"),
            sort_cells: pipeline(0, "sort_cells"),
            gauge_near_speed: pipeline(1, "gauge_near_speed"),
            find_contacts: pipeline(1, "find_contacts"),
            find_mirrors: pipeline(1, "find_mirrors"),
            warm_start: pipeline(1, "warm_start"),
            raise_impact_goals: pipeline(2, "raise_impact_goals"),
            solve_impacts: pipeline(2, "solve_impacts"),
            solve_cell: pipeline_in(&coloured_layout, 3, "solve_cell"),
            apply_deltas: pipeline(3, "apply_deltas"),
            fly: pipeline(4, "fly"),
            find_overlaps: pipeline(5, "find_overlaps"),
            apply_shifts: pipeline(5, "apply_shifts"),
            sum_tumbler_push: pipeline(6, "sum_tumbler_push"),
            write_instances: pipeline(6, "write_instances"),
            impacts_in_one_group: in_one_group("impacts_in_one_group"),
            solve_in_one_group: in_one_group("solve_in_one_group"),
            overlaps_in_one_group: in_one_group("overlaps_in_one_group"),
        }
    }
}
