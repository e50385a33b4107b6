// The contact solver, after the impacts (see impacts.wgsl): no contact
// may close faster than its gap allows within the step, and none bounces.
// Each contact pushes (never pulls) towards that, with Coulomb friction
// towards no slip, and the velocities it changes are changed at once
// (Gauss-Seidel), so a push passes on through a pile within a sweep.
//
// Contacts that share a ball cannot be worked on side by side, so a sweep
// runs in 27 passes, one for each colour of cell: the cells whose
// coordinates are the same modulo 3. One thread takes one cell, and works
// through its balls in ball order: each ball's walls and body, then each
// contact with a higher-numbered ball. A contact's balls lie in the same
// or neighbouring cells, so two cells of one colour, three apart, never
// touch the same ball, and the sweep is the same on every run.

// Balls' weights a tumbler may hold up through one ball.
const BODY_WEIGHTS: f32 = 4.0;

// The colour of cells a pass works on (x; see `colour_offset`).
struct Colour {
    index: vec4<u32>,
}
@group(1) @binding(0) var<uniform> colour: Colour;

// Colour `q`'s offset along each axis.
fn colour_offset(q: u32) -> vec3<u32> {
    return vec3<u32>(q % 3u, (q / 3u) % 3u, q / 9u);
}

// Cells of the colour of offset `o`.
fn colour_cells(o: vec3<u32>) -> u32 {
    let span = (params.dims.xyz + 2u - o) / 3u;
    return span.x * span.y * span.z;
}

// The `t`-th cell of the colour of offset `o`, or NONE past its last.
fn colour_cell(t: u32, o: vec3<u32>) -> u32 {
    let span = (params.dims.xyz + 2u - o) / 3u;
    if t >= span.x * span.y * span.z {
        return NONE;
    }
    let c = o + 3u * vec3<u32>(t % span.x, (t / span.x) % span.y, t / (span.x * span.y));
    return cell_id(vec3<i32>(c));
}

struct PairImpulse {
    // The impulse on the lower-numbered ball (the other gets its opposite).
    impulse: vec3<f32>,
    // The new impulse so far: friction xyz, normal w.
    total: vec4<f32>,
}

fn solve_pair(a: u32, b: u32, total: vec4<f32>) -> PairImpulse {
    let g = pair_geometry(a, b);
    let n = g.xyz;
    let goal = speculative_goal(g.w);
    let ra = pos[a].w;
    let rb = pos[b].w;
    let im = vel[a].w + vel[b].w;
    let normal_speed = dot(vel[a].xyz - vel[b].xyz, n);
    let normal = max(0.0, total.w + (goal - normal_speed) / im);
    // The contact points' relative velocity, less its normal part: the slip.
    let u = vel[a].xyz + cross(spin[a].xyz, -ra * n) - vel[b].xyz - cross(spin[b].xyz, rb * n);
    let slip = u - dot(u, n) * n;
    // A solid sphere's contact point is 7/2 times as easy to move sideways.
    let friction = clamp_friction(total.xyz - slip / (3.5 * im), params.material.y * normal);
    let change = (normal - total.w) * n + (friction - total.xyz);
    return PairImpulse(change, vec4<f32>(friction, normal));
}

// Pushes ball `i` by `impulse` at the point `arm` from its centre.
fn push_ball(i: u32, impulse: vec3<f32>, arm: vec3<f32>) {
    let im = vel[i].w;
    vel[i] = vec4<f32>(vel[i].xyz + impulse * im, im);
    spin[i] = vec4<f32>(spin[i].xyz + cross(arm, impulse) * inv_inertia(im, pos[i].w), 0.0);
}

// The contact of balls a < b, kept in slot `at` of a's list and `mirror`
// of b's.
fn solve_ball_pair(a: u32, b: u32, at: u32, mirror: u32) {
    let pair = solve_pair(a, b, slot_impulse[at]);
    slot_impulse[at] = pair.total;
    slot_impulse[mirror] = pair.total;
    let n = direction(pos[a].xyz - pos[b].xyz);
    push_ball(a, pair.impulse, -pos[a].w * n);
    push_ball(b, -pair.impulse, pos[b].w * n);
}

fn solve_walls(i: u32) {
    let p = pos[i].xyz;
    let r = pos[i].w;
    for (var axis = 0u; axis < 3u; axis++) {
        if !touches_wall(state[i], axis) {
            continue;
        }
        let wall = nearest_wall(p, r, axis);
        let n = wall.xyz;
        let im = vel[i].w;
        let total = wall_impulse[i * 3u + axis];
        let goal = speculative_goal(wall.w);
        let normal = max(0.0, total.w + (goal - dot(vel[i].xyz, n)) / im);
        let u = vel[i].xyz + cross(spin[i].xyz, -r * n);
        let slip = u - dot(u, n) * n;
        let friction = clamp_friction(total.xyz - slip / (3.5 * im), params.material.w * normal);
        wall_impulse[i * 3u + axis] = vec4<f32>(friction, normal);
        push_ball(i, (normal - total.w) * n + (friction - total.xyz), -r * n);
    }
}

fn solve_body(i: u32) {
    let b = body_of[i];
    if b == NONE {
        return;
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
    let k = im + body_inverse_mass(body, point, n);
    // No more than stops the two meeting (a bounce at most) and holds up
    // a few balls' weight: a ball wedged between a tumbler and a wall
    // cannot be squeezed into an ever larger push back.
    let most = ((1.0 + params.more.y) * max(approach, 0.0) + BODY_WEIGHTS * params.room_max.w * dt()) / k;
    let normal = clamp(total.w + (goal - dot(vel[i].xyz - vb, n)) / k, 0.0, most);
    body_impulse[i] = vec4<f32>(total.x, 0.0, 0.0, normal);
    vel[i] = vec4<f32>(vel[i].xyz + (normal - total.w) * n * im, im);
}

@compute @workgroup_size(256)
fn solve_cell(@builtin(global_invocation_id) id: vec3<u32>) {
    let c = colour_cell(ball_index(id), colour_offset(colour.index.x));
    if c != NONE {
        solve_cell_at(c);
    }
}

fn solve_cell_at(c: u32) {
    for (var at = cell_start[c]; at < cell_start[c + 1u]; at++) {
        let i = cell_balls[at];
        if !in_solver(i) {
            continue;
        }
        solve_walls(i);
        solve_body(i);
        for (var k = 0u; k < slot_count(state[i]); k++) {
            let j = slot_other[i * SLOTS + k];
            if j < i {
                continue;
            }
            let mirror = slot_mirror[i * SLOTS + k];
            if mirror != NONE {
                solve_ball_pair(i, j, i * SLOTS + k, mirror);
            }
        }
    }
}

@compute @workgroup_size(256)
fn apply_deltas(@builtin(global_invocation_id) id: vec3<u32>) {
    apply_deltas_of(ball_index(id));
}

fn apply_deltas_of(i: u32) {
    if !in_solver(i) {
        return;
    }
    vel[i] = vec4<f32>(vel[i].xyz + delta[i].xyz, vel[i].w);
    spin[i] = vec4<f32>(spin[i].xyz + delta_spin[i].xyz, 0.0);
}
