//! The truth the real-time light is measured against: the same scene at
//! the same moment, path-traced on the CPU's threads.
//!
//! The room, balls and tumblers are the real-time frame's, with the same
//! albedo and the same highlights made energy-conserving lobes; the bulb
//! is a small sphere light of the same power. Light is gathered by next-
//! event estimation to the lights and by sampling each surface's
//! reflection, the two joined by multiple importance sampling; Russian
//! roulette ends paths without bias. Each pixel's samples come from a
//! stream of its own, so a picture depends on its sample count and seed,
//! never on the thread count.
//!
//! [`compare`] scores a real-time frame against the reference with FLIP.

#![warn(missing_docs)]

mod albedo;
mod bvh;
mod compare;
mod geometry;
mod hdr;
mod light;
mod material;
mod render;
mod sampler;
mod scene;
mod tonemap;
mod trace;

pub use compare::{Comparison, FLIP_PIXELS_PER_DEGREE, compare, ssim};
pub use geometry::Ray;
pub use hdr::write_exr;
pub use light::SphereLight;
pub use material::{Albedo, Material};
pub use render::{Radiance, render, threads};
pub use sampler::Sampler;
pub use scene::{Mesh, Scene, SceneError};
pub use tonemap::{aces, to_picture};
pub use trace::radiance;
