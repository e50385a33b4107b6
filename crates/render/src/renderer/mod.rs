//! The frame: shadow faces, the lit opaque scene, the unlit bulb, then tone
//! mapping to the output (R4's order), with MSAA and an HDR target.
//!
//! This file records a frame's passes. The parts, a file each: what the
//! shaders read ([`bindings`]), how each kind of thing is drawn
//! ([`pipelines`]), the targets a frame is drawn into ([`targets`]) and the
//! drawn cursor ([`cursor`]).

use crate::camera::Camera;
use crate::gpu::{Gpu, RenderError};
use crate::instances::{self, BallInstance, Instance, InstanceBuffer};
use crate::mesh::{GpuMesh, MeshData};
use crate::shadow::{self, ShadowCube};
use crate::view::SceneView;
use bindings::Layouts;
use bytemuck::{Pod, Zeroable};
use cursor::Cursor;
use pipelines::Pipelines;
use std::time::{Duration, Instant};
use targets::Targets;
use wgpu::util::DeviceExt;

mod bindings;
mod cursor;
mod pipelines;
mod targets;

/// The scene is lit in linear HDR and tone-mapped at the end, so that
/// glowing things can be brighter than white.
pub const HDR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// How to draw.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderSettings {
    /// Multisample count: 4 or 1 (lowered if the adapter cannot).
    pub msaa: u32,
    /// Size of one shadow face in texels.
    pub shadow_size: u32,
    pub shadows: bool,
    pub exposure: f32,
    /// Depth-test a ball's fragments before tracing its sphere in them,
    /// where the adapter allows it. It changes no pixel; off only to measure
    /// what it saves.
    pub early_ball_depth: bool,
}

impl Default for RenderSettings {
    fn default() -> Self {
        RenderSettings {
            msaa: 4,
            shadow_size: 1024,
            shadows: true,
            exposure: 1.0,
            early_ball_depth: true,
        }
    }
}

/// What a frame cost.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FrameStats {
    pub draw_calls: u32,
    /// Time spent in our own code building and recording the frame.
    pub cpu_time: Duration,
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
struct Globals {
    view_proj: [[f32; 4]; 4],
    camera_pos: [f32; 4],
    light_pos: [f32; 4],
    light_color: [f32; 4],
    shadow: [f32; 4],
    light_view_proj: [[[f32; 4]; 4]; 6],
}

pub struct Renderer {
    settings: RenderSettings,
    output_format: wgpu::TextureFormat,
    pipelines: Pipelines,
    tonemap_layout: wgpu::BindGroupLayout,
    cursor: Cursor,
    globals: wgpu::Buffer,
    tonemap_params: wgpu::Buffer,
    scene_bind_group: wgpu::BindGroup,
    shadow_cube: ShadowCube,
    sphere: GpuMesh,
    quad: GpuMesh,
    cube: GpuMesh,
    tumbler: GpuMesh,
    instances: InstanceBuffer<Instance>,
    balls: InstanceBuffer<BallInstance>,
    targets: Option<Targets>,
}

impl Renderer {
    /// Builds the pipelines for frames in `output_format`. `tumbler_mesh`
    /// and `paint` are the tumbler's mesh and texture.
    pub fn new(
        gpu: &Gpu,
        settings: RenderSettings,
        output_format: wgpu::TextureFormat,
        tumbler_mesh: &MeshData,
        paint: &image::RgbaImage,
    ) -> Renderer {
        let device = &gpu.device;
        let settings = RenderSettings {
            msaa: gpu.msaa_samples(settings.msaa),
            early_ball_depth: settings.early_ball_depth && gpu.has_early_depth_test(),
            ..settings
        };
        let layouts = Layouts::new(device);
        let globals = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("globals"),
            size: std::mem::size_of::<Globals>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let tonemap_params = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("tonemap params"),
            contents: bytemuck::cast_slice(&[settings.exposure, 0.0, 0.0, 0.0]),
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        });
        let shadow_cube = ShadowCube::new(device, settings.shadow_size, &layouts.face);
        let scene_bind_group =
            bindings::scene_bind_group(gpu, &layouts.scene, &globals, &shadow_cube, paint);
        Renderer {
            settings,
            output_format,
            pipelines: Pipelines::new(device, &layouts, &settings, output_format),
            tonemap_layout: layouts.tonemap,
            cursor: Cursor::new(device, output_format),
            globals,
            tonemap_params,
            scene_bind_group,
            shadow_cube,
            sphere: GpuMesh::upload(device, "sphere", &MeshData::sphere(16, 24)),
            quad: GpuMesh::upload(device, "quad", &MeshData::quad()),
            cube: GpuMesh::upload(device, "cube", &MeshData::cube()),
            tumbler: GpuMesh::upload(device, "tumbler", tumbler_mesh),
            instances: InstanceBuffer::new(device, "instances"),
            balls: InstanceBuffer::new(device, "balls"),
            targets: None,
        }
    }

    /// Draws the white arrow cursor with its tip at `pixel` (from the
    /// frame's top left) in the frames that follow, or no cursor.
    pub fn set_cursor(&mut self, pixel: Option<glam::Vec2>) {
        self.cursor.at = pixel;
    }

    pub fn settings(&self) -> RenderSettings {
        self.settings
    }

    pub fn output_format(&self) -> wgpu::TextureFormat {
        self.output_format
    }

    /// Draws `view` seen by `camera` into `output` (of the output format).
    pub fn render(
        &mut self,
        gpu: &Gpu,
        view: &SceneView,
        camera: &Camera,
        output: &wgpu::TextureView,
        width: u32,
        height: u32,
    ) -> Result<FrameStats, RenderError> {
        if width == 0 || height == 0 {
            return Err(RenderError::Size {
                width,
                height,
                reason: "a frame needs at least one pixel".into(),
            });
        }
        let start = Instant::now();
        self.ensure_targets(gpu, width, height);
        let ranges = instances::fill_scene(&mut self.instances.items, view);
        self.instances.upload(gpu);
        instances::fill_balls(&mut self.balls.items, view);
        self.balls.upload(gpu);

        let faces = shadow::face_view_projections(view.light.position);
        self.shadow_cube
            .update(&gpu.queue, &faces, view.light.position);
        let globals = Globals {
            view_proj: camera
                .view_projection(width as f32 / height as f32)
                .to_cols_array_2d(),
            camera_pos: camera.eye.extend(1.0).to_array(),
            light_pos: view.light.position.extend(1.0).to_array(),
            light_color: view.light.color.extend(view.light.ambient).to_array(),
            shadow: [
                if self.settings.shadows { 1.0 } else { 0.0 },
                1.0 / self.shadow_cube.size as f32,
                0.00002,
                0.0,
            ],
            light_view_proj: faces.map(|m| m.to_cols_array_2d()),
        };
        gpu.queue
            .write_buffer(&self.globals, 0, bytemuck::bytes_of(&globals));

        let mut encoder = gpu
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("frame"),
            });
        let mut draw_calls = 0;
        if self.settings.shadows {
            for face in 0..6 {
                let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                    label: Some("shadow face"),
                    color_attachments: &[],
                    depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                        view: &self.shadow_cube.face_views[face],
                        depth_ops: Some(wgpu::Operations {
                            load: wgpu::LoadOp::Clear(1.0),
                            store: wgpu::StoreOp::Store,
                        }),
                        stencil_ops: None,
                    }),
                    timestamp_writes: None,
                    occlusion_query_set: None,
                    multiview_mask: None,
                });
                pass.set_bind_group(0, &self.shadow_cube.face_bind_groups[face], &[]);
                // The room's walls cast no shadow inside it; balls and tumblers do.
                pass.set_vertex_buffer(1, self.balls.buffer.slice(..));
                pass.set_pipeline(&self.pipelines.ball_shadow);
                draw_calls += draw(&mut pass, &self.quad, self.balls.range());
                pass.set_vertex_buffer(1, self.instances.buffer.slice(..));
                pass.set_pipeline(&self.pipelines.shadow);
                draw_calls += draw(&mut pass, &self.tumbler, ranges.tumblers.clone());
            }
        }
        let targets = self
            .targets
            .as_ref()
            .ok_or_else(|| RenderError::Readback("no render targets".into()))?;
        {
            let (view_target, resolve) = match &targets.msaa {
                Some(msaa) => (msaa, Some(&targets.hdr)),
                None => (&targets.hdr, None),
            };
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("scene"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: view_target,
                    depth_slice: None,
                    resolve_target: resolve,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color {
                            r: 0.01,
                            g: 0.01,
                            b: 0.012,
                            a: 1.0,
                        }),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &targets.depth,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(1.0),
                        store: wgpu::StoreOp::Discard,
                    }),
                    stencil_ops: None,
                }),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_bind_group(0, &self.scene_bind_group, &[]);
            // Lit and opaque first (the balls from their own buffer) ...
            pass.set_vertex_buffer(1, self.instances.buffer.slice(..));
            pass.set_pipeline(&self.pipelines.lit);
            draw_calls += draw(&mut pass, &self.quad, ranges.room.clone());
            draw_calls += draw(&mut pass, &self.tumbler, ranges.tumblers.clone());
            pass.set_vertex_buffer(1, self.balls.buffer.slice(..));
            pass.set_pipeline(&self.pipelines.ball);
            draw_calls += draw(&mut pass, &self.quad, self.balls.range());
            pass.set_vertex_buffer(1, self.instances.buffer.slice(..));
            // ... then what glows and is not lit.
            pass.set_pipeline(&self.pipelines.emissive);
            draw_calls += draw(&mut pass, &self.sphere, ranges.bulb.clone());
            // ... and last what is see-through.
            pass.set_pipeline(&self.pipelines.glow);
            draw_calls += draw(&mut pass, &self.cube, ranges.cubes.clone());
            draw_calls += draw(&mut pass, &self.sphere, ranges.shells.clone());
        }
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("tonemap"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: output,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: None,
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&self.pipelines.tonemap);
            pass.set_bind_group(0, &targets.tonemap_bind_group, &[]);
            pass.draw(0..3, 0..1);
            draw_calls += 1;
            draw_calls += self.cursor.draw(&gpu.queue, &mut pass, width, height);
        }
        let cpu_time = start.elapsed();
        gpu.queue.submit([encoder.finish()]);
        Ok(FrameStats {
            draw_calls,
            cpu_time,
        })
    }

    fn ensure_targets(&mut self, gpu: &Gpu, width: u32, height: u32) {
        if self
            .targets
            .as_ref()
            .is_some_and(|t| t.width == width && t.height == height)
        {
            return;
        }
        self.targets = Some(Targets::new(
            &gpu.device,
            (width, height),
            self.settings.msaa,
            &self.tonemap_layout,
            &self.tonemap_params,
        ));
    }
}

fn draw(pass: &mut wgpu::RenderPass, mesh: &GpuMesh, instances: std::ops::Range<u32>) -> u32 {
    if instances.is_empty() {
        return 0;
    }
    pass.set_vertex_buffer(0, mesh.vertices.slice(..));
    pass.set_index_buffer(mesh.indices.slice(..), wgpu::IndexFormat::Uint32);
    pass.draw_indexed(0..mesh.index_count, 0, instances);
    1
}
