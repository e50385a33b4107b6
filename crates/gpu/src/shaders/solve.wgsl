// The contact solver, after the impacts (see impacts.wgsl): no contact
// may close faster than its gap allows within the step, and none bounces.
// One Jacobi sweep of it: every ball works out, from the
// velocities all balls had after the last sweep, what each of its contacts
// adds to its impulse so far (normal: towards the target speed, never
// pulling; friction: towards no slip, within the Coulomb cone), and sums
// the change of its own velocity. A pair is worked out alike from both
// sides, the lower-numbered ball first, so that both get the same impulse
// to the bit and momentum is kept. `apply_deltas` then moves every ball's
// velocity on at once.

// Balls' weights a tumbler may hold up through one ball.
const BODY_WEIGHTS: f32 = 4.0;

struct PairImpulse {
    // The impulse on the lower-numbered ball (the other gets its opposite).
    impulse: vec3<f32>,
    // The new impulse so far: friction xyz, normal w.
    total: vec4<f32>,
}

fn solve_pair(a: u32, b: u32, total: vec4<f32>, share: f32) -> PairImpulse {
    let g = pair_geometry(a, b);
    let n = g.xyz;
    let goal = speculative_goal(g.w);
    let ra = pos[a].w;
    let rb = pos[b].w;
    let im = vel[a].w + vel[b].w;
    let normal_speed = dot(vel[a].xyz - vel[b].xyz, n);
    let normal = max(0.0, total.w + share * (goal - normal_speed) / im);
    // The contact points' relative velocity, less its normal part: the slip.
    let u = vel[a].xyz + cross(spin[a].xyz, -ra * n) - vel[b].xyz - cross(spin[b].xyz, rb * n);
    let slip = u - dot(u, n) * n;
    // A solid sphere's contact point is 7/2 times as easy to move sideways.
    let friction = clamp_friction(total.xyz - share * slip / (3.5 * im), params.material.y * normal);
    let change = (normal - total.w) * n + (friction - total.xyz);
    return PairImpulse(change, vec4<f32>(friction, normal));
}

@compute @workgroup_size(256)
fn solve_contacts(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = ball_index(id);
    if !in_solver(i) {
        return;
    }
    let p = pos[i].xyz;
    let r = pos[i].w;
    let im = vel[i].w;
    let ii = inv_inertia(im, r);
    let relax = params.more.w;
    let mine = contact_count(i);
    var dv = vec3<f32>(0.0);
    var dw = vec3<f32>(0.0);

    let slots = slot_count(state[i]);
    for (var k = 0u; k < slots; k++) {
        let j = slot_other[i * SLOTS + k];
        let share = relax / f32(max(mine, contact_count(j)));
        let total = slot_impulse[i * SLOTS + k];
        var change: vec3<f32>;
        if i < j {
            let pair = solve_pair(i, j, total, share);
            slot_impulse[i * SLOTS + k] = pair.total;
            change = pair.impulse;
        } else {
            let pair = solve_pair(j, i, total, share);
            slot_impulse[i * SLOTS + k] = pair.total;
            change = -pair.impulse;
        }
        let towards_other = direction(pos[j].xyz - p);
        dv += change * im;
        dw += cross(r * towards_other, change) * ii;
    }

    let share = relax / f32(mine);
    for (var axis = 0u; axis < 3u; axis++) {
        if !touches_wall(state[i], axis) {
            continue;
        }
        let wall = nearest_wall(p, r, axis);
        let n = wall.xyz;
        let total = wall_impulse[i * 3u + axis];
        let goal = speculative_goal(wall.w);
        let normal = max(0.0, total.w + share * (goal - dot(vel[i].xyz, n)) / im);
        let u = vel[i].xyz + cross(spin[i].xyz, -r * n);
        let slip = u - dot(u, n) * n;
        let friction = clamp_friction(total.xyz - share * slip / (3.5 * im), params.material.w * normal);
        wall_impulse[i * 3u + axis] = vec4<f32>(friction, normal);
        let change = (normal - total.w) * n + (friction - total.xyz);
        dv += change * im;
        dw += cross(-r * n, change) * ii;
    }

    let b = body_of[i];
    if b != NONE {
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
        let k = im + body_inverse_mass(body, point, n);
        // No more than stops the two meeting (a bounce at most) and holds up
        // a few balls' weight: a ball wedged between a tumbler and a wall
        // cannot be squeezed into an ever larger push back.
        let most = ((1.0 + params.more.y) * max(approach, 0.0) + BODY_WEIGHTS * params.room_max.w * dt()) / k;
        let normal = clamp(total.w + share * (goal - dot(vel[i].xyz - vb, n)) / k, 0.0, most);
        body_impulse[i] = vec4<f32>(total.x, 0.0, 0.0, normal);
        dv += (normal - total.w) * n * im;
    }
    delta[i] = vec4<f32>(dv, 0.0);
    delta_spin[i] = vec4<f32>(dw, 0.0);
}

@compute @workgroup_size(256)
fn apply_deltas(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = ball_index(id);
    if !in_solver(i) {
        return;
    }
    vel[i] = vec4<f32>(vel[i].xyz + delta[i].xyz, vel[i].w);
    spin[i] = vec4<f32>(spin[i].xyz + delta_spin[i].xyz, 0.0);
}
