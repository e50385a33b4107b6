//! The frame: shadow faces, the lit opaque scene, the unlit bulb, then tone
//! mapping to the output (R4's order), with MSAA and an HDR target.

use crate::camera::Camera;
use crate::gpu::{Gpu, RenderError};
use crate::instances::{self, BALL_MATERIAL, BallInstance, Instance, InstanceBuffer};
use crate::mesh::{GpuMesh, MeshData, Vertex};
use crate::shadow::{self, ShadowCube};
use crate::view::SceneView;
use bytemuck::{Pod, Zeroable};
use std::time::{Duration, Instant};
use wgpu::util::DeviceExt;

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
}

impl Default for RenderSettings {
    fn default() -> Self {
        RenderSettings {
            msaa: 4,
            shadow_size: 1024,
            shadows: true,
            exposure: 1.0,
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

/// Size-dependent render targets.
struct Targets {
    width: u32,
    height: u32,
    /// Multisampled colour (absent at 1x, where `hdr` is drawn directly).
    msaa: Option<wgpu::TextureView>,
    hdr: wgpu::TextureView,
    depth: wgpu::TextureView,
    tonemap_bind_group: wgpu::BindGroup,
}

pub struct Renderer {
    settings: RenderSettings,
    output_format: wgpu::TextureFormat,
    scene_pipeline: wgpu::RenderPipeline,
    /// Balls, each a square that traces its sphere.
    ball_pipeline: wgpu::RenderPipeline,
    emissive_pipeline: wgpu::RenderPipeline,
    glow_pipeline: wgpu::RenderPipeline,
    shadow_pipeline: wgpu::RenderPipeline,
    ball_shadow_pipeline: wgpu::RenderPipeline,
    tonemap_pipeline: wgpu::RenderPipeline,
    tonemap_layout: wgpu::BindGroupLayout,
    cursor_pipeline: wgpu::RenderPipeline,
    cursor_buffer: wgpu::Buffer,
    cursor_bind_group: wgpu::BindGroup,
    /// Where to draw the arrow cursor (pixels), if anywhere.
    cursor: Option<glam::Vec2>,
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
            ..settings
        };
        let shader = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("scene.wgsl"),
            source: wgpu::ShaderSource::Wgsl(include_str!("../shaders/scene.wgsl").into()),
        });
        let tonemap_shader = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("tonemap.wgsl"),
            source: wgpu::ShaderSource::Wgsl(include_str!("../shaders/tonemap.wgsl").into()),
        });

        let scene_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("scene"),
            entries: &[
                uniform_entry(0, wgpu::ShaderStages::VERTEX_FRAGMENT),
                wgpu::BindGroupLayoutEntry {
                    binding: 1,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Depth,
                        view_dimension: wgpu::TextureViewDimension::D2Array,
                        multisampled: false,
                    },
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: 2,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Comparison),
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: 3,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Float { filterable: true },
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: 4,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                    count: None,
                },
            ],
        });
        let face_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("shadow face"),
            entries: &[uniform_entry(0, wgpu::ShaderStages::VERTEX_FRAGMENT)],
        });
        let tonemap_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("tonemap"),
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Float { filterable: false },
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                    count: None,
                },
                uniform_entry(1, wgpu::ShaderStages::FRAGMENT),
            ],
        });

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
        let shadow_cube = ShadowCube::new(device, settings.shadow_size, &face_layout);
        let shadow_sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("shadow comparison"),
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            compare: Some(wgpu::CompareFunction::LessEqual),
            ..Default::default()
        });
        let paint_view = upload_texture(gpu, "tumbler paint", paint);
        let paint_sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("paint"),
            address_mode_u: wgpu::AddressMode::Repeat,
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            ..Default::default()
        });
        let scene_bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("scene"),
            layout: &scene_layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: globals.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(&shadow_cube.array_view),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: wgpu::BindingResource::Sampler(&shadow_sampler),
                },
                wgpu::BindGroupEntry {
                    binding: 3,
                    resource: wgpu::BindingResource::TextureView(&paint_view),
                },
                wgpu::BindGroupEntry {
                    binding: 4,
                    resource: wgpu::BindingResource::Sampler(&paint_sampler),
                },
            ],
        });

        let scene_pipeline_layout =
            device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some("scene"),
                bind_group_layouts: &[Some(&scene_layout)],
                immediate_size: 0,
            });
        let buffers = [Some(Vertex::layout()), Some(Instance::layout())];
        // Opaque passes write depth; see-through ones blend and only test it.
        let scene_pipeline_for = |entry: &str, label: &str, blend: Option<wgpu::BlendState>| {
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(label),
                layout: Some(&scene_pipeline_layout),
                vertex: wgpu::VertexState {
                    module: &shader,
                    entry_point: Some("vs_scene"),
                    compilation_options: Default::default(),
                    buffers: &buffers,
                },
                primitive: wgpu::PrimitiveState {
                    cull_mode: Some(wgpu::Face::Back),
                    ..Default::default()
                },
                depth_stencil: Some(wgpu::DepthStencilState {
                    format: DEPTH_FORMAT,
                    depth_write_enabled: Some(blend.is_none()),
                    depth_compare: Some(wgpu::CompareFunction::Less),
                    stencil: Default::default(),
                    bias: Default::default(),
                }),
                multisample: wgpu::MultisampleState {
                    count: settings.msaa,
                    ..Default::default()
                },
                fragment: Some(wgpu::FragmentState {
                    module: &shader,
                    entry_point: Some(entry),
                    compilation_options: Default::default(),
                    targets: &[Some(wgpu::ColorTargetState {
                        format: HDR_FORMAT,
                        blend,
                        write_mask: wgpu::ColorWrites::ALL,
                    })],
                }),
                multiview_mask: None,
                cache: None,
            })
        };
        let scene_pipeline = scene_pipeline_for("fs_lit", "lit", None);
        // Balls are squares that trace their sphere (see scene.wgsl): seen
        // from either side, and smooth at the outline through alpha to
        // coverage where there are samples to cover.
        let alpha_to_coverage = settings.msaa > 1;
        let (kind, specular, shininess) = BALL_MATERIAL;
        let ball_constants = [
            ("ALPHA_TO_COVERAGE", f64::from(u8::from(alpha_to_coverage))),
            ("BALL_KIND", f64::from(kind as u32)),
            ("BALL_SPECULAR", f64::from(specular)),
            ("BALL_SHININESS", f64::from(shininess)),
        ];
        let ball_buffers = [Some(Vertex::layout()), Some(BallInstance::layout())];
        let ball_pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("balls"),
            layout: Some(&scene_pipeline_layout),
            vertex: wgpu::VertexState {
                module: &shader,
                entry_point: Some("vs_ball"),
                compilation_options: Default::default(),
                buffers: &ball_buffers,
            },
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil: Some(wgpu::DepthStencilState {
                format: DEPTH_FORMAT,
                depth_write_enabled: Some(true),
                depth_compare: Some(wgpu::CompareFunction::Less),
                stencil: Default::default(),
                bias: Default::default(),
            }),
            multisample: wgpu::MultisampleState {
                count: settings.msaa,
                alpha_to_coverage_enabled: alpha_to_coverage,
                ..Default::default()
            },
            fragment: Some(wgpu::FragmentState {
                module: &shader,
                entry_point: Some("fs_ball"),
                compilation_options: wgpu::PipelineCompilationOptions {
                    constants: &ball_constants,
                    ..Default::default()
                },
                targets: &[Some(wgpu::ColorTargetState {
                    format: HDR_FORMAT,
                    blend: None,
                    write_mask: wgpu::ColorWrites::ALL,
                })],
            }),
            multiview_mask: None,
            cache: None,
        });
        let emissive_pipeline = scene_pipeline_for("fs_emissive", "emissive", None);
        // Premultiplied alpha: a fragment adds its light and covers a share
        // of what is behind; with no cover it is purely additive (the shells,
        // the cubes' glowing frames), so only the cubes' dark insides depend
        // on drawing order, and small cubes need no sorting. Depth is tested
        // (walls hide particles) but not written (particles never hide each
        // other).
        let glow_pipeline = scene_pipeline_for(
            "fs_glow",
            "glow",
            Some(wgpu::BlendState {
                color: wgpu::BlendComponent {
                    src_factor: wgpu::BlendFactor::One,
                    dst_factor: wgpu::BlendFactor::OneMinusSrcAlpha,
                    operation: wgpu::BlendOperation::Add,
                },
                alpha: wgpu::BlendComponent::OVER,
            }),
        );

        let shadow_pipeline_layout =
            device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some("shadow"),
                bind_group_layouts: &[Some(&face_layout)],
                immediate_size: 0,
            });
        // Slope-scaled bias keeps surfaces from shadowing themselves (acne).
        let shadow_bias = wgpu::DepthBiasState {
            constant: 2,
            slope_scale: 2.0,
            clamp: 0.0,
        };
        let shadow_pipeline_for = |vertex: &str,
                                   fragment: Option<&str>,
                                   buffers: &[Option<wgpu::VertexBufferLayout>],
                                   label: &str| {
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(label),
                layout: Some(&shadow_pipeline_layout),
                vertex: wgpu::VertexState {
                    module: &shader,
                    entry_point: Some(vertex),
                    compilation_options: Default::default(),
                    buffers,
                },
                primitive: wgpu::PrimitiveState::default(),
                depth_stencil: Some(wgpu::DepthStencilState {
                    format: shadow::SHADOW_FORMAT,
                    depth_write_enabled: Some(true),
                    depth_compare: Some(wgpu::CompareFunction::Less),
                    stencil: Default::default(),
                    bias: shadow_bias,
                }),
                multisample: Default::default(),
                fragment: fragment.map(|entry| wgpu::FragmentState {
                    module: &shader,
                    entry_point: Some(entry),
                    compilation_options: Default::default(),
                    targets: &[],
                }),
                multiview_mask: None,
                cache: None,
            })
        };
        let shadow_pipeline = shadow_pipeline_for("vs_shadow", None, &buffers, "shadow");
        let ball_shadow_pipeline = shadow_pipeline_for(
            "vs_ball_shadow",
            Some("fs_ball_shadow"),
            &ball_buffers,
            "ball shadow",
        );

        let tonemap_pipeline = screen_pipeline(
            device,
            "tonemap",
            &tonemap_layout,
            &tonemap_shader,
            ("vs_fullscreen", "fs_tonemap"),
            output_format,
        );

        let cursor_shader = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("cursor.wgsl"),
            source: wgpu::ShaderSource::Wgsl(include_str!("../shaders/cursor.wgsl").into()),
        });
        let cursor_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("cursor"),
            entries: &[uniform_entry(0, wgpu::ShaderStages::VERTEX)],
        });
        let cursor_buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("cursor"),
            size: 16,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let cursor_bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("cursor"),
            layout: &cursor_layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: cursor_buffer.as_entire_binding(),
            }],
        });
        let cursor_pipeline = screen_pipeline(
            device,
            "cursor",
            &cursor_layout,
            &cursor_shader,
            ("vs_cursor", "fs_cursor"),
            output_format,
        );

        Renderer {
            settings,
            output_format,
            scene_pipeline,
            ball_pipeline,
            emissive_pipeline,
            glow_pipeline,
            shadow_pipeline,
            ball_shadow_pipeline,
            tonemap_pipeline,
            tonemap_layout,
            cursor_pipeline,
            cursor_buffer,
            cursor_bind_group,
            cursor: None,
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
        self.cursor = pixel;
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
                pass.set_pipeline(&self.ball_shadow_pipeline);
                draw_calls += draw(&mut pass, &self.quad, self.balls.range());
                pass.set_vertex_buffer(1, self.instances.buffer.slice(..));
                pass.set_pipeline(&self.shadow_pipeline);
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
            pass.set_pipeline(&self.scene_pipeline);
            draw_calls += draw(&mut pass, &self.quad, ranges.room.clone());
            draw_calls += draw(&mut pass, &self.tumbler, ranges.tumblers.clone());
            pass.set_vertex_buffer(1, self.balls.buffer.slice(..));
            pass.set_pipeline(&self.ball_pipeline);
            draw_calls += draw(&mut pass, &self.quad, self.balls.range());
            pass.set_vertex_buffer(1, self.instances.buffer.slice(..));
            // ... then what glows and is not lit.
            pass.set_pipeline(&self.emissive_pipeline);
            draw_calls += draw(&mut pass, &self.sphere, ranges.bulb.clone());
            // ... and last what is see-through.
            pass.set_pipeline(&self.glow_pipeline);
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
            pass.set_pipeline(&self.tonemap_pipeline);
            pass.set_bind_group(0, &targets.tonemap_bind_group, &[]);
            pass.draw(0..3, 0..1);
            draw_calls += 1;
            if let Some(at) = self.cursor {
                let place = [at.x, at.y, width as f32, height as f32];
                gpu.queue
                    .write_buffer(&self.cursor_buffer, 0, bytemuck::cast_slice(&place));
                pass.set_pipeline(&self.cursor_pipeline);
                pass.set_bind_group(0, &self.cursor_bind_group, &[]);
                // Outline, then arrow.
                pass.draw(0..15, 0..2);
                draw_calls += 1;
            }
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
        let device = &gpu.device;
        let size = wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        };
        let texture = |label, format, samples, usage| {
            device
                .create_texture(&wgpu::TextureDescriptor {
                    label: Some(label),
                    size,
                    mip_level_count: 1,
                    sample_count: samples,
                    dimension: wgpu::TextureDimension::D2,
                    format,
                    usage,
                    view_formats: &[],
                })
                .create_view(&Default::default())
        };
        let samples = self.settings.msaa;
        let hdr = texture(
            "hdr",
            HDR_FORMAT,
            1,
            wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
        );
        let msaa = (samples > 1).then(|| {
            texture(
                "hdr msaa",
                HDR_FORMAT,
                samples,
                wgpu::TextureUsages::RENDER_ATTACHMENT,
            )
        });
        let depth = texture(
            "depth",
            DEPTH_FORMAT,
            samples,
            wgpu::TextureUsages::RENDER_ATTACHMENT,
        );
        let tonemap_bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("tonemap"),
            layout: &self.tonemap_layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::TextureView(&hdr),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: self.tonemap_params.as_entire_binding(),
                },
            ],
        });
        self.targets = Some(Targets {
            width,
            height,
            msaa,
            hdr,
            depth,
            tonemap_bind_group,
        });
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

/// A pipeline that draws straight into the output, in screen space: no
/// vertex buffers, no depth, one bind group.
fn screen_pipeline(
    device: &wgpu::Device,
    label: &str,
    layout: &wgpu::BindGroupLayout,
    shader: &wgpu::ShaderModule,
    (vertex, fragment): (&str, &str),
    output_format: wgpu::TextureFormat,
) -> wgpu::RenderPipeline {
    let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(label),
        bind_group_layouts: &[Some(layout)],
        immediate_size: 0,
    });
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(label),
        layout: Some(&pipeline_layout),
        vertex: wgpu::VertexState {
            module: shader,
            entry_point: Some(vertex),
            compilation_options: Default::default(),
            buffers: &[],
        },
        primitive: Default::default(),
        depth_stencil: None,
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module: shader,
            entry_point: Some(fragment),
            compilation_options: Default::default(),
            targets: &[Some(output_format.into())],
        }),
        multiview_mask: None,
        cache: None,
    })
}

fn uniform_entry(binding: u32, visibility: wgpu::ShaderStages) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

fn upload_texture(gpu: &Gpu, label: &str, image: &image::RgbaImage) -> wgpu::TextureView {
    let size = wgpu::Extent3d {
        width: image.width(),
        height: image.height(),
        depth_or_array_layers: 1,
    };
    let texture = gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size,
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Rgba8UnormSrgb,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    });
    gpu.queue.write_texture(
        wgpu::TexelCopyTextureInfo {
            texture: &texture,
            mip_level: 0,
            origin: wgpu::Origin3d::ZERO,
            aspect: wgpu::TextureAspect::All,
        },
        image.as_raw(),
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(4 * image.width()),
            rows_per_image: None,
        },
        size,
    );
    texture.create_view(&Default::default())
}
