// Between the impacts and the contact solver's sweeps (see solve.wgsl),
// run by the impacts' last dispatch (see impacts.wgsl) for want of a
// dispatch of its own: each ball reads only itself and its own contacts.

// Ball i at velocity `v` (w: inverse mass) after the impacts: gravity
// and its contacts' warm impulses given to its velocity, how many of them
// may push within the step counted (see `shares` in solve.wgsl), and its
// shift out of overlaps started at none. A ball reads only its own
// contacts here.
fn warm_start(i: u32, v: vec4<f32>) {
    let p = pos[i].xyz;
    let r = pos[i].w;
    let im = v.w;
    var dv = gravity() * dt();
    var dw = vec3<f32>(0.0);
    if (state[i] & SOLVED) != 0u {
        fold_body_impact(i);
        var pressing = 0u;
        for (var k = 0u; k < slot_count(state[i]); k++) {
            let j = slot_other[i * SLOTS + k];
            let d = p - pos[j].xyz;
            let closing = max(0.0, -dot(vel_start[i].xyz - vel_start[j].xyz, direction(d)));
            let gap = length(d) - r - pos[j].w;
            let near = gap - closing * dt() < params.grid.y;
            if slot_mirror[i * SLOTS + k] == NONE {
                // Not solved, but the ball may be shifted out of it.
                pressing += u32(near);
                continue;
            }
            let a = min(i, j);
            let n = direction(pos[a].xyz - pos[i + j - a].xyz);
            let total = impulse_at(i * SLOTS + k);
            // Pushing already, or closing on its margin within the step.
            pressing += u32(total.w > 0.0 || near);
            let on_i = select(-1.0, 1.0, i == a) * (total.w * n + total.xyz);
            dv += on_i * im;
            dw += cross(r * direction(pos[j].xyz - p), on_i) * inv_inertia(im, r);
        }
        for (var axis = 0u; axis < 3u; axis++) {
            if touches_wall(state[i], axis) {
                let n = nearest_wall(p, r, axis).xyz;
                let total = wall_impulse[i * 3u + axis];
                let on_i = total.w * n + total.xyz;
                dv += on_i * im;
                dw += cross(-r * n, on_i) * inv_inertia(im, r);
                pressing += 1u;
            }
        }
        let b = body_of[i];
        if b != NONE {
            let n = direction(p - bodies[b].sphere.xyz);
            dv += body_impulse[i].w * n * im;
            pressing += 1u;
        }
        state[i] = (state[i] & ~(31u << PRESSING_SHIFT)) | (min(pressing, 31u) << PRESSING_SHIFT);
    }
    vel[i] = vec4<f32>(v.xyz + dv, im);
    spin[i] = vec4<f32>(spin[i].xyz + dw, 0.0);
    put_shift(i, true, vec4<f32>(0.0));
}
