// Temporal anti-aliasing with upsampling (see temporal.rs), in three passes
// over the frame tone-mapped at the lit resolution:
//
// `fs_neighbourhood`, at the lit resolution, sums up each texel's 3 x 3
// neighbourhood once for the several output pixels that read it: its mean
// and spread in YCoCg, the most any of it moved, and whether the texel
// shows something other than the frame before did there.
//
// `fs_resolve`, at the output's resolution, follows each output pixel back to where it was the frame
// before (the motion of the lit texel it falls in), clips that history to
// the current frame's neighbourhood (variance clipping in YCoCg, Salvi
// 2016), and folds in the current sample, weighted by how close the
// jittered sample fell to the pixel's centre: over a turn of the jitter,
// each pixel gathers the samples that fell near it, as if the scene had
// been lit at the output's resolution. Its alpha keeps the weight gathered
// so far, so a pixel new to the screen settles fast and a settled one
// moves slowly.
//
// `fs_sharpen` gives back what the current frame spread over the output
// softens where a pixel has little history (new to the screen, or near what
// moves): an unsharp mask on five texels, as strong as the pixel is
// unsettled, held within their own range so that it rings nowhere.

// The frame tone-mapped at the lit resolution, and its motion.
@group(0) @binding(0) var current: texture_2d<f32>;
@group(0) @binding(1) var motion: texture_2d<f32>;
// The last frame's resolved history at the output's resolution: rgb, and
// in alpha the weight it holds.
@group(0) @binding(2) var history: texture_2d<f32>;
@group(0) @binding(3) var smooth_sampler: sampler;

struct Params {
    // xy: where this frame's sample lies in each lit texel, from its centre,
    // in texels; z: the history holds a frame (1) or not (0); w: sharpening.
    values: vec4<f32>,
    // xy: the output's size in pixels.
    output: vec4<f32>,
};
@group(0) @binding(4) var<uniform> params: Params;
// The surfaces' normals and distances from the eye (w), this frame's and
// the last's, at the lit resolution.
@group(0) @binding(5) var geometry: texture_2d<f32>;
@group(0) @binding(6) var geometry_before: texture_2d<f32>;
// The neighbourhood of each lit texel (see `fs_neighbourhood`): its mean
// in YCoCg and the most it moved in output pixels; its spread and whether
// it was disoccluded.
@group(0) @binding(7) var neighbourhood_mean: texture_2d<f32>;
@group(0) @binding(8) var neighbourhood_spread: texture_2d<f32>;

// The most weight a history keeps: a new sample at a pixel's centre then
// counts for 1 / (1 + MAX_WEIGHT) of the result, so a picture settles over
// about that many frames and noise from frame to frame averages away.
const MAX_WEIGHT: f32 = 6.0;
// The weight of a pixel with no history, the current frame spread over it:
// little, so that the sharp samples of the frames that follow soon outweigh
// its blur.
const FRESH_WEIGHT: f32 = 0.1;
// Near what moves: the most weight the history keeps, and the weight the
// current frame spread over the pixel adds each frame.
const MOVING_MAX_WEIGHT: f32 = 1.0;
const MOVING_FRESH_WEIGHT: f32 = 1.0;
// How much, as a share, the distance seen at a place may differ from the
// last frame's before the place is taken to show something else.
const DISOCCLUDED: f32 = 0.02;
// How far the history's mean over a neighbourhood may depart from now's,
// in standard errors of a mean of nine (the spread over 3) and beyond a
// floor, before the light there counts as changed.
const RELIT_SPREAD: f32 = 3.0;
const RELIT_FLOOR: f32 = 0.03;
// Motion, in output pixels, below which a surface counts as still.
const STILL: f32 = 0.05;
// How sharply a sample's weight falls with its distance d from the pixel's
// centre, in output pixels: exp(-KERNEL d^2).
const KERNEL: f32 = 16.0;
// The box a still surface's history is held to: wide, since the current
// frame's neighbourhood is sampled elsewhere than the history was (a fine
// texture varies more between them than across either), yet not without
// bound, so that a shadow moving over it does not linger.
const STILL_CLIP_SPREAD: f32 = 8.0;
const STILL_CLIP_FLOOR: f32 = 0.03;
// The weight from which a pixel counts as settled and is not sharpened.
const SETTLED_WEIGHT: f32 = 3.0;
// How far from the neighbourhood's mean, in its standard deviations, the
// history may stay: wider keeps more history (smoother), narrower ghosts
// less.
const CLIP_SPREAD: f32 = 1.25;

fn to_ycocg(c: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(
        0.25 * c.r + 0.5 * c.g + 0.25 * c.b,
        0.5 * c.r - 0.5 * c.b,
        -0.25 * c.r + 0.5 * c.g - 0.25 * c.b,
    );
}

fn from_ycocg(c: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(c.x + c.y - c.z, c.x + c.z, c.x - c.y - c.z);
}

// `h` moved towards `mean` until it lies inside the box of half-size
// `extent` around it.
fn clip_to_box(h: vec3<f32>, mean: vec3<f32>, extent: vec3<f32>) -> vec3<f32> {
    let offset = h - mean;
    let units = abs(offset / max(extent, vec3<f32>(1e-5)));
    let most = max(units.x, max(units.y, units.z));
    if most > 1.0 {
        return mean + offset / most;
    }
    return h;
}

// The history at `uv`: exact where it has not moved, else Catmull-Rom
// through the 4 x 4 texels around it in five bilinear reads (the corners
// left out), which keeps a moving picture from softening frame by frame.
fn history_at(uv: vec2<f32>, still: bool) -> vec4<f32> {
    let size = vec2<f32>(textureDimensions(history));
    if still {
        return textureLoad(history, vec2<i32>(uv * size), 0);
    }
    let position = uv * size;
    let centre = floor(position - 0.5) + 0.5;
    let f = position - centre;
    let w0 = f * (-0.5 + f * (1.0 - 0.5 * f));
    let w1 = 1.0 + f * f * (-2.5 + 1.5 * f);
    let w2 = f * (0.5 + f * (2.0 - 1.5 * f));
    let w3 = f * f * (-0.5 + 0.5 * f);
    let w12 = w1 + w2;
    let at0 = (centre - 1.0) / size;
    let at12 = (centre + w2 / w12) / size;
    let at3 = (centre + 2.0) / size;
    var sum = textureSampleLevel(history, smooth_sampler, vec2<f32>(at12.x, at0.y), 0.0) * (w12.x * w0.y);
    sum += textureSampleLevel(history, smooth_sampler, vec2<f32>(at0.x, at12.y), 0.0) * (w0.x * w12.y);
    sum += textureSampleLevel(history, smooth_sampler, at12, 0.0) * (w12.x * w12.y);
    sum += textureSampleLevel(history, smooth_sampler, vec2<f32>(at3.x, at12.y), 0.0) * (w3.x * w12.y);
    sum += textureSampleLevel(history, smooth_sampler, vec2<f32>(at12.x, at3.y), 0.0) * (w12.x * w3.y);
    let total = w12.x * w0.y + w0.x * w12.y + w12.x * w12.y + w3.x * w12.y + w12.x * w3.y;
    return max(sum / total, vec4<f32>(0.0));
}

struct Neighbourhood {
    @location(0) mean: vec4<f32>,
    @location(1) spread: vec4<f32>,
};

@fragment
fn fs_neighbourhood(@builtin(position) position: vec4<f32>) -> Neighbourhood {
    let lit_size = vec2<f32>(textureDimensions(current));
    let last = vec2<i32>(lit_size) - 1;
    let texel = vec2<i32>(position.xy);
    var sum = vec3<f32>(0.0);
    var sum_sq = vec3<f32>(0.0);
    // The most any surface around moved, in output pixels: where nothing
    // did, the history is the same surface seen again and is trusted;
    // near anything that moved, it may be what moved away.
    var most_moved = 0.0;
    for (var dy = -1; dy <= 1; dy++) {
        for (var dx = -1; dx <= 1; dx++) {
            let at_texel = clamp(texel + vec2<i32>(dx, dy), vec2<i32>(0), last);
            let c = to_ycocg(textureLoad(current, at_texel, 0).rgb);
            sum += c;
            sum_sq += c * c;
            most_moved = max(most_moved, length(textureLoad(motion, at_texel, 0).xy * params.output.xy));
        }
    }
    let mean = sum / 9.0;
    let spread = sqrt(max(sum_sq / 9.0 - mean * mean, vec3<f32>(0.0)));
    // The light changed here (a shadow moved over a still surface) where the
    // history's mean over the same neighbourhood departs from now's: means
    // over nine texels, so that a fine texture, which spreads the
    // neighbourhood as widely as a shadow darkens it, averages out of both.
    // Such a place is treated as moving.
    if params.values.z > 0.5 {
        var past_sum = vec3<f32>(0.0);
        for (var dy = -1; dy <= 1; dy++) {
            for (var dx = -1; dx <= 1; dx++) {
                let at_texel = clamp(texel + vec2<i32>(dx, dy), vec2<i32>(0), last);
                let came_from = (vec2<f32>(at_texel) + 0.5) / lit_size + textureLoad(motion, at_texel, 0).xy;
                past_sum += to_ycocg(textureSampleLevel(history, smooth_sampler, came_from, 0.0).rgb);
            }
        }
        let change = length(past_sum / 9.0 - mean);
        if change > RELIT_SPREAD * length(spread) / 3.0 + RELIT_FLOOR {
            // A pixel's worth, well clear of STILL after the target's
            // rounding to half precision.
            most_moved = max(most_moved, 1.0);
        }
    }
    // Seen at a different distance the frame before, the place showed
    // something else then (what has moved off it): its history is not
    // this surface's.
    let before = position.xy / lit_size + textureLoad(motion, texel, 0).xy;
    let distance = textureLoad(geometry, texel, 0).w;
    let texel_before = clamp(vec2<i32>(before * lit_size), vec2<i32>(0), last);
    let distance_before = textureLoad(geometry_before, texel_before, 0).w;
    let disoccluded = abs(distance_before - distance) > DISOCCLUDED * max(distance, distance_before);
    return Neighbourhood(vec4<f32>(mean, most_moved), vec4<f32>(spread, select(0.0, 1.0, disoccluded)));
}

@fragment
fn fs_resolve(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let out_size = vec2<f32>(textureDimensions(history));
    let lit_size = vec2<f32>(textureDimensions(current));
    let last = vec2<i32>(lit_size) - 1;
    let uv = position.xy / out_size;
    let sample_offset = params.values.xy;
    // The pixel's centre among the lit texels, and the texel whose sample
    // fell nearest it.
    let at = uv * lit_size - sample_offset;
    let texel = clamp(vec2<i32>(floor(at)), vec2<i32>(0), last);
    let off_centre = (at - (vec2<f32>(texel) + 0.5)) * out_size / lit_size;
    let around = textureLoad(neighbourhood_mean, texel, 0);
    let mean = around.xyz;
    let most_moved = around.w;
    let spread_and_seen = textureLoad(neighbourhood_spread, texel, 0);
    let spread = spread_and_seen.xyz;
    // The sample, and the current frame spread smoothly (for a pixel with
    // no history).
    let nearest = textureLoad(current, texel, 0).rgb;
    let spread_over = textureSampleLevel(current, smooth_sampler, at / lit_size, 0.0).rgb;

    let before = uv + textureLoad(motion, texel, 0).xy;
    let on_screen = all(before >= vec2<f32>(0.0)) && all(before <= vec2<f32>(1.0));
    if params.values.z < 0.5 || !on_screen || spread_and_seen.w > 0.5 {
        return vec4<f32>(spread_over, FRESH_WEIGHT);
    }
    let still = most_moved < STILL;
    let past = history_at(before, still);
    var kept = past.a;
    var past_color = to_ycocg(past.rgb);
    // A Gaussian of the sample's distance from the pixel's centre, in
    // output pixels.
    var weight = exp(-KERNEL * dot(off_centre, off_centre));
    var sample = nearest * weight;
    if still {
        kept = min(kept, MAX_WEIGHT);
        // Held to a wide box: the current neighbourhood is sampled
        // elsewhere than the history was, and a fine texture varies more
        // between them than across either.
        past_color = clip_to_box(past_color, mean, spread * STILL_CLIP_SPREAD + STILL_CLIP_FLOOR);
    } else {
        // Near what moves, the history may hold what moved away: it is
        // held to the neighbourhood, keeps little weight, and every frame
        // adds the current picture spread over the pixel, so that what is
        // left of a trail fades within a frame or two.
        let clipped = clip_to_box(past_color, mean, spread * CLIP_SPREAD);
        let clipped_by = length(clipped - past_color) / max(length(spread), 1e-3);
        kept = min(kept, MOVING_MAX_WEIGHT) / (1.0 + clipped_by * clipped_by);
        past_color = clipped;
        sample += spread_over * MOVING_FRESH_WEIGHT;
        weight += MOVING_FRESH_WEIGHT;
    }
    let color = (from_ycocg(past_color) * kept + sample) / (kept + weight);
    return vec4<f32>(max(color, vec3<f32>(0.0)), kept + weight);
}

@fragment
fn fs_sharpen(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let p = vec2<i32>(position.xy);
    let last = vec2<i32>(textureDimensions(history)) - 1;
    let here = textureLoad(history, p, 0);
    let c = here.rgb;
    // Sharpened as much as it is soft: a pixel that has gathered few
    // samples (new to the screen, or near what moves, where the current
    // frame spread over it stands in) fully; a settled one, already as sharp
    // as its samples, not at all.
    let amount = params.values.w * clamp(1.0 - here.a / SETTLED_WEIGHT, 0.0, 1.0);
    if amount <= 0.0 {
        return vec4<f32>(c, 1.0);
    }
    let n = textureLoad(history, clamp(p + vec2<i32>(0, -1), vec2<i32>(0), last), 0).rgb;
    let s = textureLoad(history, clamp(p + vec2<i32>(0, 1), vec2<i32>(0), last), 0).rgb;
    let e = textureLoad(history, clamp(p + vec2<i32>(1, 0), vec2<i32>(0), last), 0).rgb;
    let w = textureLoad(history, clamp(p + vec2<i32>(-1, 0), vec2<i32>(0), last), 0).rgb;
    let low = min(c, min(min(n, s), min(e, w)));
    let high = max(c, max(max(n, s), max(e, w)));
    let sharpened = c + amount * (4.0 * c - n - s - e - w);
    return vec4<f32>(clamp(sharpened, low, high), 1.0);
}
