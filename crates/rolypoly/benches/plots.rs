//! What the plots (key F4) cost the CPU: a frame of them laid out and
//! tessellated by egui, against the same frame without them, and a sample a
//! step at 10 000 balls against the step itself.
//!
//! Run with `cargo bench -p rolypoly --bench plots`. The frame's figure is
//! what the window's profiler counts as the HUD's (egui's layout and
//! tessellation), less the upload, which depends on the adapter.

use std::path::Path;
use std::time::Instant;

use glam::DVec3;
use rolypoly::window::plots::Plots;
use rolypoly_physics::{World, WorldConfig};

/// Frames timed after the warm-up.
const FRAMES: usize = 200;

fn main() {
    let mut world = World::new(WorldConfig::default(), 1).expect("the default world");
    let mut plots = Plots::default();
    plots.open = true;
    let mut events = Vec::new();
    // The 30 s the plots keep, at the default 120 steps a second.
    for _ in 0..3_600 {
        world.step();
        world.take_events(&mut events);
        plots.record(&world, &events);
    }
    let ctx = egui::Context::default();
    let input = || egui::RawInput {
        screen_rect: Some(egui::Rect::from_min_size(
            egui::Pos2::ZERO,
            egui::vec2(1280.0, 720.0),
        )),
        ..Default::default()
    };
    // A frame's layout and its tessellation (s).
    let mut frame = |with_plots: bool| {
        let started = Instant::now();
        let output = ctx.run_ui(input(), |ui| {
            ui.label("the rest of the HUD");
            if with_plots {
                plots.show(ui.ctx(), Path::new("."));
            }
        });
        let laid_out = started.elapsed().as_secs_f64();
        let meshes = ctx.tessellate(output.shapes, output.pixels_per_point);
        std::hint::black_box(meshes);
        [laid_out, started.elapsed().as_secs_f64() - laid_out]
    };
    let mut mean_ms = |with_plots: bool| {
        for _ in 0..20 {
            frame(with_plots);
        }
        let mut total = [0.0; 2];
        for _ in 0..FRAMES {
            let [a, b] = frame(with_plots);
            total = [total[0] + a, total[1] + b];
        }
        total.map(|t| t * 1e3 / FRAMES as f64)
    };
    let closed = mean_ms(false);
    let open = mean_ms(true);
    println!(
        "{:<44} {:>10} {:>10} {:>10}",
        "a frame of the HUD, 1280x720, ms", "layout", "tessellate", "both"
    );
    let row =
        |name: &str, [a, b]: [f64; 2]| println!("{name:<44} {a:>10.3} {b:>10.3} {:>10.3}", a + b);
    row("plots closed", closed);
    row("plots open, 30 s of samples", open);
    row(
        "the plots' cost",
        [open[0] - closed[0], open[1] - closed[1]],
    );

    let mut config = WorldConfig::default();
    config.balls.count = 10_000;
    config.room.size = DVec3::new(16.0, 6.0, 16.0);
    let mut world = World::new(config, 1).expect("a 10 000-ball world");
    let mut plots = Plots::default();
    plots.open = true;
    let (mut stepping, mut sampling) = (0.0, 0.0);
    let steps = 60;
    for _ in 0..steps {
        let started = Instant::now();
        world.step();
        world.take_events(&mut events);
        stepping += started.elapsed().as_secs_f64();
        let started = Instant::now();
        plots.record(&world, &events);
        sampling += started.elapsed().as_secs_f64();
    }
    let per_step = |s: f64| s * 1e3 / steps as f64;
    println!();
    println!("{:<44} {:>10}", "10 000 balls, a step", "ms");
    println!("{:<44} {:>10.3}", "the step", per_step(stepping));
    println!("{:<44} {:>10.3}", "the plots' sample", per_step(sampling));
    println!(
        "{:<44} {:>10.4}",
        "the sample's share of the step",
        sampling / stepping
    );
}
