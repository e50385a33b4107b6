//! The contact occlusion pass (L4): how open each visible point is to the
//! room around it, from the surfaces the scene pass saw, at half the
//! frame's resolution (see occlusion.wgsl); tone mapping darkens the
//! picture by it.

use super::bindings::{texture_entry, uniform_entry};
use super::pipelines::{screen_pipeline, screen_shader};
use crate::camera::Camera;
use crate::shaders::ShaderSet;
use bytemuck::{Pod, Zeroable};

/// The texture the openness is drawn into: one channel is all it needs.
const OCCLUSION_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R8Unorm;

/// How far around a point its neighbours may block its sky, in metres: a
/// little more than a default ball's diameter.
const RADIUS: f32 = 0.3;

/// How dark a point whose every sample is blocked gets: not black, as
/// some light always finds its way in.
const STRENGTH: f32 = 0.9;

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct Params {
    view_proj: [[f32; 4]; 4],
    inverse_view_proj: [[f32; 4]; 4],
    eye: [f32; 4],
    settings: [f32; 4],
}

/// The pass's pipeline.
pub(super) struct OcclusionPipeline {
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::RenderPipeline,
    params: wgpu::Buffer,
}

impl OcclusionPipeline {
    pub fn new(device: &wgpu::Device, shaders: &ShaderSet) -> OcclusionPipeline {
        let shader = screen_shader(device, shaders, &crate::shaders::OCCLUSION);
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("occlusion"),
            entries: &[
                texture_entry(0, false),
                uniform_entry(1, wgpu::ShaderStages::FRAGMENT),
            ],
        });
        let pipeline = screen_pipeline(
            device,
            "occlusion",
            &layout,
            &shader,
            ("vs_screen", "fs_occlusion"),
            OCCLUSION_FORMAT.into(),
        );
        let params = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("occlusion"),
            size: std::mem::size_of::<Params>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        OcclusionPipeline {
            layout,
            pipeline,
            params,
        }
    }

    /// The openness of a frame of `width` x `height` whose surfaces (normal
    /// and distance) are `geometry`.
    pub fn target(
        &self,
        device: &wgpu::Device,
        geometry: &wgpu::TextureView,
        (width, height): (u32, u32),
    ) -> OcclusionTarget {
        let view = device
            .create_texture(&wgpu::TextureDescriptor {
                label: Some("occlusion"),
                size: wgpu::Extent3d {
                    width: width.div_ceil(2),
                    height: height.div_ceil(2),
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: OCCLUSION_FORMAT,
                usage: wgpu::TextureUsages::RENDER_ATTACHMENT
                    | wgpu::TextureUsages::TEXTURE_BINDING,
                view_formats: &[],
            })
            .create_view(&Default::default());
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("occlusion"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::TextureView(geometry),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: self.params.as_entire_binding(),
                },
            ],
        });
        OcclusionTarget {
            view,
            bind_group,
            size: (width, height),
        }
    }

    /// Records the pass for `camera` into `target`.
    pub fn record(
        &self,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        target: &OcclusionTarget,
        camera: &Camera,
    ) -> u32 {
        let (width, height) = target.size;
        let view_proj = camera.view_projection(width as f32 / height as f32);
        let params = Params {
            view_proj: view_proj.to_cols_array_2d(),
            inverse_view_proj: view_proj.inverse().to_cols_array_2d(),
            eye: camera.eye.extend(RADIUS).to_array(),
            settings: [STRENGTH, width as f32, height as f32, 0.0],
        };
        queue.write_buffer(&self.params, 0, bytemuck::bytes_of(&params));
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("occlusion"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &target.view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::WHITE),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: None,
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &target.bind_group, &[]);
        pass.draw(0..3, 0..1);
        1
    }
}

/// The openness of frames of one size.
pub(super) struct OcclusionTarget {
    /// At half the frame's resolution, which tone mapping reads.
    pub view: wgpu::TextureView,
    bind_group: wgpu::BindGroup,
    size: (u32, u32),
}
