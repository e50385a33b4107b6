//! Stage 1, the grid (`grid.wgsl`): each ball's cell counted, the counts
//! scanned into each cell's first place (`scan`), the balls placed (which
//! counts each cell back down to zero for the next step), and each cell's
//! list sorted by ball number, so that every later pass walks the same
//! lists in the same order whatever order the atomics landed in.

use super::scan::Scan;
use super::{Kernel, Recorder, Shaders, Stamps};
use crate::bindings::Buffers;
use crate::profile::Stage;

pub struct Grid {
    count_cells: Kernel,
    place_in_cells: Kernel,
    sort_cells: Kernel,
    scan: Scan,
    cells: u64,
    /// The counts, and the buffer they are scanned in.
    cell_fill: wgpu::Buffer,
    cell_start: wgpu::Buffer,
}

impl Grid {
    pub fn new(shaders: &Shaders, buffers: &Buffers, cells: u64) -> Grid {
        let module = shaders.module("grid", &[], include_str!("grid.wgsl"));
        // The counts are copied to, and scanned in, the start of a buffer.
        assert!(buffers.section("CELL_FILL").1 == 0 && buffers.section("CELL_START").1 == 0);
        Grid {
            count_cells: shaders.pipeline(&module, "count_cells"),
            place_in_cells: shaders.pipeline(&module, "place_in_cells"),
            sort_cells: shaders.pipeline(&module, "sort_cells"),
            scan: Scan::new(shaders.device, buffers.section("CELL_START").0, cells + 1),
            cells,
            cell_fill: buffers.section("CELL_FILL").0.clone(),
            cell_start: buffers.section("CELL_START").0.clone(),
        }
    }

    /// What the scan's pipelines bind.
    pub fn scan_layouts(&self) -> Vec<super::PassLayout> {
        self.scan.layouts()
    }

    /// Two passes around the scan; the stage's stamps span all three parts.
    pub fn record(&self, step: &mut Recorder) {
        step.pass(Stage::Grid, Stamps::Start, |pass| {
            pass.over_balls(&self.count_cells);
        });
        step.encoder.copy_buffer_to_buffer(
            &self.cell_fill,
            0,
            &self.cell_start,
            0,
            4 * (self.cells + 1),
        );
        step.dispatches += self.scan.record(step.encoder);
        step.pass(Stage::Grid, Stamps::End, |pass| {
            pass.over_balls(&self.place_in_cells);
            pass.over(&self.sort_cells, self.cells);
        });
    }
}
