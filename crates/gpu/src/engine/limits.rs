//! Whether a device can hold a scene's balls: its limits against the
//! buffers' sizes, the first one too small named.

use crate::GpuError;
use crate::bindings::Sizes;
use crate::device::STORAGE_BUFFERS;
use crate::layout::MAX_ITEMS;

/// Whether a device of `limits` holds buffers of `sizes`; else the
/// first limit that is too small, named: the engine's own needs first
/// (no scene changes them), then those the scene's size decides.
pub fn check_limits(limits: &wgpu::Limits, sizes: &Sizes, adapter: &str) -> Result<(), GpuError> {
    // Whether the scene's size decides the need (and a smaller scene
    // would fit), or the engine's own make-up does.
    let limit = |what, need: u64, have: u64, by_scene: bool| {
        let adapter = || adapter.to_owned();
        match (need > have, by_scene) {
            (false, _) => Ok(()),
            (true, true) => Err(GpuError::Limit {
                adapter: adapter(),
                what,
                need,
                have,
            }),
            (true, false) => Err(GpuError::EngineLimit {
                adapter: adapter(),
                what,
                need,
                have,
            }),
        }
    };
    limit(
        "storage buffers per shader stage",
        u64::from(STORAGE_BUFFERS),
        u64::from(limits.max_storage_buffers_per_shader_stage),
        false,
    )?;
    limit(
        "buffers per shader stage",
        // The storage buffers and the step's constants.
        u64::from(STORAGE_BUFFERS + 1),
        u64::from(limits.max_buffers_and_acceleration_structures_per_shader_stage),
        false,
    )?;
    limit(
        "a storage buffer binding size (bytes)",
        sizes.largest_buffer(),
        limits.max_storage_buffer_binding_size,
        true,
    )?;
    limit(
        "a buffer size (bytes)",
        sizes.largest_buffer(),
        limits.max_buffer_size,
        true,
    )?;
    limit(
        "grid cells",
        sizes.cells + 1,
        MAX_ITEMS.min(u64::from(u32::MAX)),
        true,
    )?;
    limit("balls", sizes.balls, MAX_ITEMS, true)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_limit_too_small_for_the_scene_is_named_with_what_it_needs() {
        let sizes = |balls| Sizes {
            balls,
            cells: 1000,
            bodies: 1,
            tumblers: 0,
            colors: 7,
        };
        let roomy = wgpu::Limits {
            max_storage_buffers_per_shader_stage: 32,
            max_buffers_and_acceleration_structures_per_shader_stage: 32,
            max_storage_buffer_binding_size: 1 << 28,
            max_buffer_size: 1 << 31,
            ..wgpu::Limits::default()
        };
        assert!(check_limits(&roomy, &sizes(1_000_000), "test").is_ok());
        // WebGL-class limits have no storage buffers at all.
        let err = check_limits(
            &wgpu::Limits::downlevel_webgl2_defaults(),
            &sizes(10),
            "test",
        )
        .unwrap_err()
        .to_string();
        assert!(err.contains("storage buffers per shader stage"), "{err}");
        assert!(err.contains("--engine cpu"), "{err}");
        // The engine's own need is no matter of the scene's size: no
        // advice to shrink it.
        assert!(err.contains("whatever the scene"), "{err}");
        assert!(!err.contains("fewer balls"), "{err}");
        // An adapter of ten storage buffers a stage (SwiftShader's) runs
        // the engine, as does one of WebGPU's eight; one of four (a
        // downlevel adapter's) refuses thirty balls as it refuses a
        // million, and says so.
        for fits in [10, STORAGE_BUFFERS] {
            let limits = wgpu::Limits {
                max_storage_buffers_per_shader_stage: fits,
                max_buffers_and_acceleration_structures_per_shader_stage: fits + 1,
                ..roomy.clone()
            };
            assert!(check_limits(&limits, &sizes(30), "test").is_ok(), "{fits}");
        }
        let four = wgpu::Limits {
            max_storage_buffers_per_shader_stage: 4,
            ..roomy.clone()
        };
        let err = check_limits(&four, &sizes(30), "downlevel")
            .unwrap_err()
            .to_string();
        assert!(
            err.contains(&format!("of {STORAGE_BUFFERS},"))
                && err.contains("allows 4")
                && err.contains("whatever the scene"),
            "{err}"
        );
        // 256 MiB bindings hold two million balls' contacts, not three.
        assert!(check_limits(&roomy, &sizes(2_000_000), "test").is_ok());
        let err = check_limits(&roomy, &sizes(3_000_000), "test")
            .unwrap_err()
            .to_string();
        assert!(err.contains("storage buffer binding size"), "{err}");
        assert!(err.contains("fewer balls"), "{err}");
        // A ball's six vectors, 96 bytes, and the step's impact reports.
        let need = 96 * 3_000_000 + 3 * 16 * crate::layout::IMPACT_CAPACITY;
        assert_eq!(sizes(3_000_000).largest_buffer(), need);
        assert!(err.contains(&need.to_string()), "{err}");
    }
}
