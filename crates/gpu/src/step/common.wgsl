// What every ball pass shares: the step's constants and the buffers (see
// `bindings.rs`, which lists them in this order). Each pass binds only
// those its entry point uses.

const WORKGROUP: u32 = 256u;
// A world of few balls runs each sweeping stage (the impacts, the solver)
// as one dispatch of one workgroup, with a barrier where a large world
// ends a dispatch: the same sweeps, to rounding. Some tens of dispatches
// a step cost a small world more than their work. The impacts'
// workgroup has SMALL_GROUP threads, each taking every
// SMALL_GROUP-th ball; the solver's takes each of a large world's blocks
// in turn (see `ball_at`). The sweep counts are written above this file
// by the stage that runs them.
const SMALL_GROUP: u32 = 64u;
// Workgroups a dispatch may have along x; more spill into y.
const MAX_GROUPS: u32 = 65535u;
// SLOTS, the contacts a ball keeps with other balls in one step (its
// nearest), is written above this file from `layout.rs`.
const NONE: u32 = 0xffffffffu;
// A ball's state word: bit 0 alive; bit 1 in the solver (it has a ball or
// a body within reach); bits 4-7 how many balls it touches; bits 8-10 which
// of its nearest walls (x, y, z) it touches; bits 11-15 how many of its
// contacts may push within the step (see warm_start.wgsl); bits 16-31 its
// colour's place in the palette.
const ALIVE: u32 = 1u;
const SOLVED: u32 = 2u;
const SLOT_SHIFT: u32 = 4u;
const WALL_SHIFT: u32 = 8u;
const PRESSING_SHIFT: u32 = 11u;
const COLOR_SHIFT: u32 = 16u;
// Bodies a ball can meet besides balls and walls: tumblers' spheres and the
// fireball. `Body.info.x` is the tumbler's number, or this for the fireball.
const FIREBALL: u32 = 0xffffu;

struct Params {
    // Balls in use; cells; bodies; 1 when the fireball takes the balls it meets.
    count: u32,
    cells: u32,
    bodies: u32,
    consumes: u32,
    // The grid's cells along x, y, z, and the palette's first tumbler colour.
    dims: vec4<u32>,
    // The room's inside corner; w: the step (s).
    room_min: vec4<f32>,
    // The room's outside corner; w: gravity (m/s², along -y).
    room_max: vec4<f32>,
    // x: cell size; y: speculative margin (m); z: bounce threshold, w: event threshold (m/s).
    grid: vec4<f32>,
    // Balls: restitution, friction; walls: restitution, friction.
    material: vec4<f32>,
    // x: walls' rolling resistance; y: tumblers' restitution; z: the reach
    // within which balls are solved together even if they do not close (m);
    // w: the share of an overlap a solver sweep pushes out (see `shift_share`).
    more: vec4<f32>,
    // Tumblers whose pushes are summed; the palette's first surface colour.
    tumblers: u32,
    surface_colors: u32,
    step: u32,
    // The contact solver's over-relaxation (see solve.wgsl).
    solve_relaxation: f32,
}

struct Body {
    // Centre and radius of the sphere.
    sphere: vec4<f32>,
    // The point its motion is given about, and its velocity.
    origin: vec4<f32>,
    velocity: vec4<f32>,
    // Angular velocity (rad/s).
    spin: vec4<f32>,
    // x: tumbler number (or FIREBALL), y: sphere number, z: palette colour.
    info: vec4<u32>,
    // The rows of the inverse inertia about the pivot it turns about when
    // pushed (zero for the fireball, which no ball moves), and the pivot.
    turn_inverse: array<vec4<f32>, 3>,
    pivot: vec4<f32>,
}

struct Event {
    // Where, and the ball's number as bits.
    point: vec4<f32>,
    // Along which normal, and how fast.
    normal: vec4<f32>,
}

@group(0) @binding(0) var<uniform> params: Params;
// Arrays of one type share a buffer, section after section, each section
// named by a constant giving its first element, written above this file
// from `bindings.rs` (as is CAPACITY, the balls a section has room for):
// `motion[VEL + i]` is ball i's velocity. WebGPU promises a shader stage
// only 8 storage buffers.
//
// The balls' motion: POS centre and radius; VEL velocity and inverse mass;
// SPIN angular velocity; VEL_START the velocity at the start of the step;
// DELTA and DELTA_SPIN the second copy of the velocities and spins that
// the Jacobi sweeps alternate with (see `vel_in`).
@group(0) @binding(1) var<storage, read_write> motion: array<vec4<f32>>;
// What the solver adds up for each ball: WALL_IMPULSE its contacts with
// the room's nearest wall on each axis (three a ball); BODY_IMPULSE its
// contact with a body (x the impacts', w the resting contact's); SHIFT how
// far the solver moves it out of its overlaps this step, by position
// alone (see solve.wgsl): two copies, one after the other, that its sweeps
// alternate between as they do the velocities (see `shift_place`); and
// IMPACTS, the step's impacts, three vectors each (see `report_impact`).
@group(0) @binding(2) var<storage, read_write> pushes: array<vec4<f32>>;
// Each ball's contacts' impulses so far (friction xyz, normal w), SLOTS a
// ball in two halves (see `impulse_at`).
@group(0) @binding(3) var<storage, read_write> slot_impulse: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read_write> slot_impulse_more: array<vec4<f32>>;
// A word or two for each ball: STATE (see ALIVE, SOLVED); CELL_OF its
// cell; BODY_OF the body it touches (or NONE); BALL_RANK its place in
// CELL_BALLS, the balls by cell (see `ball_at`); FIRST_CONTACT what it
// meets first in an impact round (see `FIRST_WALL`; two copies, see
// `first_place`); BODY_IMPACT its impacts' push on its body this step and
// NEAR_SPEED the speed of the fastest ball in the 27 cells around it, both
// f32 bits (see `body_impact_of`, `near_speed_of`).
@group(0) @binding(5) var<storage, read_write> ball_words: array<u32>;
// Each ball's contacts with other balls, SLOTS a ball: SLOT_OTHER the other
// ball, SLOT_MIRROR where the other keeps the same contact, or NONE (see
// `note_mirrors` in impacts.wgsl).
@group(0) @binding(6) var<storage, read_write> slot_words: array<u32>;
// A word for each cell and one past the last: CELL_START its first place
// in CELL_BALLS (one past the end: the count); CELL_SPEED the speed of its
// fastest ball, as f32 bits (see `cell_speed_of`).
@group(0) @binding(7) var<storage, read_write> cell_words: array<u32>;
// What threads count together: CELL_FILL each cell's balls not yet placed
// (zero between steps), EVENT_COUNT the catches, IMPACT_COUNT how many
// balls meet a contact in each impact round (see impacts.wgsl),
// IMPACT_EVENTS the impacts reported.
@group(0) @binding(8) var<storage, read_write> counters: array<atomic<u32>>;
@group(0) @binding(9) var<storage, read> bodies: array<Body>;
@group(0) @binding(10) var<storage, read> palette: array<vec4<f32>>;
// What the renderer draws: centre and radius, colour (see `BallInstance`).
@group(0) @binding(11) var<storage, read_write> instances: array<vec4<f32>>;
// Each tumbler's push from the balls: impulse (w: the pushing balls' mass),
// then moment about its origin.
@group(0) @binding(12) var<storage, read_write> tumbler_push: array<vec4<f32>>;
@group(0) @binding(13) var<storage, read_write> events: array<Event>;

fn body_impact_of(i: u32) -> f32 {
    return bitcast<f32>(ball_words[BODY_IMPACT + i]);
}

fn set_body_impact(i: u32, push: f32) {
    ball_words[BODY_IMPACT + i] = bitcast<u32>(push);
}

fn near_speed_of(i: u32) -> f32 {
    return bitcast<f32>(ball_words[NEAR_SPEED + i]);
}

fn set_near_speed(i: u32, speed: f32) {
    ball_words[NEAR_SPEED + i] = bitcast<u32>(speed);
}

fn cell_speed_of(c: u32) -> f32 {
    return bitcast<f32>(cell_words[CELL_SPEED + c]);
}

fn set_cell_speed(c: u32, speed: f32) {
    cell_words[CELL_SPEED + c] = bitcast<u32>(speed);
}

// The impulse so far of contact slot `at` (ball at / SLOTS, its slot
// at % SLOTS). A ball's first SLOTS / 2 slots are kept in one buffer and
// the rest in another, so that neither outgrows the largest binding an
// adapter allows (lavapipe's 128 MiB holds a million balls' halves).
fn impulse_at(at: u32) -> vec4<f32> {
    let half = SLOTS / 2u;
    let k = at % SLOTS;
    let kept = at / SLOTS * half + k % half;
    if k < half {
        return slot_impulse[kept];
    }
    return slot_impulse_more[kept];
}

fn set_impulse(at: u32, impulse: vec4<f32>) {
    let half = SLOTS / 2u;
    let k = at % SLOTS;
    let kept = at / SLOTS * half + k % half;
    if k < half {
        slot_impulse[kept] = impulse;
    } else {
        slot_impulse_more[kept] = impulse;
    }
}

// Never within the step: any time of impact is sooner.
const NEVER: f32 = 3.0e38;

// When within the step a contact `gap` apart and closing at `approach`
// touches, if it closes fast enough to bounce and touches in time; else
// NEVER. Touching already is touching at once.
fn impact_time(approach: f32, gap: f32) -> f32 {
    if approach > params.grid.z && gap < approach * dt() {
        return max(gap, 0.0) / approach;
    }
    return NEVER;
}

// The normal (from b to a) and gap of two balls.
fn pair_geometry(a: u32, b: u32) -> vec4<f32> {
    let d = motion[POS + a].xyz - motion[POS + b].xyz;
    return vec4<f32>(direction(d), length(d) - motion[POS + a].w - motion[POS + b].w);
}

fn ball_index(id: vec3<u32>) -> u32 {
    // Dispatches wider than 65 535 workgroups spill into y.
    return id.x + id.y * MAX_GROUPS * WORKGROUP;
}

fn alive(i: u32) -> bool {
    return (ball_words[STATE + i] & ALIVE) != 0u;
}

// Whether ball `i` is one in play that the solver works on this step.
fn in_solver(i: u32) -> bool {
    return i < params.count && (ball_words[STATE + i] & (ALIVE | SOLVED)) == (ALIVE | SOLVED);
}

fn dt() -> f32 {
    return params.room_min.w;
}

fn gravity() -> vec3<f32> {
    return vec3<f32>(0.0, -params.room_max.w, 0.0);
}

// The unit vector along `d`, or up where `d` is none: two balls pressed
// into the same corner stand at the same point.
fn direction(d: vec3<f32>) -> vec3<f32> {
    let len = length(d);
    if len > 0.0 {
        return d / len;
    }
    return vec3<f32>(0.0, 1.0, 0.0);
}

fn cell_coords(p: vec3<f32>) -> vec3<i32> {
    let c = floor((p - params.room_min.xyz) / params.grid.x);
    return clamp(vec3<i32>(c), vec3<i32>(0), vec3<i32>(params.dims.xyz) - 1);
}

// Cells are numbered brick by brick (BRICK cells along x, y and z, written
// above this file from `layout.rs`), each brick's cells in a row, so that
// balls in cell order come in compact clumps: the blocks the solver's
// sweeps work on together (see `ball_at`).
fn cell_id(c: vec3<i32>) -> u32 {
    let cell = vec3<u32>(c);
    let brick = cell / BRICK;
    let inner = cell % BRICK;
    let bricks = (params.dims.xyz + BRICK - 1u) / BRICK;
    let brick_id = brick.x + bricks.x * (brick.y + bricks.y * brick.z);
    return brick_id * BRICK.x * BRICK.y * BRICK.z + inner.y + BRICK.y * (inner.x + BRICK.x * inner.z);
}

// A solid sphere's inverse moment of inertia from its inverse mass.
fn inv_inertia(inv_mass: f32, r: f32) -> f32 {
    return 2.5 * inv_mass / (r * r);
}

// The separating speed a resting contact must keep: no more closing
// than its gap allows within the step.
fn speculative_goal(gap: f32) -> f32 {
    return -max(gap, 0.0) / dt();
}

// Friction so far plus what stops the slip, within the cone of the normal impulse.
fn clamp_friction(friction: vec3<f32>, limit: f32) -> vec3<f32> {
    let len = length(friction);
    if len > limit && len > 0.0 {
        return friction * (limit / len);
    }
    return friction;
}

// The room's nearest wall on `axis`: its inward normal and the gap to it.
fn nearest_wall(p: vec3<f32>, r: f32, axis: u32) -> vec4<f32> {
    let low = p[axis] - params.room_min[axis];
    let high = params.room_max[axis] - p[axis];
    var n = vec3<f32>(0.0);
    if low <= high {
        n[axis] = 1.0;
        return vec4<f32>(n, low - r);
    }
    n[axis] = -1.0;
    return vec4<f32>(n, high - r);
}

// The surface (Floor, Ceiling, Left, Right, Back, Front) a wall normal names.
fn surface_of(n: vec3<f32>) -> u32 {
    if n.y > 0.5 { return 0u; }
    if n.y < -0.5 { return 1u; }
    if n.x > 0.5 { return 2u; }
    if n.x < -0.5 { return 3u; }
    if n.z > 0.5 { return 4u; }
    return 5u;
}

fn set_color(i: u32, palette_index: u32) {
    ball_words[STATE + i] = (ball_words[STATE + i] & 0xffffu) | (palette_index << COLOR_SHIFT);
}

// Reports ball i's impact with what `hit` and `other` name (HIT_WALL and
// the surface, HIT_BALL and the ball, HIT_BODY and the tumbler and its
// sphere): where, along which normal (from what it met towards it), how
// fast they closed, and when within the step. The reports are appended in
// whatever order the atomics land in; the CPU sorts them. Past
// IMPACT_CAPACITY they are counted only.
fn report_impact(i: u32, hit: u32, other: u32, point: vec3<f32>, normal: vec3<f32>, speed: f32, within: f32) {
    let e = atomicAdd(&counters[IMPACT_EVENTS], 1u);
    if e < IMPACT_CAPACITY {
        let at = IMPACTS + 3u * e;
        pushes[at] = vec4<f32>(point, bitcast<f32>(i));
        pushes[at + 1u] = vec4<f32>(normal, speed);
        pushes[at + 2u] = vec4<f32>(bitcast<f32>(hit), bitcast<f32>(other), within, 0.0);
    }
}

// When within the step a contact `gap` apart, closing at `speed`, met.
fn closing_time(gap: f32, speed: f32) -> f32 {
    return min(max(gap, 0.0) / max(speed, 1e-30), dt());
}

// How an impact report names a body: its tumbler, and its sphere above.
fn body_code(b: Body) -> u32 {
    return b.info.x | (b.info.y << 16u);
}

fn slot_count(s: u32) -> u32 {
    return (s >> SLOT_SHIFT) & 15u;
}

fn touches_wall(s: u32, axis: u32) -> bool {
    return ((s >> (WALL_SHIFT + axis)) & 1u) != 0u;
}

// How easily a push along `n` at `point` moves body `b` there: the inverse
// of its effective mass, turning about its pivot.
fn body_inverse_mass(b: Body, point: vec3<f32>, n: vec3<f32>) -> f32 {
    let lever = point - b.pivot.xyz;
    let moment = cross(lever, n);
    let turn = vec3<f32>(
        dot(b.turn_inverse[0].xyz, moment),
        dot(b.turn_inverse[1].xyz, moment),
        dot(b.turn_inverse[2].xyz, moment),
    );
    return max(0.0, dot(n, cross(turn, lever)));
}

// The velocity of the material point of body `b` at `point`.
fn body_point_velocity(b: Body, point: vec3<f32>) -> vec3<f32> {
    return b.velocity.xyz + cross(b.spin.xyz, point - b.origin.xyz);
}

// Adds the impacts' push on the ball's body to the step's (kept in
// `body_impulse.x`, for the tumblers' pushes).
fn fold_body_impact(i: u32) {
    pushes[BODY_IMPULSE + i].x += body_impact_of(i);
    set_body_impact(i, 0.0);
}

// A stage's Jacobi sweeps alternate between two copies of what they
// change: each sweep reads the copy the last one wrote and writes the
// other, so one dispatch is one sweep, no ball sees a neighbour half-way
// through one, and the result does not hang on the order threads run in.
// A forth sweep reads the first copy (`vel`, `spin`, the first half of
// `shift`) and writes the second (`delta`, `delta_spin`, the second half);
// a back sweep, the other way. Stages
// sweep an even number of times, so that they end in the first copy.
fn vel_in(i: u32, back: bool) -> vec4<f32> {
    if back {
        return motion[DELTA + i];
    }
    return motion[VEL + i];
}

fn spin_in(i: u32, back: bool) -> vec4<f32> {
    if back {
        return motion[DELTA_SPIN + i];
    }
    return motion[SPIN + i];
}

fn shift_in(i: u32, back: bool) -> vec4<f32> {
    return pushes[SHIFT + shift_place(i, back)];
}

// Where ball i's shift is kept in the copy a sweep `back` reads.
fn shift_place(i: u32, back: bool) -> u32 {
    return select(i, CAPACITY + i, back);
}

fn put_vel(i: u32, back: bool, v: vec4<f32>) {
    if back {
        motion[VEL + i] = v;
    } else {
        motion[DELTA + i] = v;
    }
}

fn put_spin(i: u32, back: bool, w: vec4<f32>) {
    if back {
        motion[SPIN + i] = w;
    } else {
        motion[DELTA_SPIN + i] = w;
    }
}

fn put_shift(i: u32, back: bool, s: vec4<f32>) {
    pushes[SHIFT + shift_place(i, !back)] = s;
}

// Balls in a block: a workgroup's sweeps in a dispatch work on the balls
// at places WORKGROUP * g - start .. WORKGROUP * (g + 1) - start of
// `cell_balls`, a clump of neighbours (see `cell_id`), and keep them in
// workgroup memory between sweeps, so that one dispatch runs several
// sweeps among them; a contact with a ball of another block is worked out
// once a dispatch, from the copy the dispatch started with. The solver
// sweeps so (see solve.wgsl), its blocks starting in turn at 0 and half a
// block on (see `block_start`).
fn block_index(group: vec3<u32>) -> u32 {
    return group.x + group.y * MAX_GROUPS;
}

// The ball at `place` in cell order, or NONE past the balls in play.
fn ball_at(place: u32) -> u32 {
    if place < cell_words[CELL_START + params.cells] {
        return ball_words[CELL_BALLS + place];
    }
    return NONE;
}

// The ball thread t of block g holds, the blocks starting at `start`.
fn ball_in_block(g: u32, t: u32, start: u32) -> u32 {
    let place = g * WORKGROUP + t;
    if place < start {
        return NONE;
    }
    return ball_at(place - start);
}

// Where ball `j` is kept in block `g`'s workgroup memory, or NONE if it
// is another block's, the blocks starting at `start`.
fn place_in_block(j: u32, g: u32, start: u32) -> u32 {
    let place = ball_words[BALL_RANK + j] + start;
    if place / WORKGROUP == g {
        return place % WORKGROUP;
    }
    return NONE;
}
