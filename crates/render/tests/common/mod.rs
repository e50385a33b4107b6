//! Golden-frame comparison and the pixel of a world point, shared by the
//! rendering tests.

use glam::Vec3;
use image::RgbaImage;
use rolypoly_render::Camera;
use std::path::PathBuf;

/// The pixel where a world point appears in a frame of `w` x `h`.
#[allow(dead_code)] // Not every test file that shares this module needs it.
pub fn pixel_of(camera: &Camera, p: Vec3, w: u32, h: u32) -> (u32, u32) {
    let clip = camera.view_projection(w as f32 / h as f32) * p.extend(1.0);
    let ndc = clip.truncate() / clip.w;
    let x = ((ndc.x * 0.5 + 0.5) * w as f32) as u32;
    let y = ((0.5 - ndc.y * 0.5) * h as f32) as u32;
    (x.min(w - 1), y.min(h - 1))
}

/// A frame matches its golden when fewer than 0.5% of its pixels differ by
/// more than 16/255 in any channel. (Software and hardware rasterisers round
/// differently at edges; a real change of the picture moves far more.)
const GOLDEN_SHARE: f64 = 0.005;
const GOLDEN_CHANNEL: u8 = 16;

fn golden_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../tests/golden")
}

#[allow(dead_code)] // As above.
pub fn check_golden(name: &str, actual: &RgbaImage) {
    let dir = golden_dir();
    let path = dir.join(format!("{name}.png"));
    if std::env::var_os("ROLYPOLY_BLESS").is_some() {
        actual.save(&path).expect("write golden");
        return;
    }
    let golden = image::open(&path)
        .unwrap_or_else(|e| {
            panic!(
                "golden {} missing or unreadable ({e}); render it with ROLYPOLY_BLESS=1",
                path.display()
            )
        })
        .to_rgba8();
    assert_eq!(
        golden.dimensions(),
        actual.dimensions(),
        "{name}: size differs from the golden"
    );
    let mut diff = RgbaImage::new(actual.width(), actual.height());
    let mut off = 0usize;
    for (x, y, a) in actual.enumerate_pixels() {
        let g = golden.get_pixel(x, y);
        let d = (0..3).map(|c| a.0[c].abs_diff(g.0[c])).max().unwrap_or(0);
        if d > GOLDEN_CHANNEL {
            off += 1;
        }
        let v = d.saturating_mul(4);
        diff.put_pixel(x, y, image::Rgba([v, v, v, 255]));
    }
    let share = off as f64 / (actual.width() * actual.height()) as f64;
    if share >= GOLDEN_SHARE {
        let actual_path = dir.join(format!("{name}-actual.png"));
        let diff_path = dir.join(format!("{name}-diff.png"));
        let _ = actual.save(&actual_path);
        let _ = diff.save(&diff_path);
        panic!(
            "{name}: {:.2}% of pixels differ by more than {GOLDEN_CHANNEL}/255 (allowed {:.2}%); see {} and {}",
            100.0 * share,
            100.0 * GOLDEN_SHARE,
            actual_path.display(),
            diff_path.display()
        );
    }
}
