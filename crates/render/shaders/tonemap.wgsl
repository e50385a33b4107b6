// From the HDR scene to the screen: exposure, a filmic curve, and the
// output format's own sRGB encoding.

@group(0) @binding(0) var hdr: texture_2d<f32>;

struct Params {
    // x: exposure.
    values: vec4<f32>,
};
@group(0) @binding(1) var<uniform> params: Params;

@vertex
fn vs_fullscreen(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
    // One triangle that covers the screen.
    let x = f32((index << 1u) & 2u) * 2.0 - 1.0;
    let y = f32(index & 2u) * 2.0 - 1.0;
    return vec4<f32>(x, y, 0.0, 1.0);
}

// Narkowicz's fit of the ACES filmic curve.
fn aces(x: vec3<f32>) -> vec3<f32> {
    let a = 2.51;
    let b = 0.03;
    let c = 2.43;
    let d = 0.59;
    let e = 0.14;
    return clamp((x * (a * x + b)) / (x * (c * x + d) + e), vec3<f32>(0.0), vec3<f32>(1.0));
}

@fragment
fn fs_tonemap(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let color = textureLoad(hdr, vec2<i32>(position.xy), 0).rgb;
    return vec4<f32>(aces(color * params.values.x), 1.0);
}
