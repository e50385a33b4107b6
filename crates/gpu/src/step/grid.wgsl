// The uniform grid, built so that each cell lists its balls in ball order
// whatever order the atomics land in: count, scan (see scan.wgsl), place,
// then sort each cell's short list. Placing counts each cell back down to
// zero, so the counts need no clearing between steps.

@compute @workgroup_size(256)
fn count_cells(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = ball_index(id);
    if i >= params.count {
        return;
    }
    if !alive(i) {
        ball_words[CELL_OF + i] = NONE;
        return;
    }
    let c = cell_id(cell_coords(motion[POS + i].xyz));
    ball_words[CELL_OF + i] = c;
    atomicAdd(&counters[CELL_FILL + c], 1u);
}

@compute @workgroup_size(256)
fn place_in_cells(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = ball_index(id);
    if i >= params.count || ball_words[CELL_OF + i] == NONE {
        return;
    }
    let c = ball_words[CELL_OF + i];
    ball_words[CELL_BALLS + cell_words[CELL_START + c] + atomicSub(&counters[CELL_FILL + c], 1u) - 1u] = i;
}

// Each cell's list sorted, each ball's place in the order noted, and the
// cell's fastest ball gauged.
@compute @workgroup_size(256)
fn sort_cells(@builtin(global_invocation_id) id: vec3<u32>) {
    let c = ball_index(id);
    if c >= params.cells {
        return;
    }
    let first = cell_words[CELL_START + c];
    let end = cell_words[CELL_START + c + 1u];
    for (var k = first + 1u; k < end; k++) {
        let ball = ball_words[CELL_BALLS + k];
        var m = k;
        while m > first && ball_words[CELL_BALLS + m - 1u] > ball {
            ball_words[CELL_BALLS + m] = ball_words[CELL_BALLS + m - 1u];
            m--;
        }
        ball_words[CELL_BALLS + m] = ball;
    }
    var fastest = 0.0;
    for (var k = first; k < end; k++) {
        let ball = ball_words[CELL_BALLS + k];
        ball_words[BALL_RANK + ball] = k;
        fastest = max(fastest, length(motion[VEL + ball].xyz));
    }
    set_cell_speed(c, fastest);
}
