// Impacts, before gravity and the resting contacts (the collision pass of
// Guendelman, Bridson and Fedkiw): the balls' velocities at the step's
// start are corrected so that every contact that closes fast enough to
// bounce and touch within the step parts at its restitution times the
// speed it closed at. They run in rounds of Jacobi sweeps, each round's
// impulses added to the velocities for good. A round asks a bounce of
// each contact that closes fast enough at the velocities the round starts
// with: in the first round those of the step's start; in the next, after
// the first round's bounces, so that a ball struck into its neighbour
// strikes it in turn, and a row of balls passes a blow along it as
// Newton's cradle does. Impacts push along the normal only.

@compute @workgroup_size(256)
fn raise_impact_goals(@builtin(global_invocation_id) id: vec3<u32>) {
    raise_impact_goals_of(ball_index(id));
}

fn raise_impact_goals_of(i: u32) {
    if !in_solver(i) {
        return;
    }
    var bouncing = 0u;
    for (var k = 0u; k < slot_count(state[i]); k++) {
        let j = slot_other[i * SLOTS + k];
        let a = min(i, j);
        let g = pair_geometry(a, i + j - a);
        let approach = -dot(vel[a].xyz - vel[i + j - a].xyz, g.xyz);
        let at = i * SLOTS + k;
        let goal = bounce_goal(approach, g.w, params.material.x);
        slot_impact[at] = vec2<f32>(goal, 0.0);
        bouncing += u32(goal != NO_GOAL);
    }
    var goals = vec4<f32>(NO_GOAL);
    let p = pos[i].xyz;
    let r = pos[i].w;
    for (var axis = 0u; axis < 3u; axis++) {
        if touches_wall(state[i], axis) {
            let wall = nearest_wall(p, r, axis);
            let approach = -dot(vel[i].xyz, wall.xyz);
            goals[axis] = bounce_goal(approach, wall.w, params.material.z);
            bouncing += u32(goals[axis] != NO_GOAL);
        }
    }
    let b = body_of[i];
    if b != NONE {
        let body = bodies[b];
        let d = p - body.sphere.xyz;
        let n = direction(d);
        let vb = body_point_velocity(body, body.sphere.xyz + n * body.sphere.w);
        let approach = -dot(vel[i].xyz - vb, n);
        goals.w = bounce_goal(approach, length(d) - r - body.sphere.w, params.more.y);
        bouncing += u32(goals.w != NO_GOAL);
    }
    own_impact[2u * i] = goals;
    state[i] = (state[i] & ~(31u << IMPACT_SHIFT)) | (min(bouncing, 31u) << IMPACT_SHIFT);
    fold_body_impact(i);
}


fn bouncing_count(i: u32) -> u32 {
    return max((state[i] >> IMPACT_SHIFT) & 31u, 1u);
}

// The new impulse so far of a contact with goal `goal`, impulse so far
// `total`, normal speed now `speed` and inverse effective mass `k`.
fn impact_impulse(goal: f32, total: f32, speed: f32, k: f32, share: f32) -> f32 {
    if goal == NO_GOAL {
        return 0.0;
    }
    return max(0.0, total + share * (goal - speed) / k);
}

@compute @workgroup_size(256)
fn solve_impacts(@builtin(global_invocation_id) id: vec3<u32>) {
    solve_impacts_of(ball_index(id));
}

fn solve_impacts_of(i: u32) {
    if !in_solver(i) {
        return;
    }
    let p = pos[i].xyz;
    let r = pos[i].w;
    let im = vel[i].w;
    let relax = params.more.w;
    // Shares among the contacts that bounce this round only: a lone
    // impact is met in one sweep.
    let mine = bouncing_count(i);
    var dv = vec3<f32>(0.0);
    for (var k = 0u; k < slot_count(state[i]); k++) {
        let j = slot_other[i * SLOTS + k];
        let a = min(i, j);
        let b = i + j - a;
        let g = pair_geometry(a, b);
        let share = relax / f32(max(mine, bouncing_count(j)));
        let at = i * SLOTS + k;
        let speed = dot(vel[a].xyz - vel[b].xyz, g.xyz);
        let total = impact_impulse(slot_impact[at].x, slot_impact[at].y, speed, vel[a].w + vel[b].w, share);
        // On the lower-numbered ball along the normal; the other, against it.
        let change = (total - slot_impact[at].y) * g.xyz * select(-1.0, 1.0, i == a);
        slot_impact[at] = vec2<f32>(slot_impact[at].x, total);
        dv += change * im;
    }
    let share = relax / f32(mine);
    let goals = own_impact[2u * i];
    var totals = own_impact[2u * i + 1u];
    for (var axis = 0u; axis < 3u; axis++) {
        if touches_wall(state[i], axis) {
            let n = nearest_wall(p, r, axis).xyz;
            let total = impact_impulse(goals[axis], totals[axis], dot(vel[i].xyz, n), im, share);
            dv += (total - totals[axis]) * n * im;
            totals[axis] = total;
        }
    }
    let b = body_of[i];
    if b != NONE {
        let body = bodies[b];
        let n = direction(p - body.sphere.xyz);
        let point = body.sphere.xyz + n * body.sphere.w;
        let vb = body_point_velocity(body, point);
        let k = im + body_inverse_mass(body, point, n);
        let total = impact_impulse(goals.w, totals.w, dot(vel[i].xyz - vb, n), k, share);
        dv += (total - totals.w) * n * im;
        totals.w = total;
    }
    own_impact[2u * i + 1u] = totals;
    delta[i] = vec4<f32>(dv, 0.0);
    delta_spin[i] = vec4<f32>(0.0);
}
