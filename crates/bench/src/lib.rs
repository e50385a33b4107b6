//! The same ball pit in the rolypoly engine and in Rapier, and the figures
//! that compare them: speed, and how well each keeps the balls apart, inside
//! the box and at rest. `cargo bench -p rolypoly-bench --bench
//! versus_rapier` prints the table.

#![warn(missing_docs)]

pub mod figures;
pub mod gpu_pit;
pub mod ours;
pub mod pit;
pub mod quality;
pub mod rapier_pit;
