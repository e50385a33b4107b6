//! Impact sounds of the rolypoly toy room, synthesized from its physics
//! (FoleyAutomatic's modal synthesis, van den Doel, Kry and Pai 2001).
//!
//! Every body is a bank of damped modes: a ball a solid elastic sphere, the
//! floor and walls their boards, a tumbler a hollow shell with a bell
//! inside. Each impact the physics reports strikes both bodies with a
//! Hertz force pulse at its moment within the step; rolling rumbles, the
//! fireball roars. Heard in stereo from the camera, the crowd's quieter
//! voices merged into noise, limited so that no sample clips. The crate
//! reads the physics' events and state only: no window, no GPU, no audio
//! device.
//!
//! ```
//! use rolypoly_physics::{World, WorldConfig};
//! use rolypoly_sound::{Listener, SoundConfig, Soundtrack};
//! let mut world = World::new(WorldConfig::default(), 1).unwrap();
//! let mut sound = Soundtrack::new(&SoundConfig::default(), &world);
//! let ear = Listener { position: glam::DVec3::new(0.0, 1.6, 4.0), forward: -glam::DVec3::Z };
//! let mut events = Vec::new();
//! for _ in 0..120 {
//!     world.step();
//!     world.take_events(&mut events);
//!     sound.hear_step(&world, &events, &ear);
//! }
//! assert_eq!(sound.frames().len(), 48_000);
//! ```

#![warn(missing_docs)]

mod chime;
mod config;
mod hertz;
mod limiter;
mod listener;
mod material;
pub mod modes;
mod noise;
mod resonator;
mod roar;
mod rolling;
mod soundtrack;
mod voices;
mod wav;

pub use chime::CHIME_TILT;
pub use config::{SAMPLE_RATE, SoundConfig};
pub use hertz::Contact;
pub use limiter::CEILING;
pub use listener::{Listener, Placement, SPEED_OF_SOUND};
pub use material::{Material, Properties};
pub use soundtrack::Soundtrack;
pub use voices::MAX_VOICES;
pub use wav::{to_pcm, write_wav};
