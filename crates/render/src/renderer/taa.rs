//! The temporal path's two passes (taa.wgsl) and the history they keep at
//! the output's resolution (see [`crate::temporal`]).

use super::bindings::{filtering_sampler_entry, texture_entry, uniform_entry};
use super::pipelines::{screen_pipeline, screen_shader};
use wgpu::util::DeviceExt;

/// The resolved history: the picture, and in alpha the weight it holds.
pub(super) const HISTORY_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
/// A surface's motion on screen since the last frame, in uv.
pub(super) const MOTION_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rg16Float;

/// How strongly the output is sharpened after the resolve where a pixel
/// has gathered little history: the unsharp mask's weight on the
/// difference from its four neighbours (see `fs_sharpen`).
const SHARPNESS: f32 = 0.25;

/// The resolve and sharpening pipelines, over one layout.
pub(super) struct TaaPipelines {
    layout: wgpu::BindGroupLayout,
    resolve: wgpu::RenderPipeline,
    pub sharpen: wgpu::RenderPipeline,
    params: wgpu::Buffer,
}

/// The history, twice: the frame reads one and writes the other.
pub(super) struct History {
    size: (u32, u32),
    views: [wgpu::TextureView; 2],
    /// The one the last frame wrote.
    latest: usize,
    /// Frames resolved into it so far.
    frames: u32,
}

impl History {
    /// A history for an output of `size`, holding no frame yet.
    pub fn new(device: &wgpu::Device, size: (u32, u32)) -> History {
        let view = |label| {
            device
                .create_texture(&wgpu::TextureDescriptor {
                    label: Some(label),
                    size: wgpu::Extent3d {
                        width: size.0,
                        height: size.1,
                        depth_or_array_layers: 1,
                    },
                    mip_level_count: 1,
                    sample_count: 1,
                    dimension: wgpu::TextureDimension::D2,
                    format: HISTORY_FORMAT,
                    usage: wgpu::TextureUsages::RENDER_ATTACHMENT
                        | wgpu::TextureUsages::TEXTURE_BINDING,
                    view_formats: &[],
                })
                .create_view(&Default::default())
        };
        History {
            size,
            views: [view("history a"), view("history b")],
            latest: 0,
            frames: 0,
        }
    }

    /// The output size it was made for.
    pub fn size(&self) -> (u32, u32) {
        self.size
    }

    /// Forgets every frame it holds: the next one starts afresh.
    pub fn forget(&mut self) {
        self.frames = 0;
    }
}

/// What the resolve reads this frame besides the history.
pub(super) struct ResolveInputs<'a> {
    /// The frame tone-mapped at the lit resolution.
    pub composed: &'a wgpu::TextureView,
    /// Its surfaces' motion.
    pub motion: &'a wgpu::TextureView,
    /// Its surfaces' normals and distances, and the last frame's.
    pub geometry: &'a wgpu::TextureView,
    pub geometry_before: &'a wgpu::TextureView,
    pub sampler: &'a wgpu::Sampler,
    /// Where this frame's sample lies in each lit texel (see
    /// [`crate::temporal::jitter`]).
    pub sample_offset: glam::Vec2,
}

impl TaaPipelines {
    pub fn new(device: &wgpu::Device, output_format: wgpu::TextureFormat) -> TaaPipelines {
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("taa"),
            entries: &[
                texture_entry(0, true),
                texture_entry(1, false),
                texture_entry(2, true),
                filtering_sampler_entry(3),
                uniform_entry(4, wgpu::ShaderStages::FRAGMENT),
                texture_entry(5, false),
                texture_entry(6, false),
            ],
        });
        let shader = screen_shader(device, "taa.wgsl", include_str!("../../shaders/taa.wgsl"));
        let pipeline = |label, entry, format: wgpu::TextureFormat| {
            screen_pipeline(
                device,
                label,
                &layout,
                &shader,
                ("vs_screen", entry),
                format.into(),
            )
        };
        TaaPipelines {
            resolve: pipeline("taa resolve", "fs_resolve", HISTORY_FORMAT),
            sharpen: pipeline("taa sharpen", "fs_sharpen", output_format),
            params: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("taa params"),
                contents: bytemuck::cast_slice(&[0.0f32; 4]),
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            }),
            layout,
        }
    }

    /// Records the resolve of this frame into `history`, and returns the
    /// bind group the sharpening pass reads it through (drawn by the
    /// caller into the output, with what goes over it).
    pub fn resolve(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        history: &mut History,
        inputs: &ResolveInputs,
        timestamp_writes: Option<wgpu::RenderPassTimestampWrites>,
    ) -> wgpu::BindGroup {
        let holds = if history.frames > 0 { 1.0 } else { 0.0 };
        let params = [
            inputs.sample_offset.x,
            inputs.sample_offset.y,
            holds,
            SHARPNESS,
        ];
        queue.write_buffer(&self.params, 0, bytemuck::cast_slice(&params));
        let (read, write) = (history.latest, 1 - history.latest);
        let reading = self.bind_group(device, inputs, &history.views[read]);
        let mut pass = super::screen_pass(encoder, &history.views[write], timestamp_writes);
        pass.set_pipeline(&self.resolve);
        pass.set_bind_group(0, &reading, &[]);
        pass.draw(0..3, 0..1);
        drop(pass);
        history.latest = write;
        history.frames = history.frames.saturating_add(1);
        self.bind_group(device, inputs, &history.views[write])
    }

    fn bind_group(
        &self,
        device: &wgpu::Device,
        inputs: &ResolveInputs,
        history: &wgpu::TextureView,
    ) -> wgpu::BindGroup {
        let texture = |binding, view| wgpu::BindGroupEntry {
            binding,
            resource: wgpu::BindingResource::TextureView(view),
        };
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("taa"),
            layout: &self.layout,
            entries: &[
                texture(0, inputs.composed),
                texture(1, inputs.motion),
                texture(2, history),
                wgpu::BindGroupEntry {
                    binding: 3,
                    resource: wgpu::BindingResource::Sampler(inputs.sampler),
                },
                wgpu::BindGroupEntry {
                    binding: 4,
                    resource: self.params.as_entire_binding(),
                },
                texture(5, inputs.geometry),
                texture(6, inputs.geometry_before),
            ],
        })
    }
}
