// The cursor shader: the white arrow cursor of grab mode, drawn in
// screen space over the finished frame: a black outline, then the white arrow.

struct Cursor {
    // xy: tip position in pixels; zw: frame size in pixels.
    place: vec4<f32>,
};
@group(0) @binding(0) var<uniform> cursor: Cursor;

// Five triangles of an arrow 20 pixels tall, tip at the origin, y down.
const ARROW = array<vec2<f32>, 15>(
    vec2<f32>(0.0, 0.0), vec2<f32>(0.0, 17.0), vec2<f32>(4.0, 13.0),
    vec2<f32>(0.0, 0.0), vec2<f32>(4.0, 13.0), vec2<f32>(6.0, 12.0),
    vec2<f32>(0.0, 0.0), vec2<f32>(6.0, 12.0), vec2<f32>(12.0, 12.0),
    vec2<f32>(4.0, 13.0), vec2<f32>(7.5, 20.0), vec2<f32>(9.5, 19.0),
    vec2<f32>(4.0, 13.0), vec2<f32>(9.5, 19.0), vec2<f32>(6.0, 12.0),
);

struct Out {
    @builtin(position) clip: vec4<f32>,
    @location(0) @interpolate(flat) shade: f32,
};

@vertex
fn vs_cursor(@builtin(vertex_index) index: u32, @builtin(instance_index) layer: u32) -> Out {
    var p = ARROW[index];
    var shade = 1.0;
    if layer == 0u {
        // The outline: the same arrow, grown about its middle.
        p = (p - vec2<f32>(5.0, 9.0)) * 1.3 + vec2<f32>(5.0, 9.0) + vec2<f32>(-0.5, -1.0);
        shade = 0.0;
    }
    let pixel = cursor.place.xy + p;
    let ndc = vec2<f32>(pixel.x / cursor.place.z * 2.0 - 1.0, 1.0 - pixel.y / cursor.place.w * 2.0);
    var out: Out;
    out.clip = vec4<f32>(ndc, 0.0, 1.0);
    out.shade = shade;
    return out;
}

@fragment
fn fs_cursor(in: Out) -> @location(0) vec4<f32> {
    return vec4<f32>(vec3<f32>(in.shade), 1.0);
}
