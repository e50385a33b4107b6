// What the balls did to the tumblers in the step: each tumbler's push
// from the balls, summed in a fixed order (no float atomics).

// Impulse, and the mass of the balls that pushed.
var<workgroup> push_impulse: array<vec4<f32>, 256>;
var<workgroup> push_moment: array<vec3<f32>, 256>;

// One workgroup a tumbler: its threads walk the cells around its spheres
// in turn, each ball there once, then add their sums pairwise.
@compute @workgroup_size(256)
fn sum_tumbler_push(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let t = wid.x;
    var lo = vec3<f32>(1e30);
    var hi = vec3<f32>(-1e30);
    var origin = vec3<f32>(0.0);
    for (var b = 0u; b < params.bodies; b++) {
        if bodies[b].info.x == t {
            let reach = bodies[b].sphere.w + params.grid.x;
            lo = min(lo, bodies[b].sphere.xyz - reach);
            hi = max(hi, bodies[b].sphere.xyz + reach);
            origin = bodies[b].origin.xyz;
        }
    }
    var impulse = vec4<f32>(0.0);
    var moment = vec3<f32>(0.0);
    if lo.x <= hi.x {
        let c0 = cell_coords(lo);
        let size = cell_coords(hi) - c0 + 1;
        let total = u32(size.x * size.y * size.z);
        for (var k = lid; k < total; k += WORKGROUP) {
            let off = vec3<i32>(i32(k % u32(size.x)), i32((k / u32(size.x)) % u32(size.y)), i32(k / u32(size.x * size.y)));
            let cell = cell_id(c0 + off);
            for (var m = cell_words[CELL_START + cell]; m < cell_words[CELL_START + cell + 1u]; m++) {
                let i = ball_words[CELL_BALLS + m];
                let b = ball_words[BODY_OF + i];
                if b == NONE || bodies[b].info.x != t {
                    continue;
                }
                // Its impact's push and its resting contact's.
                let pushed = pushes[BODY_IMPULSE + i].x + pushes[BODY_IMPULSE + i].w;
                if pushed <= 0.0 {
                    continue;
                }
                let n = direction(motion[POS + i].xyz - bodies[b].sphere.xyz);
                let on_tumbler = -pushed * n;
                let point = bodies[b].sphere.xyz + n * bodies[b].sphere.w;
                impulse += vec4<f32>(on_tumbler, 1.0 / motion[VEL + i].w);
                moment += cross(point - origin, on_tumbler);
            }
        }
    }
    push_impulse[lid] = impulse;
    push_moment[lid] = moment;
    workgroupBarrier();
    for (var half = 128u; half > 0u; half /= 2u) {
        if lid < half {
            push_impulse[lid] += push_impulse[lid + half];
            push_moment[lid] += push_moment[lid + half];
        }
        workgroupBarrier();
    }
    if lid == 0u {
        tumbler_push[2u * t] = push_impulse[0];
        tumbler_push[2u * t + 1u] = vec4<f32>(push_moment[0], 0.0);
    }
}
