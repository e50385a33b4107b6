//! The debug views checked by pictures: each changes the frame, and only
//! where it should: the marks within their own sizes (and outlines) of
//! where they are drawn, the rest view within the bodies it recolours;
//! and each is seen from the default camera at any size and quality.
//!
//! These draw off-screen on whatever adapter exists (lavapipe in CI).

use glam::{DVec3, Vec2, Vec3};
use image::RgbaImage;
use rolypoly_physics::{BallPlacement, Event, World, WorldConfig};
use rolypoly_render::{
    Camera, DebugLayer, DebugMark, DebugViews, MarkShape, Quality, RenderSettings, SceneView,
    Snapshot, mark_scale, mark_size, speed_color,
};

const SIZE: (u32, u32) = (480, 270);

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

/// Each mark as drawn: a segment on screen (cut into short pieces, those
/// wholly in front of the eye projected) and how far from it its pixels
/// may lie: half its size, its outline and a pixel of smoothing.
fn drawn(marks: &[DebugMark]) -> Vec<(Vec2, Vec2, f32)> {
    const PIECES: usize = 32;
    let (w, h) = SIZE;
    let view_proj = camera().view_projection(w as f32 / h as f32);
    let in_front = |p: Vec3| (view_proj * p.extend(1.0)).w > 0.05;
    let scale = mark_scale(h);
    let mut out = Vec::new();
    for m in marks {
        let (a, b) = (Vec3::from(m.from), Vec3::from(m.to));
        let reach = (0.5 * m.size + mark_size::OUTLINE) * scale + 1.5;
        match m.shape() {
            MarkShape::Dot => {
                if in_front(a) {
                    out.push((project(a), project(a), reach));
                }
            }
            MarkShape::Spike => {
                if in_front(a) {
                    let width = (0.5 * mark_size::SPIKE + mark_size::OUTLINE) * scale + 1.5;
                    out.push((project(a), project(a), m.size * scale + width));
                }
            }
            MarkShape::Line | MarkShape::Arrow => {
                if m.shape() == MarkShape::Arrow && in_front(b) {
                    let head = m.cap[1] * scale;
                    out.push((project(b), project(b), head + reach));
                }
                for k in 0..PIECES {
                    let p = a.lerp(b, k as f32 / PIECES as f32);
                    let q = a.lerp(b, (k + 1) as f32 / PIECES as f32);
                    if in_front(p) && in_front(q) {
                        out.push((project(p), project(q), reach));
                    }
                }
            }
        }
    }
    out
}

#[test]
fn each_mark_view_changes_the_frame_only_along_its_marks() {
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
            let marks = &shown.debug_marks;
            assert!(!marks.is_empty(), "{}: no marks", layer.name());
            let with = draw(&mut snap, &shown);
            let changed = differing(&without, &with);
            assert!(
                changed.len() >= 8,
                "{}: {} pixels changed",
                layer.name(),
                changed.len()
            );
            let segs = drawn(marks);
            let stray = changed
                .iter()
                .filter(|&&p| {
                    segs.iter()
                        .all(|&(a, b, reach)| distance_to_segment(p, a, b) > reach)
                })
                .count();
            assert!(
                stray * 50 <= changed.len(),
                "{} at {seconds} s: {stray} of {} changed pixels are off its marks",
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

/// The share of pixels that differ by more than 16/255 in a channel.
fn share_changed(a: &RgbaImage, b: &RgbaImage) -> f64 {
    let changed = a
        .pixels()
        .zip(b.pixels())
        .filter(|(p, q)| (0..3).any(|c| p.0[c].abs_diff(q.0[c]) > 16))
        .count();
    changed as f64 / f64::from(a.width() * a.height())
}

/// Every view, alone, is seen from the default camera one second into the
/// default scene: it changes at least 0.5 % of the pixels, at 640x360 and
/// 1920x1080 and at every quality level, on two seeds.
#[test]
fn each_view_is_seen_from_the_default_camera_at_any_size_and_quality() {
    let config = WorldConfig::default();
    let cases = [
        ((640, 360), Quality::High),
        ((640, 360), Quality::Medium),
        ((640, 360), Quality::Low),
        ((1920, 1080), Quality::High),
    ];
    let mut unseen = Vec::new();
    for seed in [1, 2] {
        let mut world = World::new(config.clone(), seed).expect("scene builds");
        let mut events = Vec::new();
        for _ in 0..(1.0 / config.solver.dt).round() as usize {
            world.step();
            events.clear();
            world.take_events(&mut events);
        }
        let plain = SceneView::from_world(&world, None);
        let camera = Camera::overview(plain.room_size);
        for ((w, h), level) in cases {
            let mut snap = Snapshot::new(&config, level.settings(), w, h, None)
                .unwrap_or_else(|e| panic!("cannot render: {e}"));
            let without = snap.capture(&plain, &camera).expect("frame");
            for layer in DebugLayer::ALL {
                let mut views = DebugViews::default();
                views.set(layer, true);
                let shown = plain.clone().with_debug(&world, &events, &views);
                let with = snap.capture(&shown, &camera).expect("frame");
                let share = share_changed(&without, &with);
                eprintln!(
                    "{} at {w}x{h}, {}, seed {seed}: {:.2} %",
                    layer.name(),
                    level.name(),
                    100.0 * share
                );
                if share < 0.005 {
                    unseen.push(format!(
                        "{} at {w}x{h}, {}, seed {seed}: {:.2} % of the pixels changed ({} marks)",
                        layer.name(),
                        level.name(),
                        100.0 * share,
                        shown.debug_marks.len()
                    ));
                }
            }
        }
    }
    assert!(unseen.is_empty(), "{}", unseen.join("\n"));
}

/// An impulse's line fits the scene whatever it carries: a tumbler's weight
/// over a step is no longer than a few ball radii, and a ball resting on
/// the floor shows one.
#[test]
fn impulse_lines_fit_the_scene_for_every_kind_of_body() {
    for seed in [1, 4] {
        let config = WorldConfig::default();
        let mut world = World::new(config.clone(), seed).expect("scene builds");
        let mut events = Vec::new();
        for _ in 0..(3.0 / config.solver.dt).round() as usize {
            world.step();
            events.clear();
            world.take_events(&mut events);
        }
        let mut views = DebugViews::default();
        views.set(DebugLayer::Impulses, true);
        let shown = SceneView::from_world(&world, None).with_debug(&world, &events, &views);
        let lines: Vec<f32> = shown
            .debug_marks
            .iter()
            .filter(|m| matches!(m.shape(), MarkShape::Line | MarkShape::Arrow))
            .map(|m| Vec3::from(m.from).distance(Vec3::from(m.to)))
            .collect();
        assert!(!lines.is_empty(), "seed {seed}: no impulse drawn");
        let r = config.balls.radius as f32;
        let longest = lines.iter().copied().fold(0.0, f32::max);
        assert!(
            longest <= 6.0 * r,
            "seed {seed}: {longest} m is longer than 6 radii"
        );
        // The tumblers' floor contacts carry their weight: drawn, and short.
        assert!(
            lines.iter().filter(|&&l| l > 0.5 * r).count() >= world.tumblers().len(),
            "seed {seed}: {lines:?}"
        );
    }
}

/// Every view has a legend: each mark it draws, named.
#[test]
fn every_view_has_a_legend() {
    for layer in DebugLayer::ALL {
        let legend = layer.legend();
        assert!(!legend.is_empty(), "{}", layer.name());
        assert!(
            legend.iter().all(|e| !e.text.is_empty()),
            "{}",
            layer.name()
        );
    }
    let impulses = DebugLayer::Impulses.legend();
    assert!(
        impulses.iter().any(|e| e.text.contains("log")),
        "{impulses:?}"
    );
}
