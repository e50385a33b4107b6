// The debug views' marks, over the finished frame at the output's
// resolution: each a screen-facing quad sized in pixels around a line, a
// dot or an arrowhead between two points of the world, with a dark outline
// and smoothed edges. A mark that a body hides (it lies further from the
// eye than the surface the scene drew at its pixel) is drawn faintly; marks
// flagged "over" (inside a body) are drawn in full.

struct Overlay {
    view_proj: mat4x4<f32>,
    // xyz: the eye; w: output pixels per mark pixel (debug_view.rs's
    // mark_scale).
    camera: vec4<f32>,
    // xy: the output's size; zw: the scene's (lit at a lower resolution at
    // lower quality levels).
    sizes: vec4<f32>,
    // x: output pixels a metre spans at clip w = 1.
    lens: vec4<f32>,
};

@group(0) @binding(0) var<uniform> overlay: Overlay;
// The scene's surfaces: their normals, and in w their distance from the eye
// (0 where nothing was drawn).
@group(0) @binding(1) var geometry: texture_2d<f32>;

// A mark's outline, in mark pixels, and its colour.
const OUTLINE: f32 = 1.0;
const OUTLINE_COLOR: vec3<f32> = vec3<f32>(0.02, 0.02, 0.03);
// How much of a hidden mark shows.
const HIDDEN: f32 = 0.6;
// An arrowhead's half width over its length.
const HEAD_WIDTH: f32 = 0.5;
// A spike's width, in mark pixels (debug_view.rs's mark_size::SPIKE).
const SPIKE_WIDTH: f32 = 2.5;
// Marks behind the near plane are cut there (clip w).
const NEAR_W: f32 = 0.01;

struct MarkIn {
    // xyz: where it starts; w: 0 line, 1 dot, 2 arrowhead, 3 spike.
    @location(0) from_shape: vec4<f32>,
    // xyz: where it ends; w: width, diameter or length, in mark pixels.
    @location(1) to_size: vec4<f32>,
    // rgb: colour; a: 1 over everything.
    @location(2) color: vec4<f32>,
    // x: the most its size may be, in metres where it is (0: no most).
    @location(3) cap: vec4<f32>,
};

struct MarkOut {
    @builtin(position) clip: vec4<f32>,
    // Output pixels from the mark's start (x along it, y across).
    @location(0) local: vec2<f32>,
    // x: shape; y: half its width (a dot's radius, a head's half base);
    // z: its length on screen; w: over everything (1) or not.
    @location(1) @interpolate(flat) shape: vec4<f32>,
    @location(2) @interpolate(flat) color: vec3<f32>,
    @location(3) world: vec3<f32>,
};

fn to_pixels(clip: vec4<f32>) -> vec2<f32> {
    return clip.xy / clip.w * 0.5 * overlay.sizes.xy;
}

@vertex
fn vs_mark(@builtin(vertex_index) corner: u32, m: MarkIn) -> MarkOut {
    var out: MarkOut;
    let scale = overlay.camera.w;
    let shape = m.from_shape.w;
    var a = m.from_shape.xyz;
    var b = m.to_size.xyz;
    var ca = overlay.view_proj * vec4<f32>(a, 1.0);
    var cb = overlay.view_proj * vec4<f32>(b, 1.0);
    // Cut at the near plane; wholly behind it, nothing.
    if ca.w < NEAR_W && cb.w < NEAR_W {
        out.clip = vec4<f32>(0.0, 0.0, 2.0, 1.0);
        return out;
    }
    if ca.w < NEAR_W || cb.w < NEAR_W {
        let t = (NEAR_W - ca.w) / (cb.w - ca.w);
        if ca.w < NEAR_W {
            a = mix(a, b, t);
            ca = mix(ca, cb, t);
        } else {
            b = mix(a, b, t);
            cb = mix(ca, cb, t);
        }
    }
    let pa = to_pixels(ca);
    let pb = to_pixels(cb);
    // Its size in output pixels, no more than its cap seen where it is.
    var size = m.to_size.w * scale;
    if m.cap.x > 0.0 {
        var w = ca.w;
        if shape > 1.5 && shape < 2.5 {
            w = cb.w;
        }
        size = min(size, m.cap.x * overlay.lens.x / w);
    }
    let span = pb - pa;
    let len = length(span);
    var dir = vec2<f32>(1.0, 0.0);
    if len > 1e-3 {
        dir = span / len;
    }
    let across = vec2<f32>(-dir.y, dir.x);
    var half = 0.5 * size;
    // Room for the outline and a pixel of smoothing.
    let pad = OUTLINE * scale + 0.75;
    // A strip of two triangles over the corners (0, 0), (1, 0), (0, 1),
    // (1, 1): four vertices a mark.
    let k = vec2<f32>(f32(corner & 1u), f32(corner >> 1u));
    var local: vec2<f32>;
    var pixel: vec2<f32>;
    var clip: vec4<f32>;
    var world: vec3<f32>;
    var drawn_length = len;
    if shape > 2.5 {
        // A spike: a line of its own length on screen, from its start
        // towards where its end shows.
        drawn_length = size;
        half = 0.5 * SPIKE_WIDTH * scale;
        local = vec2<f32>(mix(-half - pad, drawn_length + half + pad, k.x), mix(-half - pad, half + pad, k.y));
        pixel = pa + dir * local.x + across * local.y;
        clip = ca;
        world = a;
    } else if shape < 0.5 {
        // A line: its width around the segment, round ends.
        local = vec2<f32>(mix(-half - pad, len + half + pad, k.x), mix(-half - pad, half + pad, k.y));
        pixel = pa + dir * local.x + across * local.y;
        let t = clamp(local.x / max(len, 1e-3), 0.0, 1.0);
        clip = mix(ca, cb, t);
        world = mix(a, b, t);
    } else if shape < 1.5 {
        // A dot: a disc around its point.
        local = mix(vec2<f32>(-half - pad), vec2<f32>(half + pad), k);
        pixel = pa + local;
        clip = ca;
        world = a;
    } else {
        // An arrowhead: its tip at the end, its base `length` back.
        let head = size;
        drawn_length = head;
        half = HEAD_WIDTH * head;
        local = vec2<f32>(mix(-pad, head + pad, k.x), mix(-half - pad, half + pad, k.y));
        pixel = pb - dir * local.x + across * local.y;
        clip = cb;
        world = b;
    }
    out.clip = vec4<f32>(pixel / (0.5 * overlay.sizes.xy) * clip.w, clip.z, clip.w);
    out.local = local;
    out.shape = vec4<f32>(shape, half, drawn_length, m.color.a);
    out.color = m.color.rgb;
    out.world = world;
    return out;
}

// How far outside the mark's own shape a point is (pixels; negative
// inside).
fn outside(local: vec2<f32>, shape: vec4<f32>) -> f32 {
    let half = shape.y;
    let len = shape.z;
    if shape.x < 0.5 || shape.x > 2.5 {
        let along = clamp(local.x, 0.0, len);
        return distance(local, vec2<f32>(along, 0.0)) - half;
    }
    if shape.x < 1.5 {
        return length(local) - half;
    }
    // The head: a triangle with its tip at x = 0 and its base at x = len,
    // `half` either side; the distance beyond its slanted sides along
    // their outward normal.
    let slant = normalize(vec2<f32>(-half, len));
    let p = vec2<f32>(local.x, abs(local.y));
    return max(max(dot(p, slant), local.x - len), -local.x);
}

@fragment
fn fs_mark(in: MarkOut) -> @location(0) vec4<f32> {
    let scale = overlay.camera.w;
    let d = outside(in.local, in.shape);
    let rim = OUTLINE * scale;
    if d > rim + 0.5 {
        discard;
    }
    let core = 1.0 - smoothstep(-0.5, 0.5, d);
    var alpha = 1.0 - smoothstep(rim - 0.5, rim + 0.5, d);
    let color = mix(OUTLINE_COLOR, in.color, core);
    if in.shape.w < 0.5 {
        // Hidden behind a surface the scene drew nearer: faint.
        let at = vec2<i32>(in.clip.xy * overlay.sizes.zw / overlay.sizes.xy);
        let surface = textureLoad(geometry, at, 0).w;
        let eye = distance(in.world, overlay.camera.xyz);
        if surface > 0.0 && eye > surface + max(0.05, 0.01 * surface) {
            alpha *= HIDDEN;
        }
    }
    return vec4<f32>(color * alpha, alpha);
}
