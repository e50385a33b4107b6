// Each ball finds what it may touch within the step: its nearest balls in
// the 27 cells around it (in cell order, each cell in ball order, so the
// same every run), the nearest body, the nearest walls. The fireball, when
// it takes balls, has taken those it reaches just before. A contact kept from the
// last step starts from the impulse it ended that step with (the warm
// start, see warm_start.wgsl).

// The fastest ball near each: a blow passed down a column within the step
// can set a ball moving at the speed of the fastest ball around it.
@compute @workgroup_size(256)
fn gauge_near_speed(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = ball_index(id);
    if i >= params.count {
        return;
    }
    let home = cell_coords(motion[POS + i].xyz);
    var fastest = 0.0;
    for (var dz = -1; dz <= 1; dz++) {
        for (var dy = -1; dy <= 1; dy++) {
            for (var dx = -1; dx <= 1; dx++) {
                let c = home + vec3<i32>(dx, dy, dz);
                if all(c >= vec3<i32>(0)) && all(c < vec3<i32>(params.dims.xyz)) {
                    fastest = max(fastest, cell_speed_of(cell_id(c)));
                }
            }
        }
    }
    set_near_speed(i, fastest);
}

// The fireball, when it takes balls, takes those it reaches within the
// step: gone from the room, each catch reported. Before the contacts are
// found, so that a caught ball has none.
@compute @workgroup_size(256)
fn catch_in_fireball(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = ball_index(id);
    if i >= params.count || !alive(i) {
        return;
    }
    let p = motion[POS + i].xyz;
    let r = motion[POS + i].w;
    let v = motion[VEL + i].xyz;
    for (var b = 0u; b < params.bodies; b++) {
        let body = bodies[b];
        if body.info.x != FIREBALL {
            continue;
        }
        let n = direction(p - body.sphere.xyz);
        let gap = length(p - body.sphere.xyz) - r - body.sphere.w;
        let approach = max(0.0, -dot(v - body_point_velocity(body, body.sphere.xyz + n * body.sphere.w), n));
        if gap < approach * dt() {
            ball_words[STATE + i] &= ~ALIVE;
            let e = atomicAdd(&counters[EVENT_COUNT], 1u);
            if e < arrayLength(&events) {
                events[e] = Event(vec4<f32>(p - n * r, bitcast<f32>(i)), vec4<f32>(-n, approach));
            }
            return;
        }
    }
}

@compute @workgroup_size(256)
fn find_contacts(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = ball_index(id);
    if i >= params.count {
        return;
    }
    // Last step's contacts, to start from their impulses.
    let old = ball_words[STATE + i];
    let old_slots = select(0u, slot_count(old), (old & SOLVED) != 0u);
    var old_ball: array<u32, SLOTS>;
    var old_impulse: array<vec4<f32>, SLOTS>;
    for (var k = 0u; k < old_slots; k++) {
        old_ball[k] = slot_words[SLOT_OTHER + i * SLOTS + k];
        old_impulse[k] = impulse_at(i * SLOTS + k);
    }
    let old_body = select(NONE, ball_words[BODY_OF + i], (old & SOLVED) != 0u);
    let old_body_impulse = pushes[BODY_IMPULSE + i];
    for (var k = 0u; k < SLOTS; k++) {
        slot_words[SLOT_OTHER + i * SLOTS + k] = NONE;
        set_impulse(i * SLOTS + k, vec4<f32>(0.0));
    }
    var old_walls: array<vec4<f32>, 3>;
    for (var axis = 0u; axis < 3u; axis++) {
        old_walls[axis] = select(vec4<f32>(0.0), pushes[WALL_IMPULSE + i * 3u + axis], (old & SOLVED) != 0u && touches_wall(old, axis));
        pushes[WALL_IMPULSE + i * 3u + axis] = vec4<f32>(0.0);
    }
    ball_words[BODY_OF + i] = NONE;
    pushes[BODY_IMPULSE + i] = vec4<f32>(0.0);
    var s = ball_words[STATE + i] & (ALIVE | (0xffffu << COLOR_SHIFT));
    if (s & ALIVE) == 0u {
        ball_words[STATE + i] = s;
        return;
    }
    let p = motion[POS + i].xyz;
    let r = motion[POS + i].w;
    let v = motion[VEL + i].xyz;
    // A ball reads only its own: the others read `vel`, unchanged here.
    motion[VEL_START + i] = motion[VEL + i];
    let margin = params.grid.y;
    let step = dt();

    // The nearest balls by the gap the step would leave, nearest first
    // (ties: lower number first).
    var near_gap: array<f32, SLOTS>;
    var near_ball: array<u32, SLOTS>;
    var found = 0u;
    let home = cell_coords(p);
    for (var dz = -1; dz <= 1; dz++) {
        for (var dy = -1; dy <= 1; dy++) {
            for (var dx = -1; dx <= 1; dx++) {
                let c = home + vec3<i32>(dx, dy, dz);
                if any(c < vec3<i32>(0)) || any(c >= vec3<i32>(params.dims.xyz)) {
                    continue;
                }
                let cell = cell_id(c);
                for (var k = cell_words[CELL_START + cell]; k < cell_words[CELL_START + cell + 1u]; k++) {
                    let j = ball_words[CELL_BALLS + k];
                    if j == i {
                        continue;
                    }
                    let d = p - motion[POS + j].xyz;
                    let dist = length(d);
                    let gap = dist - r - motion[POS + j].w;
                    var n = vec3<f32>(0.0, 1.0, 0.0);
                    if dist > 0.0 {
                        n = d / dist;
                    }
                    let approach = max(0.0, -dot(v - motion[VEL + j].xyz, n));
                    // Within reach of any approach the step may bring: a
                    // ball struck within it (by a blow passed down a column,
                    // or off the floor) may turn on a ball it does not
                    // approach yet, as fast as the fastest ball near either.
                    let reach = (near_speed_of(i) + near_speed_of(j) + params.room_max.w * step) * step;
                    if gap >= max(margin + reach, params.more.z) {
                        continue;
                    }
                    // Ranked by the gap the step would leave: the pairs that
                    // would sink deepest into each other are kept first.
                    let left = gap - approach * step;
                    // Insert, keeping the SLOTS nearest.
                    var at = found;
                    if found == SLOTS {
                        if left >= near_gap[SLOTS - 1u] {
                            continue;
                        }
                        at = SLOTS - 1u;
                    } else {
                        found++;
                    }
                    while at > 0u && near_gap[at - 1u] > left {
                        near_gap[at] = near_gap[at - 1u];
                        near_ball[at] = near_ball[at - 1u];
                        at--;
                    }
                    near_gap[at] = left;
                    near_ball[at] = j;
                }
            }
        }
    }
    for (var k = 0u; k < found; k++) {
        let j = near_ball[k];
        slot_words[SLOT_OTHER + i * SLOTS + k] = j;
        for (var m = 0u; m < old_slots; m++) {
            if old_ball[m] == j {
                let a = min(i, j);
                let n = direction(motion[POS + a].xyz - motion[POS + i + j - a].xyz);
                // A pair that parts faster than the pile's own jitter
                // bounced last step: that impulse is not this step's.
                let parting = dot(motion[VEL + a].xyz - motion[VEL + i + j - a].xyz, n);
                if parting > params.grid.z + params.room_max.w * step {
                    continue;
                }
                // Friction kept in the new tangent plane only.
                let f = old_impulse[m].xyz;
                set_impulse(i * SLOTS + k, vec4<f32>(f - dot(f, n) * n, old_impulse[m].w));
            }
        }
    }
    s |= found << SLOT_SHIFT;

    // How far a ball struck within the step may move: as fast as the
    // fastest ball near it.
    let struck = (near_speed_of(i) + params.room_max.w * step) * step;

    // The nearest body within reach.
    var best = NONE;
    var best_gap = 0.0;
    for (var b = 0u; b < params.bodies; b++) {
        let body = bodies[b];
        let d = p - body.sphere.xyz;
        let dist = length(d);
        let gap = dist - r - body.sphere.w;
        var n = vec3<f32>(0.0, 1.0, 0.0);
        if dist > 0.0 {
            n = d / dist;
        }
        let approach = max(0.0, -dot(v - body_point_velocity(body, body.sphere.xyz + n * body.sphere.w), n));
        // The fireball that takes balls took those it reached (see
        // `catch_in_fireball`); no ball rests on it.
        if body.info.x == FIREBALL && params.consumes != 0u {
            continue;
        }
        if gap < margin + max(approach * step, struck) && (best == NONE || gap < best_gap) {
            best = b;
            best_gap = gap;
        }
    }
    ball_words[BODY_OF + i] = best;
    set_body_impact(i, 0.0);
    if best != NONE && best == old_body {
        pushes[BODY_IMPULSE + i] = vec4<f32>(0.0, 0.0, 0.0, old_body_impulse.w);
    }

    if found > 0u || best != NONE {
        s |= SOLVED;
        for (var axis = 0u; axis < 3u; axis++) {
            let wall = nearest_wall(p, r, axis);
            let closing = -dot(v, wall.xyz);
            let approach = max(0.0, closing);
            if wall.w < margin + max(approach * step, struck) {
                s |= 1u << (WALL_SHIFT + axis);
                var f = old_walls[axis];
                if -closing > params.grid.z + params.room_max.w * step {
                    f = vec4<f32>(0.0);
                }
                pushes[WALL_IMPULSE + i * 3u + axis] = vec4<f32>(f.xyz - dot(f.xyz, wall.xyz) * wall.xyz, f.w);
            }
        }
    }
    ball_words[STATE + i] = s;
}
