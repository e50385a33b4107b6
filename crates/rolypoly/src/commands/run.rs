//! `rolypoly` without a subcommand: the window on a scene.

use std::path::Path;

use rolypoly_physics::World;

use crate::cli::WindowArgs;
use crate::sandbox::Sandbox;
use crate::scene::Scene;

/// Opens the window on `world`, built from `scene` (from the file `path`,
/// if one was given) with `seed`.
pub fn window(
    world: World,
    mut scene: Scene,
    path: Option<&Path>,
    seed: u64,
    args: &WindowArgs,
) -> anyhow::Result<()> {
    let options = args.options(seed, path);
    // The light's switches given as flags are settings like any other.
    scene.light = args.effects.apply(&scene.light);
    if let Some(quality) = args.quality {
        scene.quality = quality;
    }
    if let Some(fps) = args.fps {
        scene.target_fps = fps;
    }
    let name = path.map_or_else(|| "default.toml".to_owned(), |p| p.display().to_string());
    crate::window::run(Sandbox::with_world(world, scene, &name, seed), options)
}
