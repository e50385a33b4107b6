// The contact solver, after the impacts (see impacts.wgsl): no contact
// may close faster than its gap allows within the step, and none bounces.
// Each contact pushes (never pulls) towards that, with Coulomb friction
// towards no slip.
//
// A sweep is Jacobi's (see `vel_in`): each ball works out every contact
// it has from the velocities the last sweep left, and takes the sum of
// their pushes. A dispatch runs BLOCK_SWEEPS of them among each block of
// neighbouring balls (see `solve_block`). Summed whole, pushes that each
// fix their contact alone would overshoot where a ball has several, so
// each contact is worked out as if each of its balls had only a share of
// its mass, one for each of its contacts that push: mass splitting
// (Tonge, Benevolenski and Voroshilov, "Mass splitting for jitter-free
// parallel rigid body simulation", SIGGRAPH 2012). The sweeps then
// converge to the same impulses as Gauss-Seidel's, and a pile rests
// without jitter; shares this cautious make each push small, so each is
// over-relaxed (SOLVE_RELAXATION in `engine.rs`). Both balls of a contact
// work it out alike, from the same numbers in the same order (the
// lower-numbered ball first), and keep the same impulse so far, so what
// one gains the other loses to the bit.
//
// The same sweeps push out the balls' overlaps by position alone: each
// ball carries a shift beside its velocity, which the flight adds to its
// move and which makes no motion (as split impulses do, in Catto's
// "Iterative Dynamics with Temporal Coherence", 2005, and in Bullet).
// Each sweep gives a ball its share of each overlap it would have after
// the step, moved at the velocities so far from where it is shifted to
// (see `shift_out_of`), its mass split as for its pushes; so the shifts
// meet what the velocities leave, and a pile's weight is passed down
// through the blocks as its pushes are. The speculative margin of an
// overlap is left: pushed out whole, resting balls would stand a hair
// apart, fall back in and bounce, and a pile would never rest. The
// pushes read their gaps where the balls stand, not where they are
// shifted to: a shift that opened a gap would let a velocity close it,
// and the shifts, which read the velocities, would open it further.

// Balls' weights a tumbler may hold up through one ball.
const BODY_WEIGHTS: f32 = 4.0;

// How many ways ball i's mass is split in a sweep: the most of its
// contacts that pushed in any sweep of the step so far (kept beside its
// spin), and never fewer than those `warm_start` found may push within
// the step. A contact that starts to push mid-step is counted from the
// next sweep on: one sweep overshoots a little, and none after it
// (counted once at the step's start, a pit of 10 000 balls landing blew
// up in its twentieth step). Never counted down, the shares settle, and
// the sweeps with them (counted afresh each sweep, a frictionless pile
// flickered and never came to rest).
fn shares(i: u32, seen: Seen) -> f32 {
    return max(f32(max((ball_words[STATE + i] >> PRESSING_SHIFT) & 31u, 1u)), seen.spin.w);
}

// How far past its own fix a contact whose balls' mass is split at most
// `shares` ways is pushed: a lone contact is met exactly in one sweep, and
// pushed further, it would leave a trace of a push where none belongs (a
// ball in flight held to its solved velocity); among several, each push
// is small, and over-relaxed.
fn relaxation(shares: f32) -> f32 {
    return select(params.solve_relaxation, 1.0, shares <= 1.0);
}

// A ball as a sweep sees it: its velocity (w: inverse mass), spin (w:
// the most of its contacts that pushed so far, see `shares`) and shift.
struct Seen {
    vel: vec4<f32>,
    spin: vec4<f32>,
    shift: vec4<f32>,
}

// Ball i as the last sweep left it, in the copy a sweep `back` reads.
fn seen_in(i: u32, back: bool) -> Seen {
    return Seen(vel_in(i, back), spin_in(i, back), shift_in(i, back));
}

// Where ball i stands as a sweep sees it: moved by its shift so far.
fn shifted(i: u32, seen: Seen) -> vec3<f32> {
    return motion[POS + i].xyz + seen.shift.xyz;
}

// Ball i's change of velocity, of spin and of shift, from its contacts,
// and how many of them push.
struct Push {
    velocity: vec3<f32>,
    spin: vec3<f32>,
    shift: vec3<f32>,
    pushing: f32,
}

const NO_PUSH = Push(vec3<f32>(0.0), vec3<f32>(0.0), vec3<f32>(0.0), 0.0);

// The part of an overlap `depth` deep (less the speculative margin, left)
// that a sweep pushes out for a ball whose mass is split `contacts` ways
// (its own or its partner's, the more; see `shares`).
fn shift_share(depth: f32, contacts: f32) -> f32 {
    return max(depth - params.grid.y, 0.0) * params.more.w / contacts;
}

// The contact of ball `i` kept in its slot `at`, with ball `j`, each as
// the sweep sees it.
fn solve_pair(i: u32, j: u32, at: u32, mine: Seen, theirs: Seen) -> Push {
    let a = min(i, j);
    let b = i + j - a;
    let pa = motion[POS + a];
    let pb = motion[POS + b];
    let first_is_mine = i == a;
    var seen_a = theirs;
    var seen_b = mine;
    if first_is_mine {
        seen_a = mine;
        seen_b = theirs;
    }
    let va = seen_a.vel;
    let vb = seen_b.vel;
    let d = pa.xyz - pb.xyz;
    let n = direction(d);
    let goal = speculative_goal(length(d) - pa.w - pb.w);
    // Each ball's mass split among its contacts.
    let share_a = shares(a, seen_a);
    let share_b = shares(b, seen_b);
    let k = (share_a * va.w + share_b * vb.w) / relaxation(max(share_a, share_b));
    let total = impulse_at(at);
    let normal = max(0.0, total.w + (goal - dot(va.xyz - vb.xyz, n)) / k);
    // The contact points' relative velocity, less its normal part: the slip.
    let u = va.xyz + cross(seen_a.spin.xyz, -pa.w * n) - vb.xyz - cross(seen_b.spin.xyz, pb.w * n);
    let slip = u - dot(u, n) * n;
    // A solid sphere's contact point is 7/2 times as easy to move sideways.
    let friction = clamp_friction(total.xyz - slip / (3.5 * k), params.material.y * normal);
    set_impulse(at, vec4<f32>(friction, normal));
    // On the lower-numbered ball; the other gets its opposite.
    let change = (normal - total.w) * n + (friction - total.xyz);
    let im = motion[VEL + i].w;
    let pushing = select(0.0, 1.0, normal > 0.0);
    let none = vec3<f32>(0.0);
    if first_is_mine {
        return Push(change * im, cross(-pa.w * n, change) * inv_inertia(im, pa.w), none, pushing);
    }
    return Push(-change * im, cross(pb.w * n, -change) * inv_inertia(im, pb.w), none, pushing);
}

// Ball i's shift out of ball j, each as the sweep sees it: its share of
// the overlap they would have after the step at their velocities so far,
// the lighter ball moved the further. Read after the step, so that the
// shift meets what the velocities leave, as the flight will move them.
fn shift_out_of(i: u32, j: u32, mine: Seen, theirs: Seen) -> vec3<f32> {
    let ahead = shifted(i, mine) - shifted(j, theirs) + (mine.vel.xyz - theirs.vel.xyz) * dt();
    let apart = length(ahead);
    if apart <= 0.0 {
        return vec3<f32>(0.0);
    }
    let split = max(shares(i, mine), shares(j, theirs));
    let depth = motion[POS + i].w + motion[POS + j].w - apart;
    return ahead / apart * shift_share(depth, split) * mine.vel.w / (mine.vel.w + theirs.vel.w);
}

// Ball i's contacts with the room's walls, at velocity `v` and spin `w`,
// its mass split `shares` ways. (No shift: the room holds a shifted ball
// within it, see `pushed`.)
fn solve_walls(i: u32, v: vec3<f32>, w: vec3<f32>, shares: f32) -> Push {
    let p = motion[POS + i].xyz;
    let r = motion[POS + i].w;
    let im = motion[VEL + i].w;
    var push = NO_PUSH;
    for (var axis = 0u; axis < 3u; axis++) {
        if !touches_wall(ball_words[STATE + i], axis) {
            continue;
        }
        let wall = nearest_wall(p, r, axis);
        let n = wall.xyz;
        let k = shares * im / relaxation(shares);
        let total = pushes[WALL_IMPULSE + i * 3u + axis];
        let goal = speculative_goal(wall.w);
        let normal = max(0.0, total.w + (goal - dot(v, n)) / k);
        let u = v + cross(w, -r * n);
        let slip = u - dot(u, n) * n;
        let friction = clamp_friction(total.xyz - slip / (3.5 * k), params.material.w * normal);
        pushes[WALL_IMPULSE + i * 3u + axis] = vec4<f32>(friction, normal);
        let change = (normal - total.w) * n + (friction - total.xyz);
        push.velocity += change * im;
        push.spin += cross(-r * n, change) * inv_inertia(im, r);
        push.pushing += select(0.0, 1.0, normal > 0.0);
    }
    return push;
}

// Ball i's contact with a body, at velocity `v` and shifted to `to`, its
// mass split `shares` ways. The body stands still within the step, so
// the ball alone is shifted out of it (but not out of the fireball, which
// passes through).
fn solve_body(i: u32, v: vec3<f32>, to: vec3<f32>, shares: f32) -> Push {
    let b = ball_words[BODY_OF + i];
    if b == NONE {
        return NO_PUSH;
    }
    let p = motion[POS + i].xyz;
    let r = motion[POS + i].w;
    let im = motion[VEL + i].w;
    let body = bodies[b];
    let d = p - body.sphere.xyz;
    let n = d / max(length(d), 1e-9);
    let point = body.sphere.xyz + n * body.sphere.w;
    let vb = body_point_velocity(body, point);
    let total = pushes[BODY_IMPULSE + i];
    let goal = speculative_goal(length(d) - r - body.sphere.w);
    let approach = -dot(motion[VEL_START + i].xyz - vb, n);
    // The tumbler stands still within the step, but the push is shared
    // as if it gave way: its effective mass at the point counts.
    let body_im = body_inverse_mass(body, point, n);
    // No more than stops the two meeting (a bounce at most) and holds up
    // a few balls' weight: a ball wedged between a tumbler and a wall
    // cannot be squeezed into an ever larger push back.
    let most = ((1.0 + params.more.y) * max(approach, 0.0) + BODY_WEIGHTS * params.room_max.w * dt()) / (im + body_im);
    let k = (shares * im + body_im) / relaxation(shares);
    let normal = clamp(total.w + (goal - dot(v - vb, n)) / k, 0.0, most);
    pushes[BODY_IMPULSE + i] = vec4<f32>(total.x, 0.0, 0.0, normal);
    // Out of where it would stand after the step, as `shift_out_of`.
    var apart = vec3<f32>(0.0);
    let ahead = to + v * dt() - body.sphere.xyz;
    if body.info.x != FIREBALL && length(ahead) > 0.0 {
        let overlap = r + body.sphere.w - length(ahead);
        apart = normalize(ahead) * shift_share(overlap, shares);
    }
    return Push((normal - total.w) * n * im, vec3<f32>(0.0), apart, select(0.0, 1.0, normal > 0.0));
}

// Ball i's contacts with the walls and its body.
fn solve_own(i: u32, mine: Seen) -> Push {
    let split = shares(i, mine);
    var push = solve_walls(i, mine.vel.xyz, mine.spin.xyz, split);
    add_push(&push, solve_body(i, mine.vel.xyz, shifted(i, mine), split));
    return push;
}

fn add_push(push: ptr<function, Push>, more: Push) {
    (*push).velocity += more.velocity;
    (*push).spin += more.spin;
    (*push).shift += more.shift;
    (*push).pushing += more.pushing;
}

// Ball i after a sweep's `push`, its shares kept (see `shares`), shifted
// no further than the room holds it.
fn pushed(i: u32, mine: Seen, push: Push) -> Seen {
    let p = motion[POS + i].xyz;
    let r = motion[POS + i].w;
    let held = clamp(
        p + mine.shift.xyz + push.shift,
        params.room_min.xyz + r,
        params.room_max.xyz - r,
    );
    return Seen(
        vec4<f32>(mine.vel.xyz + push.velocity, mine.vel.w),
        vec4<f32>(mine.spin.xyz + push.spin, max(shares(i, mine), push.pushing)),
        vec4<f32>(held - p, 0.0),
    );
}

// The balls of one block (see `ball_in_block`) as workgroup memory holds them
// between its sweeps.
var<workgroup> block_balls: array<Seen, WORKGROUP>;

@compute @workgroup_size(256)
fn solve_forth(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_index) t: u32) {
    solve_block(block_index(group), t, false);
}

@compute @workgroup_size(256)
fn solve_back(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_index) t: u32) {
    solve_block(block_index(group), t, true);
}

// Up to BLOCK_SWEEPS sweeps of block g's balls, thread t taking its t-th:
// a contact within the block every sweep, from what the sweep before
// left in workgroup memory; a contact with another block's ball in the
// first sweep only, from the copy the dispatch reads, as that block works
// it out too, from the same numbers, so both keep the same impulse. The
// block stops early once a sweep moves none of its balls by more than
// SETTLED_SPEED: a pile at rest, warm-started, settles in a sweep or two.
// Returns whether the first sweep moved any ball by more than that.
fn solve_block(g: u32, t: u32, back: bool) -> bool {
    let i = ball_in_block(g, t, block_start(back));
    let solved = in_solver(i);
    if i != NONE {
        block_balls[t] = seen_in(i, back);
    }
    if t == 0u {
        atomicStore(&block_moving, 0u);
    }
    workgroupBarrier();
    var first_moved = false;
    for (var sweep = 0u; sweep < BLOCK_SWEEPS; sweep++) {
        var after = Seen(vec4<f32>(0.0), vec4<f32>(0.0), vec4<f32>(0.0));
        if solved {
            let before = block_balls[t];
            after = sweep_in_block(i, g, before, sweep == 0u, back);
            let moved = length(after.vel.xyz - before.vel.xyz)
                + motion[POS + i].w * length(after.spin.xyz - before.spin.xyz)
                + length(after.shift.xyz - before.shift.xyz) / dt();
            if moved > SETTLED_SPEED {
                atomicOr(&block_moving, 1u);
            }
        }
        workgroupBarrier();
        if solved {
            block_balls[t] = after;
        }
        if t == 0u {
            block_sweeping = atomicExchange(&block_moving, 0u);
        }
        let moving = workgroupUniformLoad(&block_sweeping) != 0u;
        first_moved = first_moved || (sweep == 0u && moving);
        if !moving {
            break;
        }
    }
    if i != NONE {
        put_vel(i, back, block_balls[t].vel);
        put_spin(i, back, block_balls[t].spin);
        put_shift(i, back, block_balls[t].shift);
    }
    return first_moved;
}

// Where the blocks start in cell order: the dispatches that read the
// second copy take blocks half a block on from those of the first, so that
// a contact across one block's edge lies within the other's, and is
// worked out in every sweep of every other dispatch, not in its first
// sweep alone.
fn block_start(back: bool) -> u32 {
    return select(0u, WORKGROUP / 2u, back);
}

// The blocks a dispatch sweeps.
fn blocks(back: bool) -> u32 {
    return (params.count + block_start(back) + WORKGROUP - 1u) / WORKGROUP;
}

// A sweep that changes no ball's velocity (or its surface's speed from
// spin, or its shift over the step) by more than this (m/s) ends its
// block's sweeps in a dispatch.
const SETTLED_SPEED: f32 = 1e-5;
// Whether any of the block's balls moved more than SETTLED_SPEED in this
// sweep, and a copy of it read alike by every thread.
var<workgroup> block_moving: atomic<u32>;
var<workgroup> block_sweeping: u32;

// One sweep of ball i in block g (see `solve_block`).
fn sweep_in_block(i: u32, g: u32, mine: Seen, first: bool, back: bool) -> Seen {
    var push = solve_own(i, mine);
    for (var k = 0u; k < slot_count(ball_words[STATE + i]); k++) {
        let at = i * SLOTS + k;
        let j = slot_words[SLOT_OTHER + at];
        let near = place_in_block(j, g, block_start(back));
        // Another block's ball is seen in the first sweep only.
        if near == NONE && !first {
            push.pushing += select(0.0, 1.0, impulse_at(at).w > 0.0);
            continue;
        }
        var theirs: Seen;
        if near != NONE {
            theirs = block_balls[near];
        } else {
            theirs = seen_in(j, back);
        }
        // A contact its other ball does not list (its nearest were nearer)
        // is not solved, but this ball is shifted out of it.
        if slot_words[SLOT_MIRROR + at] != NONE {
            add_push(&push, solve_pair(i, j, at, mine, theirs));
        }
        if alive(j) {
            push.shift += shift_out_of(i, j, mine, theirs);
        }
    }
    return pushed(i, mine, push);
}

// A small world's dispatches in one workgroup (see `SMALL_GROUP` in
// `common.wgsl`), each block in turn. Once a dispatch's first sweeps
// settle every block, so would the next's, from the same velocities: the
// rest are passed over, after a back dispatch, which ends in the first
// copy.
@compute @workgroup_size(256)
fn solve_in_one_group(@builtin(local_invocation_index) t: u32) {
    for (var dispatch = 0u; dispatch < SOLVE_DISPATCHES; dispatch++) {
        let back = dispatch % 2u == 1u;
        // Every thread holds the same answer: each block's is read
        // through workgroupUniformLoad.
        var any_moved = false;
        for (var g = 0u; g < blocks(back); g++) {
            any_moved = solve_block(g, t, back) || any_moved;
        }
        storageBarrier();
        if dispatch % 2u == 1u && !any_moved {
            break;
        }
    }
}
