//! The debug views checked by pictures: each changes the frame, and only
//! where it should: the line views within a few pixels of their own
//! segments, the rest view within the bodies it recolours.
//!
//! These draw off-screen on whatever adapter exists (lavapipe in CI).

use glam::{DVec3, Vec2, Vec3};
use image::RgbaImage;
use rolypoly_physics::{BallPlacement, Event, World, WorldConfig};
use rolypoly_render::{
    Camera, DebugLayer, DebugViews, LineVertex, RenderSettings, SceneView, Snapshot, speed_color,
};

const SIZE: (u32, u32) = (480, 270);
/// How far (pixels) a line's pixels may lie from its segment: its own
/// width and the multisampled edge.
const NEAR_LINE: f32 = 2.5;

fn camera() -> Camera {
    Camera {
        eye: Vec3::new(0.0, 1.0, 4.6),
        target: Vec3::new(0.0, 0.4, 0.0),
        fov_y_deg: 50.0,
    }
}

/// A column of two balls resting on the floor, a ball in flight, and the
/// default tumblers, `seconds` in; with the last step's events.
fn world(seconds: f64, seed: u64) -> (World, Vec<Event>) {
    let mut cfg = WorldConfig::default();
    cfg.balls.count = 0;
    let r = cfg.balls.radius;
    let x = 0.6 + 0.1 * seed as f64;
    cfg.balls.placements = vec![
        BallPlacement::new(DVec3::new(x, r, 2.0), DVec3::ZERO),
        BallPlacement::new(DVec3::new(x, 3.0 * r, 2.0), DVec3::ZERO),
        BallPlacement::new(DVec3::new(-1.0, 1.0, 1.8), DVec3::new(1.5, 3.0, 0.0)),
    ];
    let mut world = World::new(cfg, seed).expect("scene builds");
    let mut events = Vec::new();
    for _ in 0..(seconds / world.config().solver.dt).round() as usize {
        world.step();
        world.take_events(&mut events);
    }
    (world, events)
}

fn draw(snap: &mut Snapshot, view: &SceneView) -> RgbaImage {
    snap.capture(view, &camera()).expect("frame")
}

/// Where a point shows in the frame (pixels from the top left).
fn project(p: Vec3) -> Vec2 {
    let (w, h) = SIZE;
    let clip = camera().view_projection(w as f32 / h as f32) * p.extend(1.0);
    let ndc = clip.truncate() / clip.w;
    Vec2::new(
        (ndc.x * 0.5 + 0.5) * w as f32,
        (0.5 - ndc.y * 0.5) * h as f32,
    )
}

fn distance_to_segment(p: Vec2, a: Vec2, b: Vec2) -> f32 {
    let ab = b - a;
    let t = if ab.length_squared() > 0.0 {
        ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0)
    } else {
        0.0
    };
    p.distance(a + ab * t)
}

/// The pixels where two frames differ by more than 12/255.
fn differing(a: &RgbaImage, b: &RgbaImage) -> Vec<Vec2> {
    a.enumerate_pixels()
        .zip(b.pixels())
        .filter(|((_, _, p), q)| (0..3).any(|c| p.0[c].abs_diff(q.0[c]) > 12))
        .map(|((x, y, _), _)| Vec2::new(x as f32 + 0.5, y as f32 + 0.5))
        .collect()
}

/// The lines as drawn: each segment cut into short pieces, those wholly in
/// front of the eye projected (the GPU clips what crosses the near plane).
fn segments(lines: &[LineVertex]) -> Vec<(Vec2, Vec2)> {
    const PIECES: usize = 32;
    let (w, h) = SIZE;
    let view_proj = camera().view_projection(w as f32 / h as f32);
    let in_front = |p: Vec3| (view_proj * p.extend(1.0)).w > 0.05;
    let mut out = Vec::new();
    for s in lines.chunks_exact(2) {
        let (a, b) = (Vec3::from(s[0].position), Vec3::from(s[1].position));
        for k in 0..PIECES {
            let p = a.lerp(b, k as f32 / PIECES as f32);
            let q = a.lerp(b, (k + 1) as f32 / PIECES as f32);
            if in_front(p) && in_front(q) {
                out.push((project(p), project(q)));
            }
        }
    }
    out
}

#[test]
fn each_line_view_changes_the_frame_only_along_its_lines() {
    let config = WorldConfig::default();
    let (w, h) = SIZE;
    let mut snap = Snapshot::new(&config, RenderSettings::default(), w, h, None)
        .unwrap_or_else(|e| panic!("cannot render: {e}"));
    for (seconds, seed) in [(0.5, 1), (0.7, 2)] {
        let (world, events) = world(seconds, seed);
        // Without the glow, which spreads a bright line's light further.
        let mut plain = SceneView::from_world(&world, None);
        plain.light.bloom = None;
        let without = draw(&mut snap, &plain);
        for layer in [
            DebugLayer::Contacts,
            DebugLayer::Impulses,
            DebugLayer::Velocities,
            DebugLayer::Grid,
            DebugLayer::Com,
        ] {
            let mut views = DebugViews::default();
            views.set(layer, true);
            let shown = plain.clone().with_debug(&world, &events, &views);
            let lines: Vec<LineVertex> = shown
                .debug_lines
                .iter()
                .chain(&shown.debug_lines_over)
                .copied()
                .collect();
            assert!(!lines.is_empty(), "{}: no lines", layer.name());
            let with = draw(&mut snap, &shown);
            let changed = differing(&without, &with);
            assert!(
                changed.len() >= 8,
                "{}: {} pixels changed",
                layer.name(),
                changed.len()
            );
            let segs = segments(&lines);
            let stray = changed
                .iter()
                .filter(|&&p| {
                    segs.iter()
                        .all(|&(a, b)| distance_to_segment(p, a, b) > NEAR_LINE)
                })
                .count();
            assert!(
                stray * 50 <= changed.len(),
                "{} at {seconds} s: {stray} of {} changed pixels are off its lines",
                layer.name(),
                changed.len()
            );
        }
    }
}

#[test]
fn the_rest_view_recolours_the_bodies_by_speed_and_nothing_else() {
    let config = WorldConfig::default();
    let (w, h) = SIZE;
    let mut snap = Snapshot::new(&config, RenderSettings::default(), w, h, None)
        .unwrap_or_else(|e| panic!("cannot render: {e}"));
    let (world, events) = world(0.5, 1);
    let mut plain = SceneView::from_world(&world, None);
    plain.light.bloom = None;
    let mut views = DebugViews::default();
    views.set(DebugLayer::Rest, true);
    let shown = plain.clone().with_debug(&world, &events, &views);
    // The resting column is grey; the ball in flight is not.
    let colors: Vec<Vec3> = shown.balls.iter().map(|b| b.color).collect();
    assert_eq!(colors[0], speed_color(0.0));
    assert_eq!(colors[1], speed_color(0.0));
    assert_ne!(colors[2], speed_color(0.0));
    let changed = differing(&draw(&mut snap, &plain), &draw(&mut snap, &shown));
    assert!(changed.len() >= 100, "{} pixels changed", changed.len());
    // Every changed pixel lies on a body: within a ball's outline or a
    // tumbler's bounding circle (a little wider for their edges and the
    // light they bounce on the floor close by).
    let (_, aspect) = (0, w as f32 / h as f32);
    let view_proj = camera().view_projection(aspect);
    let pixels_per_metre = |p: Vec3| {
        let clip = view_proj * p.extend(1.0);
        0.5 * h as f32 / ((camera().fov_y_deg.to_radians() * 0.5).tan() * clip.w)
    };
    let mut discs: Vec<(Vec2, f32)> = shown
        .balls
        .iter()
        .map(|b| {
            (
                project(b.position),
                b.radius * 1.6 * pixels_per_metre(b.position) + 2.0,
            )
        })
        .collect();
    for t in world.tumblers() {
        let c = t.center_of_mass().as_vec3();
        discs.push((project(c), 0.6 * pixels_per_metre(c)));
    }
    let stray = changed
        .iter()
        .filter(|&&p| discs.iter().all(|&(c, r)| p.distance(c) > r))
        .count();
    assert!(
        stray * 50 <= changed.len(),
        "{stray} of {} changed pixels are off the bodies",
        changed.len()
    );
}

#[test]
fn nothing_shown_draws_no_line_and_changes_no_pixel() {
    let (world, events) = world(0.5, 3);
    let plain = SceneView::from_world(&world, None);
    let shown = plain
        .clone()
        .with_debug(&world, &events, &DebugViews::default());
    assert_eq!(shown, plain);
}

#[test]
fn views_are_named_in_a_list_and_an_unknown_name_lists_them() {
    let views = DebugViews::parse("contacts, grid").unwrap();
    assert!(views.shows(DebugLayer::Contacts) && views.shows(DebugLayer::Grid));
    assert!(!views.shows(DebugLayer::Rest));
    assert_eq!(views.to_string(), "contacts,grid");
    for layer in DebugLayer::ALL {
        assert!(DebugViews::parse(layer.name()).unwrap().shows(layer));
    }
    let error = DebugViews::parse("contacts,bogus").unwrap_err();
    assert!(error.contains("`bogus`"), "{error}");
    assert!(
        error.contains("contacts, impulses, velocities, grid, rest, com"),
        "{error}"
    );
}
