// Impacts, before gravity and the resting contacts (the collision pass of
// Guendelman, Bridson and Fedkiw): the balls' velocities at the step's
// start are corrected so that every contact that closes fast enough to
// bounce and touch within the step parts at its restitution times the
// speed it closed at. They run in rounds of Jacobi sweeps (one dispatch
// each, see `vel_in`), each round's impulses added to the velocities for
// good. A round asks a bounce of
// each contact that closes fast enough at the velocities the round starts
// with: in the first round those of the step's start; in the next, after
// the first round's bounces, so that a ball struck into its neighbour
// strikes it in turn, and a row of balls passes a blow along it as
// Newton's cradle does. Impacts push along the normal only.

// The round this pipeline raises goals for, or sweeps (0, 1, 2).
override IMPACT_ROUND: u32 = 0u;

// Each round's sweeps' dispatch, workgroups along x, y and z (and a pad),
// widened as balls join its list. Bound apart from the rest, and only to
// the passes that raise goals: a buffer a dispatch reads its size from
// may not be bound for writing in that dispatch.
@group(1) @binding(0) var<storage, read_write> impact_dispatch: array<atomic<u32>>;

@compute @workgroup_size(256)
fn raise_impact_goals(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = ball_index(id);
    if i >= params.count {
        return;
    }
    // Both copies the sweeps alternate between start alike: a ball off the
    // list keeps its velocity in both.
    delta[i] = vel[i];
    if raise_impact_goals_of(i) > 0u {
        list_for_impacts(i);
    }
}

// Puts ball i on this round's list, and widens the round's dispatch to
// reach it. The list's order is the order the atomics land in, which
// changes from run to run; a Jacobi sweep's result does not.
fn list_for_impacts(i: u32) {
    let round = 4u * IMPACT_ROUND;
    let at = atomicAdd(&impact_count[IMPACT_ROUND], 1u);
    impact_list[at] = i;
    let groups = at / WORKGROUP + 1u;
    atomicMax(&impact_dispatch[round], min(groups, MAX_GROUPS));
    atomicMax(&impact_dispatch[round + 1u], (groups + MAX_GROUPS - 1u) / MAX_GROUPS);
}

// Ball i's contacts' goals for the round; returns how many bounce.
fn raise_impact_goals_of(i: u32) -> u32 {
    if !in_solver(i) {
        return 0u;
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
    return bouncing;
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

// A sweep runs a thread for each ball on the round's list, dispatched as
// many as the list holds (indirectly): a round in which nothing bounces
// costs nothing.
@compute @workgroup_size(256)
fn impacts_forth(@builtin(global_invocation_id) id: vec3<u32>) {
    let t = ball_index(id);
    if t < atomicLoad(&impact_count[IMPACT_ROUND]) {
        solve_impacts_of(impact_list[t], false);
    }
}

@compute @workgroup_size(256)
fn impacts_back(@builtin(global_invocation_id) id: vec3<u32>) {
    let t = ball_index(id);
    if t < atomicLoad(&impact_count[IMPACT_ROUND]) {
        solve_impacts_of(impact_list[t], true);
    }
}

// One Jacobi sweep of ball i's impacts (see `vel_in`).
fn solve_impacts_of(i: u32, back: bool) {
    if i >= params.count {
        return;
    }
    let v = vel_in(i, back);
    if !in_solver(i) {
        // Carried over, so that the copy the sweeps end in holds every ball.
        put_vel(i, back, v);
        return;
    }
    let p = pos[i].xyz;
    let r = pos[i].w;
    let im = v.w;
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
        let va = vel_in(a, back);
        let vb = vel_in(b, back);
        let speed = dot(va.xyz - vb.xyz, g.xyz);
        let total = impact_impulse(slot_impact[at].x, slot_impact[at].y, speed, va.w + vb.w, share);
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
            let total = impact_impulse(goals[axis], totals[axis], dot(v.xyz, n), im, share);
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
        let total = impact_impulse(goals.w, totals.w, dot(v.xyz - vb, n), k, share);
        dv += (total - totals.w) * n * im;
        totals.w = total;
    }
    own_impact[2u * i + 1u] = totals;
    put_vel(i, back, vec4<f32>(v.xyz + dv, im));
}

// A small world's rounds in one workgroup (see `SMALL_GROUP`): each
// thread takes every SMALL_GROUP-th ball, the list is not needed.
@compute @workgroup_size(SMALL_GROUP)
fn impacts_in_one_group(@builtin(local_invocation_index) t: u32) {
    for (var round = 0u; round < IMPACT_ROUNDS; round++) {
        for (var i = t; i < params.count; i += SMALL_GROUP) {
            _ = raise_impact_goals_of(i);
        }
        storageBarrier();
        for (var sweep = 0u; sweep < IMPACT_SWEEPS; sweep++) {
            for (var i = t; i < params.count; i += SMALL_GROUP) {
                solve_impacts_of(i, sweep % 2u == 1u);
            }
            storageBarrier();
        }
    }
}
