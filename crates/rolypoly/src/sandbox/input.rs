//! What a player does to the world, as data: each input the sandbox takes
//! is kept with the tick it came before, so that a run can be written out
//! and played again to the same bits (R, and `rolypoly replay`).

use glam::{DVec3, Vec3};
use rolypoly_physics::BuildError;
use serde::{Deserialize, Serialize};

use super::{THROW_SPEEDS, ThrowRefused};
use crate::scene::{Scene, SceneError};

/// One thing a player did that the simulation (or, for the camera, the
/// view) follows. Vectors are in metres and world axes.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Input {
    /// F: the fireball from `from` along `direction`.
    Fireball {
        /// Where it starts (m).
        from: [f64; 3],
        /// Which way it flies.
        direction: [f64; 3],
    },
    /// F again: the fireball gone.
    FireballOff,
    /// B: a ball thrown from `from` along `direction` at `speed` (m/s).
    Throw {
        /// Where the ball starts (m).
        from: [f64; 3],
        /// Which way it flies.
        direction: [f64; 3],
        /// How fast (m/s).
        speed: f64,
    },
    /// The left button on tumbler `tumbler` at `point`.
    Grab {
        /// The tumbler's number.
        tumbler: usize,
        /// The point held (m).
        point: [f64; 3],
    },
    /// The left button on ball `ball`: the hand holds it by its centre.
    GrabBall {
        /// The ball's number.
        ball: usize,
    },
    /// The held tumbler or ball pulled towards `to`.
    Drag {
        /// The point the hand pulls towards (m).
        to: [f64; 3],
    },
    /// The left button let go.
    Release,
    /// I.
    Restart,
    /// The panel's settings, as the text of a scene file.
    Settings {
        /// The scene file's text.
        scene: String,
    },
    /// Another scene chosen, as the text of its file.
    Load {
        /// Its name in the list.
        name: String,
        /// Its file's text.
        scene: String,
    },
    /// Where the camera is and looks: only the view follows it.
    Camera {
        /// Where it stands (m).
        position: [f32; 3],
        /// Radians about +y; 0 looks along -z.
        yaw: f32,
        /// Radians above the horizon.
        pitch: f32,
    },
}

/// Why an input changed nothing.
#[derive(Debug, thiserror::Error)]
pub enum Refused {
    /// Too many balls thrown.
    #[error(transparent)]
    Throw(#[from] ThrowRefused),
    /// A throw faster or slower than a player may throw (a recording
    /// edited by hand).
    #[error("a ball thrown at {0} m/s: allowed {lo} ..= {hi}", lo = THROW_SPEEDS.0, hi = THROW_SPEEDS.1)]
    Speed(f64),
    /// The scene could not be built.
    #[error("cannot build the scene: {0}")]
    Build(#[from] BuildError),
    /// The settings break the scene file's rules.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// The GPU engine could not take the balls.
    #[error(transparent)]
    Gpu(#[from] rolypoly_gpu::GpuError),
}

/// Where the camera is and looks.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraPose {
    /// Where it stands (m).
    pub position: Vec3,
    /// Radians about +y; 0 looks along -z.
    pub yaw: f32,
    /// Radians above the horizon.
    pub pitch: f32,
}

/// An input with the number of ticks done when it came.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Timed {
    /// Ticks done when it came.
    pub tick: u64,
    /// What it was.
    #[serde(flatten)]
    pub input: Input,
}

/// Everything since the world's line began (the sandbox made, or a scene
/// loaded): the scene it began from and the inputs since.
#[derive(Clone, Debug)]
pub struct Journal {
    /// The scene the line began from.
    pub scene: Scene,
    /// Its name.
    pub name: String,
    /// Every input since, in order.
    pub inputs: Vec<Timed>,
}

pub(super) fn array(v: DVec3) -> [f64; 3] {
    v.to_array()
}

pub(super) fn vector(a: [f64; 3]) -> DVec3 {
    DVec3::from_array(a)
}
