// The views of the frame that no frame target holds as it is shown
// (frame_view.rs), each over the whole output after the frame: the light's
// shadow cube unfolded, the pixels whose multisamples disagree, and the
// temporal path's weight of history.

struct Views {
    // xy: the output's size in pixels; z: a shadow face's side in the
    // cross, in pixels; w: a shadow face's side in texels.
    size: vec4<f32>,
    // xy: where the cross's top left lies on the output; z: the distance
    // drawn white in the shadow cube (m); w: the most weight a history
    // holds.
    place: vec4<f32>,
    // The faces' near and far planes (m): x, y; zw: the scene's size in
    // pixels.
    planes: vec4<f32>,
    // Where face k (+X, -X, +Y, -Y, +Z, -Z) lies in the cross: xy its
    // column and row.
    cells: array<vec4<f32>, 6>,
};

@group(0) @binding(0) var<uniform> views: Views;
// Read as plain floats: OpenGL cannot load texels of a depth texture.
@group(0) @binding(1) var shadow_faces: texture_2d_array<f32>;
@group(0) @binding(2) var samples: texture_multisampled_2d<f32>;
@group(0) @binding(3) var history: texture_2d<f32>;

// --- the shadow cube ---------------------------------------------------------

// The glyphs of the faces' labels, 5 x 5, the top row in the lowest bits.
const GLYPH_PLUS: u32 = 0x00427C84u;
const GLYPH_MINUS: u32 = 0x00007C00u;
const GLYPH_X: u32 = 0x01151151u;
const GLYPH_Y: u32 = 0x00421151u;
const GLYPH_Z: u32 = 0x01F1111Fu;
// Output pixels a glyph's pixel takes, and where a label stands in its face.
const GLYPH_SCALE: f32 = 3.0;
const LABEL_MARGIN: f32 = 6.0;

// Whether `p` (in glyph pixels from the glyph's top left) is inked.
fn inked(glyph: u32, p: vec2<i32>) -> bool {
    if p.x < 0 || p.y < 0 || p.x >= 5 || p.y >= 5 {
        return false;
    }
    return ((glyph >> u32(p.y * 5 + p.x)) & 1u) == 1u;
}

// Whether `p` (in output pixels from the face's top left) lies on face
// `face`'s label: its sign, then its axis.
fn on_label(face: i32, p: vec2<f32>) -> bool {
    let at = vec2<i32>(floor((p - LABEL_MARGIN) / GLYPH_SCALE));
    var sign = GLYPH_PLUS;
    if face % 2 == 1 {
        sign = GLYPH_MINUS;
    }
    var axis = GLYPH_X;
    if face / 2 == 1 {
        axis = GLYPH_Y;
    } else if face / 2 == 2 {
        axis = GLYPH_Z;
    }
    return inked(sign, at) || inked(axis, at - vec2<i32>(6, 0));
}

// A face's depth as the distance along its axis (the faces' projection is
// Direct3D's: depth runs from 0 at the near plane to 1 at the far).
fn face_distance(depth: f32) -> f32 {
    let near = views.planes.x;
    let far = views.planes.y;
    return near * far / (far - depth * (far - near));
}

@fragment
fn fs_shadow_cube(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let side = views.size.z;
    let p = position.xy - views.place.xy;
    let cell = floor(p / side);
    for (var face = 0; face < 6; face++) {
        if all(cell == views.cells[face].xy) {
            let inside = p - cell * side;
            if on_label(face, inside) {
                return vec4<f32>(1.0, 0.8, 0.1, 1.0);
            }
            let texel = vec2<i32>(inside / side * views.size.w);
            let depth = textureLoad(shadow_faces, texel, face, 0).r;
            let grey = clamp(face_distance(depth) / views.place.z, 0.0, 1.0);
            return vec4<f32>(vec3<f32>(grey), 1.0);
        }
    }
    return vec4<f32>(0.0, 0.0, 0.0, 1.0);
}

// --- the multisampled edges ----------------------------------------------------

// Samples whose distances from the eye differ by more than this share, or
// whose normals turn by more than about 8 degrees, see different surfaces.
const EDGE_DISTANCE: f32 = 0.02;
const EDGE_NORMAL_COS: f32 = 0.99;

@fragment
fn fs_msaa_edges(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let at = vec2<i32>(position.xy * views.planes.zw / views.size.xy);
    let first = textureLoad(samples, at, 0);
    let count = i32(textureNumSamples(samples));
    for (var k = 1; k < count; k++) {
        let other = textureLoad(samples, at, k);
        let far = max(first.w, other.w);
        let apart = abs(first.w - other.w) > EDGE_DISTANCE * far;
        let turned = dot(first.xyz, other.xyz) < EDGE_NORMAL_COS * length(first.xyz) * length(other.xyz);
        if apart || turned {
            return vec4<f32>(1.0);
        }
    }
    return vec4<f32>(0.0, 0.0, 0.0, 1.0);
}

// --- the temporal history ------------------------------------------------------

@fragment
fn fs_history(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let weight = textureLoad(history, vec2<i32>(position.xy), 0).a;
    return vec4<f32>(vec3<f32>(clamp(weight / views.place.w, 0.0, 1.0)), 1.0);
}
