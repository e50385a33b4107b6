// From the HDR scene to the screen: the contact occlusion darkens it, the
// bloom's glow is added, then exposure, a filmic curve, and the output
// format's own sRGB encoding.

@group(0) @binding(0) var hdr: texture_2d<f32>;

struct Params {
    // x: exposure; y: the glow's strength, divided by the levels it sums
    // (0: no bloom); z: occlusion on (1) or off (0); w: the bloom's chain
    // has a second level (1) or not (0).
    values: vec4<f32>,
    // x: unused (how the frame is shown is SHOW); y: the output encodes
    // sRGB itself (1) or not (0).
    view: vec4<f32>,
};

// How the frame is shown: one of SHOW_* (frame_view.rs's `Finish`). A
// constant of the pipeline, so that the finished frame's shader holds none
// of the views' code.
override SHOW: u32 = 0u;

const SHOW_FRAME: u32 = 0u;
const SHOW_DATA: u32 = 1u;
const SHOW_CURVE: u32 = 2u;
const SHOW_OCCLUSION: u32 = 3u;
const SHOW_BLOOM: u32 = 4u;
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

// A value to be written as the picture's own (a view's data): where the
// output encodes sRGB, the value whose encoding it is.
fn as_data(value: vec3<f32>) -> vec3<f32> {
    let v = clamp(value, vec3<f32>(0.0), vec3<f32>(1.0));
    if params.view.y < 0.5 {
        return v;
    }
    let low = v / 12.92;
    let high = pow((v + 0.055) / 1.055, vec3<f32>(2.4));
    return select(high, low, v <= vec3<f32>(0.04045));
}

// The bloom's chain, level by level: the largest over the left half, each
// smaller one in a band of the right half, top to bottom.
fn bloom_levels(uv: vec2<f32>) -> vec3<f32> {
    let levels = f32(textureNumLevels(glow));
    if uv.x < 0.5 || levels < 2.0 {
        return textureSampleLevel(glow, smooth_sampler, vec2<f32>(min(uv.x * 2.0, 1.0), uv.y), 0.0).rgb;
    }
    let bands = levels - 1.0;
    let band = min(floor(uv.y * bands), bands - 1.0);
    let inside = vec2<f32>((uv.x - 0.5) * 2.0, uv.y * bands - band);
    return textureSampleLevel(glow, smooth_sampler, inside, band + 1.0).rgb;
}

@fragment
fn fs_tonemap(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    // Drawn at the size the scene was lit at: each pixel reads its own.
    let uv = position.xy / vec2<f32>(textureDimensions(hdr));
    var color = textureLoad(hdr, vec2<i32>(position.xy), 0).rgb;
    switch SHOW {
        case SHOW_DATA: { return vec4<f32>(as_data(color), 1.0); }
        case SHOW_CURVE: { return vec4<f32>(aces(color * params.values.x), 1.0); }
        case SHOW_OCCLUSION: {
            var open = 1.0;
            if params.values.z > 0.5 {
                open = open_at(uv);
            }
            return vec4<f32>(as_data(vec3<f32>(open)), 1.0);
        }
        case SHOW_BLOOM: {
            if params.values.y <= 0.0 {
                return vec4<f32>(0.0, 0.0, 0.0, 1.0);
            }
            return vec4<f32>(aces(bloom_levels(uv) * params.values.x), 1.0);
        }
        default: {}
    }
    if params.values.z > 0.5 {
        color *= open_at(uv);
    }
    if params.values.y > 0.0 {
        color += params.values.y * glow_at(uv);
    }
    return vec4<f32>(aces(color * params.values.x), 1.0);
}
