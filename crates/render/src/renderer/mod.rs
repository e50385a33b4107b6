//! The frame, pass by pass (R4's order, and the light's effects):
//!
//! 1. [`Renderer::shadow_pass`]: the ceiling light's shadow faces, those
//!    whose casters or light moved;
//! 2. [`Renderer::scene_pass`]: the lit, opaque scene and the unlit lamps in
//!    linear HDR with MSAA, then the see-through particles;
//! 3. the contact occlusion, from the surfaces the scene pass saw
//!    ([`occlusion`]);
//! 4. the bloom's chain down and up ([`bloom`]);
//! 5. [`Renderer::tonemap_pass`]: occlusion, glow and the filmic curve into
//!    the output (lit at a lower resolution: at that resolution, then
//!    spread over the output; on the temporal path, at that resolution,
//!    then resolved against the history and sharpened, see [`taa`]), and
//!    the debug marks and the drawn cursor over it.
//!
//! The parts, a file each: what the shaders read ([`bindings`]), how each
//! kind of thing is drawn ([`pipelines`]), the targets a frame is drawn
//! into ([`targets`]), the two post passes and the cursor ([`cursor`]).

use crate::camera::Camera;
use crate::frame_view::{Drawn, FrameView, ViewCodes};
use crate::gpu::{Gpu, RenderError};
use crate::instances::{self, BallInstance, Instance, InstanceBuffer, PreviousModel, Ranges};
use crate::irradiance::{DIRECTIONS, IrradianceVolume, MAX_PROBES};
use crate::lighting;
use crate::mesh::{GpuMesh, MeshData};
use crate::shaders::ShaderSet;
use crate::shadow::{self, DrawnFaces, ShadowCube};
use crate::temporal::{self, TemporalState};
use crate::view::{PointLight, SceneView};
use bindings::Layouts;
use bloom::BloomPipelines;
use bytemuck::{Pod, Zeroable};
use cursor::Cursor;
use debug_marks::DebugMarksPass;
pub use frame_views::shadow_cross_place;
use frame_views::{FrameViewsPass, ViewSource};
use glam::UVec3;
use occlusion::OcclusionPipeline;
use pipelines::Pipelines;
use std::time::{Duration, Instant};
use taa::{History, ResolveInputs, TaaPipelines};
use targets::{TargetKit, Targets};
use timing::GpuTimer;
pub use timing::PassTimes;
pub use timing::StampSlots;
use wgpu::util::DeviceExt;

mod bindings;
mod bloom;
mod cursor;
mod debug_marks;
mod frame_views;
mod occlusion;
mod pipelines;
mod taa;
mod targets;
mod timing;

pub use crate::gpu::HDR_FORMAT;
const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
/// The surface's normal (xyz) and distance from the eye (w), written by the
/// scene pass for the occlusion: read from a colour target, which every
/// backend can, where OpenGL cannot read a depth buffer in a shader.
const GEOMETRY_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

/// What shows where nothing is drawn (never, inside the room).
const BACKGROUND: wgpu::Color = wgpu::Color {
    r: 0.01,
    g: 0.01,
    b: 0.012,
    a: 1.0,
};

/// Taken from a fragment's depth as seen from the light before it is
/// compared with a shadow face's, against shadow acne where the normal
/// offset (see `light_visibility` in scene.wgsl) is not enough.
const SHADOW_DEPTH_BIAS: f32 = 0.00002;

/// How the picture is drawn: what the adapter is asked for, fixed for the
/// renderer's life. What is lit and how (the light's effects) comes with
/// each frame's [`SceneView`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderSettings {
    /// Multisample count: 4 or 1 (lowered if the adapter cannot).
    pub msaa: u32,
    /// Size of one shadow face in texels.
    pub shadow_size: u32,
    /// Whether the point light casts shadows.
    pub shadows: bool,
    /// Shadow filter taps along each side of its square: 4 (16 taps) or 2
    /// (4), each a bilinear comparison of 2 x 2 texels.
    pub shadow_taps: u32,
    /// Draw each ball and tumbler only into the shadow faces it can cast
    /// into. It changes no pixel; off only to measure what it saves.
    pub cull_shadow_faces: bool,
    /// Share of the output's width and height the scene is lit at (1 or
    /// less); tone mapping scales it up to the output.
    pub resolution: f32,
    /// Scale of the light before tone mapping.
    pub exposure: f32,
    /// Depth-test a ball's fragments before tracing its sphere in them,
    /// where the adapter allows it. It changes no pixel; off only to measure
    /// what it saves.
    pub early_ball_depth: bool,
    /// Temporal anti-aliasing with upsampling: each frame jittered, then
    /// resolved against the frames before it at the output's resolution
    /// (see [`crate::jitter`]). It takes the place of multisampling,
    /// which it turns off.
    pub temporal: bool,
    /// Draw the tumblers with their coarse mesh, where the renderer has one
    /// (see [`Renderer::set_coarse_tumbler`]).
    pub coarse_tumblers: bool,
}

impl Default for RenderSettings {
    fn default() -> Self {
        RenderSettings {
            msaa: 4,
            shadow_size: 1024,
            shadows: true,
            shadow_taps: 4,
            cull_shadow_faces: true,
            resolution: 1.0,
            exposure: 1.0,
            early_ball_depth: true,
            temporal: false,
            coarse_tumblers: false,
        }
    }
}

/// What a frame cost.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FrameStats {
    /// Draw calls the frame recorded.
    pub draw_calls: u32,
    /// Shadow faces it drew: those whose light or casters moved since they
    /// were last drawn.
    pub shadow_faces: u32,
    /// Time spent in our own code building and recording the frame.
    pub cpu_time: Duration,
    /// Time spent submitting it: on a software renderer (lavapipe) the
    /// submission may wait for frames before it to be drawn, the GPU's
    /// time rather than ours.
    pub submit: Duration,
    /// The GPU's time for each pass of the latest frame whose timestamps
    /// have come back, where the adapter has timestamp queries and the
    /// passes are timed (see [`Renderer::set_gpu_timing`]).
    pub gpu: Option<PassTimes>,
    /// The timestamp slots this frame wrote and resolved: none unless its
    /// passes are timed.
    pub stamps: StampSlots,
}

/// The scene shader's `Globals`: the camera, both lights, the shadows and
/// the room's light for the bounce.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
struct Globals {
    view_proj: [[f32; 4]; 4],
    camera_pos: [f32; 4],
    light_pos: [f32; 4],
    light_color: [f32; 4],
    shadow: [f32; 4],
    light_view_proj: [[[f32; 4]; 4]; 6],
    light_falloff: [f32; 4],
    fireball_pos: [f32; 4],
    fireball_color: [f32; 4],
    fireball_falloff: [f32; 4],
    room: [f32; 4],
    irradiance_probes: [f32; 4],
    motion_view_proj: [[f32; 4]; 4],
    previous_view_proj: [[f32; 4]; 4],
    frame_view: [f32; 4],
    frame_size: [f32; 4],
}

/// The camera's view-projections this frame: the one it is drawn with
/// (jittered on the temporal path), the one without jitter, and the last
/// frame's without, for the surfaces' motion.
struct Projections {
    drawn: glam::Mat4,
    unjittered: glam::Mat4,
    previous: glam::Mat4,
    /// Where this frame's sample lies in each lit pixel (none off the
    /// temporal path).
    sample_offset: glam::Vec2,
}

/// The light's falloff and its reach (0: none), as the shader reads them.
fn falloff(light: PointLight) -> [f32; 4] {
    let [c0, c1, c2] = light.falloff;
    [c0, c1, c2, light.reach.unwrap_or(0.0)]
}

fn flag(on: bool) -> f32 {
    if on { 1.0 } else { 0.0 }
}

/// Draws a [`SceneView`] into a colour target: shadows, the scene, particles, occlusion, bloom, tone mapping.
pub struct Renderer {
    settings: RenderSettings,
    output_format: wgpu::TextureFormat,
    pipelines: Pipelines,
    /// The pipelines of the view shown before, kept: switching back and
    /// forth between two views builds nothing.
    other_pipelines: Option<Pipelines>,
    /// What the pipelines are built from, to build them again for another
    /// view of the frame.
    shaders: ShaderSet,
    layouts: Layouts,
    bloom: BloomPipelines,
    occlusion: OcclusionPipeline,
    tonemap_layout: wgpu::BindGroupLayout,
    upscale_layout: wgpu::BindGroupLayout,
    smooth_sampler: wgpu::Sampler,
    cursor: Cursor,
    globals: wgpu::Buffer,
    tonemap_params: wgpu::Buffer,
    scene_bind_group: wgpu::BindGroup,
    shadow_cube: ShadowCube,
    irradiance: Irradiance,
    sphere: GpuMesh,
    quad: GpuMesh,
    cube: GpuMesh,
    tumbler: GpuMesh,
    /// The tumblers' coarse mesh, drawn in its place where the settings ask.
    coarse_tumbler: Option<GpuMesh>,
    instances: InstanceBuffer<Instance>,
    balls: InstanceBuffer<BallInstance>,
    /// The last frame's balls, uploaded then: where each ball was.
    previous_balls: InstanceBuffer<BallInstance>,
    /// Where each instance was the frame before, and the last frame's
    /// instances as they were laid out, to find it.
    previous_models: InstanceBuffer<PreviousModel>,
    last_instances: Vec<Instance>,
    last_ranges: Ranges,
    /// The GPU engine's balls as the last frame drew them (the temporal
    /// path only): a copy made at the end of each frame.
    previous_gpu_balls: Option<crate::view::GpuBallBuffer>,
    /// This frame's balls where the GPU engine wrote them (see
    /// [`crate::view::GpuBallBuffer`]); the frame then draws from it.
    gpu_balls: Option<crate::view::GpuBallBuffer>,
    /// The shadow faces' own lists: each ball and tumbler once for every
    /// face it casts into.
    shadow_balls: InstanceBuffer<BallInstance>,
    shadow_tumblers: InstanceBuffer<Instance>,
    /// The debug views' marks (see [`crate::debug_view`]).
    marks: DebugMarksPass,
    /// The faces each caster reaches, reused frame to frame.
    faces_reached: Vec<u8>,
    /// What each shadow face was last drawn from.
    drawn_faces: DrawnFaces,
    /// The tumbler mesh's bounding sphere, in its own space.
    tumbler_bounds: (glam::Vec3, f32),
    targets: Option<Targets>,
    /// The temporal path's passes, its history at the output's resolution,
    /// and what it carries between frames.
    taa: TaaPipelines,
    history: Option<History>,
    temporal: TemporalState,
    /// Times the passes on the GPU, where it can, once timing is asked for.
    timer: Option<GpuTimer>,
    /// Whether the passes are timed (the profiler is open).
    timing: bool,
    /// What the frames show: the finished picture or one pass.
    view: FrameView,
    /// The pass of the views that no frame target holds.
    frame_views: FrameViewsPass,
    /// Whether the multisampled surfaces are read sample by sample.
    read_samples: bool,
}

/// Where each face's casters lie in the shadow lists.
struct FaceRanges {
    balls: [std::ops::Range<u32>; 6],
    tumblers: [std::ops::Range<u32>; 6],
}

impl Renderer {
    /// Builds the pipelines for frames in `output_format` with the shipped
    /// shaders. `tumbler_mesh` and `paint` are the tumbler's mesh and
    /// texture.
    pub fn new(
        gpu: &Gpu,
        settings: RenderSettings,
        output_format: wgpu::TextureFormat,
        tumbler_mesh: &MeshData,
        paint: &image::RgbaImage,
    ) -> Renderer {
        let shipped = ShaderSet::shipped();
        Renderer::with_shaders(gpu, settings, output_format, tumbler_mesh, paint, &shipped)
    }

    /// As [`Renderer::new`], drawing with `shaders` (a folder's, checked by
    /// [`ShaderSet::load`]).
    pub fn with_shaders(
        gpu: &Gpu,
        settings: RenderSettings,
        output_format: wgpu::TextureFormat,
        tumbler_mesh: &MeshData,
        paint: &image::RgbaImage,
        shaders: &ShaderSet,
    ) -> Renderer {
        let device = &gpu.device;
        let settings = RenderSettings {
            // The temporal path anti-aliases over frames instead.
            msaa: if settings.temporal {
                1
            } else {
                gpu.msaa_samples(settings.msaa)
            },
            early_ball_depth: settings.early_ball_depth && gpu.has_early_depth_test(),
            // A share of the output: some of it, and never more.
            resolution: settings.resolution.clamp(0.05, 1.0),
            ..settings
        };
        let layouts = Layouts::new(device);
        // The samples a pixel the msaa-edges view reads: none (1) where
        // multisampled targets cannot be read.
        let read_samples = if gpu.reads_multisampled_targets() {
            settings.msaa
        } else {
            1
        };
        let globals = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("globals"),
            size: std::mem::size_of::<Globals>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let tonemap_params = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("tonemap params"),
            contents: bytemuck::cast_slice(&[settings.exposure, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]),
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        });
        let shadow_cube = ShadowCube::new(device, settings.shadow_size, &layouts.face);
        let irradiance = Irradiance {
            texture: bindings::irradiance_texture(device),
            volume: None,
            texels: Vec::new(),
        };
        let scene_bind_group = bindings::scene_bind_group(
            gpu,
            &layouts.scene,
            &globals,
            &shadow_cube,
            paint,
            &irradiance.texture,
        );
        Renderer {
            settings,
            output_format,
            pipelines: Pipelines::new(
                device,
                shaders,
                &layouts,
                &settings,
                output_format,
                ViewCodes::FINAL,
            ),
            other_pipelines: None,
            shaders: shaders.clone(),
            layouts: layouts.clone(),
            bloom: BloomPipelines::new(device, shaders),
            occlusion: OcclusionPipeline::new(device, shaders),
            tonemap_layout: layouts.tonemap,
            upscale_layout: layouts.upscale,
            smooth_sampler: device.create_sampler(&wgpu::SamplerDescriptor {
                label: Some("smooth"),
                address_mode_u: wgpu::AddressMode::ClampToEdge,
                address_mode_v: wgpu::AddressMode::ClampToEdge,
                mag_filter: wgpu::FilterMode::Linear,
                min_filter: wgpu::FilterMode::Linear,
                ..Default::default()
            }),
            cursor: Cursor::new(device, shaders, output_format),
            globals,
            tonemap_params,
            scene_bind_group,
            shadow_cube,
            irradiance,
            sphere: GpuMesh::upload(device, "sphere", &MeshData::sphere(16, 24)),
            quad: GpuMesh::upload(device, "quad", &MeshData::quad()),
            cube: GpuMesh::upload(device, "cube", &MeshData::cube()),
            tumbler: GpuMesh::upload(device, "tumbler", tumbler_mesh),
            coarse_tumbler: None,
            instances: InstanceBuffer::new(device, "instances"),
            balls: InstanceBuffer::new(device, "balls"),
            previous_balls: InstanceBuffer::new(device, "balls before"),
            previous_models: InstanceBuffer::new(device, "models before"),
            last_instances: Vec::new(),
            last_ranges: Ranges::default(),
            previous_gpu_balls: None,
            gpu_balls: None,
            shadow_balls: InstanceBuffer::new(device, "shadow balls"),
            shadow_tumblers: InstanceBuffer::new(device, "shadow tumblers"),
            marks: DebugMarksPass::new(device, shaders, output_format),
            faces_reached: Vec::new(),
            drawn_faces: DrawnFaces::default(),
            tumbler_bounds: tumbler_mesh.bounding_sphere(),
            targets: None,
            taa: TaaPipelines::new(device, shaders, output_format),
            history: None,
            temporal: TemporalState::default(),
            timer: None,
            timing: false,
            view: FrameView::Final,
            frame_views: FrameViewsPass::new(device, shaders, output_format, read_samples),
            read_samples: read_samples > 1,
        }
    }

    /// Shows `view` in the frames that follow: the finished picture, or
    /// one of its passes (see [`FrameView`]).
    pub fn set_view(&mut self, view: FrameView) {
        self.view = view;
    }

    /// The scene's pipelines drawing the view shown: built again where the
    /// view changed what the scene shader writes (a pass's value, or the
    /// lit colour).
    fn ensure_view_pipelines(&mut self, gpu: &Gpu) {
        let codes = self.view.codes();
        if self.pipelines.view == codes {
            return;
        }
        let wanted = match self.other_pipelines.take() {
            Some(other) if other.view == codes => other,
            _ => Pipelines::new(
                &gpu.device,
                &self.shaders,
                &self.layouts,
                &self.settings,
                self.output_format,
                codes,
            ),
        };
        self.other_pipelines = Some(std::mem::replace(&mut self.pipelines, wanted));
    }

    /// What the frames show.
    pub fn view(&self) -> FrameView {
        self.view
    }

    /// The caption of the view shown, for a frame of `view` seen by
    /// `camera`: its name, what its colours mean, and why it is empty
    /// where a flag or the level turned its pass off.
    pub fn caption(&self, view: &SceneView, camera: &Camera) -> String {
        let facts = crate::frame_view::FrameFacts::new(
            if self.read_samples {
                self.settings.msaa
            } else {
                1
            },
            self.settings.shadows,
            self.settings.temporal,
            &view.light,
            farthest_from(camera.eye, view.room_size),
        );
        self.view.caption(&facts)
    }

    /// Times each frame's passes on the GPU from now on (where the adapter
    /// has timestamp queries), or stops. Off unless asked: a frame nobody
    /// profiles writes no timestamps.
    pub fn set_gpu_timing(&mut self, gpu: &Gpu, on: bool) {
        if on && self.timer.is_none() {
            self.timer = GpuTimer::new(&gpu.device, &gpu.queue);
        }
        self.timing = on;
    }

    /// Draws the white arrow cursor with its tip at `pixel` (from the
    /// frame's top left) in the frames that follow, or no cursor.
    pub fn set_cursor(&mut self, pixel: Option<glam::Vec2>) {
        self.cursor.at = pixel;
    }

    /// Gives the tumblers a coarse mesh to be drawn with where the settings
    /// ask for it (see [`crate::coarse_tumbler_mesh`]).
    pub fn set_coarse_tumbler(&mut self, gpu: &Gpu, mesh: &MeshData) {
        self.coarse_tumbler = Some(GpuMesh::upload(&gpu.device, "coarse tumbler", mesh));
    }

    /// The tumbler mesh the frames draw.
    fn tumbler_mesh(&self) -> &GpuMesh {
        match &self.coarse_tumbler {
            Some(coarse) if self.settings.coarse_tumblers => coarse,
            _ => &self.tumbler,
        }
    }

    /// How it draws now.
    pub fn settings(&self) -> RenderSettings {
        self.settings
    }

    /// Lights the scene at `share` of the output's width and height from
    /// the next frame on (the window's scale, see [`crate::DynamicScale`]);
    /// the targets are made anew when the share changes.
    pub fn set_resolution(&mut self, share: f32) {
        let share = share.clamp(0.05, 1.0);
        if share != self.settings.resolution {
            self.settings.resolution = share;
            self.targets = None;
        }
    }

    /// The colour format it draws into.
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
        let gpu_times = self.timer.as_mut().and_then(|t| t.collect(&gpu.device));
        let timed = self.timing && self.timer.as_ref().is_some_and(GpuTimer::free);
        self.ensure_targets(gpu, width, height);
        self.ensure_view_pipelines(gpu);
        std::mem::swap(&mut self.instances.items, &mut self.last_instances);
        let ranges = instances::fill_scene(&mut self.instances.items, view);
        instances::fill_previous(
            &mut self.previous_models.items,
            &self.instances.items,
            &ranges,
            &self.last_instances,
            &self.last_ranges,
        );
        self.last_ranges = ranges.clone();
        self.instances.upload(gpu);
        self.previous_models.upload(gpu);
        self.gpu_balls = view.gpu_balls.clone();
        if self.gpu_balls.is_some() {
            self.balls.items.clear();
        } else {
            // Last frame's balls, already uploaded, become where they were.
            std::mem::swap(&mut self.balls, &mut self.previous_balls);
            instances::fill_balls(&mut self.balls.items, view);
            self.balls.upload(gpu);
        }
        let faces = shadow::face_view_projections(view.light.position);
        self.shadow_cube
            .update(&gpu.queue, &faces, view.light.position);
        let probes = if view.light.indirect {
            let fireball = view.fireball_light.filter(|_| view.light.fireball_light);
            let lights: Vec<_> = std::iter::once(view.light.point())
                .chain(fireball)
                .collect();
            let surface_light = lighting::bounce(view, &lights);
            self.irradiance
                .update(&gpu.queue, view.room_size, &surface_light)
        } else {
            UVec3::ZERO
        };
        let scene_size = self
            .targets
            .as_ref()
            .map_or((width, height), |t| t.scene_size);
        let projections = self.projections(camera, (width, height), scene_size);
        let globals = self.globals(view, camera, &projections, (probes, scene_size));
        gpu.queue
            .write_buffer(&self.globals, 0, bytemuck::bytes_of(&globals));

        let mut encoder = gpu
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("frame"),
            });
        let mut draw_calls = 0;
        let mut shadow_faces = 0;
        if self.settings.shadows {
            // Balls on the GPU are not listed face by face: that would read
            // them back.
            let culled = (self.settings.cull_shadow_faces && self.gpu_balls.is_none())
                .then(|| self.sort_shadow_casters(gpu, view, &ranges));
            let stale = self.stale_faces(view.light.position, culled.as_ref());
            let (calls, faces) =
                self.shadow_pass(&mut encoder, &ranges, culled.as_ref(), stale, timed);
            draw_calls += calls;
            shadow_faces = faces;
        }
        self.marks
            .upload(gpu, &view.debug_marks, camera, (width, height), scene_size);
        let targets = self
            .targets
            .as_ref()
            .ok_or_else(|| RenderError::Readback("no render targets".into()))?;
        draw_calls += self.scene_pass(&mut encoder, targets, &ranges, timed);
        if view.light.occlusion {
            draw_calls +=
                self.occlusion
                    .record(&gpu.queue, &mut encoder, &targets.occlusion, camera);
        }
        if let Some(bloom) = &view.light.bloom {
            draw_calls += targets
                .bloom
                .record(&gpu.queue, &mut encoder, &self.bloom, bloom);
        }
        let glow = view
            .light
            .bloom
            .map_or(0.0, |b| b.strength / targets.bloom.levels as f32);
        let params = [
            self.settings.exposure,
            glow,
            flag(view.light.occlusion),
            flag(targets.bloom.levels > 1),
            0.0,
            flag(self.output_format.is_srgb()),
            0.0,
            0.0,
        ];
        gpu.queue
            .write_buffer(&self.tonemap_params, 0, bytemuck::cast_slice(&params));
        let mut history = self.history.take();
        let resolve = history.as_mut().map(|h| (h, projections.sample_offset));
        draw_calls += self.tonemap_pass(gpu, &mut encoder, targets, output, resolve, timed);
        if self.view.drawn() == Drawn::Extra {
            draw_calls +=
                self.extra_view(gpu, &mut encoder, targets, output, history.as_ref(), view);
        }
        targets.keep_geometry(&mut encoder);
        self.history = history;
        self.keep_gpu_balls(gpu, &mut encoder);
        // Kept off the temporal path too: the motion view reads it.
        self.temporal.previous_view_proj = Some(projections.unjittered);
        if self.settings.temporal {
            self.temporal.frame += 1;
        }
        let mut stamps = StampSlots::default();
        if timed && let Some(timer) = &mut self.timer {
            stamps = timer.resolve(&mut encoder);
        }
        let commands = encoder.finish();
        let cpu_time = start.elapsed();
        let submitting = Instant::now();
        gpu.queue.submit([commands]);
        let submit = submitting.elapsed();
        if timed && let Some(timer) = &mut self.timer {
            timer.submitted();
        }
        Ok(FrameStats {
            draw_calls,
            shadow_faces,
            cpu_time,
            submit,
            gpu: gpu_times,
            stamps,
        })
    }

    /// `camera`'s view-projections this frame, for an output of `size` lit
    /// at `scene_size`: jittered on the temporal path.
    fn projections(
        &self,
        camera: &Camera,
        size: (u32, u32),
        scene_size: (u32, u32),
    ) -> Projections {
        let unjittered = camera.view_projection(size.0 as f32 / size.1 as f32);
        if !self.settings.temporal {
            return Projections {
                drawn: unjittered,
                unjittered,
                previous: self.temporal.previous_view_proj.unwrap_or(unjittered),
                sample_offset: glam::Vec2::ZERO,
            };
        }
        let lit = glam::UVec2::new(scene_size.0, scene_size.1).as_vec2();
        let out = glam::UVec2::new(size.0, size.1).as_vec2();
        let offset = temporal::sample_offset(self.temporal.frame, lit, out);
        Projections {
            drawn: temporal::jittered(unjittered, offset, lit),
            unjittered,
            previous: self.temporal.previous_view_proj.unwrap_or(unjittered),
            sample_offset: offset,
        }
    }

    /// On the temporal path, copies the GPU engine's balls as this frame
    /// drew them, for the next frame's motion.
    fn keep_gpu_balls(&mut self, gpu: &Gpu, encoder: &mut wgpu::CommandEncoder) {
        let Some(now) = self.gpu_balls.as_ref().filter(|_| self.settings.temporal) else {
            return;
        };
        let bytes = u64::from(now.count) * std::mem::size_of::<BallInstance>() as u64;
        if bytes == 0 {
            return;
        }
        let kept = match self.previous_gpu_balls.take() {
            Some(kept) if kept.buffer.size() >= bytes => kept.buffer,
            _ => gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("gpu balls before"),
                size: bytes,
                usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
        };
        encoder.copy_buffer_to_buffer(&now.buffer, 0, &kept, 0, bytes);
        self.previous_gpu_balls = Some(crate::view::GpuBallBuffer {
            buffer: kept,
            count: now.count,
        });
    }

    /// The scene shader's globals for `view` seen by `camera` through
    /// `projections`, with the irradiance volume's `probes` along each axis
    /// (none: no bounce).
    fn globals(
        &self,
        view: &SceneView,
        camera: &Camera,
        projections: &Projections,
        (probes, scene_size): (UVec3, (u32, u32)),
    ) -> Globals {
        let light = &view.light;
        let ceiling = light.point();
        let fireball = view.fireball_light.filter(|_| light.fireball_light);
        let half = view.room_size * glam::Vec3::new(0.5, 1.0, 0.5);
        Globals {
            view_proj: projections.drawn.to_cols_array_2d(),
            camera_pos: camera.eye.extend(1.0).to_array(),
            light_pos: light.position.extend(1.0).to_array(),
            light_color: light.color.extend(light.ambient).to_array(),
            shadow: [
                flag(self.settings.shadows),
                1.0 / self.shadow_cube.size as f32,
                SHADOW_DEPTH_BIAS,
                0.0,
            ],
            light_view_proj: shadow::face_view_projections(light.position)
                .map(|m| m.to_cols_array_2d()),
            light_falloff: falloff(ceiling),
            fireball_pos: fireball.map_or([0.0; 4], |f| f.position.extend(1.0).to_array()),
            fireball_color: fireball.map_or([0.0; 4], |f| f.color.extend(0.0).to_array()),
            fireball_falloff: fireball.map_or([1.0, 0.0, 0.0, 0.0], falloff),
            room: half.extend(flag(light.indirect)).to_array(),
            irradiance_probes: probes.as_vec3().extend(MAX_PROBES as f32).to_array(),
            motion_view_proj: projections.unjittered.to_cols_array_2d(),
            previous_view_proj: projections.previous.to_cols_array_2d(),
            frame_view: [
                0.0,
                0.0,
                farthest_from(camera.eye, view.room_size),
                crate::frame_view::MOTION_FULL_PIXELS,
            ],
            frame_size: [scene_size.0 as f32, scene_size.1 as f32, 0.0, 0.0],
        }
    }

    /// Draws the view of the extra pass over `output`: the shadow cube, the
    /// multisampled edges or the history, or black where its pass is off.
    fn extra_view(
        &self,
        gpu: &Gpu,
        encoder: &mut wgpu::CommandEncoder,
        targets: &Targets,
        output: &wgpu::TextureView,
        history: Option<&History>,
        view: &SceneView,
    ) -> u32 {
        let source = match self.view {
            FrameView::ShadowCube => self
                .settings
                .shadows
                .then_some(ViewSource::ShadowCube(&self.shadow_cube.array_view)),
            FrameView::MsaaEdges => targets
                .geometry_msaa
                .as_ref()
                .filter(|_| self.read_samples)
                .map(ViewSource::Samples),
            _ => history.map(|h| ViewSource::History(h.latest())),
        };
        self.frame_views.draw(
            &gpu.device,
            &gpu.queue,
            encoder,
            output,
            source,
            ((targets.width, targets.height), targets.scene_size),
            (
                self.shadow_cube.size,
                farthest_from(view.light.position, view.room_size),
            ),
        )
    }

    /// Where this frame's balls are drawn from: the GPU engine's buffer, or
    /// the renderer's own.
    fn ball_source(&self) -> (&wgpu::Buffer, std::ops::Range<u32>) {
        match &self.gpu_balls {
            Some(gpu) => (&gpu.buffer, 0..gpu.count),
            None => (&self.balls.buffer, self.balls.range()),
        }
    }

    /// Where this frame's balls were the frame before: the last frame's,
    /// where they were as many; else where they are (no motion).
    fn balls_before(&self) -> &wgpu::Buffer {
        match &self.gpu_balls {
            Some(now) => self
                .previous_gpu_balls
                .as_ref()
                .filter(|before| before.count == now.count)
                .map_or(&now.buffer, |before| &before.buffer),
            None if self.previous_balls.items.len() == self.balls.items.len() => {
                &self.previous_balls.buffer
            }
            None => &self.balls.buffer,
        }
    }

    /// Lists the balls and tumblers face by face, each in the faces it can
    /// cast into (see [`shadow::faces_reached`]), and uploads the lists.
    fn sort_shadow_casters(&mut self, gpu: &Gpu, view: &SceneView, ranges: &Ranges) -> FaceRanges {
        let light = view.light.position;
        let ball_items = &self.balls.items;
        let balls = shadow::sort_into_faces(
            ball_items,
            |k| ball_items[k].sphere(),
            light,
            &mut self.faces_reached,
            &mut self.shadow_balls.items,
        );
        let (centre, radius) = self.tumbler_bounds;
        let tumbler_instances =
            &self.instances.items[ranges.tumblers.start as usize..ranges.tumblers.end as usize];
        let tumblers = shadow::sort_into_faces(
            tumbler_instances,
            |k| {
                let t = &view.tumblers[k];
                (t.model().transform_point3(centre), radius * t.scale)
            },
            light,
            &mut self.faces_reached,
            &mut self.shadow_tumblers.items,
        );
        self.shadow_balls.upload(gpu);
        self.shadow_tumblers.upload(gpu);
        FaceRanges { balls, tumblers }
    }

    /// The shadow faces to draw: where the casters are listed face by face
    /// (`culled`), those whose light or casters moved since they were
    /// drawn; else every face.
    fn stale_faces(&mut self, light: glam::Vec3, culled: Option<&FaceRanges>) -> [bool; 6] {
        let Some(culled) = culled else {
            self.drawn_faces.forget();
            return [true; 6];
        };
        let (balls, tumblers) = (&self.shadow_balls.items, &self.shadow_tumblers.items);
        self.drawn_faces.stale(light, |face| {
            let range = |r: &std::ops::Range<u32>| r.start as usize..r.end as usize;
            let ball_places = balls[range(&culled.balls[face])]
                .iter()
                .flat_map(|b| b.shadow_place());
            let tumbler_places = tumblers[range(&culled.tumblers[face])]
                .iter()
                .flat_map(|t| t.shadow_place().into_iter().flatten());
            ball_places.chain(tumbler_places)
        })
    }

    /// The ceiling light's shadow faces that are `stale`: the balls and
    /// the tumblers (the room's walls cast no shadow inside it), each only
    /// in the faces `culled` lists it in, or with none, every one in every
    /// face. Returns the draw calls and the faces drawn.
    fn shadow_pass(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        ranges: &Ranges,
        culled: Option<&FaceRanges>,
        stale: [bool; 6],
        timed: bool,
    ) -> (u32, u32) {
        let (balls, tumblers) = match culled {
            Some(_) => (&self.shadow_balls.buffer, &self.shadow_tumblers.buffer),
            None => (self.ball_source().0, &self.instances.buffer),
        };
        let first = stale.iter().position(|&s| s);
        let last = stale.iter().rposition(|&s| s);
        let mut draw_calls = 0;
        for face in (0..6).filter(|&face| stale[face]) {
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
                // The first drawn face's start and the last one's end.
                timestamp_writes: self
                    .timer
                    .as_ref()
                    .filter(|_| timed && (Some(face) == first || Some(face) == last))
                    .map(|t| {
                        t.writes(
                            (Some(face) == first).then_some(0),
                            (Some(face) == last).then_some(1),
                        )
                    }),
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_bind_group(0, &self.shadow_cube.face_bind_groups[face], &[]);
            pass.set_vertex_buffer(1, balls.slice(..));
            pass.set_pipeline(&self.pipelines.ball_shadow);
            let ball_range = culled.map_or(self.ball_source().1, |c| c.balls[face].clone());
            draw_calls += draw(&mut pass, &self.quad, ball_range);
            pass.set_vertex_buffer(1, tumblers.slice(..));
            pass.set_pipeline(&self.pipelines.shadow);
            let tumbler_range =
                culled.map_or(ranges.tumblers.clone(), |c| c.tumblers[face].clone());
            draw_calls += draw(&mut pass, self.tumbler_mesh(), tumbler_range);
        }
        (draw_calls, stale.iter().filter(|&&s| s).count() as u32)
    }

    /// The lit scene into the HDR target, and the surfaces' normals and
    /// distances for the occlusion and the debug marks, resolved there
    /// from their samples.
    fn scene_pass(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        targets: &Targets,
        ranges: &Ranges,
        timed: bool,
    ) -> u32 {
        let mut attachments = vec![
            attachment(&targets.hdr, targets.msaa.as_ref(), BACKGROUND),
            // Distance 0: nothing there.
            attachment(
                &targets.geometry,
                targets.geometry_msaa.as_ref(),
                wgpu::Color::TRANSPARENT,
            ),
        ];
        if let Some(motion) = &targets.motion {
            // No motion where nothing is drawn.
            attachments.push(attachment(motion, None, wgpu::Color::TRANSPARENT));
        }
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("scene"),
            color_attachments: &attachments,
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &targets.depth,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(1.0),
                    store: wgpu::StoreOp::Discard,
                }),
                stencil_ops: None,
            }),
            timestamp_writes: self
                .timer
                .as_ref()
                .filter(|_| timed)
                .map(|t| t.writes(Some(2), Some(3))),
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_bind_group(0, &self.scene_bind_group, &[]);
        // Lit and opaque first (the balls from their own buffer) ...
        let mut draw_calls = 0;
        pass.set_vertex_buffer(1, self.instances.buffer.slice(..));
        pass.set_vertex_buffer(2, self.previous_models.buffer.slice(..));
        pass.set_pipeline(&self.pipelines.lit);
        draw_calls += draw(&mut pass, &self.quad, ranges.room.clone());
        draw_calls += draw(&mut pass, self.tumbler_mesh(), ranges.tumblers.clone());
        let (balls, ball_range) = self.ball_source();
        pass.set_vertex_buffer(1, balls.slice(..));
        pass.set_vertex_buffer(2, self.balls_before().slice(..));
        pass.set_pipeline(&self.pipelines.ball);
        draw_calls += draw(&mut pass, &self.quad, ball_range);
        pass.set_vertex_buffer(1, self.instances.buffer.slice(..));
        pass.set_vertex_buffer(2, self.previous_models.buffer.slice(..));
        // ... then what glows and is not lit (the bulb, the fireball's heart) ...
        pass.set_pipeline(&self.pipelines.emissive);
        draw_calls += draw(&mut pass, &self.sphere, ranges.lamps.clone());
        // The views show the opaque surfaces' passes alone.
        if self.view != FrameView::Final {
            return draw_calls;
        }
        draw_calls + self.particles(&mut pass, ranges)
    }

    /// The see-through particles and the fireball, last in the scene pass:
    /// they blend over what is behind them.
    fn particles(&self, pass: &mut wgpu::RenderPass, ranges: &Ranges) -> u32 {
        pass.set_pipeline(&self.pipelines.glow);
        draw(pass, &self.cube, ranges.cubes.clone())
            + draw(pass, &self.sphere, ranges.shells.clone())
    }

    /// The HDR frame, darkened by the occlusion and glowing, tone-mapped
    /// into `output`, with the debug marks and the cursor on top. Lit at a
    /// lower resolution than the output, it is tone-mapped at that
    /// resolution and then spread over the output with one bilinear read a
    /// pixel: tone mapping reads seven texels a pixel, which at the
    /// output's resolution cost a software renderer more than the scene.
    /// On the temporal path, the frame tone-mapped at the lit resolution is
    /// resolved into the `history` with this frame's sample offset, and
    /// sharpened into the output.
    fn tonemap_pass(
        &self,
        gpu: &Gpu,
        encoder: &mut wgpu::CommandEncoder,
        targets: &Targets,
        output: &wgpu::TextureView,
        history: Option<(&mut History, glam::Vec2)>,
        timed: bool,
    ) -> u32 {
        let stamps = |start: Option<u32>, end: Option<u32>| {
            self.timer
                .as_ref()
                .filter(|_| timed)
                .map(|t| t.writes(start, end))
        };
        let mut draw_calls = 0;
        let sharpen;
        let (last, last_stamps) = match &targets.composed {
            Some((composed, upscale)) => {
                let mut pass = screen_pass(encoder, composed, stamps(Some(4), None));
                pass.set_pipeline(&self.pipelines.tonemap);
                pass.set_bind_group(0, &targets.tonemap_bind_group, &[]);
                pass.draw(0..3, 0..1);
                drop(pass);
                draw_calls += 1;
                let temporal = (
                    &targets.motion,
                    &targets.geometry_before,
                    &targets.neighbourhood,
                );
                // The views of one pass are shown as they are, never
                // blended with frames before (the history view shows the
                // finished frame's).
                let resolving = matches!(self.view, FrameView::Final | FrameView::History);
                match (history.filter(|_| resolving), temporal) {
                    (
                        Some((history, sample_offset)),
                        (Some(motion), Some((_, geometry_before)), Some(neighbourhood)),
                    ) => {
                        let inputs = ResolveInputs {
                            composed,
                            motion,
                            geometry: &targets.geometry,
                            geometry_before,
                            neighbourhood,
                            sampler: &self.smooth_sampler,
                            sample_offset,
                        };
                        sharpen = self.taa.resolve(
                            &gpu.device,
                            &gpu.queue,
                            encoder,
                            history,
                            &inputs,
                            None,
                        );
                        draw_calls += 2;
                        ((&self.taa.sharpen, &sharpen), stamps(None, Some(5)))
                    }
                    _ => ((&self.pipelines.upscale, upscale), stamps(None, Some(5))),
                }
            }
            None => (
                (&self.pipelines.tonemap, &targets.tonemap_bind_group),
                stamps(Some(4), Some(5)),
            ),
        };
        let mut pass = screen_pass(encoder, output, last_stamps);
        pass.set_pipeline(last.0);
        pass.set_bind_group(0, last.1, &[]);
        pass.draw(0..3, 0..1);
        // The debug views over the finished frame, the cursor over them.
        draw_calls
            + 1
            + self.marks.draw(&mut pass, &targets.marks_bind_group)
            + self
                .cursor
                .draw(&gpu.queue, &mut pass, targets.width, targets.height)
    }

    fn ensure_targets(&mut self, gpu: &Gpu, width: u32, height: u32) {
        // The history is the output's: a new scale keeps it.
        if self.settings.temporal
            && self
                .history
                .as_ref()
                .is_none_or(|h| h.size() != (width, height))
        {
            self.history = Some(History::new(&gpu.device, (width, height)));
        }
        if self
            .targets
            .as_ref()
            .is_some_and(|t| t.width == width && t.height == height)
        {
            return;
        }
        // At least a pixel each way, however small the share.
        let scaled =
            |side: u32| ((side as f32 * self.settings.resolution).round() as u32).clamp(1, side);
        let scene_size = (scaled(width), scaled(height));
        let kit = TargetKit {
            samples: self.settings.msaa,
            read_samples: self.read_samples,
            temporal: self.settings.temporal,
            tonemap_layout: &self.tonemap_layout,
            upscale_layout: &self.upscale_layout,
            output_format: self.output_format,
            tonemap_params: &self.tonemap_params,
            smooth_sampler: &self.smooth_sampler,
            bloom: &self.bloom,
            occlusion: &self.occlusion,
            marks: &self.marks,
        };
        self.targets = Some(Targets::new(&gpu.device, (width, height), scene_size, &kit));
    }
}

/// How far the room's farthest corner (of a room of `room_size` standing on
/// the floor, centred on the origin) lies from `point`.
fn farthest_from(point: glam::Vec3, room_size: glam::Vec3) -> f32 {
    let half = room_size * glam::Vec3::new(0.5, 1.0, 0.5);
    let mut farthest: f32 = 0.0;
    for corner in 0..8 {
        let x = if corner & 1 == 0 { -half.x } else { half.x };
        let y = if corner & 2 == 0 { 0.0 } else { half.y };
        let z = if corner & 4 == 0 { -half.z } else { half.z };
        farthest = farthest.max(point.distance(glam::Vec3::new(x, y, z)));
    }
    farthest
}

/// The irradiance volume (see irradiance.rs) and its texture.
struct Irradiance {
    texture: wgpu::Texture,
    /// The probes of the room last drawn.
    volume: Option<IrradianceVolume>,
    /// Reused for each frame's upload.
    texels: Vec<[u16; 4]>,
}

impl Irradiance {
    /// Gathers the light the room of `room_size` bounces from its surfaces'
    /// `surface_light` at each probe into the texture, working the probes
    /// out again if the room changed; returns the probes along each axis.
    fn update(
        &mut self,
        queue: &wgpu::Queue,
        room_size: glam::Vec3,
        surface_light: &[glam::Vec3; 6],
    ) -> UVec3 {
        let volume = match &self.volume {
            Some(v) if v.room_size() == room_size => v,
            _ => self.volume.insert(IrradianceVolume::new(room_size)),
        };
        self.texels.clear();
        self.texels
            .extend(volume.gather(surface_light).map(|light| {
                let [r, g, b] = light.to_array().map(|c| half::f16::from_f32(c).to_bits());
                [r, g, b, half::f16::ONE.to_bits()]
            }));
        let counts = volume.counts();
        let slab = counts.element_product() as usize;
        for (k, texels) in self.texels.chunks_exact(slab).enumerate() {
            queue.write_texture(
                wgpu::TexelCopyTextureInfo {
                    texture: &self.texture,
                    mip_level: 0,
                    origin: wgpu::Origin3d {
                        x: 0,
                        y: 0,
                        z: k as u32 * MAX_PROBES,
                    },
                    aspect: wgpu::TextureAspect::All,
                },
                bytemuck::cast_slice(texels),
                wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(counts.x * std::mem::size_of::<[u16; 4]>() as u32),
                    rows_per_image: Some(counts.y),
                },
                wgpu::Extent3d {
                    width: counts.x,
                    height: counts.y,
                    depth_or_array_layers: counts.z,
                },
            );
        }
        debug_assert_eq!(self.texels.len(), slab * DIRECTIONS.len());
        counts
    }
}

/// A pass over the whole of `target`, cleared first.
pub(super) fn screen_pass<'a>(
    encoder: &'a mut wgpu::CommandEncoder,
    target: &'a wgpu::TextureView,
    timestamp_writes: Option<wgpu::RenderPassTimestampWrites<'a>>,
) -> wgpu::RenderPass<'a> {
    encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some("tonemap"),
        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
            view: target,
            depth_slice: None,
            resolve_target: None,
            ops: wgpu::Operations {
                load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                store: wgpu::StoreOp::Store,
            },
        })],
        depth_stencil_attachment: None,
        timestamp_writes,
        occlusion_query_set: None,
        multiview_mask: None,
    })
}

/// A colour attachment that is drawn into `multi` and resolved into
/// `single`, or drawn into `single` when there are no samples to resolve.
fn attachment<'a>(
    single: &'a wgpu::TextureView,
    multi: Option<&'a wgpu::TextureView>,
    clear: wgpu::Color,
) -> Option<wgpu::RenderPassColorAttachment<'a>> {
    Some(wgpu::RenderPassColorAttachment {
        view: multi.unwrap_or(single),
        depth_slice: None,
        resolve_target: multi.map(|_| single),
        ops: wgpu::Operations {
            load: wgpu::LoadOp::Clear(clear),
            store: wgpu::StoreOp::Store,
        },
    })
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
