// The debug views' marks, over the finished frame at the output's
// resolution: each a screen-facing quad sized in pixels around a line, a
// dot, an arrow or a spike between two points of the world, with a dark outline
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
    // xyz: where it starts; w: 0 line, 1 dot, 2 arrow, 3 spike.
    @location(0) from_shape: vec4<f32>,
    // xyz: where it ends; w: width, diameter or length, in mark pixels.
    @location(1) to_size: vec4<f32>,
    // rgb: colour; a: 1 over everything.
    @location(2) color: vec4<f32>,
    // x: the most its size (an arrow's: its head's length) may be, in
    // metres where it is (0: no most); y: an arrow's head length, in mark
    // pixels.
    @location(3) cap: vec4<f32>,
};

struct MarkOut {
    @builtin(position) clip: vec4<f32>,
    // Output pixels from the mark's start (x along it, y across).
    @location(0) local: vec2<f32>,
    // x: the line's half width (a dot's radius); y: the line's length on
    // screen (a dot's 0, an arrow's up to its head); z: the outline's
    // width; w: over everything (1) or not.
    @location(1) @interpolate(flat) line: vec4<f32>,
    @location(2) @interpolate(flat) color: vec3<f32>,
    // Where it is, for the scene's surfaces to hide it.
    @location(3) world: vec3<f32>,
    // An arrow's head (x 0 for other marks): its length, where its tip is
    // along the mark, the outward normal of its upper side.
    @location(4) @interpolate(flat) head: vec4<f32>,
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
    let is_arrow = shape > 1.5 && shape < 2.5;
    // Its size in output pixels, no more than its cap seen where it is (an
    // arrow's cap holds its head, at its end).
    var size = m.to_size.w * scale;
    var head = m.cap.y * scale;
    if m.cap.x > 0.0 {
        if is_arrow {
            head = min(head, m.cap.x * overlay.lens.x / cb.w);
        } else {
            size = min(size, m.cap.x * overlay.lens.x / ca.w);
        }
    }
    let span = pb - pa;
    let len = length(span);
    // An arrow shorter on screen than its line is wide shows no direction
    // (seen end on, or a ball all but at rest): not drawn.
    if is_arrow && len < size {
        out.clip = vec4<f32>(0.0, 0.0, 2.0, 1.0);
        return out;
    }
    var dir = vec2<f32>(1.0, 0.0);
    if len > 1e-3 {
        dir = span / len;
    }
    let across = vec2<f32>(-dir.y, dir.x);
    var half = 0.5 * size;
    // Room for the outline and a pixel of smoothing.
    let pad = OUTLINE * scale + 0.75;
    // A strip of eight vertices a mark, in pairs across it: most marks are
    // a quad over the corners (0, 0), (0, 1), (1, 0), (1, 1), its last two
    // pairs repeating the second (no area); an arrow's four pairs hug its
    // line and its head, so that a crowd's arrows cover few pixels.
    let pair = corner >> 1u;
    let side = f32(corner & 1u);
    let k = vec2<f32>(f32(min(pair, 1u)), side);
    var local: vec2<f32>;
    var pixel: vec2<f32>;
    var clip: vec4<f32>;
    var world: vec3<f32>;
    var drawn_length = len;
    var head_half = 0.0;
    if shape > 2.5 {
        // A spike: a line of its own length on screen, from its start
        // towards where its end shows.
        drawn_length = size;
        half = 0.5 * SPIKE_WIDTH * scale;
        local = vec2<f32>(mix(-half - pad, drawn_length + half + pad, k.x), mix(-half - pad, half + pad, k.y));
        pixel = pa + dir * local.x + across * local.y;
        clip = ca;
        world = a;
    } else if shape > 0.5 && shape < 1.5 {
        // A dot: a disc around its point.
        local = mix(vec2<f32>(-half - pad), vec2<f32>(half + pad), k);
        pixel = pa + local;
        clip = ca;
        world = a;
    } else {
        // A line: its width around the segment, round ends.
        local = vec2<f32>(mix(-half - pad, len + half + pad, k.x), mix(-half - pad, half + pad, k.y));
        if is_arrow {
            head_half = HEAD_WIDTH * head;
            // Its line up to the head's base, then a trapezoid around the
            // head and its outline (its sides offset from the head's,
            // whose slope is HEAD_WIDTH); a head no wider than the line
            // takes the line's quad.
            if head_half >= 1.5 * half + pad {
                let base = max(len - head - pad, -half - pad);
                let xs = array<f32, 4>(-half - pad, base, base, len + pad);
                let ws = array<f32, 4>(half + pad, half + pad, head_half + 1.7 * pad, 0.7 * pad);
                local = vec2<f32>(xs[pair], mix(-ws[pair], ws[pair], side));
            }
        }
        pixel = pa + dir * local.x + across * local.y;
        let t = clamp(local.x / max(len, 1e-3), 0.0, 1.0);
        clip = mix(ca, cb, t);
        world = mix(a, b, t);
    }
    out.clip = vec4<f32>(pixel / (0.5 * overlay.sizes.xy) * clip.w, clip.z, clip.w);
    out.local = local;
    out.color = m.color.rgb;
    out.world = world;
    if is_arrow {
        let shaft = max(len - head, 0.0);
        out.line = vec4<f32>(half, shaft, OUTLINE * scale, m.color.a);
        out.head = vec4<f32>(head, len, normalize(vec2<f32>(-head_half, max(head, 1e-3))));
    } else {
        out.line = vec4<f32>(half, drawn_length, OUTLINE * scale, m.color.a);
        out.head = vec4<f32>(0.0);
    }
    return out;
}

// How far outside the mark's own shape a point is (pixels; negative
// inside): its line (a dot is a line of no length, round-ended), and an
// arrow's head, a triangle with its tip at `head.y` along the mark; beyond
// the head's slanted sides the distance is along their outward normal.
fn outside(local: vec2<f32>, line: vec4<f32>, head: vec4<f32>) -> f32 {
    let along = clamp(local.x, 0.0, line.y);
    var d = distance(local, vec2<f32>(along, 0.0)) - line.x;
    if head.x > 0.0 {
        let p = vec2<f32>(head.y - local.x, abs(local.y));
        d = min(d, max(max(dot(p, head.zw), p.x - head.x), -p.x));
    }
    return d;
}

@fragment
fn fs_mark(in: MarkOut) -> @location(0) vec4<f32> {
    let d = outside(in.local, in.line, in.head);
    let rim = in.line.z;
    if d > rim + 0.5 {
        discard;
    }
    // A pixel's ramp at each edge, the core's and the outline's.
    let core = clamp(0.5 - d, 0.0, 1.0);
    var alpha = clamp(rim + 0.5 - d, 0.0, 1.0);
    let color = mix(OUTLINE_COLOR, in.color, core);
    if in.line.w < 0.5 {
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
