// The balls move, each from where the solver shifted it out of its
// overlaps (see solve.wgsl). A ball a contact held in the solve moves at
// its solved velocity (its walls were in the solver); its rolling slows
// on the walls that pushed it. A ball alone, or one that met others only in the impacts at
// the step's start, flies its exact parabola from where the step began and
// bounces exactly off the walls it meets on the way, coming to
// rest on one when it meets it slower than the bounce threshold. Each
// takes the colour of a wall or tumbler it struck hard enough.

// The time within `left` at which a sphere `d0` from a wall, closing at
// `-un` and accelerating towards it at `-gn`, first touches it; or -1.
fn first_impact(d0: f32, un: f32, gn: f32, left: f32) -> f32 {
    if d0 <= 0.0 {
        if un < 0.0 || (un == 0.0 && gn < 0.0) {
            return 0.0;
        }
        return -1.0;
    }
    // d0 + un t + gn t² / 2 = 0.
    let a = 0.5 * gn;
    var t = -1.0;
    if abs(a) < 1e-12 {
        if un < 0.0 {
            t = -d0 / un;
        }
    } else {
        let disc = un * un - 4.0 * a * d0;
        if disc < 0.0 {
            return -1.0;
        }
        // The stable pair of roots.
        let q = -0.5 * (un + select(-1.0, 1.0, un >= 0.0) * sqrt(disc));
        let t1 = q / a;
        let t2 = select(-1.0, d0 / q, q != 0.0);
        t = select(t1, t2, t2 >= 0.0 && (t1 < 0.0 || t2 < t1));
        if t < 0.0 {
            t = -1.0;
        }
    }
    if t > left {
        return -1.0;
    }
    return t;
}

fn clamp_into_room(p: vec3<f32>, r: f32) -> vec3<f32> {
    return clamp(p, params.room_min.xyz + r, params.room_max.xyz - r);
}

// Surfaces are numbered floor, ceiling, left, right, back, front: y, x, z.
fn surface_axis(surface: u32) -> u32 {
    return array<u32, 3>(1u, 0u, 2u)[surface / 2u];
}

fn distance_to(p: vec3<f32>, surface: u32) -> f32 {
    let axis = surface_axis(surface);
    if (surface & 1u) == 0u {
        return p[axis] - params.room_min[axis];
    }
    return params.room_max[axis] - p[axis];
}

fn normal_of(surface: u32) -> vec3<f32> {
    var n = vec3<f32>(0.0);
    n[surface_axis(surface)] = select(-1.0, 1.0, (surface & 1u) == 0u);
    return n;
}

// Each pair the solver pushed that closed faster than the event threshold,
// reported by its lower-numbered ball: a pass before the flight, which
// moves the other ball as this one reads it.
@compute @workgroup_size(256)
fn report_pairs(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = ball_index(id);
    if !in_solver(i) {
        return;
    }
    for (var k = 0u; k < slot_count(ball_words[STATE + i]); k++) {
        let at = i * SLOTS + k;
        let j = slot_words[SLOT_OTHER + at];
        if j < i || slot_words[SLOT_MIRROR + at] == NONE || impulse_at(at).w <= 0.0 {
            continue;
        }
        let g = pair_geometry(i, j);
        let closing = -dot(motion[VEL_START + i].xyz - motion[VEL_START + j].xyz, g.xyz);
        if closing > params.grid.w {
            let point = motion[POS + j].xyz + g.xyz * (motion[POS + j].w + 0.5 * max(g.w, 0.0));
            report_impact(i, HIT_BALL, j, point, g.xyz, closing, closing_time(g.w, closing));
        }
    }
}

// Each ball moved, its impacts with walls and tumblers reported.
@compute @workgroup_size(256)
fn fly(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = ball_index(id);
    if i < params.count && alive(i) {
        move_ball(i);
    }
}

// The instances of the balls as they stand: after each step's flight, and
// without a step.
@compute @workgroup_size(256)
fn write_instances(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = ball_index(id);
    if i < params.count {
        put_instance(i);
    }
}

// What the renderer draws of ball i: centre and radius, colour (see
// `BallInstance`); nothing of a caught one.
fn put_instance(i: u32) {
    if !alive(i) {
        instances[2u * i] = vec4<f32>(0.0);
        instances[2u * i + 1u] = vec4<f32>(0.0);
        return;
    }
    instances[2u * i] = motion[POS + i];
    instances[2u * i + 1u] = vec4<f32>(palette[ball_words[STATE + i] >> COLOR_SHIFT].xyz, 0.0);
}

fn move_ball(i: u32) {
    let r = motion[POS + i].w;
    let im = motion[VEL + i].w;
    let step = dt();
    let events_above = params.grid.w;
    var u = motion[VEL_START + i].xyz;
    var w = motion[SPIN + i].xyz;
    let start = motion[POS + i].xyz + shift_in(i, false).xyz;
    if (ball_words[STATE + i] & SOLVED) != 0u {
        var v = motion[VEL + i].xyz;
        for (var axis = 0u; axis < 3u; axis++) {
            let pushed = pushes[WALL_IMPULSE + i * 3u + axis].w;
            if !touches_wall(ball_words[STATE + i], axis) || pushed <= 0.0 {
                continue;
            }
            let wall = nearest_wall(motion[POS + i].xyz, r, axis);
            let n = wall.xyz;
            let tangential = v - dot(v, n) * n;
            let speed = length(tangential);
            let loss = params.more.x * pushed * im;
            let keep = select(0.0, 1.0 - loss / speed, speed > loss);
            v = dot(v, n) * n + tangential * keep;
            w *= keep;
            let closing = -dot(motion[VEL_START + i].xyz, n);
            if closing > events_above {
                set_color(i, params.surface_colors + surface_of(n));
                let foot = motion[POS + i].xyz - n * (r + wall.w);
                report_impact(i, HIT_WALL, surface_of(n), foot, n, closing, closing_time(wall.w, closing));
            }
        }
        let b = ball_words[BODY_OF + i];
        if b != NONE && pushes[BODY_IMPULSE + i].w > 0.0 && bodies[b].info.x != FIREBALL {
            let body = bodies[b];
            let d = motion[POS + i].xyz - body.sphere.xyz;
            let n = direction(d);
            let point = body.sphere.xyz + n * body.sphere.w;
            let closing = -dot(motion[VEL_START + i].xyz - body_point_velocity(body, point), n);
            if closing > events_above {
                set_color(i, body.info.z);
                let gap = length(d) - r - body.sphere.w;
                report_impact(i, HIT_BODY, body_code(body), point, n, closing, closing_time(gap, closing));
            }
        }
        var held = pushes[BODY_IMPULSE + i].w > 0.0;
        for (var k = 0u; k < slot_count(ball_words[STATE + i]); k++) {
            held = held || impulse_at(i * SLOTS + k).w > 0.0;
        }
        for (var axis = 0u; axis < 3u; axis++) {
            held = held || (touches_wall(ball_words[STATE + i], axis) && pushes[WALL_IMPULSE + i * 3u + axis].w > 0.0);
        }
        if held {
            motion[POS + i] = vec4<f32>(clamp_into_room(start + v * step, r), r);
            motion[VEL + i] = vec4<f32>(v, im);
            motion[SPIN + i] = vec4<f32>(w, 0.0);
            return;
        }
        // No contact pushed it in the solve: it met its neighbours only in
        // the impacts, at the step's start. From there it flies as a lone
        // ball, its exact parabola, bouncing exactly off the walls it meets
        // on the way. (Moved a whole step at its end velocity, it would
        // fall g dt^2 / 2 too far each step, and an elastic gas under
        // gravity would lose energy in every collision.)
        u = v - gravity() * step;
    }

    let restitution = params.material.z;
    let mu = params.material.w;
    var x = start;
    var g = gravity();
    var left = step;
    for (var bounce = 0; bounce < 8; bounce++) {
        var first = -1.0;
        var hit = 0u;
        for (var s = 0u; s < 6u; s++) {
            let n = normal_of(s);
            let t = first_impact(distance_to(x, s) - r, dot(n, u), dot(n, g), left);
            if t >= 0.0 && (first < 0.0 || t < first) {
                first = t;
                hit = s;
            }
        }
        if first < 0.0 {
            x += u * left + 0.5 * g * left * left;
            u += g * left;
            break;
        }
        x += u * first + 0.5 * g * first * first;
        u += g * first;
        left -= first;
        let n = normal_of(hit);
        x += n * (r - distance_to(x, hit));
        let speed = -dot(n, u);
        let bounces = speed > params.grid.z;
        let e = select(0.0, restitution, bounces);
        // As `bounce_off_wall` in the CPU engine: the normal impulse, then
        // friction against the slip, no more than stops it.
        u += (1.0 + e) * speed * n;
        var pushed = (1.0 + e) * speed / im;
        let arm = -r * n;
        let slip_all = u + cross(w, arm);
        let slip = slip_all - dot(slip_all, n) * n;
        let slip_speed = length(slip);
        if slip_speed > 0.0 {
            let j = min(mu * pushed, slip_speed / (3.5 * im));
            let impulse = -slip / slip_speed * j;
            u += impulse * im;
            w += cross(arm, impulse) * inv_inertia(im, r);
        }
        if !bounces {
            // Exactly no normal motion: the next round must not find it
            // touching the wall again at no time.
            u -= dot(u, n) * n;
        }
        if !bounces && dot(n, g) < 0.0 {
            // Resting on it: the wall carries gravity from here on, and its
            // push slows the rolling.
            pushed += -dot(n, g) * left / im;
            g -= dot(n, g) * n;
            let tangential = u - dot(u, n) * n;
            let along = length(tangential);
            let loss = params.more.x * pushed * im;
            let keep = select(0.0, 1.0 - loss / along, along > loss);
            u = dot(u, n) * n + tangential * keep;
            w *= keep;
        }
        if speed > events_above {
            set_color(i, params.surface_colors + hit);
            report_impact(i, HIT_WALL, hit, x - r * n, n, speed, step - left);
        }
    }
    motion[POS + i] = vec4<f32>(clamp_into_room(x, r), r);
    motion[VEL + i] = vec4<f32>(u, im);
    motion[SPIN + i] = vec4<f32>(w, 0.0);
}
