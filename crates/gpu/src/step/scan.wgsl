// Exclusive prefix sum of u32, PER_THREAD values to a thread and 256
// threads to a block: each thread sums its run, the block scans the
// threads' sums, and each run is written back scanned with the block's
// total written out; the totals are scanned the same way (a level up),
// then added back to their blocks.

const BLOCK: u32 = 256u * PER_THREAD;

struct ScanParams {
    len: u32,
}

@group(0) @binding(0) var<uniform> scan: ScanParams;
// The values, scanned in place.
@group(0) @binding(1) var<storage, read_write> values: array<u32>;
// Each block's total.
@group(0) @binding(2) var<storage, read_write> block_totals: array<u32>;

var<workgroup> partial: array<u32, 256>;

fn flat(id: vec3<u32>) -> u32 {
    return id.x + id.y * 65535u * 256u;
}

@compute @workgroup_size(256)
fn scan_blocks(
    @builtin(local_invocation_index) lid: u32,
    @builtin(workgroup_id) wid: vec3<u32>,
) {
    let block = wid.x + wid.y * 65535u;
    let first = block * BLOCK + lid * PER_THREAD;
    // This thread's run, scanned.
    var run: array<u32, PER_THREAD>;
    var sum = 0u;
    for (var k = 0u; k < PER_THREAD; k++) {
        run[k] = sum;
        if first + k < scan.len {
            sum += values[first + k];
        }
    }
    partial[lid] = sum;
    workgroupBarrier();
    // Hillis-Steele: log2(256) rounds of adding the neighbour `offset` back.
    for (var offset = 1u; offset < 256u; offset *= 2u) {
        var add = 0u;
        if lid >= offset {
            add = partial[lid - offset];
        }
        workgroupBarrier();
        partial[lid] += add;
        workgroupBarrier();
    }
    let before = partial[lid] - sum;
    for (var k = 0u; k < PER_THREAD; k++) {
        if first + k < scan.len {
            values[first + k] = before + run[k];
        }
    }
    if lid == 255u {
        block_totals[block] = partial[255];
    }
}

@compute @workgroup_size(256)
fn add_block_offsets(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = flat(gid);
    if i < scan.len {
        values[i] += block_totals[i / BLOCK];
    }
}
