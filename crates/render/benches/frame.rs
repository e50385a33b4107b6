//! Off-screen frame benchmark: 1280x720, MSAA 4x, shadows on.
//!
//! Run with `cargo bench -p rolypoly-render`. For each scene it prints frames
//! per second (waiting for the GPU after every frame), the CPU time our own
//! code spends building and recording a frame, and the draw calls per frame,
//! which must not grow with the number of balls. Each scene is drawn twice
//! over: as the program draws it, and with the balls' depth tested only after
//! their fragments are traced (`early_ball_depth` off), to show what testing
//! it first saves. Each draws at least three frames and for at least two
//! seconds: a software renderer is done within two minutes, and a GPU's
//! figure averages over hundreds of frames.

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
    let mut adapter = String::new();
    let mut early_available = false;
    println!(
        "{:<36} {:>8} {:>10} {:>14} {:>11}",
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
        let view = SceneView::from_world(&world, None);
        let camera = Camera::overview(view.room_size);
        let late = RenderSettings {
            early_ball_depth: false,
            ..RenderSettings::default()
        };
        let mut rates = [0.0; 2];
        for (k, settings) in [RenderSettings::default(), late].into_iter().enumerate() {
            let mut snap = match Snapshot::new(&config, settings, width, height, None) {
                Ok(s) => s,
                Err(e) => {
                    eprintln!("error: {e}");
                    std::process::exit(1);
                }
            };
            adapter = snap.gpu.describe();
            early_available |= snap.renderer.settings().early_ball_depth;
            let label = if k == 0 {
                name.to_string()
            } else {
                "  the same, ball depth tested late".to_string()
            };
            let frame = measure(&mut snap, &view, &camera);
            rates[k] = frame.per_second;
            println!(
                "{:<36} {:>8} {:>10.2} {:>14.3} {:>11}",
                label, frame.count, frame.per_second, frame.cpu_ms, frame.draw_calls
            );
        }
        println!(
            "{:<36} {:>8} {:>10.2}",
            "  early over late",
            "",
            rates[0] / rates[1]
        );
    }
    println!("adapter: {adapter}");
    if !early_available {
        println!(
            "(this adapter has no early depth test for shaders that write depth: both rows draw alike)"
        );
    }
}

/// Frames drawn, their rate, our CPU time per frame and draw calls per frame.
struct Frames {
    count: u32,
    per_second: f64,
    cpu_ms: f64,
    draw_calls: u32,
}

/// Draws `view` over and over, at least `MIN_FRAMES` times and for at
/// least `MIN_SECONDS`, after one frame to warm up.
fn measure(snap: &mut Snapshot, view: &SceneView, camera: &Camera) -> Frames {
    const MIN_FRAMES: u32 = 3;
    const MIN_SECONDS: f64 = 2.0;
    let mut run = || {
        snap.draw(view, camera)
            .unwrap_or_else(|e| panic!("frame: {e}"))
    };
    run();
    let mut cpu = Duration::ZERO;
    let mut draw_calls = 0;
    let mut count = 0u32;
    let start = Instant::now();
    while count < MIN_FRAMES || start.elapsed().as_secs_f64() < MIN_SECONDS {
        let stats = run();
        cpu += stats.cpu_time;
        draw_calls = stats.draw_calls;
        count += 1;
    }
    Frames {
        count,
        per_second: f64::from(count) / start.elapsed().as_secs_f64(),
        cpu_ms: cpu.as_secs_f64() * 1e3 / f64::from(count),
        draw_calls,
    }
}
