// Impacts, before gravity and the resting contacts (the collision pass of
// Guendelman, Bridson and Fedkiw): the balls' velocities at the step's
// start are corrected so that contacts that close fast enough to bounce
// and touch within the step part at their restitution times the speed
// they closed at, one impact after another in the order they meet, as
// the CPU engine meets them.
//
// They run in rounds, two dispatches each. In the first, each ball finds
// the contact it meets first (`first_contact_of`): the soonest to touch
// of those that bounce, ties broken by the numbers of the two sides, so
// that both balls of a contact rank it alike. In the second, each ball
// whose first contact is also its partner's first (or a wall, or its
// body) bounces off it (`bounce_first`). The soonest contact among any
// group of balls is first for both its balls, so every round meets at
// least that one. A ball meets at most one contact a round: each impact
// is two bodies' alone, solved exactly (momentum kept, and all the energy
// an elastic one had), where a group solved at once would lose some. A
// ball struck in one round strikes its neighbour in the next, and a row
// of balls passes a blow along it as Newton's cradle does. Impacts push
// along the normal only. What is left after the last round the resting
// contacts stop without a bounce.
//
// Each round reads one copy of the velocities and writes the other (see
// `vel_in`): the first dispatch copies every ball over, the second
// writes the bounces.

// The round this pipeline finds first contacts for, or bounces.
override IMPACT_ROUND: u32 = 0u;

// Codes of `first_contact` past a ball's SLOTS contact slots: the walls
// along x, y and z, then its body. NONE: nothing to meet.
const FIRST_WALL: u32 = SLOTS;
const FIRST_BODY: u32 = SLOTS + 3u;

// Each round's bounce dispatch, workgroups along x, y and z (and a pad),
// widened as balls join its list. Bound apart from the rest, and only to
// the passes that find first contacts: a buffer a dispatch reads its size
// from may not be bound for writing in that dispatch.
@group(1) @binding(0) var<storage, read_write> impact_dispatch: array<atomic<u32>>;

fn round_reads_back() -> bool {
    return IMPACT_ROUND % 2u == 1u;
}

@compute @workgroup_size(256)
fn find_first_contacts(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = ball_index(id);
    if i >= params.count {
        return;
    }
    if find_first_contact(i, round_reads_back()) {
        list_for_impacts(i);
    }
}

// Puts ball i on this round's list, and widens the round's dispatch to
// reach it. The list's order is the order the atomics land in, which
// changes from run to run; what each ball does on it does not.
fn list_for_impacts(i: u32) {
    let round = 4u * IMPACT_ROUND;
    let at = atomicAdd(&impact_count[IMPACT_ROUND], 1u);
    impact_list[at] = i;
    let groups = at / WORKGROUP + 1u;
    atomicMax(&impact_dispatch[round], min(groups, MAX_GROUPS));
    atomicMax(&impact_dispatch[round + 1u], (groups + MAX_GROUPS - 1u) / MAX_GROUPS);
}

// Ball i carried over to the copy the round writes, and the contact it
// meets first noted; returns whether it has one.
fn find_first_contact(i: u32, back: bool) -> bool {
    put_vel(i, back, vel_in(i, back));
    let first = first_contact_of(i, back);
    first_contact[i] = first;
    return first != NONE;
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

// The contact ball i meets first at the velocities of copy `back`: a slot,
// FIRST_WALL + axis, FIRST_BODY, or NONE.
fn first_contact_of(i: u32, back: bool) -> u32 {
    if !in_solver(i) {
        return NONE;
    }
    var first = NONE;
    var soonest = Rank(NEVER, NONE, NONE);
    for (var k = 0u; k < slot_count(state[i]); k++) {
        let at = i * SLOTS + k;
        if slot_mirror[at] == NONE {
            continue;
        }
        let j = slot_other[at];
        let a = min(i, j);
        let b = i + j - a;
        let g = pair_geometry(a, b);
        let approach = -dot(vel_in(a, back).xyz - vel_in(b, back).xyz, g.xyz);
        let rank = Rank(impact_time(approach, g.w), a, b);
        if rank.time != NEVER && ranks_before(rank, soonest) {
            first = k;
            soonest = rank;
        }
    }
    let p = pos[i].xyz;
    let r = pos[i].w;
    let v = vel_in(i, back).xyz;
    for (var axis = 0u; axis < 3u; axis++) {
        if touches_wall(state[i], axis) {
            let wall = nearest_wall(p, r, axis);
            let rank = Rank(impact_time(-dot(v, wall.xyz), wall.w), i, FIRST_WALL + axis);
            if rank.time != NEVER && ranks_before(rank, soonest) {
                first = FIRST_WALL + axis;
                soonest = rank;
            }
        }
    }
    let b = body_of[i];
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

// The change of ball i's velocity `v` (copy `back`) from its first
// contact `first`, if that contact bounces this round: along the normal,
// restitution times the approach more than stops it.
fn bounce_of(i: u32, first: u32, v: vec3<f32>, back: bool) -> vec3<f32> {
    let im = vel_in(i, back).w;
    if first < FIRST_WALL {
        let at = i * SLOTS + first;
        let j = slot_other[at];
        // Bounces only if it is the other ball's first too.
        if first_contact[j] != slot_mirror[at] - j * SLOTS {
            return vec3<f32>(0.0);
        }
        // Worked out alike by both balls, from the lower-numbered's side.
        let a = min(i, j);
        let b = i + j - a;
        let g = pair_geometry(a, b);
        let va = vel_in(a, back);
        let vb = vel_in(b, back);
        let approach = -dot(va.xyz - vb.xyz, g.xyz);
        let impulse = (1.0 + params.material.x) * approach / (va.w + vb.w);
        return impulse * im * g.xyz * select(-1.0, 1.0, i == a);
    }
    let p = pos[i].xyz;
    let r = pos[i].w;
    if first < FIRST_BODY {
        let n = nearest_wall(p, r, first - FIRST_WALL).xyz;
        return (1.0 + params.material.z) * -dot(v, n) * n;
    }
    let body = bodies[body_of[i]];
    let n = direction(p - body.sphere.xyz);
    let point = body.sphere.xyz + n * body.sphere.w;
    let approach = -dot(v - body_point_velocity(body, point), n);
    let impulse = (1.0 + params.more.y) * approach / (im + body_inverse_mass(body, point, n));
    body_impact[i] += impulse;
    return impulse * im * n;
}

// Ball i bounced off its first contact, if that bounces this round.
fn bounce_first(i: u32, back: bool) {
    let first = first_contact[i];
    if first == NONE {
        return;
    }
    let v = vel_in(i, back);
    put_vel(i, back, vec4<f32>(v.xyz + bounce_of(i, first, v.xyz, back), v.w));
}

// A thread for each ball on the round's list, dispatched as many as the
// list holds (indirectly): a round in which nothing bounces costs nothing.
@compute @workgroup_size(256)
fn bounce_first_contacts(@builtin(global_invocation_id) id: vec3<u32>) {
    let t = ball_index(id);
    if t < atomicLoad(&impact_count[IMPACT_ROUND]) {
        bounce_first(impact_list[t], round_reads_back());
    }
}

// A small world's rounds in one workgroup (see `SMALL_GROUP`): each
// thread takes every SMALL_GROUP-th ball, the list is not needed.
@compute @workgroup_size(SMALL_GROUP)
fn impacts_in_one_group(@builtin(local_invocation_index) t: u32) {
    for (var round = 0u; round < IMPACT_ROUNDS; round++) {
        let back = round % 2u == 1u;
        for (var i = t; i < params.count; i += SMALL_GROUP) {
            _ = find_first_contact(i, back);
        }
        storageBarrier();
        for (var i = t; i < params.count; i += SMALL_GROUP) {
            bounce_first(i, back);
        }
        storageBarrier();
    }
}
