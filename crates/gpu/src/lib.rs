//! The rolypoly balls on the GPU: WGSL compute shaders through wgpu, on any
//! adapter with compute shaders (Vulkan, Metal, DX12; lavapipe in tests).
//!
//! A step, in the order it runs (each stage a module of `step/` with its
//! WGSL file beside it):
//! 1. **grid**: each ball's cell is counted, the counts are scanned
//!    (`scan`), the balls placed, and each cell's list sorted by ball
//!    number, so that every later pass walks the same lists in the same
//!    order whatever order the atomics landed in;
//! 2. **contacts**: each ball keeps its nearest balls within reach, the
//!    nearest tumbler sphere, the nearest walls; the fireball takes the
//!    balls it reaches, if the scene says so;
//! 3. **impacts**: rounds in which each ball meets the contact it touches
//!    first, if that contact's other side meets it first too, so impacts
//!    come in time order and a blow passes from ball to ball within the
//!    step; each round's bounces dispatched over the balls with a first
//!    contact, as many as the GPU counted;
//! 4. **solve**: Jacobi sweeps of impulses, normal and friction, with mass
//!    splitting, a thread a ball; both balls of a contact work it out
//!    alike, so there are no float atomics; the same sweeps shift the
//!    balls out of what is left of their overlaps, by position alone;
//! 5. **report**: the tumblers' pushes, summed in a fixed order;
//! 6. **flight**: balls a contact held move at their solved velocity,
//!    others along their exact parabola, bouncing exactly off the walls,
//!    each from where the solver shifted it; the same pass writes the
//!    renderer's ball instances.
//!
//! Stages 3 and 4 alternate between two copies of what they change, each
//! impact round (one dispatch) or solver dispatch (up to twelve sweeps
//! among each block of neighbouring balls) reading one and writing the
//! other. A world of up to 1024
//! balls runs each of those stages in one workgroup instead, with barriers
//! where a large world ends a dispatch: the same work, but that it passes
//! over the solver's last dispatches once they would change nothing,
//! within 1e-5 m/s.
//!
//! The same scene, seed and inputs give the same bits on rerun on the same
//! adapter and driver.

#![warn(missing_docs)]

mod bindings;
mod device;
mod engine;
mod error;
mod layout;
mod profile;
mod readback;
mod step;
mod wait;

pub use device::{Compute, best_adapter, check_compute, describe, limits};
pub use engine::{BallState, GpuBalls, GpuSnapshot, REPORT_DELAY, StepReport, THROW_ROOM};
pub use error::GpuError;
pub use profile::{STAGES, Stage};
pub use step::PassLayout;
pub use wait::{
    DEFAULT_GPU_TIMEOUT, GpuTimeout, WaitBound, WaitError, program_gpu_timeout,
    set_program_gpu_timeout,
};
