//! Frames drawn off-screen for `render`, `record` and `replay`: the
//! renderer for a scene, the camera the flags choose, a tumbler mesh read
//! from an OBJ file.

use std::path::Path;

use anyhow::Context;
use glam::Vec3;
use rolypoly_physics::WorldConfig;
use rolypoly_render::{
    Camera, DebugViews, LightConfig, MeshData, Quality, QualityChoice, RenderSettings, Snapshot,
};

use crate::cli::FrameArgs;
use crate::legend::OffscreenLegend;
use crate::simulation::Simulation;

/// What draws the frames of `render`, `record` and `replay`: the off-screen renderer
/// for the scene, and the camera.
pub struct Frames {
    snapshot: Snapshot,
    camera: Camera,
    shadows: bool,
    level: Quality,
    /// The debug views drawn over every frame.
    debug: DebugViews,
    /// Their legend, drawn into every frame where asked.
    legend: Option<OffscreenLegend>,
}

impl Frames {
    /// Frames of `width` x `height` of the scene `config` drawn as `args`
    /// say, at the scene's `quality` unless they say otherwise (auto is
    /// high here: a picture does not depend on the machine).
    pub fn new(
        config: &WorldConfig,
        quality: QualityChoice,
        args: &FrameArgs,
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
            ..drawn
        };
        let snapshot = Snapshot::new(config, settings, width, height, mesh)?;
        let legend = args.legend.then(|| OffscreenLegend::new(&snapshot.gpu));
        let camera = chosen_camera(args.camera, config);
        Ok(Frames {
            snapshot,
            camera,
            shadows: settings.shadows,
            level,
            debug: args.show.unwrap_or_default(),
            legend,
        })
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
        let view = sim.view_showing(light, &self.debug);
        let snap = &mut self.snapshot;
        snap.target
            .render(&snap.gpu, &mut snap.renderer, &view, camera)?;
        if let Some(legend) = &mut self.legend {
            let size = [snap.target.width, snap.target.height];
            legend.draw(&snap.gpu, snap.target.view(), size, &self.debug);
        }
        Ok(snap.target.read(&snap.gpu, &what)?)
    }

    /// The device the frames are drawn with.
    pub fn device(&self) -> crate::sandbox::Device {
        let gpu = &self.snapshot.gpu;
        crate::sandbox::Device {
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
        format!(
            "quality {}, MSAA {}x, shadows {}, on {}",
            self.level.name(),
            self.snapshot.renderer.settings().msaa,
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
