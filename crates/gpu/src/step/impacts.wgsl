// Impacts, before gravity and the resting contacts (the collision pass of
// Guendelman, Bridson and Fedkiw): the balls' velocities at the step's
// start are corrected so that contacts that close fast enough to bounce
// and touch within the step part at their restitution times the speed
// they closed at, one impact after another in the order they meet, as
// the CPU engine meets them.
//
// They run in IMPACT_ROUNDS rounds. In each, every ball finds the contact
// it meets first (`first_contact_of`): the soonest to touch of those that
// bounce, ties broken by the numbers of the two sides, so that both balls
// of a contact rank it alike. Then each ball whose first contact is also
// its partner's first (or a wall, or its body) bounces off it
// (`bounce_of`). The soonest contact among any group of balls is first
// for both its balls, so every round meets at least that one. A ball
// meets at most one contact a round: each impact is two bodies' alone,
// solved exactly (momentum kept, and all the energy an elastic one had),
// where a group solved at once would lose some. A ball struck in one
// round strikes its neighbour in the next, and a row of balls passes a
// blow along it as Newton's cradle does. Impacts push along the normal
// only. What is left after the last round the resting contacts stop
// without a bounce.
//
// One dispatch ends each round and starts the next (`meet_in_round`):
// each ball works out its own and its neighbours' bounces in the round
// before from that round's first contacts, as each of them does, and
// finds its first contact of this round at the velocities so reached.
// So the rounds take IMPACT_ROUNDS + 1 dispatches, not two each. Round r
// reads the velocities copy (r - 1) % 2 holds (see `vel_in`) and writes
// copy r % 2, and the first contacts likewise (see `first_place`); the
// last dispatch only bounces, and warm-starts the solver, into the first
// copy.

// The round this pipeline starts (or, the last, only ends).
override IMPACT_ROUND: u32 = 0u;

// Codes of `first_contact` past a ball's SLOTS contact slots: the walls
// along x, y and z, then its body. NONE: nothing to meet.
const FIRST_WALL: u32 = SLOTS;
const FIRST_BODY: u32 = SLOTS + 3u;

@compute @workgroup_size(256)
fn meet_in_round(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = ball_index(id);
    if i < params.count {
        meet(i, IMPACT_ROUND);
    }
}

// A small world's rounds in one workgroup (see `SMALL_GROUP`): each thread
// takes every SMALL_GROUP-th ball.
@compute @workgroup_size(SMALL_GROUP)
fn impacts_in_one_group(@builtin(local_invocation_index) t: u32) {
    for (var round = 0u; round <= IMPACT_ROUNDS; round++) {
        for (var i = t; i < params.count; i += SMALL_GROUP) {
            meet(i, round);
        }
        storageBarrier();
    }
}

// Ball i's part in the dispatch that ends round `round - 1` and starts
// round `round`: its bounce in the round before (its body's share of the
// push kept), its velocity written, and its first contact in this round
// found and counted. The first round first notes the mirrors of its
// contacts, which every later pass reads; the last dispatch, which only
// ends a round, then starts the solver (see warm_start.wgsl).
fn meet(i: u32, round: u32) {
    var v: vec4<f32>;
    if round == 0u {
        note_mirrors(i);
        v = motion[VEL + i];
    } else {
        let bounce = bounce_in(i, round - 1u);
        v = bounce.velocity;
        report_bounce(i, bounce);
        set_body_impact(i, body_impact_of(i) + bounce.push_on_body);
        if round < IMPACT_ROUNDS {
            put_vel(i, reads_back(round - 1u), v);
        } else if alive(i) {
            // The first copy, as the solver's sweeps start from it.
            warm_start(i, v);
        }
    }
    if round < IMPACT_ROUNDS {
        let first = first_contact_of(i, round, v.xyz);
        ball_words[FIRST_CONTACT + first_place(i, round)] = first;
        if first != NONE {
            atomicAdd(&counters[IMPACT_COUNT + round], 1u);
        }
    }
}

// Where each of ball i's contacts is kept by its other ball, noted once a
// step (see `slot_mirror`): a ball whose list is full may leave out one
// that lists it, and such a one-sided contact is met neither here nor by
// the solver's pushes, only by its shifts (see solve.wgsl).
fn note_mirrors(i: u32) {
    for (var k = 0u; k < slot_count(ball_words[STATE + i]); k++) {
        let j = slot_words[SLOT_OTHER + i * SLOTS + k];
        var mirror = NONE;
        for (var m = 0u; m < slot_count(ball_words[STATE + j]); m++) {
            if slot_words[SLOT_OTHER + j * SLOTS + m] == i {
                mirror = j * SLOTS + m;
                break;
            }
        }
        slot_words[SLOT_MIRROR + i * SLOTS + k] = mirror;
        // Both balls of a contact start the solver from the same impulse
        // (see solve.wgsl): the lower-numbered ball's, which only its
        // own thread writes, and not here.
        if mirror != NONE && j < i {
            set_impulse(i * SLOTS + k, impulse_at(mirror));
        }
    }
}

// Whether round `round` starts from the second copy of the velocities.
fn reads_back(round: u32) -> bool {
    return round % 2u == 1u;
}

// Where ball i's first contact in round `round` is kept: two copies, one
// after the other, so that a round's are read while the next's are found.
fn first_place(i: u32, round: u32) -> u32 {
    return (round % 2u) * (CAPACITY) + i;
}

// Ball j's velocity (w: inverse mass) as round `round` starts: as the
// step starts, or after its bounce in the round before.
fn velocity_in(j: u32, round: u32) -> vec4<f32> {
    if round == 0u {
        return motion[VEL + j];
    }
    return bounce_in(j, round - 1u).velocity;
}

// A ball after its bounce in a round (the velocity it starts it with, if
// it does not bounce), and its push on its body there; and what it met
// (HIT_WALL, HIT_BALL, HIT_BODY or NONE, and which), where, along which
// normal (towards the ball), how fast and when.
struct Bounce {
    velocity: vec4<f32>,
    push_on_body: f32,
    hit: u32,
    other: u32,
    point: vec3<f32>,
    normal: vec3<f32>,
    speed: f32,
    within: f32,
}

fn no_bounce(v: vec4<f32>) -> Bounce {
    return Bounce(v, 0.0, NONE, NONE, vec3<f32>(0.0), vec3<f32>(0.0), 0.0, 0.0);
}

// Ball i's bounce reported, if it met something fast enough; a pair's by
// its lower-numbered ball.
fn report_bounce(i: u32, b: Bounce) {
    if b.hit != NONE && b.speed > params.grid.w && (b.hit != HIT_BALL || i < b.other) {
        report_impact(i, b.hit, b.other, b.point, b.normal, b.speed, b.within);
    }
}

// Ball j after round `round`: it bounces off its first contact if that is
// a wall, its body, or a ball whose first contact it is too; along the
// normal, restitution times the approach more than stops it. A ball
// works out its neighbours' bounces as they do their own, from the same
// numbers.
fn bounce_in(j: u32, round: u32) -> Bounce {
    let back = reads_back(round);
    let v = vel_in(j, back);
    let first = ball_words[FIRST_CONTACT + first_place(j, round)];
    if first == NONE {
        return no_bounce(v);
    }
    let im = v.w;
    if first < FIRST_WALL {
        let at = j * SLOTS + first;
        let other = slot_words[SLOT_OTHER + at];
        if ball_words[FIRST_CONTACT + first_place(other, round)] != slot_words[SLOT_MIRROR + at] - other * SLOTS {
            return no_bounce(v);
        }
        // Worked out alike by both balls, from the lower-numbered's side.
        let a = min(j, other);
        let b = j + other - a;
        let g = pair_geometry(a, b);
        let va = vel_in(a, back);
        let vb = vel_in(b, back);
        let approach = -dot(va.xyz - vb.xyz, g.xyz);
        let impulse = (1.0 + params.material.x) * approach / (va.w + vb.w);
        let change = impulse * im * g.xyz * select(-1.0, 1.0, j == a);
        // Reported by a, from b towards it.
        let point = motion[POS + b].xyz + g.xyz * (motion[POS + b].w + 0.5 * max(g.w, 0.0));
        return Bounce(vec4<f32>(v.xyz + change, im), 0.0, HIT_BALL, b, point, g.xyz, approach, closing_time(g.w, approach));
    }
    let p = motion[POS + j].xyz;
    let r = motion[POS + j].w;
    if first < FIRST_BODY {
        let wall = nearest_wall(p, r, first - FIRST_WALL);
        let n = wall.xyz;
        let approach = -dot(v.xyz, n);
        let change = (1.0 + params.material.z) * approach * n;
        let foot = p - n * (r + wall.w);
        return Bounce(vec4<f32>(v.xyz + change, im), 0.0, HIT_WALL, surface_of(n), foot, n, approach, closing_time(wall.w, approach));
    }
    let body = bodies[ball_words[BODY_OF + j]];
    let n = direction(p - body.sphere.xyz);
    let point = body.sphere.xyz + n * body.sphere.w;
    let approach = -dot(v.xyz - body_point_velocity(body, point), n);
    let impulse = (1.0 + params.more.y) * approach / (im + body_inverse_mass(body, point, n));
    let gap = length(p - body.sphere.xyz) - r - body.sphere.w;
    return Bounce(vec4<f32>(v.xyz + impulse * im * n, im), impulse, HIT_BODY, body_code(body), point, n, approach, closing_time(gap, approach));
}

// An impact's rank: sooner first, then by the lower and the higher number
// of its two sides (a wall or a body ranks as a side numbered past every
// ball). Both balls of a contact rank it alike.
struct Rank {
    time: f32,
    low: u32,
    high: u32,
}

fn ranks_before(a: Rank, b: Rank) -> bool {
    if a.time != b.time {
        return a.time < b.time;
    }
    if a.low != b.low {
        return a.low < b.low;
    }
    return a.high < b.high;
}

// The contact ball i meets first in round `round`, at the velocity `v` it
// starts it with and those its neighbours do: a slot, FIRST_WALL + axis,
// FIRST_BODY, or NONE.
fn first_contact_of(i: u32, round: u32, v: vec3<f32>) -> u32 {
    if !in_solver(i) {
        return NONE;
    }
    var first = NONE;
    var soonest = Rank(NEVER, NONE, NONE);
    for (var k = 0u; k < slot_count(ball_words[STATE + i]); k++) {
        let at = i * SLOTS + k;
        if slot_words[SLOT_MIRROR + at] == NONE {
            continue;
        }
        let j = slot_words[SLOT_OTHER + at];
        let a = min(i, j);
        let b = i + j - a;
        let g = pair_geometry(a, b);
        // From the lower-numbered ball's side, as its partner ranks it.
        let vj = velocity_in(j, round).xyz;
        let relative = select(vj - v, v - vj, i == a);
        let rank = Rank(impact_time(-dot(relative, g.xyz), g.w), a, b);
        if rank.time != NEVER && ranks_before(rank, soonest) {
            first = k;
            soonest = rank;
        }
    }
    let p = motion[POS + i].xyz;
    let r = motion[POS + i].w;
    for (var axis = 0u; axis < 3u; axis++) {
        if touches_wall(ball_words[STATE + i], axis) {
            let wall = nearest_wall(p, r, axis);
            let rank = Rank(impact_time(-dot(v, wall.xyz), wall.w), i, FIRST_WALL + axis);
            if rank.time != NEVER && ranks_before(rank, soonest) {
                first = FIRST_WALL + axis;
                soonest = rank;
            }
        }
    }
    let b = ball_words[BODY_OF + i];
    if b != NONE {
        let body = bodies[b];
        let d = p - body.sphere.xyz;
        let n = direction(d);
        let vb = body_point_velocity(body, body.sphere.xyz + n * body.sphere.w);
        let gap = length(d) - r - body.sphere.w;
        let rank = Rank(impact_time(-dot(v - vb, n), gap), i, FIRST_BODY);
        if rank.time != NEVER && ranks_before(rank, soonest) {
            first = FIRST_BODY;
        }
    }
    return first;
}
