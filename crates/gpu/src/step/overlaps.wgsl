// What the velocities left of overlap is pushed out by position alone, in
// Jacobi sweeps like the solver's, one dispatch each (see `pos_in`): each
// ball its share of each overlap with a ball (the lighter moved more) or a
// body. The velocities are left alone, so this makes no motion. The last SLOP of an
// overlap is left: pushed out whole, resting balls would stand a hair
// apart, fall back in and bounce, and a pile would never rest.

@compute @workgroup_size(256)
fn overlaps_forth(@builtin(global_invocation_id) id: vec3<u32>) {
    push_out_overlaps_of(ball_index(id), false);
}

@compute @workgroup_size(256)
fn overlaps_back(@builtin(global_invocation_id) id: vec3<u32>) {
    push_out_overlaps_of(ball_index(id), true);
}

// One Jacobi sweep of ball i's overlaps (see `pos_in`).
fn push_out_overlaps_of(i: u32, back: bool) {
    if i >= params.count {
        return;
    }
    let me = pos_in(i, back);
    if !in_solver(i) {
        // Carried over, so that the copy the sweeps end in holds every ball.
        put_pos(i, back, me);
        return;
    }
    let p = me.xyz;
    let r = me.w;
    let im = vel[i].w;
    let mine = contact_count(i);
    let relax = params.more.w;
    let slop = params.grid.y;
    var shift = vec3<f32>(0.0);
    let slots = slot_count(state[i]);
    for (var k = 0u; k < slots; k++) {
        let j = slot_other[i * SLOTS + k];
        if !alive(j) {
            continue;
        }
        let other = pos_in(j, back);
        let d = p - other.xyz;
        let dist = length(d);
        let overlap = r + other.w - dist - slop;
        if overlap <= 0.0 || dist <= 0.0 {
            continue;
        }
        let share = relax / f32(max(mine, contact_count(j)));
        shift += d / dist * overlap * share * im / (im + vel[j].w);
    }
    let b = body_of[i];
    if b != NONE && bodies[b].info.x != FIREBALL {
        let d = p - bodies[b].sphere.xyz;
        let dist = length(d);
        let overlap = r + bodies[b].sphere.w - dist - slop;
        if overlap > 0.0 && dist > 0.0 {
            shift += d / dist * overlap * relax / f32(mine);
        }
    }
    let moved = clamp(p + shift, params.room_min.xyz + r, params.room_max.xyz - r);
    put_pos(i, back, vec4<f32>(moved, r));
}

// A small world's sweeps in one workgroup (see `SMALL_GROUP`).
@compute @workgroup_size(SMALL_GROUP)
fn overlaps_in_one_group(@builtin(local_invocation_index) t: u32) {
    for (var sweep = 0u; sweep < SHIFT_SWEEPS; sweep++) {
        for (var i = t; i < params.count; i += SMALL_GROUP) {
            push_out_overlaps_of(i, sweep % 2u == 1u);
        }
        storageBarrier();
    }
}
