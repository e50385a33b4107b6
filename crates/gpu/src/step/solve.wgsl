// The contact solver, after the impacts (see impacts.wgsl): no contact
// may close faster than its gap allows within the step, and none bounces.
// Each contact pushes (never pulls) towards that, with Coulomb friction
// towards no slip.
//
// A sweep is one dispatch, a thread a ball (Jacobi, see `vel_in`): each
// ball works out every contact it has from the velocities the last sweep
// left, and takes the sum of their pushes. Summed whole, pushes that each
// fix their contact alone would overshoot where a ball has several, so
// each contact is worked out as if each of its balls had only its share
// of its mass, a share for each contact it has: mass splitting (Tonge,
// Benevolenski and Voroshilov, "Mass splitting for jitter-free parallel
// rigid body simulation", SIGGRAPH 2012). The sweeps then converge to the
// same impulses as Gauss-Seidel's, and a pile rests without jitter. Both
// balls of a contact work it out alike, from the same numbers in the same
// order (the lower-numbered ball first), and keep the same impulse so
// far, so what one gains the other loses to the bit.

// Balls' weights a tumbler may hold up through one ball.
const BODY_WEIGHTS: f32 = 4.0;

// Ball i's change of velocity (xyz) and of spin, from one contact.
struct Push {
    velocity: vec3<f32>,
    spin: vec3<f32>,
}

// The contact of ball `i` kept in its slot `at`, with ball `j`.
fn solve_pair(i: u32, j: u32, at: u32, back: bool) -> Push {
    let a = min(i, j);
    let b = i + j - a;
    let pa = pos[a];
    let pb = pos[b];
    let va = vel_in(a, back);
    let vb = vel_in(b, back);
    let d = pa.xyz - pb.xyz;
    let n = direction(d);
    let goal = speculative_goal(length(d) - pa.w - pb.w);
    // Each ball's mass split among its contacts.
    let k = solve_shares(a) * va.w + solve_shares(b) * vb.w;
    let total = slot_impulse[at];
    let normal = max(0.0, total.w + (goal - dot(va.xyz - vb.xyz, n)) / k);
    // The contact points' relative velocity, less its normal part: the slip.
    let u = va.xyz + cross(spin_in(a, back).xyz, -pa.w * n) - vb.xyz - cross(spin_in(b, back).xyz, pb.w * n);
    let slip = u - dot(u, n) * n;
    // A solid sphere's contact point is 7/2 times as easy to move sideways.
    let friction = clamp_friction(total.xyz - slip / (3.5 * k), params.material.y * normal);
    slot_impulse[at] = vec4<f32>(friction, normal);
    // On the lower-numbered ball; the other gets its opposite.
    let change = (normal - total.w) * n + (friction - total.xyz);
    let im = vel[i].w;
    if i == a {
        return Push(change * im, cross(-pa.w * n, change) * inv_inertia(im, pa.w));
    }
    return Push(-change * im, cross(pb.w * n, -change) * inv_inertia(im, pb.w));
}

// Ball i's contacts with the room's walls, at velocity `v` and spin `w`,
// its mass split `shares` ways.
fn solve_walls(i: u32, v: vec3<f32>, w: vec3<f32>, shares: f32) -> Push {
    let p = pos[i].xyz;
    let r = pos[i].w;
    let im = vel[i].w;
    var push = Push(vec3<f32>(0.0), vec3<f32>(0.0));
    for (var axis = 0u; axis < 3u; axis++) {
        if !touches_wall(state[i], axis) {
            continue;
        }
        let wall = nearest_wall(p, r, axis);
        let n = wall.xyz;
        let k = shares * im;
        let total = wall_impulse[i * 3u + axis];
        let goal = speculative_goal(wall.w);
        let normal = max(0.0, total.w + (goal - dot(v, n)) / k);
        let u = v + cross(w, -r * n);
        let slip = u - dot(u, n) * n;
        let friction = clamp_friction(total.xyz - slip / (3.5 * k), params.material.w * normal);
        wall_impulse[i * 3u + axis] = vec4<f32>(friction, normal);
        let change = (normal - total.w) * n + (friction - total.xyz);
        push.velocity += change * im;
        push.spin += cross(-r * n, change) * inv_inertia(im, r);
    }
    return push;
}

// Ball i's contact with a body, at velocity `v`, its mass split `shares` ways.
fn solve_body(i: u32, v: vec3<f32>, shares: f32) -> vec3<f32> {
    let b = body_of[i];
    if b == NONE {
        return vec3<f32>(0.0);
    }
    let p = pos[i].xyz;
    let r = pos[i].w;
    let im = vel[i].w;
    let body = bodies[b];
    let d = p - body.sphere.xyz;
    let n = d / max(length(d), 1e-9);
    let point = body.sphere.xyz + n * body.sphere.w;
    let vb = body_point_velocity(body, point);
    let total = body_impulse[i];
    let goal = speculative_goal(length(d) - r - body.sphere.w);
    let approach = -dot(vel_start[i].xyz - vb, n);
    // The tumbler stands still within the step, but the push is shared
    // as if it gave way: its effective mass at the point counts.
    let body_im = body_inverse_mass(body, point, n);
    // No more than stops the two meeting (a bounce at most) and holds up
    // a few balls' weight: a ball wedged between a tumbler and a wall
    // cannot be squeezed into an ever larger push back.
    let most = ((1.0 + params.more.y) * max(approach, 0.0) + BODY_WEIGHTS * params.room_max.w * dt()) / (im + body_im);
    let normal = clamp(total.w + (goal - dot(v - vb, n)) / (shares * im + body_im), 0.0, most);
    body_impulse[i] = vec4<f32>(total.x, 0.0, 0.0, normal);
    return (normal - total.w) * n * im;
}

@compute @workgroup_size(256)
fn solve_forth(@builtin(global_invocation_id) id: vec3<u32>) {
    solve_ball(ball_index(id), false);
}

@compute @workgroup_size(256)
fn solve_back(@builtin(global_invocation_id) id: vec3<u32>) {
    solve_ball(ball_index(id), true);
}

// One sweep of ball i's contacts.
fn solve_ball(i: u32, back: bool) {
    if i >= params.count {
        return;
    }
    let v = vel_in(i, back);
    let w = spin_in(i, back);
    if !in_solver(i) {
        // Carried over, so that the copy the sweeps end in holds every ball.
        put_vel(i, back, v);
        put_spin(i, back, w);
        return;
    }
    let shares = solve_shares(i);
    var push = solve_walls(i, v.xyz, w.xyz, shares);
    push.velocity += solve_body(i, v.xyz, shares);
    for (var k = 0u; k < slot_count(state[i]); k++) {
        let at = i * SLOTS + k;
        if slot_mirror[at] != NONE {
            let pair = solve_pair(i, slot_other[at], at, back);
            push.velocity += pair.velocity;
            push.spin += pair.spin;
        }
    }
    put_vel(i, back, vec4<f32>(v.xyz + push.velocity, v.w));
    put_spin(i, back, vec4<f32>(w.xyz + push.spin, 0.0));
}

// After the impacts, gravity and each ball's contacts' warm impulses are
// given to its velocity. A ball reads only its own contacts here.
@compute @workgroup_size(256)
fn warm_start(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = ball_index(id);
    if i >= params.count || !alive(i) {
        return;
    }
    let p = pos[i].xyz;
    let r = pos[i].w;
    let im = vel[i].w;
    var dv = gravity() * dt();
    var dw = vec3<f32>(0.0);
    if (state[i] & SOLVED) != 0u {
        fold_body_impact(i);
        var pressing = 0u;
        for (var k = 0u; k < slot_count(state[i]); k++) {
            let j = slot_other[i * SLOTS + k];
            if slot_mirror[i * SLOTS + k] == NONE {
                continue;
            }
            let d = p - pos[j].xyz;
            let closing = max(0.0, -dot(vel_start[i].xyz - vel_start[j].xyz, direction(d)));
            pressing += u32(length(d) - r - pos[j].w - closing * dt() < params.grid.y);
            let a = min(i, j);
            let n = direction(pos[a].xyz - pos[i + j - a].xyz);
            let total = slot_impulse[i * SLOTS + k];
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
        state[i] = (state[i] & ~(31u << IMPACT_SHIFT)) | (min(pressing, 31u) << IMPACT_SHIFT);
    }
    vel[i] = vec4<f32>(vel[i].xyz + dv, im);
    spin[i] = vec4<f32>(spin[i].xyz + dw, 0.0);
}

// A small world's sweeps in one workgroup (see `SMALL_GROUP`).
@compute @workgroup_size(SMALL_GROUP)
fn solve_in_one_group(@builtin(local_invocation_index) t: u32) {
    for (var sweep = 0u; sweep < SOLVE_SWEEPS; sweep++) {
        for (var i = t; i < params.count; i += SMALL_GROUP) {
            solve_ball(i, sweep % 2u == 1u);
        }
        storageBarrier();
    }
}
