//! The debug views' marks, drawn last in tone mapping's pass: at the
//! output's resolution whatever the scene's (so a low quality level, lit
//! at half size, draws them as sharp as high), in the output's colours
//! (not lit, not tone-mapped, no bloom), faint where a body hides them.

use super::bindings::{texture_entry, uniform_entry};
use crate::camera::Camera;
use crate::debug_view::{DebugMark, mark_scale};
use crate::gpu::Gpu;
use crate::instances::InstanceBuffer;
use crate::shaders::ShaderSet;

/// The shader's `Overlay`.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct Overlay {
    view_proj: [[f32; 4]; 4],
    camera: [f32; 4],
    sizes: [f32; 4],
    lens: [f32; 4],
}

/// The pipeline, its uniform and the marks' instances.
pub(super) struct DebugMarksPass {
    pipeline: wgpu::RenderPipeline,
    pub layout: wgpu::BindGroupLayout,
    overlay: wgpu::Buffer,
    marks: InstanceBuffer<DebugMark>,
}

impl DebugMarksPass {
    /// The pass, for frames in `output_format`.
    pub fn new(
        device: &wgpu::Device,
        shaders: &ShaderSet,
        output_format: wgpu::TextureFormat,
    ) -> DebugMarksPass {
        let shader = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(crate::shaders::DEBUG_MARKS.name),
            source: wgpu::ShaderSource::Wgsl(shaders.source(&crate::shaders::DEBUG_MARKS).into()),
        });
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("debug marks"),
            entries: &[
                // overlay: the camera, the sizes
                uniform_entry(0, wgpu::ShaderStages::VERTEX | wgpu::ShaderStages::FRAGMENT),
                // geometry: the scene's surfaces and their distances
                texture_entry(1, false),
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("debug marks"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("debug marks"),
            layout: Some(&pipeline_layout),
            vertex: wgpu::VertexState {
                module: &shader,
                entry_point: Some("vs_mark"),
                compilation_options: Default::default(),
                buffers: &[Some(DebugMark::layout())],
            },
            primitive: wgpu::PrimitiveState {
                topology: wgpu::PrimitiveTopology::TriangleStrip,
                ..Default::default()
            },
            depth_stencil: None,
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module: &shader,
                entry_point: Some("fs_mark"),
                compilation_options: Default::default(),
                // Premultiplied: each mark over what is drawn.
                targets: &[Some(wgpu::ColorTargetState {
                    format: output_format,
                    blend: Some(wgpu::BlendState::PREMULTIPLIED_ALPHA_BLENDING),
                    write_mask: wgpu::ColorWrites::ALL,
                })],
            }),
            multiview_mask: None,
            cache: None,
        });
        let overlay = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("debug marks overlay"),
            size: std::mem::size_of::<Overlay>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        DebugMarksPass {
            pipeline,
            layout,
            overlay,
            marks: InstanceBuffer::new(device, "debug marks"),
        }
    }

    /// The bind group over the scene's `geometry` target.
    pub fn bind_group(
        &self,
        device: &wgpu::Device,
        geometry: &wgpu::TextureView,
    ) -> wgpu::BindGroup {
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("debug marks"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: self.overlay.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(geometry),
                },
            ],
        })
    }

    /// Uploads this frame's `marks`, seen by `camera` in an output of
    /// `output` pixels whose scene was lit at `scene` pixels.
    pub fn upload(
        &mut self,
        gpu: &Gpu,
        marks: &[DebugMark],
        camera: &Camera,
        output: (u32, u32),
        scene: (u32, u32),
    ) {
        self.marks.items.clear();
        self.marks.items.extend_from_slice(marks);
        self.marks.upload(gpu);
        if marks.is_empty() {
            return;
        }
        let aspect = output.0 as f32 / output.1 as f32;
        let overlay = Overlay {
            view_proj: camera.view_projection(aspect).to_cols_array_2d(),
            camera: camera.eye.extend(mark_scale(output.1)).to_array(),
            sizes: [
                output.0 as f32,
                output.1 as f32,
                scene.0 as f32,
                scene.1 as f32,
            ],
            // A metre at distance w spans this over w pixels.
            lens: [
                0.5 * output.1 as f32 / (0.5 * camera.fov_y_deg.to_radians()).tan(),
                0.0,
                0.0,
                0.0,
            ],
        };
        gpu.queue
            .write_buffer(&self.overlay, 0, bytemuck::bytes_of(&overlay));
    }

    /// Draws the marks uploaded into `pass`; returns the draw calls made.
    pub fn draw(&self, pass: &mut wgpu::RenderPass, bind_group: &wgpu::BindGroup) -> u32 {
        if self.marks.items.is_empty() {
            return 0;
        }
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, bind_group, &[]);
        pass.set_vertex_buffer(0, self.marks.buffer.slice(..));
        pass.draw(0..8, self.marks.range());
        1
    }
}
