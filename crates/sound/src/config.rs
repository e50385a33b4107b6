//! A scene's sound settings (`sound.*`) and the constants that set how the
//! room sounds.

use crate::material::Material;

/// Samples per second of everything the sound makes.
pub const SAMPLE_RATE: u32 = 48_000;

/// What a scene says of its sound.
#[derive(Clone, Debug, PartialEq)]
pub struct SoundConfig {
    /// Whether the room sounds at all.
    pub enabled: bool,
    /// The master volume, a gain (1 is as calibrated).
    pub volume: f64,
    /// What the balls are made of.
    pub balls: Material,
    /// What the floor's boards are made of.
    pub floor: Material,
    /// What the walls and the ceiling are made of.
    pub walls: Material,
    /// What the tumblers' shells are made of.
    pub tumblers: Material,
}

impl Default for SoundConfig {
    fn default() -> SoundConfig {
        SoundConfig {
            enabled: true,
            volume: 1.0,
            balls: Material::Plastic,
            floor: Material::Wood,
            walls: Material::Plaster,
            tumblers: Material::Plastic,
        }
    }
}
