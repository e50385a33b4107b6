//! Frames drawn off-screen for `render`, `record`, `replay` and Python:
//! the renderer for a scene, the camera the options choose, a tumbler mesh
//! read from an OBJ file.

use std::path::{Path, PathBuf};

use anyhow::Context;
use glam::Vec3;
use rolypoly_physics::WorldConfig;
use rolypoly_render::{
    Camera, DebugViews, FrameView, LightConfig, MeshData, Quality, QualityChoice, RenderSettings,
    Snapshot,
};

use rolypoly_render::Gpu;
use rolypoly_render::shaders::ShaderSet;

use crate::simulation::Simulation;

/// How frames are drawn: what `rolypoly render`'s flags and Python's
/// arguments choose. None takes the scene's or the quality level's.
#[derive(Clone, Debug, Default)]
pub struct FrameOptions {
    /// How finely: high, medium, low or auto (drawn as high off-screen).
    pub quality: Option<QualityChoice>,
    /// Multisample anti-aliasing: 4 or 1.
    pub msaa: Option<u32>,
    /// The camera's eye and the point it looks at; None: the overview.
    pub camera: Option<[f32; 6]>,
    /// Drawn without the point light's shadows.
    pub no_shadows: bool,
    /// Each shadow face's size in texels.
    pub shadow_size: Option<u32>,
    /// The shadow filter's taps along each side.
    pub shadow_taps: Option<u32>,
    /// An OBJ file to draw the tumblers with.
    pub tumbler_obj: Option<PathBuf>,
    /// A folder of the renderer's shaders to draw with instead of the
    /// shipped ones (`shaders --export` writes one).
    pub shaders: Option<PathBuf>,
    /// The debug views drawn over every frame.
    pub show: Option<DebugViews>,
    /// Share of the width and height the scene is lit at (default: the
    /// quality level's).
    pub scale: Option<f32>,
    /// Temporal anti-aliasing with upsampling (see
    /// [`rolypoly_render::jitter`]): every frame drawn adds to the next.
    pub temporal: bool,
    /// What the frames show: the finished picture (none) or one of its
    /// passes.
    pub view: Option<FrameView>,
}

/// Frames a second of the frames drawn before a temporal picture's moment,
/// for its history: a display's rate.
pub const HISTORY_FPS: f64 = 60.0;

/// Something drawn over every frame before it is read back: the program
/// draws the debug views' legend so.
pub trait Overlay: Send {
    /// Draws over the frame `target` of `size` that shows `views`.
    fn draw(&mut self, gpu: &Gpu, target: &wgpu::TextureView, size: [u32; 2], views: &DebugViews);
}

/// A device, its queue and adapter: where the GPU engine runs.
#[derive(Clone)]
pub struct Device {
    /// The device.
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
    /// Its adapter.
    pub adapter: wgpu::Adapter,
}

/// What draws the frames of `render`, `record`, `replay` and Python: the off-screen renderer
/// for the scene, and the camera.
pub struct Frames {
    snapshot: Snapshot,
    camera: Camera,
    shadows: bool,
    level: Quality,
    /// The debug views drawn over every frame.
    debug: DebugViews,
    /// What is drawn over every frame (the program's legend), if anything.
    overlay: Option<Box<dyn Overlay>>,
}

impl Frames {
    /// Frames of `width` x `height` of the scene `config` drawn as `args`
    /// say, at the scene's `quality` unless they say otherwise (auto is
    /// high here: a picture does not depend on the machine).
    pub fn new(
        config: &WorldConfig,
        quality: QualityChoice,
        args: &FrameOptions,
        (width, height): (u32, u32),
    ) -> anyhow::Result<Frames> {
        let mesh = args.tumbler_obj.as_deref().map(read_obj).transpose()?;
        let level = args.quality.unwrap_or(quality).first();
        let drawn = level.settings();
        let settings = RenderSettings {
            msaa: args.msaa.unwrap_or(drawn.msaa),
            shadow_size: args.shadow_size.unwrap_or(drawn.shadow_size),
            shadow_taps: args.shadow_taps.unwrap_or(drawn.shadow_taps),
            shadows: !args.no_shadows,
            resolution: args.scale.unwrap_or(drawn.resolution),
            temporal: args.temporal,
            ..drawn
        };
        // A folder's shaders are checked before the GPU is opened.
        let shaders = match &args.shaders {
            Some(dir) => ShaderSet::load(dir)?,
            None => ShaderSet::shipped(),
        };
        let mut snapshot = Snapshot::drawn_with(
            Gpu::headless()?,
            config,
            settings,
            (width, height),
            mesh,
            &shaders,
        )?;
        snapshot.renderer.set_view(args.view.unwrap_or_default());
        let camera = chosen_camera(args.camera, config);
        Ok(Frames {
            snapshot,
            camera,
            shadows: settings.shadows,
            level,
            debug: args.show.unwrap_or_default(),
            overlay: None,
        })
    }

    /// Whether each frame adds to a history that the next frame draws on
    /// (the temporal path).
    pub fn temporal(&self) -> bool {
        self.snapshot.renderer.settings().temporal
    }

    /// The frame of `sim` at the moment `steps` steps from its start, which
    /// it is run to, drawn after the frames before it that it reads: on the
    /// temporal path those of the
    /// [`HISTORY_FRAMES`](rolypoly_render::HISTORY_FRAMES) moments before
    /// it, [`HISTORY_FPS`] a second apart (or from the start, where the
    /// moment comes sooner: frames of the first moment, the jitter moving),
    /// so that the picture holds its history; in the motion view the one
    /// moment a frame before, so that it shows what moved since.
    pub fn draw_at(
        &mut self,
        sim: &mut Simulation,
        steps: u64,
        light: &LightConfig,
    ) -> anyhow::Result<image::RgbaImage> {
        let before = if self.temporal() {
            rolypoly_render::HISTORY_FRAMES
        } else if self.snapshot.renderer.view() == FrameView::Motion {
            1
        } else {
            0
        };
        let apart = crate::steps_for(1.0 / HISTORY_FPS, sim.world.config().solver.dt).max(1);
        let camera = self.camera;
        for k in (1..=before).rev() {
            let at = steps.saturating_sub(u64::from(k) * apart);
            sim.ticks(at.saturating_sub(sim.world.step_count()));
            sim.check_gpu()?;
            self.render(sim, light, &camera)?;
        }
        sim.ticks(steps.saturating_sub(sim.world.step_count()));
        sim.check_gpu()?;
        self.draw(sim, light)
    }

    /// The GPU the frames are drawn on.
    pub fn gpu(&self) -> &Gpu {
        &self.snapshot.gpu
    }

    /// Draws `overlay` over every frame from now on.
    pub fn set_overlay(&mut self, overlay: Box<dyn Overlay>) {
        self.overlay = Some(overlay);
    }

    /// The frame of `sim` now, lit by `light`.
    pub fn draw(
        &mut self,
        sim: &Simulation,
        light: &LightConfig,
    ) -> anyhow::Result<image::RgbaImage> {
        let camera = self.camera;
        self.draw_from(sim, light, &camera)
    }

    /// The camera the flags chose: `--camera`, or the overview.
    pub fn camera(&self) -> Camera {
        self.camera
    }

    /// The frame of `sim` now, lit by `light`, seen by `camera`.
    pub fn draw_from(
        &mut self,
        sim: &Simulation,
        light: &LightConfig,
        camera: &Camera,
    ) -> anyhow::Result<image::RgbaImage> {
        let what = format!("the frame at t = {:.3} s", sim.world.time());
        self.render(sim, light, camera)?;
        let snap = &mut self.snapshot;
        if let Some(overlay) = &mut self.overlay {
            let size = [snap.target.width, snap.target.height];
            overlay.draw(&snap.gpu, snap.target.view(), size, &self.debug);
        }
        Ok(snap.target.read(&snap.gpu, &what)?)
    }

    /// Draws the frame of `sim` now without reading it back.
    fn render(
        &mut self,
        sim: &Simulation,
        light: &LightConfig,
        camera: &Camera,
    ) -> anyhow::Result<()> {
        let view = sim.view_showing(light, &self.debug);
        let snap = &mut self.snapshot;
        snap.target
            .render(&snap.gpu, &mut snap.renderer, &view, camera)?;
        Ok(())
    }

    /// What the frames show, and the caption that says so for a frame of
    /// `sim` lit by `light`.
    pub fn view_caption(&self, sim: &Simulation, light: &LightConfig) -> (FrameView, String) {
        let view = sim.view_showing(light, &self.debug);
        let renderer = &self.snapshot.renderer;
        (renderer.view(), renderer.caption(&view, &self.camera))
    }

    /// The device the frames are drawn with.
    pub fn device(&self) -> Device {
        let gpu = &self.snapshot.gpu;
        Device {
            device: gpu.device.clone(),
            queue: gpu.queue.clone(),
            adapter: gpu.adapter.clone(),
        }
    }

    /// Moves `sim`'s balls to the GPU engine, on the device these frames
    /// are drawn with: they are drawn from where it steps them.
    pub fn move_balls_to_gpu(&self, sim: &mut Simulation) -> anyhow::Result<()> {
        let gpu = &self.snapshot.gpu;
        sim.move_balls_to_gpu(&gpu.device, &gpu.queue, &gpu.adapter)?;
        Ok(())
    }

    /// How the frames are drawn, in words, and on what.
    pub fn describe(&self) -> String {
        let settings = self.snapshot.renderer.settings();
        let scale = if settings.resolution < 1.0 {
            format!(", lit at {:.2} of the size", settings.resolution)
        } else {
            String::new()
        };
        let temporal = if settings.temporal { ", temporal" } else { "" };
        format!(
            "quality {}, MSAA {}x{scale}{temporal}, shadows {}, on {}",
            self.level.name(),
            settings.msaa,
            if self.shadows { "on" } else { "off" },
            self.snapshot.gpu.describe()
        )
    }
}

/// Reads a tumbler mesh from an OBJ file.
pub fn read_obj(path: &Path) -> anyhow::Result<MeshData> {
    let text = std::fs::read_to_string(path)
        .with_context(|| format!("cannot read tumbler mesh `{}`", path.display()))?;
    Ok(rolypoly_render::from_obj(
        &text,
        &path.display().to_string(),
    )?)
}

/// The camera `--camera` gives (eye, then target), or the overview of the
/// room of `config`: what `render` and `record` draw from, and where
/// `sound` and `record` hear from.
pub fn chosen_camera(camera: Option<[f32; 6]>, config: &WorldConfig) -> Camera {
    let overview = Camera::overview(config.room.size.as_vec3());
    match camera {
        Some([ex, ey, ez, tx, ty, tz]) => Camera {
            eye: Vec3::new(ex, ey, ez),
            target: Vec3::new(tx, ty, tz),
            ..overview
        },
        None => overview,
    }
}
