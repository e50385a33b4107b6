//! The interactive window (I1-I7): mouse look and W/A/S/D, the fireball,
//! pause, grab-and-drag, re-initialising, the HUD and screenshots.

mod app;
mod fixed_steps;
mod fly_camera;
mod hud;
mod log;

pub use app::{WindowOptions, run};
