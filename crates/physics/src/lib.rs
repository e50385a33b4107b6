//! Deterministic rigid-body physics for the rolypoly toy room.
//!
//! A closed room, balls that bounce, roll and take on the colour of what they
//! hit, roly-poly tumblers that rock back upright and roll without slipping,
//! and a fireball that flies at constant speed. The crate knows nothing of
//! rendering or particles: it reports [`Event`]s that others consume.
//!
//! ```
//! use rolypoly_physics::{World, WorldConfig};
//! let mut world = World::new(WorldConfig::default(), 1).unwrap();
//! for _ in 0..120 {
//!     world.step();
//! }
//! let events = world.drain_events().count();
//! assert!(world.time() > 0.99 && events > 0);
//! ```

#![warn(missing_docs)]

mod balls;
mod broadphase;
mod ccd;
pub mod config;
mod contact;
mod events;
mod fireball;
mod impulses;
mod repose;
mod rng;
mod room;
mod sphere_impact;
mod threads;
mod tumbler;
mod world;

pub use balls::{Balls, Tint};
pub use config::*;
pub use events::{Event, EventKind};
pub use fireball::Fireball;
pub use impulses::BallImpulses;
pub use repose::angle_of_repose;
pub use rng::Rng;
pub use room::{Room, Surface};
pub use tumbler::{Grip, Tumbler, TumblerShape, axis_extent};
pub use world::{
    BallPick, BuildError, ContactKind, ContactProbe, Energy, Pick, Stage, StateError, StepTimes,
    World, WorldState, placement_problem,
};
