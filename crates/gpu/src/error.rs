//! Why the GPU engine could not start or step.

use thiserror::Error;

/// Why the GPU engine could not start or go on.
#[derive(Debug, Error)]
pub enum GpuError {
    /// No adapter at all.
    #[error(
        "the gpu engine found no graphics adapter (backends tried: {backends}); install a \
         Vulkan driver (on Debian or Ubuntu: `apt-get install libvulkan1 mesa-vulkan-drivers`) \
         or run with --engine cpu"
    )]
    NoAdapter {
        /// The backends tried, in words.
        backends: String,
    },
    /// An adapter without compute shaders (OpenGL ES 3.0, WebGL).
    #[error(
        "the gpu engine needs compute shaders, and the graphics adapter {adapter} has none; \
         run with --engine cpu, or choose another adapter with WGPU_BACKEND"
    )]
    NoCompute {
        /// The adapter, in words.
        adapter: String,
    },
    /// The adapter would not open a device.
    #[error(
        "the graphics adapter {adapter} refused to open a device for the gpu engine: {message}"
    )]
    NoDevice {
        /// The adapter, in words.
        adapter: String,
        /// What it said.
        message: String,
    },
    /// A limit of the device is too small for the engine itself, whatever
    /// the scene: no smaller scene runs on it.
    #[error(
        "the gpu engine needs {what} of {need}, and the graphics adapter {adapter} allows {have}, \
         whatever the scene; run with --engine cpu"
    )]
    EngineLimit {
        /// The adapter, in words.
        adapter: String,
        /// Which limit.
        what: &'static str,
        /// What the engine needs.
        need: u64,
        /// What the device allows.
        have: u64,
    },
    /// A limit of the device is too small for the scene's size.
    #[error(
        "the gpu engine needs {what} of {need} for this scene, and the graphics adapter {adapter} \
         allows {have}; use fewer balls, larger balls or a smaller room, or run with --engine cpu"
    )]
    Limit {
        /// The adapter, in words.
        adapter: String,
        /// Which limit.
        what: &'static str,
        /// What the scene needs.
        need: u64,
        /// What the device allows.
        have: u64,
    },
    /// The scene asks for something the GPU engine does not simulate.
    #[error("the gpu engine cannot run this scene: {0}; run it with --engine cpu")]
    Unsupported(String),
    /// Reading results back from the GPU failed.
    #[error("reading the balls back from the GPU failed: {0}")]
    Readback(String),
    /// A wait on the GPU ran out of time or failed.
    #[error(transparent)]
    Wait(#[from] crate::wait::WaitError),
    /// The scene's own balls could not be placed.
    #[error("{0}")]
    Build(String),
}
