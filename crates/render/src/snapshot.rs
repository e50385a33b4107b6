//! One-call off-screen frames of a physics world: what `rolypoly render`,
//! the golden tests and the benchmark use.

use crate::camera::Camera;
use crate::gpu::{Gpu, RenderError};
use crate::mesh::MeshData;
use crate::offscreen::{OFFSCREEN_FORMAT, OffscreenTarget};
use crate::renderer::{FrameStats, RenderSettings, Renderer};
use crate::shaders::ShaderSet;
use crate::view::SceneView;
use image::RgbaImage;
use rolypoly_physics::WorldConfig;

/// A GPU, a renderer and an off-screen target of one size.
pub struct Snapshot {
    /// The device it draws with.
    pub gpu: Gpu,
    /// The renderer.
    pub renderer: Renderer,
    /// The frame it draws into.
    pub target: OffscreenTarget,
}

impl Snapshot {
    /// Opens the GPU and prepares frames of `width` x `height` for scenes
    /// whose tumblers are shaped as in `config`. `tumbler_mesh` replaces the
    /// built-in mesh (for example one read from a user's OBJ file).
    pub fn new(
        config: &WorldConfig,
        settings: RenderSettings,
        width: u32,
        height: u32,
        tumbler_mesh: Option<MeshData>,
    ) -> Result<Snapshot, RenderError> {
        Snapshot::on(
            Gpu::headless()?,
            config,
            settings,
            width,
            height,
            tumbler_mesh,
        )
    }

    /// As [`Snapshot::new`], on a GPU already open.
    pub fn on(
        gpu: Gpu,
        config: &WorldConfig,
        settings: RenderSettings,
        width: u32,
        height: u32,
        tumbler_mesh: Option<MeshData>,
    ) -> Result<Snapshot, RenderError> {
        let shipped = ShaderSet::shipped();
        Snapshot::drawn_with(
            gpu,
            config,
            settings,
            (width, height),
            tumbler_mesh,
            &shipped,
        )
    }

    /// As [`Snapshot::on`], drawing with `shaders`.
    pub fn drawn_with(
        gpu: Gpu,
        config: &WorldConfig,
        settings: RenderSettings,
        (width, height): (u32, u32),
        tumbler_mesh: Option<MeshData>,
        shaders: &ShaderSet,
    ) -> Result<Snapshot, RenderError> {
        let spheres = &config.tumblers.spheres;
        // A mesh of the user's own has no coarse level to draw.
        let made_from_spheres = tumbler_mesh.is_none();
        let mesh = match tumbler_mesh {
            Some(mesh) => mesh,
            None => {
                crate::tumbler_mesh::mesh_for(spheres, &WorldConfig::default().tumblers.spheres)?
            }
        };
        let paint = crate::paint::tumbler_paint(spheres);
        let mut renderer =
            Renderer::with_shaders(&gpu, settings, OFFSCREEN_FORMAT, &mesh, &paint, shaders);
        if made_from_spheres {
            renderer.set_coarse_tumbler(&gpu, &crate::tumbler_mesh::coarse_tumbler_mesh(spheres));
        }
        let target = OffscreenTarget::new(&gpu, width, height)?;
        Ok(Snapshot {
            gpu,
            renderer,
            target,
        })
    }

    /// Draws a frame and waits for it; returns what it cost.
    pub fn draw(&mut self, view: &SceneView, camera: &Camera) -> Result<FrameStats, RenderError> {
        let stats = self
            .target
            .render(&self.gpu, &mut self.renderer, view, camera)?;
        self.target.finish(&self.gpu, "an off-screen frame")?;
        Ok(stats)
    }

    /// Draws a frame and reads it back.
    pub fn capture(&mut self, view: &SceneView, camera: &Camera) -> Result<RgbaImage, RenderError> {
        self.target
            .render(&self.gpu, &mut self.renderer, view, camera)?;
        self.target.read(&self.gpu, "an off-screen frame")
    }
}
