//! The temporal path's passes (taa.wgsl): each lit texel's neighbourhood,
//! the resolve into the history kept at the output's resolution, and the
//! sharpening into the output (see [`crate::temporal`]).

use super::bindings::{filtering_sampler_entry, texture_entry, uniform_entry};
use super::pipelines::{screen_pipeline, screen_pipeline_into, screen_shader};
use crate::shaders::ShaderSet;
use wgpu::util::DeviceExt;

/// The resolved history: the picture, and in alpha the weight it holds.
pub(super) const HISTORY_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
/// A surface's motion on screen since the last frame, in uv.
pub(super) const MOTION_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rg16Float;
/// Each lit texel's neighbourhood: its mean and spread in YCoCg, the most
/// it moved and whether it was disoccluded.
pub(super) const NEIGHBOURHOOD_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

/// How strongly the output is sharpened after the resolve where a pixel
/// has gathered little history: the unsharp mask's weight on the
/// difference from its four neighbours (see `fs_sharpen`).
const SHARPNESS: f32 = 0.25;

/// The neighbourhood, resolve and sharpening pipelines.
pub(super) struct TaaPipelines {
    /// What the neighbourhood pass reads.
    around_layout: wgpu::BindGroupLayout,
    around: wgpu::RenderPipeline,
    /// What the resolve and the sharpening read.
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

    /// The history the last frame resolved (alpha: each pixel's weight).
    pub fn latest(&self) -> &wgpu::TextureView {
        &self.views[self.latest]
    }

    /// The output size it was made for.
    pub fn size(&self) -> (u32, u32) {
        self.size
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
    /// Where the neighbourhood pass writes each lit texel's (mean and most
    /// moved; spread and disoccluded).
    pub neighbourhood: &'a [wgpu::TextureView; 2],
    pub sampler: &'a wgpu::Sampler,
    /// Where this frame's sample lies in each lit texel (see
    /// [`crate::temporal::jitter`]).
    pub sample_offset: glam::Vec2,
}

impl TaaPipelines {
    pub fn new(
        device: &wgpu::Device,
        shaders: &ShaderSet,
        output_format: wgpu::TextureFormat,
    ) -> TaaPipelines {
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("taa"),
            entries: &[
                texture_entry(0, true),
                texture_entry(1, false),
                texture_entry(2, true),
                filtering_sampler_entry(3),
                uniform_entry(4, wgpu::ShaderStages::FRAGMENT),
                texture_entry(7, false),
                texture_entry(8, false),
            ],
        });
        let around_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("taa neighbourhood"),
            entries: &[
                texture_entry(0, false),
                texture_entry(1, false),
                texture_entry(2, true),
                filtering_sampler_entry(3),
                uniform_entry(4, wgpu::ShaderStages::FRAGMENT),
                texture_entry(5, false),
                texture_entry(6, false),
            ],
        });
        let shader = screen_shader(device, shaders, &crate::shaders::TAA);
        let target = Some(wgpu::ColorTargetState::from(NEIGHBOURHOOD_FORMAT));
        let around = screen_pipeline_into(
            device,
            "taa neighbourhood",
            &around_layout,
            &shader,
            ("vs_screen", "fs_neighbourhood"),
            &[target.clone(), target],
            &[],
        );
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
            around_layout,
            around,
            resolve: pipeline("taa resolve", "fs_resolve", HISTORY_FORMAT),
            sharpen: pipeline("taa sharpen", "fs_sharpen", output_format),
            params: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("taa params"),
                contents: bytemuck::cast_slice(&[0.0f32; 8]),
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            }),
            layout,
        }
    }

    /// Records this frame's neighbourhoods and its resolve into `history`,
    /// and returns the bind group the sharpening pass reads it through
    /// (drawn by the caller into the output, with what goes over it).
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
        let (width, height) = history.size;
        let params = [
            inputs.sample_offset.x,
            inputs.sample_offset.y,
            holds,
            SHARPNESS,
            width as f32,
            height as f32,
            0.0,
            0.0,
        ];
        queue.write_buffer(&self.params, 0, bytemuck::cast_slice(&params));
        let (read, write) = (history.latest, 1 - history.latest);
        self.neighbourhood(device, encoder, inputs, &history.views[read]);
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

    /// Each lit texel's neighbourhood, into `inputs.neighbourhood`, and
    /// whether the light there changed since the `history`.
    fn neighbourhood(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        inputs: &ResolveInputs,
        history: &wgpu::TextureView,
    ) {
        let reading = self.bind_group_over(
            device,
            "taa neighbourhood",
            &self.around_layout,
            inputs,
            history,
            [(5, inputs.geometry), (6, inputs.geometry_before)],
        );
        let attachment = |view| {
            Some(wgpu::RenderPassColorAttachment {
                view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                    store: wgpu::StoreOp::Store,
                },
            })
        };
        let [mean, spread] = inputs.neighbourhood;
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("taa neighbourhood"),
            color_attachments: &[attachment(mean), attachment(spread)],
            depth_stencil_attachment: None,
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(&self.around);
        pass.set_bind_group(0, &reading, &[]);
        pass.draw(0..3, 0..1);
    }

    /// What the resolve and the sharpening read, with `history` as the
    /// history.
    fn bind_group(
        &self,
        device: &wgpu::Device,
        inputs: &ResolveInputs,
        history: &wgpu::TextureView,
    ) -> wgpu::BindGroup {
        let [mean, spread] = inputs.neighbourhood;
        self.bind_group_over(
            device,
            "taa",
            &self.layout,
            inputs,
            history,
            [(7, mean), (8, spread)],
        )
    }

    /// A bind group over `layout`: what every pass of the path reads (the
    /// frame, its motion, `history`, the sampler and the parameters), and
    /// the two textures of the pass's `own`.
    fn bind_group_over(
        &self,
        device: &wgpu::Device,
        label: &str,
        layout: &wgpu::BindGroupLayout,
        inputs: &ResolveInputs,
        history: &wgpu::TextureView,
        own: [(u32, &wgpu::TextureView); 2],
    ) -> wgpu::BindGroup {
        let texture = |binding, view| wgpu::BindGroupEntry {
            binding,
            resource: wgpu::BindingResource::TextureView(view),
        };
        let [(a, first), (b, second)] = own;
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(label),
            layout,
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
                texture(a, first),
                texture(b, second),
            ],
        })
    }
}
