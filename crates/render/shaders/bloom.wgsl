// Bloom: what is brighter than a threshold glows (L1).
//
// The HDR frame is filtered down a chain of half-size images and back up,
// as in Jimenez's "Next generation post processing in Call of Duty:
// Advanced Warfare" (2014): each step down takes 13 taps (five overlapping
// 4 x 4 boxes, which keeps the result from flickering as bright pixels move),
// but the first, from the whole frame, which takes one 4 x 4 box and keeps
// only what lies above the threshold; each step up
// spreads the smaller image with a 3 x 3 tent and adds it to the larger,
// up to the second level; tone mapping adds that to the top level as it
// reads them. Together they hold the sum of every level: a wide, soft glow.

@group(0) @binding(0) var source: texture_2d<f32>;
@group(0) @binding(1) var source_sampler: sampler;

struct Params {
    // xy: one texel of the source, in uv; z: the threshold; w: the soft
    // knee's half width.
    values: vec4<f32>,
};
@group(0) @binding(2) var<uniform> params: Params;

fn tap(uv: vec2<f32>, offset: vec2<f32>) -> vec3<f32> {
    return textureSampleLevel(source, source_sampler, uv + offset * params.values.xy, 0.0).rgb;
}

// The 13 taps: the centre box (weight 1/2) and the four corner boxes
// (1/8 each), each box the average of its four bilinear taps.
fn downsample(uv: vec2<f32>) -> vec3<f32> {
    let a = tap(uv, vec2<f32>(-2.0, -2.0));
    let b = tap(uv, vec2<f32>(0.0, -2.0));
    let c = tap(uv, vec2<f32>(2.0, -2.0));
    let d = tap(uv, vec2<f32>(-2.0, 0.0));
    let e = tap(uv, vec2<f32>(0.0, 0.0));
    let f = tap(uv, vec2<f32>(2.0, 0.0));
    let g = tap(uv, vec2<f32>(-2.0, 2.0));
    let h = tap(uv, vec2<f32>(0.0, 2.0));
    let i = tap(uv, vec2<f32>(2.0, 2.0));
    let j = tap(uv, vec2<f32>(-1.0, -1.0));
    let k = tap(uv, vec2<f32>(1.0, -1.0));
    let l = tap(uv, vec2<f32>(-1.0, 1.0));
    let m = tap(uv, vec2<f32>(1.0, 1.0));
    return e * 0.125 + (a + c + g + i) * 0.03125 + (b + d + f + h) * 0.0625 + (j + k + l + m) * 0.125;
}

// What of `color` lies above the threshold, by its brightest channel, with
// a quadratic knee so that the glow fades in rather than switching on.
fn above_threshold(color: vec3<f32>) -> vec3<f32> {
    let threshold = params.values.z;
    let knee = params.values.w;
    let brightness = max(color.r, max(color.g, color.b));
    var soft = clamp(brightness - threshold + knee, 0.0, 2.0 * knee);
    soft = soft * soft / (4.0 * knee + 1e-4);
    let kept = max(soft, brightness - threshold) / max(brightness, 1e-4);
    return color * kept;
}

// The first step reads the whole frame, the costliest read of the chain:
// the 4 x 4 box around each texel (four bilinear taps, a third of the 13)
// still counts every pixel of the frame, so a small bright spot that moves
// neither drops out nor flickers.
fn box_downsample(uv: vec2<f32>) -> vec3<f32> {
    return (tap(uv, vec2<f32>(-1.0, -1.0)) + tap(uv, vec2<f32>(1.0, -1.0))
        + tap(uv, vec2<f32>(-1.0, 1.0)) + tap(uv, vec2<f32>(1.0, 1.0))) * 0.25;
}

@fragment
fn fs_downsample_first(in: ScreenOut) -> @location(0) vec4<f32> {
    return vec4<f32>(above_threshold(box_downsample(in.uv)), 1.0);
}

@fragment
fn fs_downsample(in: ScreenOut) -> @location(0) vec4<f32> {
    return vec4<f32>(downsample(in.uv), 1.0);
}

// Added to the larger image by the pipeline's blending.
@fragment
fn fs_upsample(in: ScreenOut) -> @location(0) vec4<f32> {
    let corners = tap(in.uv, vec2<f32>(-1.0, -1.0)) + tap(in.uv, vec2<f32>(1.0, -1.0))
        + tap(in.uv, vec2<f32>(-1.0, 1.0)) + tap(in.uv, vec2<f32>(1.0, 1.0));
    let sides = tap(in.uv, vec2<f32>(0.0, -1.0)) + tap(in.uv, vec2<f32>(-1.0, 0.0))
        + tap(in.uv, vec2<f32>(1.0, 0.0)) + tap(in.uv, vec2<f32>(0.0, 1.0));
    let centre = tap(in.uv, vec2<f32>(0.0, 0.0));
    return vec4<f32>((centre * 4.0 + sides * 2.0 + corners) / 16.0, 1.0);
}
