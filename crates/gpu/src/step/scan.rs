//! An exclusive prefix sum of `u32` on the GPU (`scan.wgsl`): each
//! block of [`BLOCK`] is scanned in place, the blocks' totals are scanned a
//! level up, and added back. Deterministic: integers, no atomics. Blocks of
//! a thousand make a million cells two levels: three dispatches.

use crate::bindings::{READ_WRITE, compute_buffer};
use crate::layout::{WORKGROUP, groups};
use wgpu::util::DeviceExt;

/// Values each thread sums in a run of its own.
const PER_THREAD: u32 = 4;

/// Values a workgroup scans.
const BLOCK: u64 = WORKGROUP as u64 * PER_THREAD as u64;

/// The scan's pipelines and, for one buffer of a given length, its levels.
pub struct Scan {
    scan_blocks: wgpu::ComputePipeline,
    add_block_offsets: wgpu::ComputePipeline,
    /// Level by level, the values scanned and the bind group that binds
    /// them with the level above's buffer of block totals.
    levels: Vec<Level>,
    /// Keeps the totals' buffers alive.
    _totals: Vec<wgpu::Buffer>,
    /// The values' buffer's size: the largest binding.
    largest_binding: u64,
}

struct Level {
    len: u64,
    bind_group: wgpu::BindGroup,
}

impl Scan {
    /// A scan of the first `len` values of `values`.
    pub fn new(device: &wgpu::Device, values: &wgpu::Buffer, len: u64) -> Scan {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("scan"),
            source: wgpu::ShaderSource::Wgsl(
                format!(
                    "const PER_THREAD: u32 = {PER_THREAD}u;\n{}",
                    include_str!("scan.wgsl")
                )
                .into(),
            ),
        });
        let storage = |binding| compute_buffer(binding, READ_WRITE);
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("scan"),
            entries: &[
                // var<uniform> scan: ScanParams
                compute_buffer(0, wgpu::BufferBindingType::Uniform),
                // var<storage, read_write> values: array<u32>
                storage(1),
                // var<storage, read_write> block_totals: array<u32>
                storage(2),
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("scan"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = |entry: &str| {
            device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(entry),
                layout: Some(&pipeline_layout),
                module: &module,
                entry_point: Some(entry),
                compilation_options: Default::default(),
                cache: None,
            })
        };
        // Each level's length, down to the one block whose total is the sum.
        let mut lens = vec![len.max(1)];
        loop {
            let above = lens[lens.len() - 1].div_ceil(BLOCK);
            lens.push(above);
            if above == 1 {
                break;
            }
        }
        let totals: Vec<wgpu::Buffer> = lens[1..]
            .iter()
            .map(|&n| {
                device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("scan block totals"),
                    size: 4 * n.max(1),
                    usage: wgpu::BufferUsages::STORAGE,
                    mapped_at_creation: false,
                })
            })
            .collect();
        let levels = (0..lens.len() - 1)
            .map(|k| {
                let uniform = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("scan length"),
                    contents: bytemuck::cast_slice(&[lens[k] as u32, 0, 0, 0]),
                    usage: wgpu::BufferUsages::UNIFORM,
                });
                let values = if k == 0 { values } else { &totals[k - 1] };
                let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("scan level"),
                    layout: &layout,
                    entries: &[
                        wgpu::BindGroupEntry {
                            binding: 0,
                            resource: uniform.as_entire_binding(),
                        },
                        wgpu::BindGroupEntry {
                            binding: 1,
                            resource: values.as_entire_binding(),
                        },
                        wgpu::BindGroupEntry {
                            binding: 2,
                            resource: totals[k].as_entire_binding(),
                        },
                    ],
                });
                Level {
                    len: lens[k],
                    bind_group,
                }
            })
            .collect();
        Scan {
            scan_blocks: pipeline("scan_blocks"),
            add_block_offsets: pipeline("add_block_offsets"),
            levels,
            _totals: totals,
            largest_binding: values.size(),
        }
    }

    /// What its two pipelines bind: the values, the block totals and the
    /// level's length.
    pub fn layouts(&self) -> Vec<super::PassLayout> {
        ["scan_blocks", "add_block_offsets"]
            .map(|entry| super::PassLayout {
                entry: entry.to_owned(),
                storage_buffers: 2,
                uniform_buffers: 1,
                bind_groups: 1,
                largest_binding: self.largest_binding,
                bindings: vec![0, 1, 2],
            })
            .to_vec()
    }

    /// Records the scan into `encoder`: down the levels scanning blocks,
    /// then back up adding each block's offset. A level of one block is
    /// scanned whole, and its total is not added back. Returns the
    /// dispatches recorded.
    pub fn record(&self, encoder: &mut wgpu::CommandEncoder) -> u32 {
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("scan"),
            timestamp_writes: None,
        });
        pass.set_pipeline(&self.scan_blocks);
        for level in &self.levels {
            pass.set_bind_group(0, &level.bind_group, &[]);
            let (x, y) = groups(level.len.div_ceil(u64::from(PER_THREAD)));
            pass.dispatch_workgroups(x, y, 1);
        }
        pass.set_pipeline(&self.add_block_offsets);
        for level in self.levels.iter().rev().skip(1) {
            pass.set_bind_group(0, &level.bind_group, &[]);
            let (x, y) = groups(level.len);
            pass.dispatch_workgroups(x, y, 1);
        }
        (2 * self.levels.len()).saturating_sub(1) as u32
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::readback::read_buffer;

    /// The GPU's exclusive scan of `values`.
    fn scanned(compute: &crate::Compute, values: &[u32]) -> Vec<u32> {
        let device = &compute.device;
        let buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("values"),
            contents: bytemuck::cast_slice(values),
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        });
        let staging = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("staging"),
            size: buffer.size(),
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let scan = Scan::new(device, &buffer, values.len() as u64);
        let mut encoder = device.create_command_encoder(&Default::default());
        scan.record(&mut encoder);
        encoder.copy_buffer_to_buffer(&buffer, 0, &staging, 0, buffer.size());
        compute.queue.submit([encoder.finish()]);
        let bound = crate::WaitBound::new(compute.adapter.clone());
        let bytes = read_buffer(device, &bound, &staging, 4 * values.len(), || {
            "the scan".to_string()
        })
        .unwrap();
        bytemuck::pod_collect_to_vec(&bytes)
    }

    #[test]
    fn the_scan_matches_a_running_sum_at_the_block_edges() {
        let compute = crate::Compute::headless().expect("an adapter");
        // One block, one past it, two levels, one past two levels, three.
        let two_levels = BLOCK * BLOCK;
        for len in [
            1,
            2,
            BLOCK - 1,
            BLOCK,
            BLOCK + 1,
            two_levels - 1,
            two_levels,
            two_levels + 1,
            2 * two_levels + 3 * BLOCK + 5,
        ] {
            let values: Vec<u32> = (0..len as u32).map(|i| (i * 7 + 3) % 5).collect();
            let expected: Vec<u32> = values
                .iter()
                .scan(0, |sum, &v| {
                    let before = *sum;
                    *sum += v;
                    Some(before)
                })
                .collect();
            assert_eq!(scanned(&compute, &values), expected, "{len} values");
        }
    }
}
