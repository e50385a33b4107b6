// Between the impacts and the contact solver's sweeps (see solve.wgsl),
// run by the impacts' last dispatch (see impacts.wgsl) for want of a
// dispatch of its own: each ball reads only itself and its own contacts.

// Ball i at velocity `v` (w: inverse mass) after the impacts: gravity
// and its contacts' warm impulses given to its velocity, how many of them
// may push within the step counted (see `shares` in solve.wgsl), and its
// shift out of overlaps started at none. A ball reads only its own
// contacts here.
fn warm_start(i: u32, v: vec4<f32>) {
    let p = motion[POS + i].xyz;
    let r = motion[POS + i].w;
    let im = v.w;
    var dv = gravity() * dt();
    var dw = vec3<f32>(0.0);
    if (ball_words[STATE + i] & SOLVED) != 0u {
        fold_body_impact(i);
        var pressing = 0u;
        for (var k = 0u; k < slot_count(ball_words[STATE + i]); k++) {
            let j = slot_words[SLOT_OTHER + i * SLOTS + k];
            let d = p - motion[POS + j].xyz;
            let closing = max(0.0, -dot(motion[VEL_START + i].xyz - motion[VEL_START + j].xyz, direction(d)));
            let gap = length(d) - r - motion[POS + j].w;
            let near = gap - closing * dt() < params.grid.y;
            if slot_words[SLOT_MIRROR + i * SLOTS + k] == NONE {
                // Not solved, but the ball may be shifted out of it.
                pressing += u32(near);
                continue;
            }
            let a = min(i, j);
            let n = direction(motion[POS + a].xyz - motion[POS + i + j - a].xyz);
            let total = impulse_at(i * SLOTS + k);
            // Pushing already, or closing on its margin within the step.
            pressing += u32(total.w > 0.0 || near);
            let on_i = select(-1.0, 1.0, i == a) * (total.w * n + total.xyz);
            dv += on_i * im;
            dw += cross(r * direction(motion[POS + j].xyz - p), on_i) * inv_inertia(im, r);
        }
        for (var axis = 0u; axis < 3u; axis++) {
            if touches_wall(ball_words[STATE + i], axis) {
                let n = nearest_wall(p, r, axis).xyz;
                let total = pushes[WALL_IMPULSE + i * 3u + axis];
                let on_i = total.w * n + total.xyz;
                dv += on_i * im;
                dw += cross(-r * n, on_i) * inv_inertia(im, r);
                pressing += 1u;
            }
        }
        let b = ball_words[BODY_OF + i];
        if b != NONE {
            let n = direction(p - bodies[b].sphere.xyz);
            dv += pushes[BODY_IMPULSE + i].w * n * im;
            pressing += 1u;
        }
        ball_words[STATE + i] = (ball_words[STATE + i] & ~(31u << PRESSING_SHIFT)) | (min(pressing, 31u) << PRESSING_SHIFT);
    }
    motion[VEL + i] = vec4<f32>(v.xyz + dv, im);
    motion[SPIN + i] = vec4<f32>(motion[SPIN + i].xyz + dw, 0.0);
    put_shift(i, true, vec4<f32>(0.0));
}
