// Exclusive prefix sum of u32, 256 to a workgroup: each block is scanned
// in place and its total written out; the totals are scanned the same way
// (a level up), then added back to their blocks.

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
    @builtin(global_invocation_id) gid: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
    @builtin(workgroup_id) wid: vec3<u32>,
) {
    let i = flat(gid);
    var value = 0u;
    if i < scan.len {
        value = values[i];
    }
    partial[lid] = value;
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
    if i < scan.len {
        values[i] = partial[lid] - value;
    }
    if lid == 255u {
        block_totals[wid.x + wid.y * 65535u] = partial[255];
    }
}

@compute @workgroup_size(256)
fn add_block_offsets(
    @builtin(global_invocation_id) gid: vec3<u32>,
    @builtin(workgroup_id) wid: vec3<u32>,
) {
    let i = flat(gid);
    if i < scan.len {
        values[i] += block_totals[wid.x + wid.y * 65535u];
    }
}
