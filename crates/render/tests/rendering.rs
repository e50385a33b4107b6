//! Rendering checked by pictures (R1-R3, R6): golden frames of the default
//! scene, shadows where a tumbler or a ball hides the light, balls drawn as
//! the exact spheres they are, and MSAA on silhouettes.
//!
//! These draw off-screen on whatever adapter exists (lavapipe in CI). No
//! adapter is a failure, never a skip.

use glam::{Vec2, Vec3};
use image::RgbaImage;
use rolypoly_physics::{World, WorldConfig};
use rolypoly_render::{BallView, Camera, Gpu, RenderSettings, SceneView, Snapshot};

mod common;
use common::{check_golden, pixel_of};

fn snapshot(config: &WorldConfig, settings: RenderSettings, w: u32, h: u32) -> Snapshot {
    Snapshot::new(config, settings, w, h, None).unwrap_or_else(|e| panic!("cannot render: {e}"))
}

fn world_at(config: &WorldConfig, seed: u64, seconds: f64) -> World {
    let mut world = World::new(config.clone(), seed).expect("scene builds");
    for _ in 0..(seconds / config.solver.dt).round() as usize {
        world.step();
    }
    world
}

fn luminance(img: &RgbaImage, x: u32, y: u32) -> f32 {
    let p = img.get_pixel(x, y).0;
    (0.2126 * p[0] as f32 + 0.7152 * p[1] as f32 + 0.0722 * p[2] as f32) / 255.0
}

/// The frame with the default settings, and with the settings `change`
/// makes of them.
fn default_and(
    change: impl FnOnce(&mut RenderSettings),
    config: &WorldConfig,
    view: &SceneView,
    camera: &Camera,
    (w, h): (u32, u32),
) -> (RgbaImage, RgbaImage) {
    let mut changed = RenderSettings::default();
    change(&mut changed);
    let [default, changed] = [RenderSettings::default(), changed].map(|settings| {
        snapshot(config, settings, w, h)
            .capture(view, camera)
            .expect("frame")
    });
    (default, changed)
}

// --- golden frames ---------------------------------------------------------

#[test]
fn default_scene_matches_its_golden_frames() {
    let config = WorldConfig::default();
    let mut snap = snapshot(&config, RenderSettings::default(), 480, 270);
    let camera = Camera::overview(config.room.size.as_vec3());
    for (name, seconds) in [("default-t0", 0.0), ("default-t2", 2.0)] {
        let world = world_at(&config, 1, seconds);
        let frame = snap
            .capture(&SceneView::from_world(&world, None), &camera)
            .expect("frame");
        check_golden(name, &frame);
    }
}

/// OpenGL is where a machine without Vulkan draws, and it differs: there a
/// texture's kind is fixed when it is made, and six square layers became a
/// cube map that the shadow lookup saw as all shadow. Its frames must match
/// the same goldens.
#[test]
fn opengl_draws_the_same_golden_frame() {
    let gpu = Gpu::headless_on(&[wgpu::Backends::GL])
        .unwrap_or_else(|e| panic!("no OpenGL adapter: {e}"));
    let config = WorldConfig::default();
    let mut snap = Snapshot::on(gpu, &config, RenderSettings::default(), 480, 270, None)
        .unwrap_or_else(|e| panic!("cannot render on OpenGL: {e}"));
    let camera = Camera::overview(config.room.size.as_vec3());
    let world = world_at(&config, 1, 2.0);
    let frame = snap
        .capture(&SceneView::from_world(&world, None), &camera)
        .expect("frame");
    check_golden("default-t2", &frame);
}

// --- shadows -----------------------------------------------------------------

#[test]
fn a_tumbler_shadows_the_floor_and_lit_floor_is_unchanged() {
    let mut config = WorldConfig::default();
    config.balls.count = 0;
    let (w, h) = (320, 180);
    let world = world_at(&config, 1, 0.0);
    let view = SceneView::from_world(&world, None);
    let camera = Camera::overview(view.room_size);
    // Where the light, through the middle of tumbler 3's body, meets the floor.
    let t = &view.tumblers[3];
    let body = t.position + Vec3::new(0.0, 0.25, 0.0);
    let light = view.light.position;
    let along = light.y / (light.y - body.y);
    let shaded_point = light + (body - light) * along;
    // A floor point the light sees directly: beside the tumbler, well clear.
    let side = (shaded_point - t.position).cross(Vec3::Y).normalize() * 1.2;
    let lit_point = shaded_point + side;
    for tumbler in &view.tumblers {
        assert!(
            Vec2::new(
                lit_point.x - tumbler.position.x,
                lit_point.z - tumbler.position.z
            )
            .length()
                > 0.8
        );
    }
    let shaded = pixel_of(&camera, shaded_point, w, h);
    let lit = pixel_of(&camera, lit_point, w, h);

    let (on, off) = default_and(|s| s.shadows = false, &config, &view, &camera, (w, h));

    let (s_on, s_off) = (
        luminance(&on, shaded.0, shaded.1),
        luminance(&off, shaded.0, shaded.1),
    );
    assert!(
        // The bounce light fills the shadow (0.83 of the light kept here,
        // as faint as the path-traced reference shows it); without
        // shadows it would keep all.
        s_on < 0.9 * s_off,
        "shadowed floor: {s_on:.3} with shadows, {s_off:.3} without"
    );
    let (l_on, l_off) = (luminance(&on, lit.0, lit.1), luminance(&off, lit.0, lit.1));
    assert!(
        (l_on - l_off).abs() < 2.0 / 255.0,
        "lit floor: {l_on:.3} with shadows, {l_off:.3} without"
    );
}

// --- MSAA --------------------------------------------------------------------

/// Share of strong horizontal edges whose middle pixel lies strictly between
/// its neighbours (a blend of the two sides).
fn blended_edge_share(img: &RgbaImage) -> (f64, usize) {
    let (mut edges, mut blended) = (0usize, 0usize);
    for y in 0..img.height() {
        for x in 1..img.width() - 1 {
            let (a, m, b) = (
                luminance(img, x - 1, y),
                luminance(img, x, y),
                luminance(img, x + 1, y),
            );
            let jump = (b - a).abs();
            if jump < 0.25 {
                continue;
            }
            edges += 1;
            let (lo, hi) = (a.min(b), a.max(b));
            if m > lo + 0.15 * jump && m < hi - 0.15 * jump {
                blended += 1;
            }
        }
    }
    (blended as f64 / edges.max(1) as f64, edges)
}

/// The blended share of strong edges (see [`blended_edge_share`]) in a
/// 240 x 160 frame at 4x MSAA and at 1x, once both show enough edges of
/// `what` to judge.
fn blended_shares_at_4x_and_1x(
    config: &WorldConfig,
    view: &SceneView,
    camera: &Camera,
    what: &str,
) -> (f64, f64) {
    let (four, one) = default_and(|s| s.msaa = 1, config, view, camera, (240, 160));
    let (share4, edges4) = blended_edge_share(&four);
    let (share1, edges1) = blended_edge_share(&one);
    assert!(
        edges4 > 20 && edges1 > 20,
        "no {what} in view ({edges4}, {edges1} edges)"
    );
    (share4, share1)
}

#[test]
fn msaa_blends_silhouette_edges() {
    let mut config = WorldConfig::default();
    config.balls.count = 0;
    let world = world_at(&config, 1, 0.0);
    let view = SceneView::from_world(&world, None);
    // Close to a tumbler, its outline against the wall behind.
    let camera = Camera {
        eye: Vec3::new(-2.2, 0.6, 0.2),
        target: Vec3::new(-2.2, 0.45, -1.2),
        fov_y_deg: 50.0,
    };
    let (share4, share1) = blended_shares_at_4x_and_1x(&config, &view, &camera, "silhouette");
    // (Some strong edges are texture and shading, which blend either way.)
    assert!(
        share4 > 0.25,
        "with 4x only {:.0}% of edge pixels are blends",
        100.0 * share4
    );
    assert!(
        share4 > 2.0 * share1,
        "4x {:.0}% vs 1x {:.0}% blended edge pixels",
        100.0 * share4,
        100.0 * share1
    );
}

// --- balls -------------------------------------------------------------------

/// The room alone, without balls or tumblers, and a camera close to where
/// the balls are placed.
fn empty_room_and_close_camera() -> (WorldConfig, SceneView, Camera) {
    let mut config = WorldConfig::default();
    config.balls.count = 0;
    let world = world_at(&config, 1, 0.0);
    let mut view = SceneView::from_world(&world, None);
    view.tumblers.clear();
    // Close: the nearer the eye, the more of a sphere's outline lies
    // outside the circle of its radius around the centre.
    let camera = Camera {
        eye: Vec3::new(0.3, 1.25, 0.85),
        target: Vec3::new(0.18, 1.02, 0.0),
        fov_y_deg: 65.0,
    };
    (config, view, camera)
}

/// A red ball and a blue one sunk into it, closer to the camera on one side
/// and further on the other, so that each hides part of the other.
fn two_balls_that_meet() -> Vec<BallView> {
    vec![
        BallView {
            position: Vec3::new(0.0, 1.0, 0.0),
            radius: 0.3,
            color: Vec3::new(0.9, 0.08, 0.05),
        },
        BallView {
            position: Vec3::new(0.38, 1.05, 0.1),
            radius: 0.25,
            color: Vec3::new(0.05, 0.15, 0.9),
        },
    ]
}

/// Where the ray `origin + t dir` (`dir` of unit length) meets a ball: the
/// distance `t` of the first hit, or `None`, and how far the ray passes from
/// the centre in radii.
fn trace(ball: &BallView, origin: Vec3, dir: Vec3) -> (Option<f32>, f32) {
    let to_origin = origin - ball.position;
    let along = to_origin.dot(dir);
    let across = (to_origin - along * dir).length();
    let hit = (across < ball.radius)
        .then(|| -along - (ball.radius * ball.radius - across * across).sqrt());
    (hit, across / ball.radius)
}

#[test]
fn balls_are_exact_spheres_that_hide_each_other_where_they_meet() {
    let (config, mut view, camera) = empty_room_and_close_camera();
    // A black room, that no part of a ball (not even its white highlight)
    // is mistaken for, and no glow or occlusion to spread a ball's colour
    // beyond its outline. The ambient light stays even: a black room
    // bounces none, which would leave the balls' dark sides black too.
    view.room_colors = [Vec3::ZERO; 6];
    view.light.bloom = None;
    view.light.occlusion = false;
    view.light.indirect = false;
    let (w, h) = (240, 160);
    // One sample per pixel and no shadows: a pixel is a ball's exactly when
    // the ray through its centre meets that ball first.
    let settings = RenderSettings {
        msaa: 1,
        shadows: false,
        ..RenderSettings::default()
    };
    let mut snap = snapshot(&config, settings, w, h);
    let empty = snap.capture(&view, &camera).expect("frame");
    view.balls = two_balls_that_meet();
    let frame = snap.capture(&view, &camera).expect("frame");

    let (mut checked, mut wrong) = ([0usize; 3], Vec::new());
    for y in 0..h {
        for x in 0..w {
            let centre = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
            let (origin, dir) = camera.ray(centre, Vec2::new(w as f32, h as f32));
            let hits = [0, 1].map(|k| trace(&view.balls[k], origin, dir));
            // Leave out the pixels that a hair decides: on an outline, or
            // where the two surfaces are at nearly the same depth.
            let near_outline = hits.iter().any(|(_, miss)| (miss - 1.0).abs() < 0.03);
            let expected = match (hits[0].0, hits[1].0) {
                (Some(a), Some(b)) if (a - b).abs() < 0.01 => continue,
                (Some(a), Some(b)) => Some(usize::from(b < a)),
                (Some(_), None) => Some(0),
                (None, Some(_)) => Some(1),
                (None, None) => None,
            };
            if near_outline {
                continue;
            }
            let (p, q) = (frame.get_pixel(x, y).0, empty.get_pixel(x, y).0);
            let changed = (0..3).any(|c| p[c].abs_diff(q[c]) > 24);
            let seen = changed.then(|| usize::from(p[2] > p[0]));
            checked[expected.map_or(2, |k| k)] += 1;
            if seen != expected {
                wrong.push((x, y, expected, seen));
            }
        }
    }
    assert!(
        checked.iter().all(|&n| n > 500),
        "red, blue and wall pixels checked: {checked:?}"
    );
    assert!(
        wrong.is_empty(),
        "{} pixels are not what the spheres show, e.g. {:?}",
        wrong.len(),
        &wrong[..wrong.len().min(8)]
    );
}

#[test]
fn msaa_smooths_the_outlines_of_balls() {
    let (config, mut view, camera) = empty_room_and_close_camera();
    view.balls = two_balls_that_meet();
    let (share4, share1) = blended_shares_at_4x_and_1x(&config, &view, &camera, "outline");
    assert!(
        share4 > 0.25 && share4 > 2.0 * share1,
        "4x {:.0}% vs 1x {:.0}% blended edge pixels",
        100.0 * share4,
        100.0 * share1
    );
}

#[test]
fn a_ball_casts_a_round_shadow_on_the_floor() {
    let (config, mut view, _) = empty_room_and_close_camera();
    let camera = Camera::overview(view.room_size);
    let ball = BallView {
        position: Vec3::new(1.2, 1.2, 0.8),
        radius: 0.25,
        color: Vec3::splat(0.9),
    };
    view.balls = vec![ball];
    let (w, h) = (320, 180);
    // The shadow's centre, where the light's ray through the ball's centre
    // meets the floor, and roughly its radius there.
    let light = view.light.position;
    let along = light.y / (light.y - ball.position.y);
    let shadow_centre = light + (ball.position - light) * along;
    let shadow_radius = ball.radius * along;
    let away = (shadow_centre - light).cross(Vec3::Y).normalize();
    let points = [
        shadow_centre,
        shadow_centre + away * (0.6 * shadow_radius),
        shadow_centre + away * (2.0 * shadow_radius),
    ];
    let pixels = points.map(|p| pixel_of(&camera, p, w, h));
    // The camera sees the floor there, not the ball.
    for &(x, y) in &pixels {
        let centre = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
        let (origin, dir) = camera.ray(centre, Vec2::new(w as f32, h as f32));
        assert!(trace(&ball, origin, dir).0.is_none());
    }
    let (on, off) = default_and(|s| s.shadows = false, &config, &view, &camera, (w, h));
    let ratio = |(x, y): (u32, u32)| luminance(&on, x, y) / luminance(&off, x, y);
    let [middle, inside, outside] = pixels.map(ratio);
    // The bounce light fills the shadow: its centre keeps 0.73 of the
    // light (measured), not none.
    assert!(
        middle < 0.8,
        "the shadow's centre keeps {middle:.2} of its light"
    );
    assert!(inside < 0.8, "inside the shadow's edge keeps {inside:.2}");
    assert!(
        (outside - 1.0).abs() < 0.02,
        "beside the shadow the floor keeps {outside:.2} of its light"
    );
}

/// The early depth test only drops fragments that would have lost the
/// depth test anyway: a crowd of balls, each hiding others and shadowing
/// them, comes out the same with it as without it. (Mesa's software
/// renderers test such fragments late either way, so there this checks
/// that the setting changes nothing else; a GPU tests them early. That the
/// written depth keeps its promise is checked on every adapter by
/// `balls_are_exact_spheres_that_hide_each_other_where_they_meet`: a square
/// standing behind the sphere's surface would bury the surface in it.)
#[test]
fn early_ball_depth_changes_no_pixel() {
    let mut config = WorldConfig::default();
    config.balls.count = 3000;
    config.room.size = glam::DVec3::new(6.0, 4.0, 6.0);
    let world = world_at(&config, 1, 0.5);
    let view = SceneView::from_world(&world, None);
    let camera = Camera::overview(view.room_size);
    let (early, late) = default_and(
        |s| s.early_ball_depth = false,
        &config,
        &view,
        &camera,
        (320, 180),
    );
    let differing = early
        .pixels()
        .zip(late.pixels())
        .filter(|(a, b)| (0..3).any(|c| a.0[c].abs_diff(b.0[c]) > 2))
        .count();
    // A pixel where two balls meet at the same depth may go either way.
    assert!(
        differing <= 10,
        "{differing} of {} pixels differ",
        320 * 180
    );
}

/// A ball whose surface is nearer the eye than the camera's near plane (2
/// cm) is still drawn where it is further than that: its square, which
/// would stand in front of the near plane, is moved back behind it.
#[test]
fn a_ball_a_centimetre_from_the_eye_is_still_drawn() {
    let (config, mut view, _) = empty_room_and_close_camera();
    let ball = BallView {
        position: Vec3::new(0.0, 1.0, 0.0),
        radius: 0.3,
        color: Vec3::new(0.9, 0.08, 0.05),
    };
    view.balls = vec![ball];
    let camera = Camera {
        eye: ball.position + Vec3::new(0.0, 0.0, ball.radius + 0.01),
        target: ball.position,
        fov_y_deg: 65.0,
    };
    let settings = RenderSettings {
        msaa: 1,
        ..RenderSettings::default()
    };
    let frame = snapshot(&config, settings, 64, 36)
        .capture(&view, &camera)
        .expect("frame");
    // Seen from a centimetre away the ball fills the view, except a ring
    // around the middle that is nearer than the near plane.
    let (w, h) = frame.dimensions();
    let red = |x: u32, y: u32| {
        let p = frame.get_pixel(x, y).0;
        p[0] > 2 * p[1].max(p[2]) && p[0] > 20
    };
    let corners = [(0, 0), (w - 1, 0), (0, h - 1), (w - 1, h - 1)];
    assert!(
        corners.iter().all(|&(x, y)| red(x, y)),
        "corners {:?}",
        corners.map(|(x, y)| frame.get_pixel(x, y).0)
    );
}

#[test]
fn draw_calls_do_not_depend_on_the_ball_count() {
    let mut calls = Vec::new();
    for balls in [0, 30, 2000] {
        let mut config = WorldConfig::default();
        config.balls.count = balls;
        let world = world_at(&config, 1, 0.0);
        let mut snap = snapshot(&config, RenderSettings::default(), 64, 36);
        let view = SceneView::from_world(&world, None);
        let stats = snap
            .draw(&view, &Camera::overview(view.room_size))
            .expect("frame");
        calls.push(stats.draw_calls);
    }
    // With no balls there is nothing to instance; with any, one draw per pass.
    assert_eq!(calls[1], calls[2], "draw calls {calls:?}");
    assert!(calls[0] < calls[1]);
}

#[test]
fn a_zero_sized_frame_is_an_error_not_a_panic() {
    let config = WorldConfig::default();
    let err = Snapshot::new(&config, RenderSettings::default(), 0, 10, None)
        .err()
        .expect("must fail");
    assert!(err.to_string().contains("0x10"), "{err}");
}

#[test]
fn grab_mode_draws_a_white_arrow_cursor_where_it_is_told() {
    let mut config = WorldConfig::default();
    config.balls.count = 0;
    let world = world_at(&config, 1, 0.0);
    let view = SceneView::from_world(&world, None);
    let camera = Camera::overview(view.room_size);
    let mut snap = snapshot(&config, RenderSettings::default(), 160, 90);
    let plain = snap.capture(&view, &camera).expect("frame");
    snap.renderer.set_cursor(Some(Vec2::new(40.0, 20.0)));
    let with = snap.capture(&view, &camera).expect("frame");
    // Inside the arrow, just below its tip: white; its outline is black.
    let inside = with.get_pixel(42, 30).0;
    assert!(inside[..3].iter().all(|&c| c > 240), "{inside:?}");
    let outline = with.get_pixel(39, 26).0;
    assert!(outline[..3].iter().all(|&c| c < 40), "{outline:?}");
    // Elsewhere the frame is untouched.
    assert_eq!(with.get_pixel(120, 70), plain.get_pixel(120, 70));
    snap.renderer.set_cursor(None);
    assert_eq!(snap.capture(&view, &camera).expect("frame"), plain);
}

/// Where the adapter has timestamp queries, the frame's passes come back
/// timed within a few frames once timing is asked for (each shorter than
/// the frame took on the clock); where it has none, no times are made up.
#[test]
fn the_passes_are_timed_on_the_gpu_where_it_can() {
    let config = WorldConfig::default();
    let mut snap = snapshot(&config, RenderSettings::default(), 160, 90);
    snap.renderer.set_gpu_timing(&snap.gpu, true);
    let has_timestamps = snap
        .gpu
        .device
        .features()
        .contains(wgpu::Features::TIMESTAMP_QUERY);
    let mut view = SceneView::from_world(&world_at(&config, 1, 0.5), None);
    let camera = Camera::overview(view.room_size);
    let mut timed = None;
    for _ in 0..6 {
        // The light moves, so that every frame draws its shadow faces.
        view.light.position.x += 0.01;
        let started = std::time::Instant::now();
        let stats = snap.draw(&view, &camera).expect("frame");
        if let Some(times) = stats.gpu {
            timed = Some((times, started.elapsed()));
        }
    }
    match timed {
        Some((times, _)) => {
            assert!(has_timestamps);
            for (name, t) in times.named() {
                assert!(t < std::time::Duration::from_secs(5), "{name}: {t:?}");
            }
            assert!(times.scene > std::time::Duration::ZERO, "{times:?}");
            assert!(times.shadow > std::time::Duration::ZERO, "{times:?}");
        }
        None => assert!(!has_timestamps, "timestamps never came back"),
    }
    eprintln!("timestamps: {has_timestamps}, {timed:?}");
}

/// Timestamps cost nothing unless someone profiles, and a frame resolves
/// only the slots its passes wrote: resolving an unwritten slot holds the
/// submission for about 20 s on some drivers (NVIDIA's on Vulkan).
#[test]
fn timestamps_are_written_only_while_timed_and_resolved_only_where_written() {
    let config = WorldConfig::default();
    let view = SceneView::from_world(&world_at(&config, 1, 0.0), None);
    let camera = Camera::overview(view.room_size);
    for shadows in [true, false] {
        let settings = RenderSettings {
            shadows,
            ..RenderSettings::default()
        };
        let mut snap = snapshot(&config, settings, 64, 36);
        let untimed = snap.draw(&view, &camera).expect("frame");
        assert_eq!(untimed.stamps, Default::default(), "shadows {shadows}");
        snap.renderer.set_gpu_timing(&snap.gpu, true);
        // The light moved: every shadow face is drawn again.
        let mut moved = view.clone();
        moved.light.position.x += 0.1;
        let timed = snap.draw(&moved, &camera).expect("frame");
        assert_eq!(
            timed.stamps.resolved, timed.stamps.written,
            "shadows {shadows}"
        );
        if snap
            .gpu
            .device
            .features()
            .contains(wgpu::Features::TIMESTAMP_QUERY)
        {
            // The scene and tone mapping's slots always; the shadow faces'
            // only when they are drawn.
            let shadow_slots = 0b11;
            let expected = 0b11_1100 | if shadows { shadow_slots } else { 0 };
            assert_eq!(timed.stamps.written, expected, "shadows {shadows}");
        }
        snap.renderer.set_gpu_timing(&snap.gpu, false);
        let off_again = snap.draw(&view, &camera).expect("frame");
        assert_eq!(off_again.stamps, Default::default(), "shadows {shadows}");
    }
}

/// A frame drawn with the frame before's shadow faces, where their casters
/// did not move, and the same frame drawn anew with every face.
fn drawn_after(
    config: &WorldConfig,
    before: &SceneView,
    now: &SceneView,
    camera: &Camera,
) -> (u32, RgbaImage, RgbaImage) {
    let settings = RenderSettings::default();
    let mut kept = snapshot(config, settings, 160, 90);
    kept.draw(before, camera).expect("frame");
    let stats = kept
        .target
        .render(&kept.gpu, &mut kept.renderer, now, camera)
        .expect("frame");
    let frame = kept.target.read(&kept.gpu, "the frame").expect("read");
    let anew = snapshot(config, settings, 160, 90)
        .capture(now, camera)
        .expect("frame");
    (stats.shadow_faces, frame, anew)
}

#[test]
fn a_shadow_face_is_drawn_again_only_when_its_light_or_casters_moved() {
    for (seed, seconds) in [(1, 2.0), (4, 0.7)] {
        let config = WorldConfig::default();
        let world = world_at(&config, seed, seconds);
        let view = SceneView::from_world(&world, None);
        let camera = Camera::overview(view.room_size);

        // Nothing moved: no face is drawn, and the frame is the same.
        let (faces, frame, anew) = drawn_after(&config, &view, &view, &camera);
        assert_eq!(faces, 0, "seed {seed}");
        assert!(frame == anew, "seed {seed}: a frame of kept faces differs");

        // One ball moved: the faces it was in or is in now, not all six.
        let mut rolled = view.clone();
        rolled.balls[3].position += Vec3::new(0.3, 0.0, -0.2);
        let (faces, frame, anew) = drawn_after(&config, &view, &rolled, &camera);
        assert!((1..6).contains(&faces), "seed {seed}: {faces} faces");
        assert!(
            frame == anew,
            "seed {seed}: the moved ball's shadow is stale"
        );

        // A tumbler moved, and the light: every face the light lights anew.
        let mut rocked = view.clone();
        rocked.tumblers[0].position.x += 0.2;
        let (faces, frame, anew) = drawn_after(&config, &view, &rocked, &camera);
        assert!(faces >= 1, "seed {seed}");
        assert!(frame == anew, "seed {seed}: the tumbler's shadow is stale");
        let mut lamp = view.clone();
        lamp.light.position.z += 0.05;
        let (faces, frame, anew) = drawn_after(&config, &view, &lamp, &camera);
        assert_eq!(faces, 6, "seed {seed}");
        assert!(frame == anew, "seed {seed}");
    }
}
