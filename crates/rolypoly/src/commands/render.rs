//! `rolypoly render`: a run to a moment, that frame as a PNG: drawn in
//! real time, path-traced (`--reference`), or both and measured one
//! against the other (`--compare`).

use std::path::{Path, PathBuf};
use std::sync::Mutex;

use anyhow::Context;
use rolypoly_physics::WorldConfig;
use rolypoly_render::{LightConfig, QualityChoice, RenderSettings};

use crate::cli::{ReferenceArgs, RenderArgs, steps_for};
use crate::frames::{chosen_camera, read_obj};
use crate::progress::Progress;
use crate::simulation::Simulation;

/// Runs `sim` to the requested time and writes that frame, drawn at the
/// scene's `quality` unless the flags say otherwise. With `gpu`, the GPU
/// engine steps the balls, on the device that draws them.
pub fn render(
    mut sim: Simulation,
    light: &LightConfig,
    quality: QualityChoice,
    gpu: bool,
    args: &RenderArgs,
) -> anyhow::Result<()> {
    check_reference_flags(&args.truth, args, gpu)?;
    let sim = &mut sim;
    if args.frame.fireball {
        sim.world.launch_fireball(None);
    }
    let against = args
        .truth
        .against
        .as_deref()
        .map(|path| read_reference(path, args.size))
        .transpose()?;
    if args.truth.reference {
        // The reference alone needs no graphics adapter.
        sim.ticks(steps_for(args.time, sim.world.config().solver.dt));
        let picture = trace_reference(sim, light, args)?;
        if let Some(reference) = &against {
            measure(reference, &picture, args.out()?)?;
        }
        return Ok(());
    }
    let mut frames = args.frame.frames(sim.world.config(), quality, args.size)?;
    if gpu {
        frames.move_balls_to_gpu(sim)?;
    }
    let steps = steps_for(args.time, sim.world.config().solver.dt);
    let image = frames.draw_at(sim, steps, light)?;
    save(&image, args.out()?)?;
    let (width, height) = args.size;
    println!(
        "wrote {} ({width}x{height}, t = {:.3} s, {})",
        args.out()?.display(),
        sim.world.time(),
        frames.describe()
    );
    let (view, caption) = frames.view_caption(sim, light);
    if view != rolypoly_render::FrameView::Final {
        println!("view {caption}");
    }
    let reference = match against {
        Some(reference) => Some(reference),
        None if args.truth.compare => Some(trace_reference(sim, light, args)?),
        None => None,
    };
    if let Some(reference) = reference {
        measure(&reference, &image, args.out()?)?;
    }
    Ok(())
}

/// Scores `picture` against `reference`: FLIP's map beside `out`, its mean and the SSIM
/// printed.
fn measure(
    reference: &image::RgbaImage,
    picture: &image::RgbaImage,
    out: &Path,
) -> anyhow::Result<()> {
    let comparison = rolypoly_reference::compare(reference, picture);
    let flip = beside(out, "flip");
    save(&comparison.map, &flip)?;
    println!("wrote {} (FLIP's error map)", flip.display());
    println!(
        "mean FLIP error against the reference: {:.4}",
        comparison.mean
    );
    println!(
        "SSIM against the reference: {:.4}",
        rolypoly_reference::ssim(reference, picture)
    );
    Ok(())
}

/// A reference picture written before, for --against, of the frame's
/// `size`.
fn read_reference(path: &Path, size: (u32, u32)) -> anyhow::Result<image::RgbaImage> {
    let picture = image::open(path)
        .with_context(|| format!("cannot read the reference picture `{}`", path.display()))?
        .to_rgba8();
    if picture.dimensions() != size {
        let (w, h) = picture.dimensions();
        anyhow::bail!(
            "the reference picture is {w}x{h} and the frame {}x{}: measure against a reference of the frame's --size",
            size.0,
            size.1
        );
    }
    Ok(picture)
}

/// The reference's flags make sense only with a reference, and a
/// reference only of what the CPU holds.
fn check_reference_flags(
    truth: &ReferenceArgs,
    args: &RenderArgs,
    gpu: bool,
) -> anyhow::Result<()> {
    if !truth.traced() {
        if truth.spp.is_some() || truth.reference_seed.is_some() || truth.hdr.is_some() {
            anyhow::bail!("--spp, --reference-seed and --hdr go with --reference or --compare");
        }
    } else if gpu {
        anyhow::bail!(
            "the reference traces balls stepped on the CPU; the GPU engine keeps its balls on the GPU: trace it with --engine cpu"
        );
    }
    if (truth.traced() || truth.against.is_some()) && args.frame.show.is_some() {
        anyhow::bail!(
            "the debug views (--show) are drawn over the real-time frame only, not measured against a reference"
        );
    }
    Ok(())
}

/// The frame of `sim` now, path-traced as `args` say; its radiance also
/// to `--hdr`, and with `--compare` the picture beside `--out`.
fn trace_reference(
    sim: &Simulation,
    light: &LightConfig,
    args: &RenderArgs,
) -> anyhow::Result<image::RgbaImage> {
    let truth = &args.truth;
    let config = sim.world.config();
    let mesh = match &args.frame.tumbler_obj {
        Some(path) => read_obj(path)?,
        None => rolypoly_render::mesh_for(
            &config.tumblers.spheres,
            &WorldConfig::default().tumblers.spheres,
        )?,
    };
    let paint = rolypoly_render::tumbler_paint(&config.tumblers.spheres);
    let scene = rolypoly_reference::Scene::from_view(&sim.view(light), &mesh, &paint)?;
    let camera = chosen_camera(args.frame.camera, config);
    let spp = truth.spp.unwrap_or(ReferenceArgs::DEFAULT_SPP);
    let seed = truth.reference_seed.unwrap_or(ReferenceArgs::DEFAULT_SEED);
    let (width, height) = args.size;
    let progress = Mutex::new(Progress::new(height, "rows"));
    let radiance = rolypoly_reference::render(&scene, &camera, args.size, spp, seed, &|| {
        if let Ok(mut p) = progress.lock() {
            p.advance();
        }
    });
    if let Ok(p) = progress.lock() {
        p.finish();
    }
    if let Some(hdr) = &truth.hdr {
        rolypoly_reference::write_exr(&radiance, hdr)
            .with_context(|| format!("cannot write `{}`", hdr.display()))?;
        println!("wrote {} (linear radiance)", hdr.display());
    }
    let picture = rolypoly_reference::to_picture(&radiance, RenderSettings::default().exposure);
    let out = if truth.compare {
        beside(args.out()?, "reference")
    } else {
        args.out()?.to_path_buf()
    };
    save(&picture, &out)?;
    println!(
        "wrote {} ({width}x{height}, t = {:.3} s, path-traced reference, {spp} samples a pixel, seed {seed}, on {} threads)",
        out.display(),
        sim.world.time(),
        rolypoly_reference::threads(),
    );
    Ok(picture)
}

/// `out` with `-what` added to its name: FRAME.png -> FRAME-what.png.
fn beside(out: &Path, what: &str) -> PathBuf {
    let stem = out
        .file_stem()
        .map_or_else(|| "frame".into(), |s| s.to_string_lossy().into_owned());
    out.with_file_name(format!("{stem}-{what}.png"))
}

fn save<P: image::PixelWithColorType>(
    image: &image::ImageBuffer<P, Vec<P::Subpixel>>,
    out: &Path,
) -> anyhow::Result<()>
where
    [P::Subpixel]: image::EncodableLayout,
{
    image
        .save_with_format(out, image::ImageFormat::Png)
        .with_context(|| format!("cannot write `{}`", out.display()))
}
