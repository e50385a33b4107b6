//! Stage 4, the contact solver (`solve.wgsl`), from the velocities the
//! impacts' last dispatch warm-started (`warm_start.wgsl`): Jacobi sweeps
//! with mass splitting, a few a dispatch among each block of neighbouring
//! balls (see `ball_at` in `common.wgsl`), that also shift the balls out
//! of their overlaps.

use super::{Kernel, Recorder, Shaders};
use crate::layout::WORKGROUP;
use crate::profile::Stage;

/// How the solver sweeps a step.
pub struct SweepCounts {
    /// Dispatches, each running `block_sweeps` sweeps among each block of
    /// neighbouring balls. Even: each reads one copy of the velocities and
    /// writes the other, and the last must end in the first (see `vel_in`
    /// in `common.wgsl`).
    pub dispatches: u32,
    pub block_sweeps: u32,
}

pub struct Solve {
    /// The dispatches that read the first copy and those that read the
    /// second, taken in turn.
    each_way: [Kernel; 2],
    dispatches: u32,
    in_one_group: Kernel,
}

impl Solve {
    pub fn new(shaders: &Shaders, counts: &SweepCounts) -> Solve {
        let module = shaders.module(
            "solve",
            &[
                ("SOLVE_DISPATCHES", counts.dispatches),
                ("BLOCK_SWEEPS", counts.block_sweeps),
            ],
            include_str!("solve.wgsl"),
        );
        let pipeline = |entry: &str| shaders.pipeline(&module, entry);
        Solve {
            each_way: [pipeline("solve_forth"), pipeline("solve_back")],
            dispatches: counts.dispatches,
            in_one_group: pipeline("solve_in_one_group"),
        }
    }

    /// A workgroup a block in each dispatch, or a small world's in one.
    pub fn record(&self, step: &mut Recorder) {
        let small = step.small;
        step.stage(Stage::Solve, |pass| {
            if small {
                return pass.workgroups(&self.in_one_group, 1, 1);
            }
            // The back dispatches' blocks start half a block on (see
            // `block_start` in the WGSL): one block more.
            let balls = pass.balls();
            for dispatch in 0..self.dispatches as usize {
                let threads = balls + u64::from(WORKGROUP / 2) * (dispatch % 2) as u64;
                pass.over(&self.each_way[dispatch % 2], threads);
            }
        });
    }
}
