//! The temporal path follows the GPU engine's balls from its own buffer as
//! it follows the CPU's: the same moving balls, drawn either way, give the
//! same picture.
//!
//! These draw off-screen on whatever adapter exists (lavapipe in CI).

use glam::Vec3;
use image::RgbaImage;
use rolypoly_physics::{World, WorldConfig};
use rolypoly_render::{Camera, GpuBallBuffer, RenderSettings, SceneView, Snapshot};
use wgpu::util::DeviceExt;

const SIZE: (u32, u32) = (320, 180);
/// The frames drawn, a display's rate apart.
const FRAMES: u32 = 20;
const FRAME_TIME: f32 = 1.0 / 60.0;

fn settings() -> RenderSettings {
    RenderSettings {
        temporal: true,
        resolution: 0.5,
        ..RenderSettings::default()
    }
}

/// `view` with each ball carried `frame` frames along its own velocity: a
/// few metres a second, across the picture and down.
fn moved(view: &SceneView, frame: u32) -> SceneView {
    let mut view = view.clone();
    for (i, ball) in view.balls.iter_mut().enumerate() {
        let velocity = Vec3::new(1.0 + (i % 3) as f32, -1.5, 0.5 * (i % 2) as f32);
        ball.position += velocity * FRAME_TIME * frame as f32;
    }
    view
}

/// The balls of `view` as the GPU engine lays them out (see
/// `BallInstance`): centre and radius, colour, padding.
fn gpu_buffer(snapshot: &Snapshot, view: &SceneView) -> GpuBallBuffer {
    let data: Vec<[f32; 8]> = view
        .balls
        .iter()
        .map(|b| {
            let (p, c) = (b.position, b.color);
            [p.x, p.y, p.z, b.radius, c.x, c.y, c.z, 0.0]
        })
        .collect();
    let buffer = snapshot
        .gpu
        .device
        .create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("engine balls"),
            contents: bytemuck::cast_slice(&data),
            usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_SRC,
        });
    GpuBallBuffer {
        buffer,
        count: view.balls.len() as u32,
    }
}

/// The last of the frames of `view`'s balls moving, on the temporal path,
/// drawn from the renderer's own list or (`engine`) from a GPU buffer.
fn last_frame(config: &WorldConfig, view: &SceneView, engine: bool) -> RgbaImage {
    let mut snapshot =
        Snapshot::new(config, settings(), SIZE.0, SIZE.1, None).expect("an adapter to draw on");
    let camera = Camera::overview(view.room_size);
    let mut last = None;
    for frame in 0..FRAMES {
        let mut drawn = moved(view, frame);
        if engine {
            drawn.gpu_balls = Some(gpu_buffer(&snapshot, &drawn));
            drawn.balls.clear();
        }
        last = Some(snapshot.capture(&drawn, &camera).expect("a frame"));
    }
    last.expect("frames were drawn")
}

#[test]
fn balls_from_a_gpu_buffer_move_in_the_temporal_frame_as_the_cpu_ones_do() {
    let config = WorldConfig::default();
    let mut world = World::new(config.clone(), 4).expect("scene builds");
    for _ in 0..120 {
        world.step();
    }
    let view = SceneView::from_world(&world, None);
    assert!(view.balls.len() >= 20);
    let cpu = last_frame(&config, &view, false);
    let gpu = last_frame(&config, &view, true);
    let differing = cpu
        .pixels()
        .zip(gpu.pixels())
        .filter(|(a, b)| (0..3).any(|c| a[c].abs_diff(b[c]) > 2))
        .count();
    assert_eq!(differing, 0, "{differing} pixels differ");
    // The balls did move: the first frame's picture is another.
    let first = {
        let mut snapshot =
            Snapshot::new(&config, settings(), SIZE.0, SIZE.1, None).expect("an adapter");
        snapshot
            .capture(&view, &Camera::overview(view.room_size))
            .expect("a frame")
    };
    let moved_pixels = cpu
        .pixels()
        .zip(first.pixels())
        .filter(|(a, b)| (0..3).any(|c| a[c].abs_diff(b[c]) > 16))
        .count();
    assert!(moved_pixels > 200, "only {moved_pixels} pixels changed");
}
