//! The interactive window (I1-I7): mouse look and W/A/S/D, the fireball,
//! pause and single steps, grab-and-drag, thrown balls, re-initialising,
//! the sandbox panel, the HUD and screenshots.

mod app;
pub(crate) mod fly_camera;
mod frame_rate;
mod hud;
mod log;
mod orbit_camera;
mod panel;
pub mod plots;
mod profiler;
mod quality;
mod shader_watch;
mod sound;

pub use app::{WindowOptions, run};
