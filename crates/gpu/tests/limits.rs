//! Every pipeline of the GPU engine within WebGPU's default limits
//! (`wgpu::Limits::default()`), the limits any WebGPU adapter has: the
//! engine runs wherever WebGPU does.

mod common;

use common::{build, compute};
use rolypoly_physics::WorldConfig;

#[test]
fn every_pipeline_fits_webgpu_default_limits() {
    let compute = compute();
    let webgpu = wgpu::Limits::default();
    // The default scene (tumblers, fireball) and one of a million balls'
    // bindings' sizes are the same pipelines; the scene decides only the
    // sizes, checked by the sizes' own limits.
    let (_world, balls) = build(&compute, WorldConfig::default(), 1);
    let layouts = balls.pass_layouts();
    println!("on {}", compute.adapter);
    println!(
        "{:<24} {:>15} {:>15} {:>11} {:>16}  bindings",
        "pass", "storage buffers", "uniform buffers", "bind groups", "largest binding"
    );
    for l in layouts {
        println!(
            "{:<24} {:>15} {:>15} {:>11} {:>16}  {:?}",
            l.entry,
            l.storage_buffers,
            l.uniform_buffers,
            l.bind_groups,
            l.largest_binding,
            l.bindings
        );
    }
    assert!(layouts.len() >= 15, "{} pipelines", layouts.len());
    for l in layouts {
        assert!(
            l.storage_buffers <= webgpu.max_storage_buffers_per_shader_stage,
            "{}: {} storage buffers",
            l.entry,
            l.storage_buffers
        );
        assert!(
            l.storage_buffers + l.uniform_buffers
                <= webgpu.max_buffers_and_acceleration_structures_per_shader_stage,
            "{}",
            l.entry
        );
        assert!(l.bind_groups <= webgpu.max_bind_groups, "{}", l.entry);
        assert!(
            l.largest_binding <= webgpu.max_storage_buffer_binding_size,
            "{}: {} bytes",
            l.entry,
            l.largest_binding
        );
    }
}
