//! The data the ball passes share with the CPU, laid out as the WGSL in
//! `step/common.wgsl` declares it, and how work is split into
//! workgroups.

use bytemuck::{Pod, Zeroable};

/// Threads in a workgroup, in every pass (`WORKGROUP` in the WGSL).
pub const WORKGROUP: u32 = 256;
/// Contacts a ball keeps with other balls in one step (`SLOTS` in the
/// WGSL, written there from here).
pub const SLOTS: u64 = 12;
// A ball's state word counts its contacts in four bits.
const _: () = assert!(SLOTS < 16);
/// Cells along x, y and z of the bricks the grid numbers its cells by
/// (`BRICK` in the WGSL, see `cell_id`): a dense pile's brick holds about
/// as many balls as a workgroup has threads (a cell is three radii wide),
/// and a tall one holds the columns that bear a pile's weight. The bench's
/// 10 000-ball pit sank 6.1 mm in its first half second with these (eight
/// solver dispatches of six sweeps), 6.7 with bricks four cells a side.
pub const BRICK: [u32; 3] = [2, 8, 4];

/// The cells of a grid `dims` cells wide: whole bricks.
pub fn grid_cells(dims: [u32; 3]) -> u64 {
    dims.iter()
        .zip(BRICK)
        .map(|(&d, b)| u64::from(d.div_ceil(b) * b))
        .product()
}

/// The most workgroups a dispatch has along one dimension; wider ones
/// spill into y (`ball_index` in the WGSL).
pub const MAX_GROUPS: u32 = 65_535;
/// Items one dispatch can cover.
pub const MAX_ITEMS: u64 = MAX_GROUPS as u64 * MAX_GROUPS as u64 * WORKGROUP as u64;
/// The body number that means the fireball (`FIREBALL`).
pub const FIREBALL: u32 = 0xffff;
/// Impact rounds (see `impacts.wgsl`), a dispatch each and one more: each ball
/// meets at most one contact a round, in time order, and a ball struck in
/// one round strikes its neighbour in the next, so a blow passes along a
/// row of thirteen balls within a step. Even, as the rounds alternate
/// between two copies of the velocities and must end in the first. An
/// impact still due after the last round is stopped by the resting
/// contacts, without a bounce; in a landing pile a fast one left so sinks
/// deep. The bench's 10 000-ball pit, read every 0.05 s through its
/// landing, sank at worst 5.9, 6.9 and 6.8 mm with six rounds (seeds 1 to
/// 3), 7.4 with eight (seed 1), 9.9 and 4.4 with ten (seeds 1 and 2), 3.2,
/// 3.4 and 3.0 with twelve, 2.3 and 2.5 with sixteen, and 4.6 (seed 1)
/// with the three rounds of Jacobi sweeps before (each with the overlaps
/// pushed out in sixteen sweeps after the flight). An elastic gas of 400
/// balls under gravity lost 0.25 % of its energy in 10 s with four rounds,
/// 0.12 % with six or more.
pub const IMPACT_ROUNDS: u32 = 12;
const _: () = assert!(IMPACT_ROUNDS.is_multiple_of(2));
/// Catches reported in one step at most (`events`' length).
pub const EVENT_CAPACITY: u64 = 1024;

/// `Params` in the WGSL: the step's constants.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
pub struct Params {
    pub count: u32,
    pub cells: u32,
    pub bodies: u32,
    pub consumes: u32,
    pub dims: [u32; 4],
    /// Inside corner; w: the step.
    pub room_min: [f32; 4],
    /// Outside corner; w: gravity.
    pub room_max: [f32; 4],
    /// Cell size, margin, bounce threshold, event threshold.
    pub grid: [f32; 4],
    /// Ball restitution and friction, wall restitution and friction.
    pub material: [f32; 4],
    /// Wall rolling resistance, tumbler restitution, reach, the shifts'
    /// relaxation.
    pub more: [f32; 4],
    pub tumblers: u32,
    pub surface_colors: u32,
    pub step: u32,
    /// The contact solver's over-relaxation.
    pub solve_relaxation: f32,
}

/// `Body` in the WGSL: one sphere of a tumbler, or the fireball.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
pub struct Body {
    pub sphere: [f32; 4],
    pub origin: [f32; 4],
    pub velocity: [f32; 4],
    pub spin: [f32; 4],
    /// Tumbler number (or [`FIREBALL`]), sphere number, palette colour.
    pub info: [u32; 4],
    /// The rows of the inverse inertia about the point it turns about
    /// (zero for the fireball, which no ball moves).
    pub turn_inverse: [[f32; 4]; 3],
    /// The point it turns about.
    pub pivot: [f32; 4],
}

/// `Event` in the WGSL: a ball the fireball caught.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
pub struct Catch {
    /// Where; w: the ball's number, as bits.
    pub point: [f32; 4],
    /// From the ball towards the fireball; w: how fast they met.
    pub normal: [f32; 4],
}

/// A ball's impact as the step reports it (`report_impact` in the WGSL),
/// three vectors of the `pushes` buffer's `IMPACTS` section.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
pub struct Impact {
    /// Where; w: the ball's number, as bits.
    pub point: [f32; 4],
    /// From what it met towards the ball; w: how fast they closed.
    pub normal: [f32; 4],
    /// What it met (`HIT_WALL`, `HIT_BALL`, `HIT_BODY`), which (the
    /// surface, the ball, or the tumbler and its sphere in the low and high
    /// halves), and when within the step (s, f32 bits).
    pub info: [u32; 4],
}

/// What a ball met, in [`Impact::info`].
pub const HIT_WALL: u32 = 0;
/// Another ball.
pub const HIT_BALL: u32 = 1;
/// A tumbler's sphere.
pub const HIT_BODY: u32 = 2;

/// Impacts reported in one step at most; past it they are counted only.
pub const IMPACT_CAPACITY: u64 = 8192;

/// Workgroups for `items` items, spilled into y past [`MAX_GROUPS`].
pub fn groups(items: u64) -> (u32, u32) {
    let groups = items.div_ceil(u64::from(WORKGROUP)).max(1);
    if groups <= u64::from(MAX_GROUPS) {
        (groups as u32, 1)
    } else {
        (MAX_GROUPS, groups.div_ceil(u64::from(MAX_GROUPS)) as u32)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dispatches_cover_every_item_and_spill_into_y() {
        for items in [
            0,
            1,
            255,
            256,
            257,
            65_535 * 256,
            65_535 * 256 + 1,
            20_000_000,
        ] {
            let (x, y) = groups(items);
            assert!(x <= MAX_GROUPS && y <= MAX_GROUPS);
            assert!(u64::from(x) * u64::from(y) * 256 >= items, "{items}");
        }
        assert_eq!(groups(257), (2, 1));
        assert_eq!(groups(65_535 * 256 + 1), (65_535, 2));
    }

    #[test]
    fn a_grid_has_whole_bricks_of_cells() {
        assert_eq!(grid_cells([2, 8, 4]), 64);
        assert_eq!(grid_cells([1, 1, 1]), 64);
        assert_eq!(grid_cells([5, 9, 3]), 6 * 16 * 4);
    }

    #[test]
    fn the_structs_are_as_large_as_the_shader_reads_them() {
        assert_eq!(std::mem::size_of::<Params>(), 128);
        assert_eq!(std::mem::size_of::<Body>(), 144);
        assert_eq!(std::mem::size_of::<Catch>(), 32);
    }
}
