//! `rolypoly make-tumbler-obj`: the tumbler's mesh, made from a scene's
//! spheres, as a Wavefront OBJ file.

use anyhow::Context;
use rolypoly_physics::WorldConfig;

use crate::cli::MakeTumblerObjArgs;

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
