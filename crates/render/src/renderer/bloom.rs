//! The bloom pass (L1): the HDR frame filtered down a chain of half-size
//! images and back up (see bloom.wgsl); tone mapping adds the top two
//! levels of the chain to the picture.

use super::HDR_FORMAT;
use super::bindings::{filtering_sampler_entry, texture_entry, uniform_entry};
use super::pipelines::{screen_pipeline, screen_shader};
use crate::shaders::ShaderSet;
use crate::view::Bloom;

/// Most levels of the chain: the smallest is 1/64 of the frame, a glow
/// about a tenth of the frame wide.
const MAX_LEVELS: u32 = 6;

/// How far below the threshold the glow starts fading in, as a share of
/// the threshold.
const KNEE: f32 = 0.5;

/// The three ways a level is drawn, on one bind group layout.
pub(super) struct BloomPipelines {
    layout: wgpu::BindGroupLayout,
    sampler: wgpu::Sampler,
    /// Down from the frame, keeping what is above the threshold.
    first: wgpu::RenderPipeline,
    down: wgpu::RenderPipeline,
    /// Up, added to the level above.
    up: wgpu::RenderPipeline,
}

impl BloomPipelines {
    pub fn new(device: &wgpu::Device, shaders: &ShaderSet) -> BloomPipelines {
        let shader = screen_shader(device, shaders, &crate::shaders::BLOOM);
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("bloom"),
            entries: &[
                texture_entry(0, true),
                filtering_sampler_entry(1),
                uniform_entry(2, wgpu::ShaderStages::FRAGMENT),
            ],
        });
        let pipeline = |entry: &str, blend: Option<wgpu::BlendState>| {
            let target = wgpu::ColorTargetState {
                format: HDR_FORMAT,
                blend,
                write_mask: wgpu::ColorWrites::ALL,
            };
            screen_pipeline(
                device,
                entry,
                &layout,
                &shader,
                ("vs_screen", entry),
                target,
            )
        };
        let add = wgpu::BlendComponent {
            src_factor: wgpu::BlendFactor::One,
            dst_factor: wgpu::BlendFactor::One,
            operation: wgpu::BlendOperation::Add,
        };
        BloomPipelines {
            first: pipeline("fs_downsample_first", None),
            down: pipeline("fs_downsample", None),
            up: pipeline(
                "fs_upsample",
                Some(wgpu::BlendState {
                    color: add,
                    alpha: add,
                }),
            ),
            sampler: device.create_sampler(&wgpu::SamplerDescriptor {
                label: Some("bloom"),
                address_mode_u: wgpu::AddressMode::ClampToEdge,
                address_mode_v: wgpu::AddressMode::ClampToEdge,
                mag_filter: wgpu::FilterMode::Linear,
                min_filter: wgpu::FilterMode::Linear,
                ..Default::default()
            }),
            layout,
        }
    }
}

/// One step of the chain: the level drawn into, and what it reads.
struct Step {
    target: wgpu::TextureView,
    bind_group: wgpu::BindGroup,
    /// The step's parameters (see `Params` in bloom.wgsl).
    params: wgpu::Buffer,
    texel: [f32; 2],
}

/// The chain for frames of one size.
pub(super) struct BloomChain {
    down: Vec<Step>,
    up: Vec<Step>,
    /// The whole chain, whose top two levels tone mapping reads: the way
    /// up stops at the second, whose sum tone mapping reads straight from
    /// the smaller image. Spreading it into the top level, the largest,
    /// would be the chain's costliest step.
    pub glow: wgpu::TextureView,
    /// How many levels the glow sums.
    pub levels: u32,
}

impl BloomChain {
    /// The chain below `hdr`, a frame of `width` x `height`.
    pub fn new(
        device: &wgpu::Device,
        pipelines: &BloomPipelines,
        hdr: &wgpu::TextureView,
        (width, height): (u32, u32),
    ) -> BloomChain {
        let top_size = ((width / 2).max(1), (height / 2).max(1));
        let levels = (top_size.0.min(top_size.1).ilog2() + 1).clamp(1, MAX_LEVELS);
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("bloom"),
            size: wgpu::Extent3d {
                width: top_size.0,
                height: top_size.1,
                depth_or_array_layers: 1,
            },
            mip_level_count: levels,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: HDR_FORMAT,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        });
        let level = |i: u32| {
            texture.create_view(&wgpu::TextureViewDescriptor {
                label: Some("bloom level"),
                base_mip_level: i,
                mip_level_count: Some(1),
                ..Default::default()
            })
        };
        let size_of = |i: u32| ((top_size.0 >> i).max(1), (top_size.1 >> i).max(1));
        let step =
            |target: wgpu::TextureView, source: &wgpu::TextureView, source_size: (u32, u32)| {
                let params = device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("bloom step"),
                    size: 16,
                    usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                });
                let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("bloom step"),
                    layout: &pipelines.layout,
                    entries: &[
                        wgpu::BindGroupEntry {
                            binding: 0,
                            resource: wgpu::BindingResource::TextureView(source),
                        },
                        wgpu::BindGroupEntry {
                            binding: 1,
                            resource: wgpu::BindingResource::Sampler(&pipelines.sampler),
                        },
                        wgpu::BindGroupEntry {
                            binding: 2,
                            resource: params.as_entire_binding(),
                        },
                    ],
                });
                Step {
                    target,
                    bind_group,
                    params,
                    texel: [1.0 / source_size.0 as f32, 1.0 / source_size.1 as f32],
                }
            };
        let mut down = vec![step(level(0), hdr, (width, height))];
        for i in 1..levels {
            down.push(step(level(i), &level(i - 1), size_of(i - 1)));
        }
        let up = (2..levels)
            .rev()
            .map(|i| step(level(i - 1), &level(i), size_of(i)))
            .collect();
        BloomChain {
            down,
            up,
            glow: texture.create_view(&Default::default()),
            levels,
        }
    }

    /// Records the chain down and up, for `bloom`'s threshold.
    pub fn record(
        &self,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        pipelines: &BloomPipelines,
        bloom: &Bloom,
    ) -> u32 {
        let mut draw_calls = 0;
        let steps = self.down.iter().map(|s| (s, false));
        let steps = steps.chain(self.up.iter().map(|s| (s, true)));
        for (k, (step, up)) in steps.enumerate() {
            let params = [
                step.texel[0],
                step.texel[1],
                bloom.threshold,
                KNEE * bloom.threshold,
            ];
            queue.write_buffer(&step.params, 0, bytemuck::cast_slice(&params));
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some(if up { "bloom up" } else { "bloom down" }),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &step.target,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        // Going up adds to what the way down left there.
                        load: if up {
                            wgpu::LoadOp::Load
                        } else {
                            wgpu::LoadOp::Clear(wgpu::Color::BLACK)
                        },
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: None,
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(match (k, up) {
                (0, _) => &pipelines.first,
                (_, false) => &pipelines.down,
                (_, true) => &pipelines.up,
            });
            pass.set_bind_group(0, &step.bind_group, &[]);
            pass.draw(0..3, 0..1);
            draw_calls += 1;
        }
        draw_calls
    }
}
