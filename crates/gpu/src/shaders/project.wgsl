// What the velocities left of overlap is pushed out by position alone, in
// Jacobi sweeps like the solver's: each ball its share of each overlap
// with a ball (the lighter moved more) or a body, then all at once. The
// velocities are left alone, so this makes no motion. The last SLOP of an
// overlap is left: pushed out whole, resting balls would stand a hair
// apart, fall back in and bounce, and a pile would never rest.

@compute @workgroup_size(256)
fn find_overlaps(@builtin(global_invocation_id) id: vec3<u32>) {
    find_overlaps_of(ball_index(id));
}

fn find_overlaps_of(i: u32) {
    if !in_solver(i) {
        return;
    }
    let p = pos[i].xyz;
    let r = pos[i].w;
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
        let d = p - pos[j].xyz;
        let dist = length(d);
        let overlap = r + pos[j].w - dist - slop;
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
    delta[i] = vec4<f32>(shift, 0.0);
}

@compute @workgroup_size(256)
fn apply_shifts(@builtin(global_invocation_id) id: vec3<u32>) {
    apply_shifts_of(ball_index(id));
}

fn apply_shifts_of(i: u32) {
    if !in_solver(i) {
        return;
    }
    let r = pos[i].w;
    let p = clamp(pos[i].xyz + delta[i].xyz, params.room_min.xyz + r, params.room_max.xyz - r);
    pos[i] = vec4<f32>(p, r);
}
