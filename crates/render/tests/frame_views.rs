//! The views of the frame's passes, each checked by its law on whatever
//! adapter exists (lavapipe in CI), over two seeds of where a ball hangs:
//! the floor's normals decode to +y and each wall's to its inward normal;
//! depth falls along the floor away from the camera; the shadow reads 0 in
//! a ball's umbra and 1 far from it; the shadow cube's -Y face moves a
//! ball's silhouette by where the light projects it; motion is zero over a
//! still scene; the multisampled edges are empty with one sample and lie
//! on outlines with four; the ambient, diffuse and specular views add up
//! to the lit frame; a panning camera's floor moves as the camera does.

use glam::{DVec3, Vec2, Vec3};
use image::RgbaImage;
use rolypoly_physics::{BallPlacement, World, WorldConfig};
use rolypoly_render::{
    Camera, FrameView, MOTION_FULL_PIXELS, RenderSettings, SHADOW_CROSS, SceneView, Snapshot,
    shadow_cross_place,
};

mod common;
use common::pixel_of;

const SIZE: (u32, u32) = (480, 270);

/// The default room with one ball hanging at `ball` and nothing else.
fn room_with_ball(ball: Vec3) -> (WorldConfig, SceneView) {
    let mut config = WorldConfig::default();
    config.balls.count = 0;
    config.tumblers.placements.clear();
    config.balls.placements = vec![BallPlacement::new(ball.as_dvec3(), DVec3::ZERO)];
    let world = World::new(config.clone(), 1).expect("scene builds");
    (config, SceneView::from_world(&world, None))
}

/// Where the ball hangs for seed `seed`.
fn ball_at(seed: u64) -> Vec3 {
    Vec3::new(0.5 + 0.3 * seed as f32, 1.2, 0.8 - 0.2 * seed as f32)
}

fn camera(config: &WorldConfig) -> Camera {
    Camera::overview(config.room.size.as_vec3())
}

/// A renderer of [`SIZE`] with `msaa` samples, showing `view`.
fn snapshot(config: &WorldConfig, view: FrameView, msaa: u32) -> Snapshot {
    let settings = RenderSettings {
        msaa,
        ..RenderSettings::default()
    };
    let mut snap =
        Snapshot::new(config, settings, SIZE.0, SIZE.1, None).expect("an adapter to draw with");
    snap.renderer.set_view(view);
    snap
}

fn drawn(config: &WorldConfig, scene: &SceneView, view: FrameView, msaa: u32) -> RgbaImage {
    snapshot(config, view, msaa)
        .capture(scene, &camera(config))
        .expect("frame")
}

/// The value (0 ..= 1 a channel) a data view wrote at `pixel`.
fn value(img: &RgbaImage, (x, y): (u32, u32)) -> Vec3 {
    let p = img.get_pixel(x, y).0;
    Vec3::new(p[0] as f32, p[1] as f32, p[2] as f32) / 255.0
}

fn pixel(config: &WorldConfig, p: Vec3) -> (u32, u32) {
    pixel_of(&camera(config), p, SIZE.0, SIZE.1)
}

#[test]
fn normals_decode_to_the_floors_and_each_walls_inward_normal() {
    for seed in [0, 1] {
        let (config, scene) = room_with_ball(ball_at(seed));
        let img = drawn(&config, &scene, FrameView::Normals, 4);
        let half = config.room.size.as_vec3() * Vec3::new(0.5, 1.0, 0.5);
        let points = [
            (Vec3::new(-1.0, 0.0, 1.0), Vec3::Y),
            (Vec3::new(1.2, 0.0, -1.0), Vec3::Y),
            (Vec3::new(-half.x, 1.5, 0.0), Vec3::X),
            (Vec3::new(half.x, 1.5, 0.0), Vec3::NEG_X),
            (Vec3::new(0.3, 1.0, -half.z), Vec3::Z),
        ];
        for (point, normal) in points {
            let decoded = (value(&img, pixel(&config, point)) * 2.0 - 1.0).normalize();
            let degrees = decoded.angle_between(normal).to_degrees();
            assert!(
                degrees < 2.0,
                "seed {seed}: at {point} the normal reads {decoded}, {degrees:.2} degrees from {normal}"
            );
        }
    }
}

#[test]
fn depth_falls_along_the_floor_away_from_the_camera() {
    for seed in [0, 1] {
        let (config, scene) = room_with_ball(ball_at(seed));
        let img = drawn(&config, &scene, FrameView::Depth, 4);
        let half_z = 0.5 * config.room.size.z as f32;
        let x = -1.2 + 0.4 * seed as f32;
        let greys: Vec<f32> = (0..8)
            .map(|k| {
                let z = half_z - 0.3 - k as f32 * (2.0 * half_z - 0.6) / 7.0;
                value(&img, pixel(&config, Vec3::new(x, 0.0, z))).x
            })
            .collect();
        for pair in greys.windows(2) {
            assert!(pair[1] < pair[0], "seed {seed}: greys {greys:?}");
        }
    }
}

/// Where the ceiling light's ray through `point` meets the floor.
fn on_floor_behind(light: Vec3, point: Vec3) -> Vec3 {
    let t = light.y / (light.y - point.y);
    light + (point - light) * t
}

#[test]
fn the_shadow_reads_nothing_in_a_balls_umbra_and_all_far_from_it() {
    for seed in [0, 1] {
        let ball = ball_at(seed);
        let (config, scene) = room_with_ball(ball);
        let img = drawn(&config, &scene, FrameView::Shadow, 4);
        let umbra = on_floor_behind(scene.light.position, ball);
        let (ux, uy) = pixel(&config, umbra);
        let (bx, by) = pixel(&config, ball);
        assert!(
            Vec2::new(ux as f32 - bx as f32, uy as f32 - by as f32).length() > 30.0,
            "seed {seed}: the ball hides its own shadow from the camera"
        );
        assert!(value(&img, (ux, uy)).x < 0.02, "seed {seed}: umbra lit");
        let far = Vec3::new(-umbra.x, 0.0, -umbra.z * 0.5);
        assert!(
            value(&img, pixel(&config, far)).x > 0.98,
            "seed {seed}: the open floor is shadowed"
        );
    }
}

/// The mean pixel of the grey (drawn) texels of face `face` of the shadow
/// cube's cross in `img`, in pixels from the face's top left.
fn silhouette_centre(img: &RgbaImage, face: usize) -> Vec2 {
    let (place, side) = shadow_cross_place(SIZE);
    let (column, row) = SHADOW_CROSS[face];
    let corner = place + Vec2::new(column as f32, row as f32) * side;
    let (mut sum, mut count) = (Vec2::ZERO, 0.0);
    for y in 0..side as u32 {
        for x in 0..side as u32 {
            let p = corner + Vec2::new(x as f32, y as f32);
            // Nothing drawn is the far plane, white; the labels are white in red.
            if img.get_pixel(p.x as u32, p.y as u32).0[0] < 240 {
                sum += Vec2::new(x as f32, y as f32);
                count += 1.0;
            }
        }
    }
    assert!(count > 0.0, "no silhouette on face {face}");
    sum / count
}

#[test]
fn a_ball_moved_under_the_light_moves_its_silhouette_on_the_down_face_by_its_projection() {
    const DOWN: usize = 3;
    for seed in [0, 1] {
        let first = Vec3::new(0.1 * seed as f32, 1.0, 0.2);
        let moved = first + Vec3::new(0.4, 0.0, 0.0);
        let (config, scene) = room_with_ball(first);
        let before = silhouette_centre(&drawn(&config, &scene, FrameView::ShadowCube, 4), DOWN);
        let (_, scene) = room_with_ball(moved);
        let after = silhouette_centre(&drawn(&config, &scene, FrameView::ShadowCube, 4), DOWN);
        // A 90-degree face: a point d below the light and x across shows
        // x / d of half the face's side from its centre, +x to the right.
        let (_, side) = shadow_cross_place(SIZE);
        let below = scene.light.position.y - first.y;
        let expected = 0.4 / below * side / 2.0;
        let shift = after - before;
        assert!(
            (shift.x - expected).abs() < 0.15 * expected && shift.y.abs() < 1.0,
            "seed {seed}: the silhouette moved by {shift}, the projection says ({expected}, 0)"
        );
    }
}

#[test]
fn motion_is_zero_everywhere_over_a_still_scene_from_a_still_camera() {
    for seed in [0, 1] {
        let (config, scene) = room_with_ball(ball_at(seed));
        let mut snap = snapshot(&config, FrameView::Motion, 4);
        for frame in 0..2 {
            let img = snap.capture(&scene, &camera(&config)).expect("frame");
            let moving = img.pixels().filter(|p| p.0[..3] != [0, 0, 0]).count();
            assert_eq!(moving, 0, "seed {seed}, frame {frame}: pixels moving");
        }
    }
}

/// Narkowicz's ACES curve (tonemap.wgsl's `aces`) and its inverse, and
/// sRGB's encoding and decoding of 8 bits: the term views are drawn in
/// the frame's own tone mapping, so their linear light is read back
/// through them.
const ACES: (f32, f32, f32, f32, f32) = (2.51, 0.03, 2.43, 0.59, 0.14);

fn aces(x: f32) -> f32 {
    let (a, b, c, d, e) = ACES;
    ((x * (a * x + b)) / (x * (c * x + d) + e)).clamp(0.0, 1.0)
}

/// The light `x` whose curve is `y` (y below 1): the positive root of
/// (a - c y) x^2 + (b - d y) x - e y = 0.
fn aces_inverse(y: f32) -> f32 {
    let (a, b, c, d, e) = ACES;
    let (qa, qb, qc) = (a - c * y, b - d * y, -e * y);
    (-qb + (qb * qb - 4.0 * qa * qc).sqrt()) / (2.0 * qa)
}

fn srgb_decode(v: u8) -> f32 {
    let v = v as f32 / 255.0;
    if v <= 0.04045 {
        v / 12.92
    } else {
        ((v + 0.055) / 1.055).powf(2.4)
    }
}

fn srgb_encode(c: f32) -> f32 {
    let s = if c <= 0.003_130_8 {
        12.92 * c
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    };
    (s * 255.0).clamp(0.0, 255.0)
}

#[test]
fn ambient_diffuse_and_specular_add_up_to_the_lit_frame() {
    for seed in [2, 7] {
        let config = WorldConfig::default();
        let mut world = World::new(config.clone(), seed).expect("scene builds");
        for _ in 0..30 {
            world.step();
        }
        let mut scene = SceneView::from_world(&world, None);
        // Only Blinn-Phong's three terms light the frame.
        scene.light.bloom = None;
        scene.light.indirect = false;
        scene.light.occlusion = false;
        let frames: Vec<RgbaImage> = [
            FrameView::Final,
            FrameView::Ambient,
            FrameView::Diffuse,
            FrameView::Specular,
        ]
        .into_iter()
        .map(|view| drawn(&config, &scene, view, 4))
        .collect();
        let (mut error, mut counted, mut lit) = (0.0f64, 0usize, 0usize);
        for (i, frame_pixel) in frames[0].pixels().enumerate() {
            let frame = frame_pixel.0;
            // A saturated channel (the bulb, which is no term of the light)
            // cannot be read back through the curve.
            if frame[..3].contains(&255) {
                continue;
            }
            for (channel, &shown) in frame[..3].iter().enumerate() {
                let light: f32 = frames[1..]
                    .iter()
                    .map(|term| aces_inverse(srgb_decode(term.as_raw()[4 * i + channel])))
                    .sum();
                let summed = srgb_encode(aces(light));
                error += (summed - shown as f32).abs() as f64;
            }
            counted += 1;
            lit += usize::from(frame[..3].iter().any(|&c| c > 20));
        }
        let mean = error / (3 * counted) as f64;
        println!("seed {seed}: the terms' sum is off the frame by {mean:.3} of 255 on average");
        assert!(
            counted > frames[0].pixels().len() * 9 / 10 && lit > counted / 2,
            "seed {seed}: too few pixels to compare ({counted}, {lit} lit)"
        );
        assert!(
            mean < 1.0,
            "seed {seed}: the terms' sum is off by {mean:.3} of 255 on average"
        );
    }
}

/// Where a world point appears in a frame of [`SIZE`], in pixels from the
/// top left, unrounded.
fn screen_point(camera: &Camera, p: Vec3) -> Vec2 {
    let clip = camera.view_projection(SIZE.0 as f32 / SIZE.1 as f32) * p.extend(1.0);
    let ndc = clip.truncate() / clip.w;
    Vec2::new(
        (ndc.x * 0.5 + 0.5) * SIZE.0 as f32,
        (0.5 - ndc.y * 0.5) * SIZE.1 as f32,
    )
}

/// The motion view's vector at a pixel, in pixels: its colour is a hue
/// (three cosines a third of a turn apart, scene.wgsl's `motion_color`)
/// times the length over [`MOTION_FULL_PIXELS`], and the hue's three
/// components summed along their own directions are 3/4 of the unit
/// vector of the motion.
fn motion_at(img: &RgbaImage, pixel: (u32, u32)) -> Vec2 {
    let c = value(img, pixel);
    let third = std::f32::consts::TAU / 3.0;
    let along = |k: f32| Vec2::new((k * third).cos(), (k * third).sin());
    (c.x * along(0.0) + c.y * along(1.0) + c.z * along(-1.0)) * MOTION_FULL_PIXELS / 0.75
}

#[test]
fn a_panning_cameras_floor_moves_on_screen_as_the_camera_does() {
    for seed in [0, 1] {
        let (config, scene) = room_with_ball(ball_at(seed));
        let mut snap = snapshot(&config, FrameView::Motion, 4);
        let before = camera(&config);
        // A turn to the side and a step along, a few pixels' worth.
        let step = Vec3::new(0.03 + 0.01 * seed as f32, 0.0, 0.02);
        let after = Camera {
            eye: before.eye + step,
            target: before.target + step + Vec3::new(0.03, 0.0, 0.0),
            ..before
        };
        snap.capture(&scene, &before).expect("frame");
        let img = snap.capture(&scene, &after).expect("frame");
        for k in 0..12 {
            let point = Vec3::new(-1.6 + 0.3 * k as f32, 0.0, 0.6 - 0.1 * k as f32);
            // The motion view writes where each point was the frame before,
            // from where it is now.
            let expected = screen_point(&before, point) - screen_point(&after, point);
            assert!(
                expected.length() > 2.0,
                "seed {seed}: the pan is too small to see"
            );
            let read = motion_at(&img, pixel(&config, point));
            assert!(
                (read - expected).length() < 1.0,
                "seed {seed}: at {point} the floor moved {read} pixels, the cameras say {expected}"
            );
        }
    }
}

#[test]
fn multisampled_edges_are_none_with_one_sample_and_on_outlines_with_four() {
    let white = |img: &RgbaImage, (x, y): (u32, u32)| img.get_pixel(x, y).0[0] > 128;
    for seed in [0, 1] {
        let ball = ball_at(seed);
        let (config, scene) = room_with_ball(ball);
        let single = drawn(&config, &scene, FrameView::MsaaEdges, 1);
        assert!(
            single.pixels().all(|p| p.0[..3] == [0, 0, 0]),
            "seed {seed}"
        );
        let mut snap = snapshot(&config, FrameView::MsaaEdges, 4);
        let four = snap.capture(&scene, &camera(&config)).expect("frame");
        let caption = snap.renderer.caption(&scene, &camera(&config));
        let backend = snap.gpu.adapter.get_info().backend;
        if backend == wgpu::Backend::Gl && caption.contains("empty here") {
            // An adapter whose multisamples cannot be read (OpenGL) says
            // so, and shows no edge rather than wrong ones.
            println!("seed {seed}: {caption}");
            assert!(four.pixels().all(|p| p.0[..3] == [0, 0, 0]), "seed {seed}");
            continue;
        }
        // Along the ball's outline (a circle about its centre), and nowhere
        // on the open floor.
        let (cx, cy) = pixel(&config, ball);
        let outline = four
            .enumerate_pixels()
            .filter(|(x, y, _)| {
                let d = Vec2::new(*x as f32 - cx as f32, *y as f32 - cy as f32).length();
                d < 25.0 && white(&four, (*x, *y))
            })
            .count();
        assert!(
            outline > 10,
            "seed {seed}: {outline} edge pixels at the ball"
        );
        for k in 0..20 {
            let floor = Vec3::new(-1.5 + 0.15 * k as f32, 0.0, 0.5);
            assert!(
                !white(&four, pixel(&config, floor)),
                "seed {seed}: the open floor at {floor} counts as an edge"
            );
        }
    }
}
