//! Off-screen frame benchmark: 1280x720, MSAA 4x, shadows on, the fireball
//! in flight.
//!
//! Run with `cargo bench -p rolypoly-render --bench frame`. For each scene
//! it prints frames per second (waiting for the GPU after every frame), the
//! CPU time our own code spends building and recording a frame, and the draw calls per frame,
//! which must not grow with the number of balls. Each scene is drawn with
//! every light effect on (as the program draws it), with each one off in
//! turn, and with all off, and the all-on rate as a share of the all-off
//! one; then once more with the balls' depth tested only after their
//! fragments are traced (`early_ball_depth` off), to show what testing it
//! first saves. Then each quality level (all effects on), and the shadow
//! faces' share of a high frame with and without culling: the time a frame
//! loses to shadows (against one without), over its whole time. Each draws
//! at least three frames and for at least two seconds: a software renderer
//! is done within five minutes, and a GPU's figure averages over hundreds
//! of frames. Last, half a second in, every debug view at once against
//! none, and the processor's time to build their lines from the world;
//! then each view of the frame's passes against the finished frame, frame
//! by frame in turn: its rate over the frame's, and the time it adds.
//!
//! `cargo bench -p rolypoly-render --bench frame -- --row-seconds S` draws
//! each row for at least S seconds instead of two (a GPU's rows need less);
//! `-- --only TEXT,TEXT` draws only the scenes whose name holds one of them
//! (`default,10k`); `-- --million` ends with a million balls drawn from the
//! GPU engine's own buffer (as `--engine gpu` draws the million-ball
//! scene), the drawing alone, against the target of 30 frames a second on
//! an H100-class GPU.

use rolypoly_physics::{World, WorldConfig};
use rolypoly_render::{
    Camera, DebugLayer, DebugViews, FrameView, GpuBallBuffer, Light, Quality, RenderSettings,
    SceneView, Snapshot,
};
use std::time::{Duration, Instant};

const WIDTH: u32 = 1280;
const HEIGHT: u32 = 720;

/// Frames a second the million-ball row is to reach on an H100-class GPU.
const MILLION_TARGET_FPS: f64 = 30.0;

/// How long each row draws, at least, unless `--row-seconds` says.
static ROW_SECONDS: std::sync::OnceLock<f64> = std::sync::OnceLock::new();

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let row_seconds = match args.iter().position(|a| a == "--row-seconds") {
        None => 2.0,
        Some(at) => match args.get(at + 1).map(|s| s.parse::<f64>()) {
            Some(Ok(s)) if s.is_finite() && s > 0.0 => s,
            _ => {
                eprintln!("frame: --row-seconds needs a number of seconds above 0");
                std::process::exit(2);
            }
        },
    };
    let _ = ROW_SECONDS.set(row_seconds);
    let million = args.iter().any(|a| a == "--million");
    let only = args
        .iter()
        .position(|a| a == "--only")
        .and_then(|at| args.get(at + 1))
        .cloned();
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
    let cases = cases.into_iter().filter(|(name, _)| {
        only.as_ref()
            .is_none_or(|list| list.split(',').any(|text| name.contains(text)))
    });
    for (name, config) in cases {
        let mut world = match World::new(config.clone(), 1) {
            Ok(w) => w,
            Err(e) => {
                eprintln!("{name}: {e}");
                std::process::exit(1);
            }
        };
        world.launch_fireball(None);
        let all_on = SceneView::from_world(&world, None);
        let camera = Camera::overview(all_on.room_size);
        let with = |change: fn(&mut Light)| {
            let mut view = all_on.clone();
            change(&mut view.light);
            view
        };
        let variants: [(&str, SceneView); 6] = [
            ("", all_on.clone()),
            ("  no bloom", with(|l| l.bloom = None)),
            ("  no fireball light", with(|l| l.fireball_light = false)),
            ("  no indirect light", with(|l| l.indirect = false)),
            ("  no occlusion", with(|l| l.occlusion = false)),
            (
                "  all effects off",
                with(|l| {
                    l.bloom = None;
                    l.fireball_light = false;
                    l.indirect = false;
                    l.occlusion = false;
                }),
            ),
        ];
        let mut snap = snapshot(&config, RenderSettings::default());
        adapter = snap.gpu.describe();
        early_available |= snap.renderer.settings().early_ball_depth;
        let mut rates = Vec::new();
        for (label, view) in &variants {
            let label = if label.is_empty() { name } else { label };
            let frame = measure(&mut snap, view, &camera);
            rates.push(frame.per_second);
            print_row(label, &frame);
        }
        println!(
            "{:<36} {:>8} {:>10.2}",
            "  all on over all off",
            "",
            rates[0] / rates[rates.len() - 1]
        );
        let late = RenderSettings {
            early_ball_depth: false,
            ..RenderSettings::default()
        };
        let frame = measure(&mut snapshot(&config, late), &all_on, &camera);
        print_row("  ball depth tested late", &frame);
        println!(
            "{:<36} {:>8} {:>10.2}",
            "  early over late",
            "",
            rates[0] / frame.per_second
        );
        for level in [Quality::Medium, Quality::Low] {
            let frame = measure(&mut snapshot(&config, level.settings()), &all_on, &camera);
            print_row(&format!("  quality {}", level.name()), &frame);
        }
        let high = rates[0];
        let unculled = RenderSettings {
            cull_shadow_faces: false,
            ..RenderSettings::default()
        };
        let unculled = measure(&mut snapshot(&config, unculled), &all_on, &camera);
        print_row("  shadow faces not culled", &unculled);
        let unshadowed = RenderSettings {
            shadows: false,
            ..RenderSettings::default()
        };
        let unshadowed = measure(&mut snapshot(&config, unshadowed), &all_on, &camera).per_second;
        // A frame's time is 1 / rate; the shadows' share is what they add.
        let share = |rate: f64| 100.0 * (1.0 - rate / unshadowed);
        println!(
            "{:<36} {:>8} {:>9.0}% {:>13.0}%",
            "  shadow share, culled / not",
            "",
            share(high),
            share(unculled.per_second)
        );
        println!(
            "{:<36} {:>8} {:>10.2}",
            "  culled over not",
            "",
            high / unculled.per_second
        );
        let mut views = DebugViews::default();
        for layer in DebugLayer::ALL {
            views.set(layer, true);
        }
        // Half a second in, so that the balls touch and the contacts show.
        let mut stepped = world.clone();
        for _ in 0..60 {
            stepped.step();
        }
        let plain = SceneView::from_world(&stepped, None);
        let started = Instant::now();
        let builds = 5;
        let mut shown = plain.clone();
        for _ in 0..builds {
            shown = plain.clone().with_debug(&stepped, &[], &views);
        }
        let build_ms = started.elapsed().as_secs_f64() * 1e3 / f64::from(builds);
        // Frame by frame in turn, so that whatever else the machine does
        // slows both alike.
        let (without, frame) = measure_in_turn(
            &mut snap,
            [(&plain, FrameView::Final), (&shown, FrameView::Final)],
            &camera,
        );
        print_row("  half a second in", &without);
        print_row("  every debug view", &frame);
        println!(
            "{:<36} {:>8} {:>10.2} {:>14.3} {:>11}",
            "  views over none, build ms, marks",
            "",
            frame.per_second / without.per_second,
            build_ms,
            shown.debug_marks.len()
        );
        // Each view alone, in turn with none: which one costs what.
        for layer in DebugLayer::ALL {
            let mut alone = DebugViews::default();
            alone.set(layer, true);
            let view = plain.clone().with_debug(&stepped, &[], &alone);
            let (none, frame) = measure_in_turn(
                &mut snap,
                [(&plain, FrameView::Final), (&view, FrameView::Final)],
                &camera,
            );
            println!(
                "{:<36} {:>8} {:>10.2}",
                format!("  {} alone over none", layer.name()),
                "",
                frame.per_second / none.per_second
            );
        }
        // Each view of the frame's passes, in turn with the finished frame:
        // what showing one pass costs over drawing the frame.
        for shown in FrameView::ALL.into_iter().skip(1) {
            let (finished, frame) = measure_in_turn(
                &mut snap,
                [(&plain, FrameView::Final), (&plain, shown)],
                &camera,
            );
            println!(
                "{:<36} {:>8} {:>10.2} {:>14} {:>11}",
                format!("  view {} over final", shown.name()),
                "",
                frame.per_second / finished.per_second,
                format!(
                    "{:+.1} ms",
                    1e3 * (1.0 / frame.per_second - 1.0 / finished.per_second)
                ),
                frame.draw_calls
            );
        }
    }
    if million {
        million_from_the_gpu_engine();
    }
    println!("adapter: {adapter}");
    if !early_available {
        println!(
            "(this adapter has no early depth test for shaders that write depth: both rows draw alike)"
        );
    }
}

/// A million balls of scenes/ballpit-1m.toml, stepped once by the GPU
/// engine on the renderer's device and drawn from its buffer.
fn million_from_the_gpu_engine() {
    let mut config = WorldConfig::default();
    config.balls.count = 1_000_000;
    config.balls.radius = 0.1;
    config.balls.start_fill = 0.4;
    config.room.size = glam::DVec3::new(76.0, 5.0, 76.0);
    let fail = |what: &str, e: &dyn std::fmt::Display| -> ! {
        eprintln!("error: the million-ball row: {what}: {e}");
        std::process::exit(1);
    };
    let mut world = World::new(config.clone(), 1).unwrap_or_else(|e| fail("world", &e));
    let mut snap = snapshot(&config, RenderSettings::default());
    let gpu = &snap.gpu;
    let mut balls = rolypoly_gpu::GpuBalls::new(
        gpu.device.clone(),
        gpu.queue.clone(),
        &gpu.adapter,
        &mut world,
    )
    .unwrap_or_else(|e| fail("gpu engine", &e));
    balls.step(&mut world).unwrap_or_else(|e| fail("step", &e));
    balls.finish().unwrap_or_else(|e| fail("step", &e));
    let mut view = SceneView::from_world(&world, None);
    view.gpu_balls = Some(GpuBallBuffer {
        buffer: balls.instances().clone(),
        count: balls.len() as u32,
    });
    let camera = Camera::overview(view.room_size);
    let frame = measure(&mut snap, &view, &camera);
    print_row("1M balls, GPU engine's buffer", &frame);
    println!(
        "{:<36} {:>8} {:>10}",
        "  target on an H100-class GPU",
        "",
        format!(
            "{MILLION_TARGET_FPS:.0}: {}",
            if frame.per_second >= MILLION_TARGET_FPS {
                "met"
            } else {
                "not met"
            }
        )
    );
}

fn snapshot(config: &WorldConfig, settings: RenderSettings) -> Snapshot {
    Snapshot::new(config, settings, WIDTH, HEIGHT, None).unwrap_or_else(|e| {
        eprintln!("error: {e}");
        std::process::exit(1);
    })
}

fn print_row(label: &str, frame: &Frames) {
    println!(
        "{:<36} {:>8} {:>10.2} {:>14.3} {:>11}",
        label, frame.count, frame.per_second, frame.cpu_ms, frame.draw_calls
    );
}

/// Frames drawn, their rate, our CPU time per frame and draw calls per frame.
struct Frames {
    count: u32,
    per_second: f64,
    cpu_ms: f64,
    draw_calls: u32,
}

/// Draws the two scenes of `views` in turn, each shown as its view of the
/// frame, frame by frame, for as long as [`measure`] draws one; returns
/// each one's frames.
fn measure_in_turn(
    snap: &mut Snapshot,
    views: [(&SceneView, FrameView); 2],
    camera: &Camera,
) -> (Frames, Frames) {
    let min_seconds = 2.0 * ROW_SECONDS.get().copied().unwrap_or(2.0);
    let mut spent = [Duration::ZERO; 2];
    let mut cpu = [Duration::ZERO; 2];
    let mut draw_calls = [0; 2];
    let mut count = 0u32;
    for (view, shown) in views {
        snap.renderer.set_view(shown);
        snap.draw(view, camera)
            .unwrap_or_else(|e| panic!("frame: {e}"));
    }
    let start = Instant::now();
    while count < 3 || start.elapsed().as_secs_f64() < min_seconds {
        for (k, (view, shown)) in views.iter().enumerate() {
            snap.renderer.set_view(*shown);
            let began = Instant::now();
            let stats = snap
                .draw(view, camera)
                .unwrap_or_else(|e| panic!("frame: {e}"));
            spent[k] += began.elapsed();
            cpu[k] += stats.cpu_time;
            draw_calls[k] = stats.draw_calls;
        }
        count += 1;
    }
    let frames = |k: usize| Frames {
        count,
        per_second: f64::from(count) / spent[k].as_secs_f64(),
        cpu_ms: cpu[k].as_secs_f64() * 1e3 / f64::from(count),
        draw_calls: draw_calls[k],
    };
    (frames(0), frames(1))
}

/// Draws `view` over and over, at least `MIN_FRAMES` times and for at
/// least `MIN_SECONDS`, after one frame to warm up.
fn measure(snap: &mut Snapshot, view: &SceneView, camera: &Camera) -> Frames {
    const MIN_FRAMES: u32 = 3;
    let min_seconds = ROW_SECONDS.get().copied().unwrap_or(2.0);
    let mut run = || {
        snap.draw(view, camera)
            .unwrap_or_else(|e| panic!("frame: {e}"))
    };
    run();
    let mut cpu = Duration::ZERO;
    let mut draw_calls = 0;
    let mut count = 0u32;
    let start = Instant::now();
    while count < MIN_FRAMES || start.elapsed().as_secs_f64() < min_seconds {
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
