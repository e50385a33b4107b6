// The finished frame, tone-mapped at the resolution the scene was lit at,
// spread over the output's pixels with the bilinear filter: one read a
// pixel at the output's resolution (see `tonemap_pass` in renderer/mod.rs).

@group(0) @binding(0) var composed: texture_2d<f32>;
@group(0) @binding(1) var smooth_sampler: sampler;

@fragment
fn fs_upscale(in: ScreenOut) -> @location(0) vec4<f32> {
    return vec4<f32>(textureSampleLevel(composed, smooth_sampler, in.uv, 0.0).rgb, 1.0);
}
