//! Particle effects of the rolypoly fireball, in the style of a
//! "cyber-punk space collapse": a fading trail of cubes, a ring spreading in
//! a wall it hits, and the collapse and burst of a ball it hits (X1-X5).
//!
//! It reads the physics' events and the fireball's state, and knows nothing
//! of wgpu: the renderer draws what [`Effects`] and [`FireballLook`] say.

#![warn(missing_docs)]

mod config;
mod effects;
mod look;
mod particle;
mod ring;

pub use config::{BallHitConfig, EffectsConfig, TrailConfig, WallHitConfig};
pub use effects::{BallHit, Effects, EffectsStats, FLASH_SECONDS, Flash, WallHit};
pub use look::{CORE_COLOR, Core, FireballLook, HEART_COLOR, SHELL_COLORS, Shell};
pub use particle::{Particle, ParticleKind, WALL_HIT_PEAK};
pub use ring::{Full, ParticleRing};
