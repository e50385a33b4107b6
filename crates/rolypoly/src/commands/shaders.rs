//! `rolypoly shaders --export DIR`: the renderer's shaders as shipped,
//! written out with a README naming what each draws.

use rolypoly_render::shaders;

use crate::cli::ShadersArgs;

/// Writes the shipped shaders into the folder asked for.
pub fn export(args: &ShadersArgs) -> anyhow::Result<()> {
    let written = shaders::export(&args.export)?;
    println!(
        "wrote {} files into {}: {}",
        written.len(),
        args.export.display(),
        shaders::SHIPPED.map(|f| f.name).join(", ")
    );
    Ok(())
}
