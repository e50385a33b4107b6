//! Every constant of the particle effects (a scene file's `[effects]`).

use serde::{Deserialize, Serialize};

/// The fireball's trail (X2): cubes dropped at random intervals along its path.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TrailConfig {
    /// A new cube comes after a random wait in this range (seconds).
    pub interval_min: f64,
    /// The longest wait (seconds).
    pub interval_max: f64,
    /// How long a cube lives (seconds).
    pub life: f64,
    /// Cube size at birth, as a share of the fireball's radius.
    pub size: f64,
}

/// The fireball hitting a wall (X3): a ring of cubes spreading in the wall.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct WallHitConfig {
    /// How long the event keeps spawning (seconds).
    pub duration: f64,
    /// Cubes spawned per second while it lasts.
    pub rate: f64,
    /// Radius the ring reaches at the end of the event (metres).
    pub radius: f64,
    /// How long a cube lives (seconds).
    pub life: f64,
    /// Cube size (metres) at its largest.
    pub size: f64,
}

/// The fireball hitting a ball (X4): cubes collapse onto the ball, then a burst.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct BallHitConfig {
    /// How long the event keeps spawning (seconds).
    pub duration: f64,
    /// Cubes spawned per second while it lasts.
    pub rate: f64,
    /// Radius of the shell the cubes start on at the beginning of the event
    /// (metres); it shrinks to nothing by the end.
    pub radius: f64,
    /// How long a cube lives (seconds).
    pub life: f64,
    /// Cube size (metres) at its largest.
    pub size: f64,
    /// The energy burst at the end: its life and largest size.
    pub burst_life: f64,
    /// The burst's largest size (metres).
    pub burst_size: f64,
}

/// Every constant of the particle effects.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct EffectsConfig {
    /// Particles alive at once, at most (X5); spawning beyond fails and is counted.
    pub capacity: usize,
    /// The fireball's trail.
    pub trail: TrailConfig,
    /// The fireball hitting a wall.
    pub wall_hit: WallHitConfig,
    /// The fireball hitting a ball.
    pub ball_hit: BallHitConfig,
}

impl Default for EffectsConfig {
    fn default() -> Self {
        EffectsConfig {
            capacity: 4096,
            trail: TrailConfig {
                interval_min: 0.005,
                interval_max: 0.03,
                life: 0.7,
                size: 0.6,
            },
            wall_hit: WallHitConfig {
                duration: 0.5,
                rate: 300.0,
                radius: 0.9,
                life: 0.45,
                size: 0.12,
            },
            ball_hit: BallHitConfig {
                duration: 0.7,
                rate: 200.0,
                radius: 0.6,
                life: 0.35,
                size: 0.08,
                burst_life: 0.4,
                burst_size: 0.5,
            },
        }
    }
}
