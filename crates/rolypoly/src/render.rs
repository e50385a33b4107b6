//! `rolypoly render` and `rolypoly make-tumbler-obj`: frames and meshes
//! without a window.

use std::path::Path;

use anyhow::Context;
use glam::Vec3;
use rolypoly_fx::{Effects, EffectsConfig};
use rolypoly_physics::{World, WorldConfig};
use rolypoly_render::{Camera, LightConfig, MeshData, RenderSettings, SceneView, Snapshot};

use crate::cli::{FrameArgs, MakeTumblerObjArgs, RenderArgs, steps_for};

/// Simulates `world` and its effects to the requested time and writes that
/// frame.
pub fn render(
    world: &mut World,
    effects: EffectsConfig,
    light: &LightConfig,
    seed: u64,
    args: &RenderArgs,
) -> anyhow::Result<()> {
    if args.frame.fireball {
        world.launch_fireball(None);
    }
    let mut fx = Effects::new(effects, seed);
    advance(
        world,
        &mut fx,
        steps_for(args.time, world.config().solver.dt),
    );
    let mut frames = Frames::new(world.config(), &args.frame, args.size)?;
    let image = frames.draw(world, &fx, light)?;
    image
        .save_with_format(&args.out, image::ImageFormat::Png)
        .with_context(|| format!("cannot write `{}`", args.out.display()))?;
    let (width, height) = args.size;
    println!(
        "wrote {} ({width}x{height}, t = {:.3} s, {})",
        args.out.display(),
        world.time(),
        frames.describe()
    );
    Ok(())
}

/// What draws the frames of `render` and `record`: the off-screen renderer
/// for the scene, and the camera.
pub struct Frames {
    snapshot: Snapshot,
    camera: Camera,
    shadows: bool,
}

impl Frames {
    /// Frames of `width` x `height` of the scene `config` drawn as `args`
    /// say.
    pub fn new(
        config: &WorldConfig,
        args: &FrameArgs,
        (width, height): (u32, u32),
    ) -> anyhow::Result<Frames> {
        let mesh = args.tumbler_obj.as_deref().map(read_obj).transpose()?;
        let settings = RenderSettings {
            msaa: args.msaa,
            shadow_size: args.shadow_size,
            shadows: !args.no_shadows,
            ..RenderSettings::default()
        };
        let snapshot = Snapshot::new(config, settings, width, height, mesh)?;
        let overview = Camera::overview(config.room.size.as_vec3());
        let camera = match args.camera {
            Some([ex, ey, ez, tx, ty, tz]) => Camera {
                eye: Vec3::new(ex, ey, ez),
                target: Vec3::new(tx, ty, tz),
                ..overview
            },
            None => overview,
        };
        Ok(Frames {
            snapshot,
            camera,
            shadows: settings.shadows,
        })
    }

    /// The frame of `world` now, with its effects `fx`, lit by `light`.
    pub fn draw(
        &mut self,
        world: &World,
        fx: &Effects,
        light: &LightConfig,
    ) -> anyhow::Result<image::RgbaImage> {
        let view = SceneView::from_world(world, None)
            .with_effects(fx, world)
            .with_light(light);
        Ok(self.snapshot.capture(&view, &self.camera)?)
    }

    /// How the frames are drawn, in words, and on what.
    pub fn describe(&self) -> String {
        format!(
            "MSAA {}x, shadows {}, on {}",
            self.snapshot.renderer.settings().msaa,
            if self.shadows { "on" } else { "off" },
            self.snapshot.gpu.describe()
        )
    }
}

/// Steps the world and its effects together, as the window does at a fixed
/// time step.
pub fn advance(world: &mut World, fx: &mut Effects, steps: u64) {
    let mut events = Vec::new();
    for _ in 0..steps {
        fx.step_with(world, &mut events);
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

/// Writes the tumbler mesh made from the scene's spheres.
pub fn make_tumbler_obj(config: &WorldConfig, args: &MakeTumblerObjArgs) -> anyhow::Result<()> {
    let mesh = rolypoly_render::tumbler_mesh(&config.tumblers.spheres);
    let text = rolypoly_render::to_obj(&mesh, rolypoly_render::OBJ_HEADER);
    std::fs::write(&args.out, text)
        .with_context(|| format!("cannot write `{}`", args.out.display()))?;
    println!(
        "wrote {} ({} vertices, {} triangles)",
        args.out.display(),
        mesh.vertices.len(),
        mesh.indices.len() / 3
    );
    Ok(())
}
