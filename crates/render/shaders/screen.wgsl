// The vertex shader of the passes that work on whole images (occlusion,
// bloom, tone mapping): one triangle that covers the target, with uv from
// its top left. Put in front of each such pass's own shader.

struct ScreenOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) uv: vec2<f32>,
};

@vertex
fn vs_screen(@builtin(vertex_index) index: u32) -> ScreenOut {
    let x = f32((index << 1u) & 2u);
    let y = f32(index & 2u);
    var out: ScreenOut;
    out.clip = vec4<f32>(x * 2.0 - 1.0, y * 2.0 - 1.0, 0.0, 1.0);
    out.uv = vec2<f32>(x, 1.0 - y);
    return out;
}
