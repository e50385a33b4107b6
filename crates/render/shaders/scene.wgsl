// The lit scene, the balls (spheres traced on squares), the light's bulb, and
// the depth-only shadow faces.
//
// Lighting is Blinn-Phong (ambient + diffuse + specular with the half
// vector) from two point lights: the ceiling light, and the fireball's
// glow while there is one. The ceiling light's shadows come from six depth
// faces (a cube drawn as a 2D array, one layer per face). A fragment looks
// its distance up through the same view-projection the face was drawn
// with, so the face conventions of a cube sampler never come into it.
// On top, one bounce of diffuse light from the room's six surfaces (see
// `indirect_light`).

struct Globals {
    view_proj: mat4x4<f32>,
    camera_pos: vec4<f32>,
    // xyz: position of the light; w: unused.
    light_pos: vec4<f32>,
    // rgb: colour times intensity; w: ambient strength.
    light_color: vec4<f32>,
    // x: shadows on (1) or off (0); y: one texel of a shadow face (1 / size);
    // z: depth bias; w: unused.
    shadow: vec4<f32>,
    light_view_proj: array<mat4x4<f32>, 6>,
    // The light falls off as 1 / (x + y d + z d^2) at distance d; w: where
    // it fades to nothing (0: it reaches everywhere).
    light_falloff: vec4<f32>,
    // xyz: the fireball's light; w: 1 while it shines, else 0.
    fireball_pos: vec4<f32>,
    // rgb: the fireball light's colour times intensity; w: unused.
    fireball_color: vec4<f32>,
    // As light_falloff, for the fireball.
    fireball_falloff: vec4<f32>,
    // xyz: half the room's width, its height, half its depth;
    // w: indirect light on (1) or off (0).
    room: vec4<f32>,
    // xyz: the irradiance volume's probes along each axis; w: its texture's
    // probes along each axis and direction.
    irradiance_probes: vec4<f32>,
    // The view-projection without the temporal path's jitter (view_proj
    // has it), and the last frame's: a surface's motion on screen is
    // measured between the two (see `motion_of`).
    motion_view_proj: mat4x4<f32>,
    previous_view_proj: mat4x4<f32>,
    // For the frame's views (frame_view.rs): x: unused (which view is
    // shown is FRAME_VIEW); y, z: the depth view's distances for white and
    // black; w: the motion view's pixels a frame at full brightness.
    frame_view: vec4<f32>,
    // xy: the scene's size in pixels, for the motion view; zw: unused.
    frame_size: vec4<f32>,
};

@group(0) @binding(0) var<uniform> globals: Globals;
@group(0) @binding(1) var shadow_map: texture_depth_2d_array;
@group(0) @binding(2) var shadow_sampler: sampler_comparison;
@group(0) @binding(3) var paint: texture_2d<f32>;
@group(0) @binding(4) var paint_sampler: sampler;
// The light bounced by the room's surfaces, gathered at a grid of probes
// from each of six directions (see irradiance.rs): one slab along z per
// direction, in the order +x, -x, +y, -y, +z, -z.
@group(0) @binding(5) var irradiance: texture_3d<f32>;
@group(0) @binding(6) var irradiance_sampler: sampler;

struct VertexIn {
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
};

// One drawn object. `material`: x = kind, y = specular strength,
// z = shininess, w = emission.
struct InstanceIn {
    @location(3) m0: vec4<f32>,
    @location(4) m1: vec4<f32>,
    @location(5) m2: vec4<f32>,
    @location(6) m3: vec4<f32>,
    @location(7) color: vec4<f32>,
    @location(8) material: vec4<f32>,
};

// The same object's model matrix the frame before, for its motion.
struct PreviousIn {
    @location(9) m0: vec4<f32>,
    @location(10) m1: vec4<f32>,
    @location(11) m2: vec4<f32>,
    @location(12) m3: vec4<f32>,
};

const KIND_PLAIN: f32 = 0.0;
const KIND_WOOD: f32 = 1.0;
const KIND_PAINTED: f32 = 2.0;

struct VertexOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
    // Flat: the same for the whole object, and compared exactly below.
    @location(3) @interpolate(flat) color: vec4<f32>,
    @location(4) @interpolate(flat) material: vec4<f32>,
    // Where this point of the object was the frame before.
    @location(5) previous: vec3<f32>,
};

fn model_of(i: InstanceIn) -> mat4x4<f32> {
    return mat4x4<f32>(i.m0, i.m1, i.m2, i.m3);
}

@vertex
fn vs_scene(v: VertexIn, i: InstanceIn, before: PreviousIn) -> VertexOut {
    let model = model_of(i);
    let world = model * vec4<f32>(v.position, 1.0);
    var out: VertexOut;
    out.clip = globals.view_proj * world;
    out.world = world.xyz;
    out.previous = (mat4x4<f32>(before.m0, before.m1, before.m2, before.m3) * vec4<f32>(v.position, 1.0)).xyz;
    // Models carry rotation and uniform scale only, so the model matrix
    // turns normals correctly once they are renormalised.
    out.normal = normalize((model * vec4<f32>(v.normal, 0.0)).xyz);
    out.uv = v.uv;
    out.color = i.color;
    out.material = i.material;
    return out;
}

// --- procedural surfaces -------------------------------------------------

fn hash2(p: vec2<f32>) -> f32 {
    let q = fract(p * vec2<f32>(123.34, 456.21));
    let r = q + dot(q, q + 45.32);
    return fract(r.x * r.y);
}

fn value_noise(p: vec2<f32>) -> f32 {
    let i = floor(p);
    let f = fract(p);
    let u = f * f * (3.0 - 2.0 * f);
    let a = hash2(i);
    let b = hash2(i + vec2<f32>(1.0, 0.0));
    let c = hash2(i + vec2<f32>(0.0, 1.0));
    let d = hash2(i + vec2<f32>(1.0, 1.0));
    return mix(mix(a, b, u.x), mix(c, d, u.x), u.y);
}

// Planks 0.2 m wide running along x, each with its own shade and grain.
fn wood(base: vec3<f32>, p: vec2<f32>) -> vec3<f32> {
    let plank_width = 0.2;
    let row = floor(p.y / plank_width);
    let along = p.x + hash2(vec2<f32>(row, 7.0)) * 3.0;
    let plank = floor(along / 1.6);
    let id = vec2<f32>(row, plank);
    let shade = 0.82 + 0.3 * hash2(id);
    let grain_pos = vec2<f32>(along * 3.0, (p.y - row * plank_width) * 40.0 + hash2(id) * 10.0);
    let grain = value_noise(grain_pos * vec2<f32>(0.5, 1.0)) * 0.6 + value_noise(grain_pos * 4.0) * 0.4;
    let rings = 0.5 + 0.5 * sin(grain * 12.0 + along * 2.0);
    // Dark seams between planks.
    let v = fract(p.y / plank_width);
    let u = fract(along / 1.6);
    let seam = smoothstep(0.0, 0.03, v) * smoothstep(1.0, 0.97, v) * smoothstep(0.0, 0.004, u) * smoothstep(1.0, 0.996, u);
    return base * shade * (0.78 + 0.22 * rings) * (0.55 + 0.45 * seam);
}

// A faint plaster texture, so walls are not flat paint.
fn plaster(base: vec3<f32>, p: vec3<f32>) -> vec3<f32> {
    let n = value_noise(p.xy * 9.0 + p.zz * 5.0) * 0.5 + value_noise(p.zy * 23.0 + p.xx * 3.0) * 0.5;
    return base * (0.93 + 0.07 * n);
}

// --- shadows --------------------------------------------------------------

fn shadow_face(d: vec3<f32>) -> i32 {
    let a = abs(d);
    if a.x >= a.y && a.x >= a.z {
        return select(1, 0, d.x > 0.0);
    }
    if a.y >= a.z {
        return select(3, 2, d.y > 0.0);
    }
    return select(5, 4, d.z > 0.0);
}

// Shadow filter taps along each side (the quality level's; see quality.rs).
override SHADOW_TAPS: i32 = 4;

// 1 where the light reaches the point, 0 in shadow, soft in between.
fn light_visibility(world: vec3<f32>, normal: vec3<f32>) -> f32 {
    if globals.shadow.x < 0.5 {
        return 1.0;
    }
    let texel = globals.shadow.y;
    let to_point = world - globals.light_pos.xyz;
    // Normal offset: a shadow texel covers more ground further from the
    // light, so push the lookup off the surface by about one texel there.
    let distance = length(to_point);
    let lookup = world + normal * (2.5 * texel * distance);
    let face = shadow_face(lookup - globals.light_pos.xyz);
    let clip = globals.light_view_proj[face] * vec4<f32>(lookup, 1.0);
    let ndc = clip.xyz / clip.w;
    let uv = vec2<f32>(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5);
    let reference = ndc.z - globals.shadow.z;
    // SHADOW_TAPS x SHADOW_TAPS taps spread over the same square, each a
    // bilinear 2 x 2 comparison: soft edges.
    let taps = max(SHADOW_TAPS, 1);
    let spacing = texel * 3.6 / f32(max(taps - 1, 1));
    let middle = 0.5 * f32(taps - 1);
    var lit = 0.0;
    for (var y = 0; y < taps; y++) {
        for (var x = 0; x < taps; x++) {
            let offset = (vec2<f32>(f32(x), f32(y)) - middle) * spacing;
            lit += textureSampleCompareLevel(shadow_map, shadow_sampler, uv + offset, face, reference);
        }
    }
    return lit / f32(taps * taps);
}

// --- passes ----------------------------------------------------------------

// What the opaque passes write: the lit colour, for the contact occlusion
// (occlusion.wgsl) the surface's normal and its distance from the eye, and
// for the temporal path its motion (a target only that path has).
struct SceneFragment {
    @location(0) color: vec4<f32>,
    @location(1) geometry: vec4<f32>,
    @location(2) motion: vec2<f32>,
};

fn geometry_of(world: vec3<f32>, n: vec3<f32>) -> vec4<f32> {
    return vec4<f32>(n, distance(world, globals.camera_pos.xyz));
}

fn screen_uv(view_proj: mat4x4<f32>, point: vec3<f32>) -> vec2<f32> {
    let clip = view_proj * vec4<f32>(point, 1.0);
    return clip.xy / clip.w * vec2<f32>(0.5, -0.5);
}

// How far on screen (in uv, from the top left) a surface point at `world`
// that was at `previous` the frame before has moved back: where to find it
// in the last frame is its uv plus this.
fn motion_of(world: vec3<f32>, previous: vec3<f32>) -> vec2<f32> {
    return screen_uv(globals.previous_view_proj, previous) - screen_uv(globals.motion_view_proj, world);
}

@fragment
fn fs_lit(in: VertexOut) -> SceneFragment {
    let kind = in.material.x;
    var base = in.color.rgb;
    if kind == KIND_WOOD {
        base = wood(base, in.world.xz);
    } else if kind == KIND_PAINTED {
        let p = textureSampleLevel(paint, paint_sampler, in.uv, 0.0);
        // Alpha marks the paint that takes the tumbler's own colour.
        base = mix(p.rgb, p.rgb * in.color.rgb, p.a);
    } else if kind == KIND_PLAIN {
        base = plaster(base, in.world);
    }
    let n = normalize(in.normal);
    let motion = motion_of(in.world, in.previous);
    return SceneFragment(vec4<f32>(shown(base, in.world, n, in.material, motion), 1.0), geometry_of(in.world, n), motion);
}

// The terms of Blinn-Phong at a point, each in linear light.
struct LightTerms {
    ambient: vec3<f32>,
    diffuse: vec3<f32>,
    specular: vec3<f32>,
    bounce: vec3<f32>,
    // The share of the ceiling light that reaches the point.
    visible: f32,
};

// Diffuse (xyz of the first) and specular light from a point light at
// `position` of `color` that falls off as `falloff` says.
fn point_light(position: vec3<f32>, color: vec3<f32>, falloff: vec4<f32>, base: vec3<f32>, world: vec3<f32>, n: vec3<f32>, v: vec3<f32>, material: vec4<f32>) -> array<vec3<f32>, 2> {
    let to_light = position - world;
    let distance = length(to_light);
    let l = to_light / distance;
    let h = normalize(l + v);
    // Where the light has a reach (w), it fades to nothing there (as
    // `attenuated` in lighting.rs).
    var window = 1.0;
    if falloff.w > 0.0 {
        let edge = max(1.0 - pow(distance / falloff.w, 4.0), 0.0);
        window = edge * edge;
    }
    let light = color * window / (falloff.x + falloff.y * distance + falloff.z * distance * distance);
    let diffuse = base * max(dot(n, l), 0.0) * light;
    let specular = material.y * pow(max(dot(n, h), 0.0), material.z) * light * step(0.0, dot(n, l));
    return array<vec3<f32>, 2>(diffuse, specular);
}

// Ambient; where the ceiling light reaches, its diffuse and specular; the
// fireball's; and the light the room's surfaces send back.
fn light_terms(base: vec3<f32>, world: vec3<f32>, n: vec3<f32>, material: vec4<f32>) -> LightTerms {
    let v = normalize(globals.camera_pos.xyz - world);
    var terms: LightTerms;
    terms.visible = light_visibility(world, n);
    let ceiling = point_light(globals.light_pos.xyz, globals.light_color.rgb, globals.light_falloff, base, world, n, v, material);
    terms.diffuse = terms.visible * ceiling[0];
    terms.specular = terms.visible * ceiling[1];
    if globals.fireball_pos.w > 0.5 {
        let fireball = point_light(globals.fireball_pos.xyz, globals.fireball_color.rgb, globals.fireball_falloff, base, world, n, v, material);
        terms.diffuse += fireball[0];
        terms.specular += fireball[1];
    }
    terms.ambient = base * globals.light_color.w;
    // The light the room bounces back, worked out from each surface in its
    // colour (see lighting.rs); it takes the ambient's place.
    if globals.room.w > 0.5 {
        terms.bounce = base * indirect_light(world, n);
    }
    return terms;
}

fn blinn_phong(base: vec3<f32>, world: vec3<f32>, n: vec3<f32>, material: vec4<f32>) -> vec3<f32> {
    let terms = light_terms(base, world, n, material);
    var indirect = terms.ambient;
    if globals.room.w > 0.5 {
        indirect = terms.bounce;
    }
    return terms.diffuse + terms.specular + indirect;
}

// --- the frame's views (frame_view.rs) -----------------------------------------

// The view the pipelines draw: VIEW_FINAL, or one pass's VIEW_*. A
// constant of the pipeline, not a uniform, so that the finished frame's
// shader holds none of the views' code (a software rasterizer runs a
// uniform branch's both sides).
override FRAME_VIEW: u32 = 0u;

const VIEW_FINAL: u32 = 0u;
const VIEW_ALBEDO: u32 = 1u;
const VIEW_NORMALS: u32 = 2u;
const VIEW_DEPTH: u32 = 3u;
const VIEW_SHADOW: u32 = 4u;
const VIEW_AMBIENT: u32 = 5u;
const VIEW_DIFFUSE: u32 = 6u;
const VIEW_SPECULAR: u32 = 7u;
const VIEW_BOUNCE: u32 = 8u;
const VIEW_MOTION: u32 = 9u;

// A motion on screen (in uv, see `motion_of`) as colour: its direction as
// a hue, three cosines a third of a turn apart (so r + g + b is 1.5 times
// the brightness), its length in pixels as brightness.
fn motion_color(motion: vec2<f32>) -> vec3<f32> {
    let pixels = motion * globals.frame_size.xy;
    let length_px = length(pixels);
    if length_px == 0.0 {
        return vec3<f32>(0.0);
    }
    let angle = atan2(pixels.y, pixels.x);
    let third = 2.0943951;
    let hue = 0.5 + 0.5 * vec3<f32>(cos(angle), cos(angle - third), cos(angle + third));
    return hue * min(length_px / globals.frame_view.w, 1.0);
}

// What a lit surface writes: its lit colour, or in a view of one pass,
// that pass's value.
fn shown(base: vec3<f32>, world: vec3<f32>, n: vec3<f32>, material: vec4<f32>, motion: vec2<f32>) -> vec3<f32> {
    if FRAME_VIEW == VIEW_FINAL {
        return blinn_phong(base, world, n, material);
    }
    return surface_view(FRAME_VIEW, base, world, n, light_terms(base, world, n, material), motion);
}

// The value view `view` shows of a surface whose light is `terms`.
fn surface_view(view: u32, base: vec3<f32>, world: vec3<f32>, n: vec3<f32>, terms: LightTerms, motion: vec2<f32>) -> vec3<f32> {
    switch view {
        case VIEW_ALBEDO: { return base; }
        case VIEW_NORMALS: { return n * 0.5 + 0.5; }
        case VIEW_DEPTH: {
            let d = distance(world, globals.camera_pos.xyz);
            return vec3<f32>(clamp((globals.frame_view.z - d) / (globals.frame_view.z - globals.frame_view.y), 0.0, 1.0));
        }
        case VIEW_SHADOW: { return vec3<f32>(terms.visible); }
        case VIEW_AMBIENT: { return terms.ambient; }
        case VIEW_DIFFUSE: { return terms.diffuse; }
        case VIEW_SPECULAR: { return terms.specular; }
        case VIEW_BOUNCE: { return terms.bounce; }
        case VIEW_MOTION: { return motion_color(motion); }
        default: { return vec3<f32>(0.0); }
    }
}

// What an unlit surface (a lamp) writes in a view: in the term views
// nothing, it is no term of Blinn-Phong's; in the others as a surface.
fn unlit_view(view: u32, emitted: vec3<f32>, world: vec3<f32>, n: vec3<f32>, motion: vec2<f32>) -> vec3<f32> {
    var terms: LightTerms;
    terms.visible = 1.0;
    return surface_view(view, emitted, world, n, terms, motion);
}

// --- one bounce of light from the room's surfaces ----------------------------
//
// Each of the six surfaces is a large, evenly lit panel: it sends back the
// light that falls on it on average, in its own colour (worked out on the
// CPU each frame from both lights; see lighting.rs). How much of it a
// point receives is the panel's form factor seen from there, gathered
// ahead of the frame at a grid of probes for patches facing each axis
// direction (irradiance.rs). A point reads the three directions its normal
// leans towards, each weighed by the square of the normal's component
// along it (the squares sum to one), blended between its eight nearest
// probes by the texture filter.

// The light gathered at `cell` (in probes, clamped to those in use) from
// direction `slab` (0 ..= 5).
fn gathered(cell: vec3<f32>, slab: f32) -> vec3<f32> {
    let per_axis = globals.irradiance_probes.w;
    let texel = vec3<f32>(cell.xy, cell.z + slab * per_axis);
    let uvw = texel / vec3<f32>(per_axis, per_axis, 6.0 * per_axis);
    return textureSampleLevel(irradiance, irradiance_sampler, uvw, 0.0).rgb;
}

// Light arriving at `world` (normal `n`) from the six surfaces.
fn indirect_light(world: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    let probes = globals.irradiance_probes.xyz;
    let room = globals.room.xyz;
    let from_corner = (world - vec3<f32>(-room.x, 0.0, -room.z)) / vec3<f32>(2.0 * room.x, room.y, 2.0 * room.z);
    // Probe k stands at the centre of its cell, k + 1/2; beyond the outer
    // probes the light is taken as theirs.
    let cell = clamp(from_corner * probes, vec3<f32>(0.5), probes - 0.5);
    let weight = n * n;
    return weight.x * gathered(cell, select(1.0, 0.0, n.x >= 0.0))
        + weight.y * gathered(cell, select(3.0, 2.0, n.y >= 0.0))
        + weight.z * gathered(cell, select(5.0, 4.0, n.z >= 0.0));
}

// --- balls: spheres traced on a square ---------------------------------------
//
// A ball is not a mesh: it is a square that faces the eye, just large enough
// to cover the sphere, and each fragment traces its ray to the exact sphere
// and writes the depth of the point it hits. Two triangles per ball instead
// of hundreds keep a pit of 100 000 balls cheap, and the outline is a true
// circle at any distance. The shadow faces draw the balls the same way, with
// the light as the eye.

// A ball needs no matrix: its centre, its radius and its colour, 32 bytes
// where an object with a model matrix takes 96. All balls share one
// material, given to the ball pipeline as constants.
struct BallIn {
    // xyz: the centre; w: the radius.
    @location(3) sphere: vec4<f32>,
    @location(4) color: vec3<f32>,
};

override BALL_KIND: f32;
override BALL_SPECULAR: f32;
override BALL_SHININESS: f32;

struct BallOut {
    @builtin(position) clip: vec4<f32>,
    // The point on the square; the ray runs from the eye through it.
    @location(0) world: vec3<f32>,
    @location(1) @interpolate(flat) sphere: vec4<f32>,
    @location(2) @interpolate(flat) color: vec3<f32>,
    // The centre the frame before (the eye's view only).
    @location(3) @interpolate(flat) previous_centre: vec3<f32>,
};

// A ball's sphere the frame before, for its motion.
struct BallBefore {
    @location(5) sphere: vec4<f32>,
};

// Corner `corner` (each coordinate -1 or 1) of the square, square to the
// line of sight from `eye`, that covers the sphere's outline. It stands on the
// plane that touches the sphere nearest the eye, so that every ray through it
// meets the sphere, if at all, beyond it: the depth traced for a fragment is
// never nearer than the square's own, and the GPU may test the square's depth
// before tracing (see `fs_ball`). The cone of rays grazing the sphere meets
// that plane, at distance p along the axis, in a circle of radius
// p r / sqrt(d^2 - r^2). A plane closer to the eye than BALL_SQUARE_NEAREST
// would be cut away by the camera's near plane, and with it the whole ball;
// it is moved back to there (the fragment keeps its depth's promise by
// taking the larger of the two). An eye inside the sphere sees no outline;
// the square collapses and the ball is not drawn, as a mesh seen from inside
// is culled.
const BALL_SQUARE_NEAREST: f32 = 0.06;

fn ball_square_corner(sphere: vec4<f32>, eye: vec3<f32>, corner: vec2<f32>) -> vec3<f32> {
    let centre = sphere.xyz;
    let radius = sphere.w;
    let to_centre = centre - eye;
    let d2 = dot(to_centre, to_centre);
    if d2 <= radius * radius {
        return centre;
    }
    let d = sqrt(d2);
    let axis = to_centre / d;
    let plane = max(d - radius, min(d, BALL_SQUARE_NEAREST));
    let half = plane * radius * inverseSqrt(d2 - radius * radius);
    let helper = select(vec3<f32>(0.0, 1.0, 0.0), vec3<f32>(1.0, 0.0, 0.0), abs(axis.y) > 0.9);
    let side = normalize(cross(axis, helper));
    let up = cross(side, axis);
    return eye + axis * plane + (side * corner.x + up * corner.y) * half;
}

// Where the ray from `eye` through `through` meets the sphere, and how far
// (in radii) it passes from the centre: above 1 it misses, and the point is
// then the nearest on the outline.
struct BallHit {
    point: vec3<f32>,
    miss: f32,
};

fn trace_ball(sphere: vec4<f32>, eye: vec3<f32>, through: vec3<f32>) -> BallHit {
    let dir = normalize(through - eye);
    let from_centre = eye - sphere.xyz;
    let along = dot(from_centre, dir);
    // The ray's nearest approach to the centre, taken as a vector: squaring
    // distances of metres to compare with the radius would lose it to rounding.
    let across = from_centre - along * dir;
    let r2 = sphere.w * sphere.w;
    let a2 = dot(across, across);
    let t = -along - sqrt(max(r2 - a2, 0.0));
    return BallHit(eye + t * dir, sqrt(a2) / sphere.w);
}

fn depth_of(view_proj: mat4x4<f32>, point: vec3<f32>) -> f32 {
    let clip = view_proj * vec4<f32>(point, 1.0);
    return clip.z / clip.w;
}

// The depth a ball's fragment writes: the traced point's, but never nearer
// than the square's `square_depth` there, the promise the GPU's early depth
// test relies on (`@early_depth_test(greater_equal)`, added to the ball
// entry points where the adapter allows it).
fn ball_depth(view_proj: mat4x4<f32>, point: vec3<f32>, square_depth: f32) -> f32 {
    return max(depth_of(view_proj, point), square_depth);
}

// The corner `v` of the square that covers `ball` seen from `eye`, drawn
// with `view_proj`: the same for the eye's view and the light's.
fn ball_square(v: VertexIn, ball: BallIn, eye: vec3<f32>, view_proj: mat4x4<f32>) -> BallOut {
    let world = ball_square_corner(ball.sphere, eye, v.position.xy * 2.0 - 1.0);
    var out: BallOut;
    out.clip = view_proj * vec4<f32>(world, 1.0);
    out.world = world;
    out.sphere = ball.sphere;
    out.color = ball.color;
    out.previous_centre = ball.sphere.xyz;
    return out;
}

@vertex
fn vs_ball(v: VertexIn, ball: BallIn, before: BallBefore) -> BallOut {
    var out = ball_square(v, ball, globals.camera_pos.xyz, globals.view_proj);
    out.previous_centre = before.sphere.xyz;
    return out;
}

// With multisampling, a fragment on the outline covers the share of its
// samples that the sphere covers (alpha to coverage), so the edge is smooth
// like a mesh's; without, a pixel is the ball's if its centre is.
override ALPHA_TO_COVERAGE: bool = true;

struct BallFragment {
    @location(0) color: vec4<f32>,
    @location(1) geometry: vec4<f32>,
    @location(2) motion: vec2<f32>,
    @builtin(frag_depth) depth: f32,
};

@fragment
fn fs_ball(in: BallOut) -> BallFragment {
    let hit = trace_ball(in.sphere, globals.camera_pos.xyz, in.world);
    // How far inside the outline, in pixels, from how fast `miss` changes.
    let inside = (1.0 - hit.miss) / max(fwidth(hit.miss), 1e-6);
    let coverage = clamp(inside + 0.5, 0.0, 1.0);
    if coverage <= 0.0 || (!ALPHA_TO_COVERAGE && coverage < 0.5) {
        discard;
    }
    let n = normalize(hit.point - in.sphere.xyz);
    var out: BallFragment;
    let material = vec4<f32>(BALL_KIND, BALL_SPECULAR, BALL_SHININESS, 0.0);
    // The ball moves as a whole: its spin does not show on its one colour.
    out.motion = motion_of(hit.point, hit.point - in.sphere.xyz + in.previous_centre);
    out.color = vec4<f32>(shown(in.color, hit.point, n, material, out.motion), coverage);
    out.geometry = geometry_of(hit.point, n);
    out.depth = ball_depth(globals.view_proj, hit.point, in.clip.z);
    return out;
}

// Unlit and glowing: the light's bulb (and, with it, anything emissive).
@fragment
fn fs_emissive(in: VertexOut) -> SceneFragment {
    let n = normalize(in.normal);
    let motion = motion_of(in.world, in.previous);
    var color = in.color.rgb * in.material.w;
    if FRAME_VIEW != VIEW_FINAL {
        color = unlit_view(FRAME_VIEW, in.color.rgb, in.world, n, motion);
    }
    return SceneFragment(vec4<f32>(color, 1.0), geometry_of(in.world, n), motion);
}

// Glowing and see-through, unlit, in premultiplied alpha: rgb is the light
// added, a how much of what is behind is covered.
// Kind 0, a cube: a hole in space (a dark, half-covering inside) framed by a
// bright edge and a circuit-like grid: a "space collapse" look.
// Kind 1, a shell: glow, brightest at its rim, over a veil.
const SHELL_COVER: f32 = 0.7;
@fragment
fn fs_glow(in: VertexOut) -> @location(0) vec4<f32> {
    let alpha = in.color.a;
    if in.material.x < 0.5 {
        let q = abs(in.uv - vec2<f32>(0.5));
        let edge = max(q.x, q.y);
        let frame = smoothstep(0.34, 0.47, edge);
        let cells = abs(fract(in.uv * 3.0) - vec2<f32>(0.5));
        let grid = smoothstep(0.43, 0.5, max(cells.x, cells.y)) * (1.0 - frame);
        let glow = in.color.rgb * (frame + 0.35 * grid);
        let cover = 0.8 * (1.0 - frame);
        let void_color = vec3<f32>(0.015, 0.0, 0.04);
        return vec4<f32>((glow + void_color * cover) * alpha, cover * alpha);
    }
    let v = normalize(globals.camera_pos.xyz - in.world);
    let facing = abs(dot(normalize(in.normal), v));
    let strength = 0.9 + 1.6 * pow(1.0 - facing, 2.0);
    // Covering much of what is behind, so that it shows as fire even
    // against a bright wall.
    return vec4<f32>(in.color.rgb * strength * alpha, SHELL_COVER * alpha);
}

struct ShadowFace {
    view_proj: mat4x4<f32>,
    // xyz: the light, which the face looks out from; w: unused.
    light_pos: vec4<f32>,
};

@group(0) @binding(0) var<uniform> shadow_face_uniform: ShadowFace;

@vertex
fn vs_shadow(v: VertexIn, i: InstanceIn) -> @builtin(position) vec4<f32> {
    return shadow_face_uniform.view_proj * (model_of(i) * vec4<f32>(v.position, 1.0));
}

@vertex
fn vs_ball_shadow(v: VertexIn, ball: BallIn) -> BallOut {
    return ball_square(v, ball, shadow_face_uniform.light_pos.xyz, shadow_face_uniform.view_proj);
}

// The depth of the sphere seen from the light. A written depth takes none of
// the pipeline's slope-scaled bias; the lit pass's lookup, pushed off the
// surface along its normal (see `light_visibility`), keeps a ball from
// shadowing itself all the same.
@fragment
fn fs_ball_shadow(in: BallOut) -> @builtin(frag_depth) f32 {
    let light = shadow_face_uniform.light_pos.xyz;
    let hit = trace_ball(in.sphere, light, in.world);
    if hit.miss > 1.0 {
        discard;
    }
    return ball_depth(shadow_face_uniform.view_proj, hit.point, in.clip.z);
}
