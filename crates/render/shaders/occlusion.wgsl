// Contact occlusion (L4): how much of the open sky above each visible point
// is blocked by what lies close around it, read from what the scene pass
// saw (screen-space ambient occlusion). Its cost is the frame's size, not
// the number of balls.
//
// At half the frame's resolution: each point is rebuilt from its distance
// from the eye, which the scene pass wrote with its normal, and SAMPLES
// points are spread in the hemisphere above it, up to the radius away. A
// sample whose pixel shows something nearer the eye than the sample is
// inside an object: the sky in that direction is blocked. Samples blocked
// by something far behind or in front of the point (a ball in front of a
// distant wall) count less the further it is. Each pixel turns its pattern
// by its own angle; tone mapping blurs the pattern away.

// What the scene pass saw at each pixel: xyz the surface's normal, w its
// distance from the eye (0: nothing).
@group(0) @binding(0) var geometry: texture_2d<f32>;

struct Params {
    view_proj: mat4x4<f32>,
    inverse_view_proj: mat4x4<f32>,
    // xyz: the eye; w: the radius of the hemisphere, in metres.
    eye: vec4<f32>,
    // x: how dark a fully blocked point gets (0 ..= 1); yz: the frame's size
    // in pixels; w: unused.
    settings: vec4<f32>,
};
@group(0) @binding(1) var<uniform> params: Params;

const SAMPLES: i32 = 8;
const TAU: f32 = 6.283185307;
const GOLDEN_ANGLE: f32 = 2.399963230;

fn frame_size() -> vec2<i32> {
    return vec2<i32>(params.settings.yz);
}

fn surface_at(pixel: vec2<i32>) -> vec4<f32> {
    return textureLoad(geometry, clamp(pixel, vec2<i32>(0), frame_size() - 1), 0);
}

// The world point seen at `pixel` (of the full frame) at `distance` from
// the eye.
fn world_at(pixel: vec2<i32>, distance: f32) -> vec3<f32> {
    let uv = (vec2<f32>(pixel) + 0.5) / vec2<f32>(frame_size());
    let far = params.inverse_view_proj * vec4<f32>(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0, 1.0, 1.0);
    let ray = normalize(far.xyz / far.w - params.eye.xyz);
    return params.eye.xyz + ray * distance;
}

// A fixed-looking noise that changes from pixel to pixel (Jimenez's
// interleaved gradient noise).
fn pixel_noise(pixel: vec2<f32>) -> f32 {
    return fract(52.9829189 * fract(dot(pixel, vec2<f32>(0.06711056, 0.00583715))));
}

@fragment
fn fs_occlusion(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let pixel = vec2<i32>(position.xy) * 2;
    let surface = surface_at(pixel);
    if surface.w <= 0.0 {
        return vec4<f32>(1.0);
    }
    let p = world_at(pixel, surface.w);
    let n = normalize(surface.xyz);
    // Two directions across the normal.
    let helper = select(vec3<f32>(0.0, 1.0, 0.0), vec3<f32>(1.0, 0.0, 0.0), abs(n.y) > 0.9);
    let t = normalize(cross(n, helper));
    let b = cross(n, t);
    let radius = params.eye.w;
    let turn = pixel_noise(position.xy) * TAU;
    // Lifted off the surface, so that it does not block itself.
    let origin = p + n * (0.02 * radius);
    var blocked = 0.0;
    for (var k = 0; k < SAMPLES; k++) {
        // Spread over the hemisphere by the cosine, nearer the point more
        // often than far.
        let u = (f32(k) + 0.5) / f32(SAMPLES);
        let angle = f32(k) * GOLDEN_ANGLE + turn;
        let across = sqrt(u);
        let direction = t * (across * cos(angle)) + b * (across * sin(angle)) + n * sqrt(1.0 - u);
        let reach = radius * mix(0.2, 1.0, fract(f32(k) * 0.618034 + 0.5));
        let sample = origin + direction * reach;
        let clip = params.view_proj * vec4<f32>(sample, 1.0);
        if clip.w <= 0.0 {
            continue;
        }
        let ndc = clip.xyz / clip.w;
        let uv = vec2<f32>(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5);
        if any(uv < vec2<f32>(0.0)) || any(uv >= vec2<f32>(1.0)) {
            continue;
        }
        let sample_pixel = vec2<i32>(uv * vec2<f32>(frame_size()));
        let seen = surface_at(sample_pixel).w;
        if seen > 0.0 && seen < distance(sample, params.eye.xyz) {
            // Blocked by something near the point: fully; far in front of it
            // or behind it, as told by the distances from the eye: less.
            blocked += clamp(radius / max(abs(seen - surface.w), 1e-4), 0.0, 1.0);
        }
    }
    let open = 1.0 - params.settings.x * blocked / f32(SAMPLES);
    return vec4<f32>(open, open, open, 1.0);
}
