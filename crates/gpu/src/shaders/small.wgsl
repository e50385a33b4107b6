// A small world's sweeps in one workgroup: the same work as the passes
// of impacts.wgsl, solve.wgsl and project.wgsl, each thread taking every
// SMALL_GROUP-th ball or cell, with a barrier where the large world ends a
// dispatch. Some three hundred dispatches a step cost a small world more
// than their work; one each for the impacts, the solver and the overlaps
// does not. The counts are the engine's, given when the pipelines are made.

override IMPACT_ROUNDS: u32;
override IMPACT_SWEEPS: u32;
override SOLVE_SWEEPS: u32;
override SHIFT_SWEEPS: u32;
override COLOURS: u32;

// Threads of the one workgroup: a small world has few balls to share out.
const SMALL_GROUP: u32 = 64u;

@compute @workgroup_size(SMALL_GROUP)
fn impacts_in_one_group(@builtin(local_invocation_index) t: u32) {
    for (var round = 0u; round < IMPACT_ROUNDS; round++) {
        for (var i = t; i < params.count; i += SMALL_GROUP) {
            raise_impact_goals_of(i);
        }
        storageBarrier();
        for (var sweep = 0u; sweep < IMPACT_SWEEPS; sweep++) {
            for (var i = t; i < params.count; i += SMALL_GROUP) {
                solve_impacts_of(i);
            }
            storageBarrier();
            for (var i = t; i < params.count; i += SMALL_GROUP) {
                apply_deltas_of(i);
            }
            storageBarrier();
        }
    }
}

@compute @workgroup_size(SMALL_GROUP)
fn solve_in_one_group(@builtin(local_invocation_index) t: u32) {
    for (var sweep = 0u; sweep < SOLVE_SWEEPS; sweep++) {
        for (var q = 0u; q < COLOURS; q++) {
            let o = colour_offset(q);
            for (var k = t; k < colour_cells(o); k += SMALL_GROUP) {
                solve_cell_at(colour_cell(k, o));
            }
            storageBarrier();
        }
    }
}

@compute @workgroup_size(SMALL_GROUP)
fn overlaps_in_one_group(@builtin(local_invocation_index) t: u32) {
    for (var sweep = 0u; sweep < SHIFT_SWEEPS; sweep++) {
        for (var i = t; i < params.count; i += SMALL_GROUP) {
            find_overlaps_of(i);
        }
        storageBarrier();
        for (var i = t; i < params.count; i += SMALL_GROUP) {
            apply_shifts_of(i);
        }
        storageBarrier();
    }
}
