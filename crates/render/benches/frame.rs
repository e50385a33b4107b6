//! Off-screen frame benchmark: 1280x720, MSAA 4x, shadows on.
//!
//! Run with `cargo bench -p rolypoly-render`. For each scene it prints frames
//! per second (waiting for the GPU after every frame), the CPU time our own
//! code spends building and recording a frame, and the draw calls per frame,
//! which must not grow with the number of balls. Each scene draws at least
//! three frames and for at least two seconds: a software renderer is done
//! within a minute, and a GPU's figure averages over hundreds of frames.

use rolypoly_physics::{World, WorldConfig};
use rolypoly_render::{Camera, RenderSettings, SceneView, Snapshot};
use std::time::{Duration, Instant};

fn main() {
    let (width, height) = (1280, 720);
    let mut ten_k = WorldConfig::default();
    ten_k.balls.count = 10_000;
    ten_k.room.size = glam::DVec3::new(16.0, 6.0, 16.0);
    // The balls of scenes/ballpit-100k.toml, spread through the lowest 2 m
    // of its room.
    let mut hundred_k = WorldConfig::default();
    hundred_k.balls.count = 100_000;
    hundred_k.balls.radius = 0.1;
    hundred_k.balls.start_fill = 0.4;
    hundred_k.room.size = glam::DVec3::new(24.0, 5.0, 24.0);
    let cases = [
        ("default scene (30 balls)", WorldConfig::default()),
        ("10k balls, 16 x 6 x 16 m room", ten_k),
        ("100k balls, 24 x 5 x 24 m room", hundred_k),
    ];
    const MIN_FRAMES: u32 = 3;
    const MIN_SECONDS: f64 = 2.0;
    let mut adapter = String::new();
    println!(
        "{:<32} {:>8} {:>10} {:>14} {:>11}",
        "scene", "frames", "frames/s", "CPU ms/frame", "draw calls"
    );
    for (name, config) in cases {
        let world = match World::new(config.clone(), 1) {
            Ok(w) => w,
            Err(e) => {
                eprintln!("{name}: {e}");
                std::process::exit(1);
            }
        };
        let mut snap = match Snapshot::new(&config, RenderSettings::default(), width, height, None)
        {
            Ok(s) => s,
            Err(e) => {
                eprintln!("error: {e}");
                std::process::exit(1);
            }
        };
        adapter = snap.gpu.describe();
        let view = SceneView::from_world(&world, None);
        let camera = Camera::overview(view.room_size);
        let run = |snap: &mut Snapshot| {
            snap.draw(&view, &camera)
                .unwrap_or_else(|e| panic!("frame: {e}"))
        };
        run(&mut snap);
        let mut cpu = Duration::ZERO;
        let mut calls = 0;
        let mut frames = 0u32;
        let start = Instant::now();
        while frames < MIN_FRAMES || start.elapsed().as_secs_f64() < MIN_SECONDS {
            let stats = run(&mut snap);
            cpu += stats.cpu_time;
            calls = stats.draw_calls;
            frames += 1;
        }
        let elapsed = start.elapsed().as_secs_f64();
        println!(
            "{:<32} {:>8} {:>10.2} {:>14.3} {:>11}",
            name,
            frames,
            frames as f64 / elapsed,
            cpu.as_secs_f64() * 1e3 / frames as f64,
            calls
        );
    }
    println!("adapter: {adapter}");
}
