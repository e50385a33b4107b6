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
        cell_of[i] = NONE;
        return;
    }
    let c = cell_id(cell_coords(pos[i].xyz));
    cell_of[i] = c;
    atomicAdd(&cell_fill[c], 1u);
}

@compute @workgroup_size(256)
fn place_in_cells(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = ball_index(id);
    if i >= params.count || cell_of[i] == NONE {
        return;
    }
    let c = cell_of[i];
    cell_balls[cell_start[c] + atomicSub(&cell_fill[c], 1u) - 1u] = i;
}

// Each cell's list sorted, each ball's place in the order noted, and the
// cell's fastest ball gauged.
@compute @workgroup_size(256)
fn sort_cells(@builtin(global_invocation_id) id: vec3<u32>) {
    let c = ball_index(id);
    if c >= params.cells {
        return;
    }
    let first = cell_start[c];
    let end = cell_start[c + 1u];
    for (var k = first + 1u; k < end; k++) {
        let ball = cell_balls[k];
        var m = k;
        while m > first && cell_balls[m - 1u] > ball {
            cell_balls[m] = cell_balls[m - 1u];
            m--;
        }
        cell_balls[m] = ball;
    }
    var fastest = 0.0;
    for (var k = first; k < end; k++) {
        let ball = cell_balls[k];
        ball_rank[ball] = k;
        fastest = max(fastest, length(vel[ball].xyz));
    }
    cell_speed[c] = fastest;
}
