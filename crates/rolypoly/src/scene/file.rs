//! The partial schema: what a scene file may contain. Every key is
//! optional except inside list entries, where a half-given sphere or
//! placement makes no sense.

use rolypoly_physics::Rgb;
use serde::Deserialize;
use toml::Spanned;

pub(super) type Vec3 = [f64; 3];

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub(super) struct FileScene {
    pub(super) gravity: Option<Spanned<f64>>,
    pub(super) room: Option<FileRoom>,
    pub(super) light: Option<FileLight>,
    pub(super) balls: Option<FileBalls>,
    pub(super) tumblers: Option<FileTumblers>,
    pub(super) fireball: Option<FileFireball>,
    pub(super) grab: Option<FileGrab>,
    pub(super) solver: Option<FileSolver>,
    pub(super) effects: Option<FileEffects>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct FileRoom {
    pub(super) size: Option<Spanned<Vec3>>,
    pub(super) restitution: Option<Spanned<f64>>,
    pub(super) friction: Option<Spanned<f64>>,
    pub(super) rolling_resistance: Option<Spanned<f64>>,
    pub(super) colors: Option<FileRoomColors>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct FileRoomColors {
    pub(super) floor: Option<Spanned<Vec3>>,
    pub(super) ceiling: Option<Spanned<Vec3>>,
    pub(super) left: Option<Spanned<Vec3>>,
    pub(super) right: Option<Spanned<Vec3>>,
    pub(super) back: Option<Spanned<Vec3>>,
    pub(super) front: Option<Spanned<Vec3>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct FileLight {
    pub(super) color: Option<Spanned<Vec3>>,
    pub(super) intensity: Option<Spanned<f64>>,
    pub(super) ambient: Option<Spanned<f64>>,
    pub(super) bulb_radius: Option<Spanned<f64>>,
    pub(super) drop: Option<Spanned<f64>>,
    pub(super) bloom: Option<Spanned<bool>>,
    pub(super) bloom_strength: Option<Spanned<f64>>,
    pub(super) bloom_threshold: Option<Spanned<f64>>,
    pub(super) fireball_light: Option<Spanned<bool>>,
    pub(super) indirect: Option<Spanned<bool>>,
    pub(super) occlusion: Option<Spanned<bool>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct FileBalls {
    /// Signed so that a negative count is a range error, not a type error.
    pub(super) count: Option<Spanned<i64>>,
    pub(super) radius: Option<Spanned<f64>>,
    pub(super) mass: Option<Spanned<f64>>,
    pub(super) restitution: Option<Spanned<f64>>,
    pub(super) speed_min: Option<Spanned<f64>>,
    pub(super) speed_max: Option<Spanned<f64>>,
    pub(super) start_fill: Option<Spanned<f64>>,
    pub(super) color: Option<Spanned<Vec3>>,
    pub(super) placement: Option<Vec<FileBallPlacement>>,
}

/// One `[[balls.placement]]`: a position is required; a ball left without
/// a velocity starts at rest.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct FileBallPlacement {
    pub(super) position: Spanned<Vec3>,
    pub(super) velocity: Option<Spanned<Vec3>>,
    pub(super) spin: Option<Spanned<Vec3>>,
    pub(super) color: Option<Spanned<Vec3>>,
    pub(super) radius: Option<Spanned<f64>>,
    pub(super) mass: Option<Spanned<f64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct FileTumblers {
    pub(super) restitution: Option<Spanned<f64>>,
    pub(super) floor_friction: Option<Spanned<f64>>,
    pub(super) damping: Option<Spanned<f64>>,
    pub(super) colors: Option<Spanned<Vec<Spanned<Vec3>>>>,
    pub(super) spheres: Option<Spanned<Vec<FileSphere>>>,
    pub(super) placement: Option<Vec<FilePlacement>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct FileSphere {
    pub(super) height: Spanned<f64>,
    pub(super) radius: Spanned<f64>,
    pub(super) mass: Spanned<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct FilePlacement {
    pub(super) x: Spanned<f64>,
    pub(super) z: Spanned<f64>,
    pub(super) tilt_axis: Option<Spanned<Vec3>>,
    pub(super) tilt_deg: Option<Spanned<f64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct FileFireball {
    pub(super) radius: Option<Spanned<f64>>,
    pub(super) speed: Option<Spanned<f64>>,
    pub(super) spawn: Option<Spanned<Vec3>>,
    pub(super) direction: Option<Spanned<Vec3>>,
    pub(super) consumes_balls: Option<Spanned<bool>>,
    pub(super) starts_active: Option<Spanned<bool>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct FileGrab {
    pub(super) stiffness: Option<Spanned<f64>>,
    pub(super) damping: Option<Spanned<f64>>,
    pub(super) max_force: Option<Spanned<f64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct FileSolver {
    pub(super) dt: Option<Spanned<f64>>,
    /// Signed so that a negative count is a range error, not a type error.
    pub(super) iterations: Option<Spanned<i64>>,
    pub(super) bounce_threshold: Option<Spanned<f64>>,
    pub(super) event_threshold: Option<Spanned<f64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct FileEffects {
    /// Signed so that a negative count is a range error, not a type error.
    pub(super) capacity: Option<Spanned<i64>>,
    pub(super) trail: Option<FileTrail>,
    pub(super) wall_hit: Option<FileWallHit>,
    pub(super) ball_hit: Option<FileBallHit>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct FileTrail {
    pub(super) interval_min: Option<Spanned<f64>>,
    pub(super) interval_max: Option<Spanned<f64>>,
    pub(super) life: Option<Spanned<f64>>,
    pub(super) size: Option<Spanned<f64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct FileWallHit {
    pub(super) duration: Option<Spanned<f64>>,
    pub(super) rate: Option<Spanned<f64>>,
    pub(super) radius: Option<Spanned<f64>>,
    pub(super) life: Option<Spanned<f64>>,
    pub(super) size: Option<Spanned<f64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct FileBallHit {
    pub(super) duration: Option<Spanned<f64>>,
    pub(super) rate: Option<Spanned<f64>>,
    pub(super) radius: Option<Spanned<f64>>,
    pub(super) life: Option<Spanned<f64>>,
    pub(super) size: Option<Spanned<f64>>,
    pub(super) burst_life: Option<Spanned<f64>>,
    pub(super) burst_size: Option<Spanned<f64>>,
}

pub(super) fn rgb(c: Vec3) -> Rgb {
    c.map(|x| x as f32)
}
