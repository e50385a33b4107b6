//! A run's state as bytes, to carry to another process or machine: the
//! world's state and its effects' (see [`rolypoly_physics::WorldState`]),
//! with whatever a front end keeps beside them. A run made there from the
//! same scene and seed takes the state on and steps on to the same bits.
//!
//! The bytes are a short header (what they are, the format, the version of
//! rolypoly that wrote them) and then the state in postcard's compact
//! encoding. Floating-point numbers travel as their bits. Bytes of another
//! format or another version are refused by name: another version may step
//! differently, and a state that only nearly steps on is of no use.

use rolypoly_fx::Effects;
use rolypoly_physics::{Event, StateError, WorldState};
use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};

use crate::simulation::Simulation;

/// What the bytes start with.
const MAGIC: &[u8; 18] = b"rolypoly snapshot\n";

/// The layout of what follows the header; raised when it changes.
const FORMAT: u32 = 1;

/// The version of rolypoly that writes and reads them.
const VERSION: &str = env!("CARGO_PKG_VERSION");

/// A simulation's state apart from its scene (see [`Simulation::state`]).
#[derive(Clone, Serialize, Deserialize)]
pub struct SimulationState {
    world: WorldState,
    fx: Effects,
    events: Vec<Event>,
}

impl std::fmt::Debug for SimulationState {
    /// The world's state; the particles are many and say little.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SimulationState")
            .field("world", &self.world)
            .field("particles", &self.fx.stats())
            .finish_non_exhaustive()
    }
}

/// Why bytes are not a snapshot this program can take on.
#[derive(Debug, thiserror::Error)]
pub enum SnapshotError {
    /// They are not a snapshot at all.
    #[error("these bytes are not a rolypoly snapshot")]
    NotASnapshot,
    /// A snapshot of another format or version.
    #[error(
        "this snapshot was written by rolypoly {version} (snapshot format {format}); this is \
         rolypoly {VERSION} (format {FORMAT}), which cannot promise to step it on to the same bits"
    )]
    Version {
        /// The version that wrote it.
        version: String,
        /// Its format.
        format: u32,
    },
    /// A snapshot cut short or damaged.
    #[error("this snapshot is damaged or cut short: {0}")]
    Damaged(String),
    /// A state that cannot be of the run's scene.
    #[error("this snapshot cannot be taken on: {0}")]
    State(#[from] StateError),
}

/// The header and then `value`'s postcard bytes.
pub fn encode<T: Serialize>(value: &T) -> Vec<u8> {
    let mut bytes = MAGIC.to_vec();
    bytes.extend_from_slice(&FORMAT.to_le_bytes());
    let version = VERSION.as_bytes();
    bytes.push(u8::try_from(version.len()).expect("a version is short"));
    bytes.extend_from_slice(version);
    // Writing into a vector cannot fail, and every state type serializes.
    postcard::to_extend(value, bytes).expect("a state serializes")
}

/// What [`encode`] wrote, if these bytes are of this format and version.
pub fn decode<T: DeserializeOwned>(bytes: &[u8]) -> Result<T, SnapshotError> {
    let rest = bytes
        .strip_prefix(MAGIC.as_slice())
        .ok_or(SnapshotError::NotASnapshot)?;
    let cut = || SnapshotError::Damaged("it ends inside its header".to_string());
    let (format, rest) = rest.split_first_chunk::<4>().ok_or_else(cut)?;
    let format = u32::from_le_bytes(*format);
    let (&length, rest) = rest.split_first().ok_or_else(cut)?;
    let (version, rest) = rest.split_at_checked(usize::from(length)).ok_or_else(cut)?;
    let version = String::from_utf8_lossy(version);
    if format != FORMAT || version != VERSION {
        return Err(SnapshotError::Version {
            version: version.into_owned(),
            format,
        });
    }
    let (value, left) =
        postcard::take_from_bytes(rest).map_err(|e| SnapshotError::Damaged(e.to_string()))?;
    if !left.is_empty() {
        return Err(SnapshotError::Damaged(format!(
            "{} bytes follow its end",
            left.len()
        )));
    }
    Ok(value)
}

impl Simulation {
    /// A copy of the state a simulation of the same scene and seed steps on
    /// from: the world's, the effects' and the last step's events. On the
    /// GPU engine the balls are the engine's to copy (the world holds none).
    pub fn state(&self) -> SimulationState {
        SimulationState {
            world: self.world.state(),
            fx: self.fx.clone(),
            events: self.last_events().to_vec(),
        }
    }

    /// Takes on `state`, from [`Simulation::state`] of a simulation of the
    /// same scene; refused, the simulation unchanged, where it cannot be.
    pub fn set_state(&mut self, state: SimulationState) -> Result<(), StateError> {
        let SimulationState { world, fx, events } = state;
        self.world.set_state(world)?;
        self.fx = fx;
        self.set_last_events(events);
        Ok(())
    }
}
