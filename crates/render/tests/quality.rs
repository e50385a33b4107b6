//! Quality levels and the shadow cube's culling, checked by pictures: each
//! level below high draws the same picture but at its edges (where
//! multisampling and resolution show), and culling changes no pixel.
//!
//! These draw off-screen on whatever adapter exists (lavapipe in CI).

use image::RgbaImage;
use rolypoly_physics::{World, WorldConfig};
use rolypoly_render::{Camera, Quality, RenderSettings, SceneView, Snapshot};

const SIZE: (u32, u32) = (480, 270);

fn frame(config: &WorldConfig, view: &SceneView, settings: RenderSettings) -> RgbaImage {
    let (w, h) = SIZE;
    Snapshot::new(config, settings, w, h, None)
        .unwrap_or_else(|e| panic!("cannot render: {e}"))
        .capture(view, &Camera::overview(view.room_size))
        .expect("frame")
}

fn view_at(config: &WorldConfig, seed: u64, seconds: f64) -> SceneView {
    let mut world = World::new(config.clone(), seed).expect("scene builds");
    for _ in 0..(seconds / config.solver.dt).round() as usize {
        world.step();
    }
    SceneView::from_world(&world, None)
}

fn luminance(img: &RgbaImage, x: u32, y: u32) -> f32 {
    let p = img.get_pixel(x, y).0;
    (0.2126 * p[0] as f32 + 0.7152 * p[1] as f32 + 0.0722 * p[2] as f32) / 255.0
}

/// Pixels of `img` within `reach` pixels of an edge: of a pair of
/// neighbours whose luminance differs by more than `EDGE_STEP`.
fn near_edges(img: &RgbaImage, reach: i64) -> Vec<bool> {
    const EDGE_STEP: f32 = 0.06;
    let (w, h) = (img.width() as i64, img.height() as i64);
    let mut edge = vec![false; (w * h) as usize];
    for y in 0..h {
        for x in 0..w {
            let here = luminance(img, x as u32, y as u32);
            let step = [(1, 0), (0, 1)].iter().any(|&(dx, dy)| {
                x + dx < w
                    && y + dy < h
                    && (luminance(img, (x + dx) as u32, (y + dy) as u32) - here).abs() > EDGE_STEP
            });
            edge[(y * w + x) as usize] = step;
        }
    }
    let mut near = vec![false; edge.len()];
    for y in 0..h {
        for x in 0..w {
            near[(y * w + x) as usize] = (-reach..=reach).any(|dy| {
                (-reach..=reach).any(|dx| {
                    let (u, v) = (x + dx, y + dy);
                    (0..w).contains(&u) && (0..h).contains(&v) && edge[(v * w + u) as usize]
                })
            });
        }
    }
    near
}

/// How a frame differs from high's away from its edges and at them.
struct Difference {
    /// Share of pixels away from edges that differ by more than 16/255.
    far_share: f64,
    /// Mean difference (of 255, the largest channel's) away from edges.
    far_mean: f64,
    /// Share of all pixels that differ by more than 16/255.
    all_share: f64,
    /// Share of pixels near an edge.
    edge_share: f64,
}

fn difference(high: &RgbaImage, other: &RgbaImage, reach: i64) -> Difference {
    let near = near_edges(high, reach);
    let (mut far, mut far_differ, mut far_sum, mut differ) = (0usize, 0usize, 0f64, 0usize);
    for (k, (p, q)) in high.pixels().zip(other.pixels()).enumerate() {
        let d = (0..3).map(|c| p.0[c].abs_diff(q.0[c])).max().unwrap_or(0);
        differ += usize::from(d > 16);
        if !near[k] {
            far += 1;
            far_differ += usize::from(d > 16);
            far_sum += f64::from(d);
        }
    }
    let n = near.len() as f64;
    Difference {
        far_share: far_differ as f64 / far.max(1) as f64,
        far_mean: far_sum / far.max(1) as f64,
        all_share: differ as f64 / n,
        edge_share: 1.0 - far as f64 / n,
    }
}

/// Each level below high draws the same picture except at edges: away
/// from them (more than one pixel for medium, two for low, which lights at
/// half the resolution), at most 0.5 % (medium) or 2 % (low) of the pixels
/// differ by more than 16/255, by 1 or 4 of 255 on average; at least 70 %
/// of the pixels that differ lie near an edge; and each level does differ
/// (it is drawn as it says). Measured on lavapipe: 0.16 % and 0.45 % away
/// from edges, 77 to 93 % of the differing pixels at edges (the bounce
/// light, as bright as the truth, makes the shadows' edges fainter, so
/// fewer pixels differ there).
#[test]
fn each_level_differs_from_high_only_at_edges() {
    let config = WorldConfig::default();
    for (seed, seconds) in [(1, 2.0), (4, 0.5), (9, 1.0)] {
        let view = view_at(&config, seed, seconds);
        let high = frame(&config, &view, Quality::High.settings());
        for (level, reach, max_far_share, max_far_mean) in [
            (Quality::Medium, 1, 0.005, 1.0),
            (Quality::Low, 2, 0.02, 4.0),
        ] {
            let other = frame(&config, &view, level.settings());
            let d = difference(&high, &other, reach);
            let what = format!("seed {seed}, {}", level.name());
            assert!(
                d.far_share <= max_far_share,
                "{what}: {:.3} % differ away from edges",
                100.0 * d.far_share
            );
            assert!(
                d.far_mean <= max_far_mean,
                "{what}: {:.2}/255 away from edges",
                d.far_mean
            );
            assert!(
                d.all_share > 0.003,
                "{what}: only {:.3} % differ from high",
                100.0 * d.all_share
            );
            let at_edges = 1.0 - d.far_share * (1.0 - d.edge_share) / d.all_share;
            assert!(
                at_edges >= 0.7,
                "{what}: {:.0} % of the differing pixels at edges",
                100.0 * at_edges
            );
        }
    }
}

/// Drawing each ball and tumbler only into the shadow faces it can cast
/// into changes no pixel: the default scene at 2 s, and 2 000 balls as
/// they start, spread through the room.
#[test]
fn culling_the_shadow_faces_changes_no_pixel() {
    let mut crowded = WorldConfig::default();
    crowded.balls.count = 2000;
    crowded.balls.radius = 0.08;
    for (config, seconds) in [(WorldConfig::default(), 2.0), (crowded, 0.0)] {
        let view = view_at(&config, 1, seconds);
        let culled = frame(&config, &view, RenderSettings::default());
        let unculled = RenderSettings {
            cull_shadow_faces: false,
            ..RenderSettings::default()
        };
        let all = frame(&config, &view, unculled);
        let differ = culled
            .pixels()
            .zip(all.pixels())
            .filter(|(p, q)| p != q)
            .count();
        assert_eq!(
            differ, 0,
            "{} balls: {differ} pixels differ",
            config.balls.count
        );
    }
}
