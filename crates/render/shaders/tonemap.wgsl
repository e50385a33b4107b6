// From the HDR scene to the screen: the contact occlusion darkens it, the
// bloom's glow is added, then exposure, a filmic curve, and the output
// format's own sRGB encoding.

@group(0) @binding(0) var hdr: texture_2d<f32>;

struct Params {
    // x: exposure; y: the glow's strength, divided by the levels it sums
    // (0: no bloom); z: occlusion on (1) or off (0); w: the bloom's chain
    // has a second level (1) or not (0).
    values: vec4<f32>,
};
@group(0) @binding(1) var<uniform> params: Params;
@group(0) @binding(2) var glow: texture_2d<f32>;
@group(0) @binding(3) var openness: texture_2d<f32>;
@group(0) @binding(4) var smooth_sampler: sampler;

// Narkowicz's fit of the ACES filmic curve.
fn aces(x: vec3<f32>) -> vec3<f32> {
    let a = 2.51;
    let b = 0.03;
    let c = 2.43;
    let d = 0.59;
    let e = 0.14;
    return clamp((x * (a * x + b)) / (x * (c * x + d) + e), vec3<f32>(0.0), vec3<f32>(1.0));
}

// The occlusion, blurred over about 4 x 4 of its half-resolution texels:
// four bilinear taps, each the mean of 2 x 2, which smooths away the
// pattern each pixel turned by its own angle.
fn open_at(uv: vec2<f32>) -> f32 {
    let texel = 2.0 / vec2<f32>(textureDimensions(hdr));
    var sum = 0.0;
    for (var k = 0; k < 4; k++) {
        let corner = vec2<f32>(f32(k & 1), f32(k >> 1u)) * 2.0 - 1.0;
        sum += textureSampleLevel(openness, smooth_sampler, uv + corner * texel, 0.0).r;
    }
    return sum * 0.25;
}

// The bloom's glow: its chain's top level, and the second, which holds the
// sum of all below it (see bloom.rs), spread smoothly from its smaller image.
fn glow_at(uv: vec2<f32>) -> vec3<f32> {
    var sum = textureSampleLevel(glow, smooth_sampler, uv, 0.0).rgb;
    if params.values.w > 0.5 {
        sum += textureSampleLevel(glow, smooth_sampler, uv, 1.0).rgb;
    }
    return sum;
}

@fragment
fn fs_tonemap(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    // Drawn at the size the scene was lit at: each pixel reads its own.
    let uv = position.xy / vec2<f32>(textureDimensions(hdr));
    var color = textureLoad(hdr, vec2<i32>(position.xy), 0).rgb;
    if params.values.z > 0.5 {
        color *= open_at(uv);
    }
    if params.values.y > 0.0 {
        color += params.values.y * glow_at(uv);
    }
    return vec4<f32>(aces(color * params.values.x), 1.0);
}
