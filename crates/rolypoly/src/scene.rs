//! Scene files (SPEC S6, A4): the built-in default scene overridden by a
//! user's TOML file, then range-checked.
//!
//! A scene is the physics ([`WorldConfig`]), the particle effects
//! ([`EffectsConfig`], the file's `[effects]`) and the ceiling light
//! ([`LightConfig`], the file's `[light]`). A file may set any subset of
//! keys; everything it leaves out keeps the value of [`WorldConfig::default`],
//! [`EffectsConfig::default`] or [`LightConfig::default`]. The file is parsed
//! into a partial schema whose tables all reject unknown keys, so a typo is an
//! error instead of a silently ignored setting. Every value read from the file keeps its source
//! span, so a range error can point at the line where the value was written.

use std::collections::HashMap;
use std::fmt;
use std::ops::Range;
use std::path::Path;

use glam::DVec3;
use rolypoly_fx::EffectsConfig;
use rolypoly_physics::{Rgb, SphereSpec, TumblerPlacement, WorldConfig};
use rolypoly_render::LightConfig;
use serde::Deserialize;
use toml::Spanned;

/// Where the configuration comes from when no scene file is given.
pub const BUILTIN_ORIGIN: &str = "built-in default scene";

/// Largest number of balls a scene may ask for.
pub const MAX_BALLS: usize = 1_000_000;

/// The number of spheres in a tumbler's compound shape (SPEC P6).
pub const TUMBLER_SPHERES: usize = 6;

/// Smallest and largest particle capacity a scene may ask for.
pub const PARTICLE_CAPACITY: (usize, usize) = (16, 1_000_000);

/// Names of the room's surfaces, in the order of `RoomConfig::colors`.
const SURFACE_NAMES: [&str; 6] = ["floor", "ceiling", "left", "right", "back", "front"];

/// Where a value came from: a file (with the line, when known) or a
/// command-line option.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Location {
    pub origin: String,
    pub line: Option<usize>,
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.line {
            Some(line) => write!(f, "{}:{line}", self.origin),
            None => f.write_str(&self.origin),
        }
    }
}

/// Why a scene could not be loaded. Every variant names where the problem is.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// The file could not be read (missing, a directory, no permission...).
    #[error("cannot read scene file `{path}`")]
    Read {
        path: String,
        #[source]
        source: std::io::Error,
    },
    /// Malformed TOML, an unknown key or a value of the wrong type.
    #[error("{at}: {message}")]
    Syntax { at: Location, message: String },
    /// A value outside the range the simulation can handle.
    #[error("{at}: {key} = {value} is out of range: allowed {allowed}")]
    OutOfRange {
        at: Location,
        key: String,
        value: String,
        allowed: String,
    },
    /// A structural rule that is not a numeric range (list lengths and such).
    #[error("{at}: {key}: {problem}")]
    Invalid {
        at: Location,
        key: String,
        problem: String,
    },
}

/// A loaded scene: the physics, the particle effects and the light.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Scene {
    pub world: WorldConfig,
    pub effects: EffectsConfig,
    pub light: LightConfig,
}

/// Settings given on the command line; they win over the scene file and are
/// range-checked with the same rules.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Overrides {
    /// `balls.count`, from `--balls`.
    pub balls: Option<usize>,
    /// `gravity`, from `--gravity`.
    pub gravity: Option<f64>,
}

/// Loads the scene at `path` over the default scene, or the default scene
/// itself when `path` is `None`, and checks every value.
pub fn load_scene(path: Option<&Path>) -> Result<Scene, SceneError> {
    load_scene_with(path, &Overrides::default())
}

/// [`load_scene`], then applies command-line overrides and checks the result.
pub fn load_scene_with(path: Option<&Path>, overrides: &Overrides) -> Result<Scene, SceneError> {
    match path {
        None => build(None, BUILTIN_ORIGIN, overrides),
        Some(path) => {
            let origin = path.display().to_string();
            let source = std::fs::read_to_string(path).map_err(|source| SceneError::Read {
                path: origin.clone(),
                source,
            })?;
            build(Some(&source), &origin, overrides)
        }
    }
}

/// Parses scene text over the default scene and checks every value;
/// `origin` names the text in error messages (usually the file name).
pub fn parse_scene(source: &str, origin: &str) -> Result<Scene, SceneError> {
    parse_scene_with(source, origin, &Overrides::default())
}

/// [`parse_scene`], then applies command-line overrides and checks the result.
pub fn parse_scene_with(
    source: &str,
    origin: &str,
    overrides: &Overrides,
) -> Result<Scene, SceneError> {
    build(Some(source), origin, overrides)
}

/// Checks a scene that did not come from a file (for instance one edited at
/// run time) against the same rules as a scene file.
pub fn validate(scene: &Scene) -> Result<(), SceneError> {
    let sources = Sources {
        origin: BUILTIN_ORIGIN.to_owned(),
        from_file: false,
        lines: HashMap::new(),
        options: HashMap::new(),
    };
    Checker {
        scene,
        sources: &sources,
    }
    .check()
}

fn build(source: Option<&str>, origin: &str, overrides: &Overrides) -> Result<Scene, SceneError> {
    let mut scene = Scene::default();
    let mut sources = Sources {
        origin: origin.to_owned(),
        from_file: source.is_some(),
        lines: HashMap::new(),
        options: HashMap::new(),
    };
    if let Some(source) = source {
        let file: FileScene =
            toml::from_str(source).map_err(|e| syntax_error(&e, source, origin))?;
        let mut overlay = Overlay {
            source,
            origin,
            lines: HashMap::new(),
        };
        overlay.apply(file, &mut scene)?;
        sources.lines = overlay.lines;
    }
    if let Some(count) = overrides.balls {
        scene.world.balls.count = count;
        sources
            .options
            .insert("balls.count".into(), "--balls".into());
    }
    if let Some(gravity) = overrides.gravity {
        scene.world.gravity = gravity;
        sources.options.insert("gravity".into(), "--gravity".into());
    }
    Checker {
        scene: &scene,
        sources: &sources,
    }
    .check()?;
    Ok(scene)
}

/// 1-based line of a byte offset.
fn line_of(source: &str, offset: usize) -> usize {
    let end = offset.min(source.len());
    source.as_bytes()[..end]
        .iter()
        .filter(|&&b| b == b'\n')
        .count()
        + 1
}

fn syntax_error(error: &toml::de::Error, source: &str, origin: &str) -> SceneError {
    let line = error.span().map(|span| line_of(source, span.start));
    // toml's messages are one line per fact; keep them on one line.
    let message = error
        .message()
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect::<Vec<_>>()
        .join("; ")
        .replacen("unknown field", "unknown key", 1)
        .replacen("missing field", "missing key", 1);
    SceneError::Syntax {
        at: Location {
            origin: origin.to_owned(),
            line,
        },
        message: qualify_unknown_key(message, source, line),
    }
}

/// Turns "unknown key `colour`" into "unknown key `balls.colour`" when the
/// offending line is a plain `key = value` under a table header, so the
/// user sees the full path of what was not understood.
fn qualify_unknown_key(message: String, source: &str, line: Option<usize>) -> String {
    let Some(rest) = message.strip_prefix("unknown key `") else {
        return message;
    };
    let Some((key, tail)) = rest.split_once('`') else {
        return message;
    };
    match line.and_then(|line| table_of_key(source, line, key)) {
        Some(table) if !table.is_empty() => format!("unknown key `{table}.{key}`{tail}"),
        _ => message,
    }
}

/// The table header in effect for `key = ...` on 1-based `line`, or `None`
/// when that line is not such an assignment. An empty string is the top level.
fn table_of_key(source: &str, line: usize, key: &str) -> Option<String> {
    let lines: Vec<&str> = source.lines().collect();
    let text = lines.get(line.checked_sub(1)?)?.trim_start();
    if !text.strip_prefix(key)?.trim_start().starts_with('=') {
        return None;
    }
    let header = lines[..line - 1].iter().rev().find_map(|l| table_header(l));
    Some(header.unwrap_or_default())
}

/// The dotted name of a `[table]` or `[[array]]` header line.
fn table_header(line: &str) -> Option<String> {
    let line = line.split('#').next()?.trim();
    let inner = line
        .strip_prefix("[[")
        .and_then(|l| l.strip_suffix("]]"))
        .or_else(|| line.strip_prefix('[').and_then(|l| l.strip_suffix(']')))?
        .trim();
    // Rejects lines of a multi-line array such as `[0.1, 0.2, 0.3],`.
    let is_name = inner.starts_with(|c: char| c.is_ascii_alphabetic() || c == '"' || c == '\'')
        && inner
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '.' | ' ' | '"' | '\''));
    is_name.then(|| {
        inner
            .split('.')
            .map(str::trim)
            .collect::<Vec<_>>()
            .join(".")
    })
}

// ---------------------------------------------------------------------------
// The partial schema: what a file may contain. Every key is optional except
// inside list entries, where a half-given sphere or placement makes no sense.

type Vec3 = [f64; 3];

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct FileScene {
    gravity: Option<Spanned<f64>>,
    room: Option<FileRoom>,
    light: Option<FileLight>,
    balls: Option<FileBalls>,
    tumblers: Option<FileTumblers>,
    fireball: Option<FileFireball>,
    grab: Option<FileGrab>,
    solver: Option<FileSolver>,
    effects: Option<FileEffects>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FileRoom {
    size: Option<Spanned<Vec3>>,
    restitution: Option<Spanned<f64>>,
    friction: Option<Spanned<f64>>,
    rolling_resistance: Option<Spanned<f64>>,
    colors: Option<FileRoomColors>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FileRoomColors {
    floor: Option<Spanned<Vec3>>,
    ceiling: Option<Spanned<Vec3>>,
    left: Option<Spanned<Vec3>>,
    right: Option<Spanned<Vec3>>,
    back: Option<Spanned<Vec3>>,
    front: Option<Spanned<Vec3>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FileLight {
    color: Option<Spanned<Vec3>>,
    intensity: Option<Spanned<f64>>,
    ambient: Option<Spanned<f64>>,
    bulb_radius: Option<Spanned<f64>>,
    drop: Option<Spanned<f64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FileBalls {
    /// Signed so that a negative count is a range error, not a type error.
    count: Option<Spanned<i64>>,
    radius: Option<Spanned<f64>>,
    mass: Option<Spanned<f64>>,
    restitution: Option<Spanned<f64>>,
    speed_min: Option<Spanned<f64>>,
    speed_max: Option<Spanned<f64>>,
    start_fill: Option<Spanned<f64>>,
    color: Option<Spanned<Vec3>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FileTumblers {
    restitution: Option<Spanned<f64>>,
    floor_friction: Option<Spanned<f64>>,
    damping: Option<Spanned<f64>>,
    colors: Option<Spanned<Vec<Spanned<Vec3>>>>,
    spheres: Option<Spanned<Vec<FileSphere>>>,
    placement: Option<Vec<FilePlacement>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FileSphere {
    height: Spanned<f64>,
    radius: Spanned<f64>,
    mass: Spanned<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FilePlacement {
    x: Spanned<f64>,
    z: Spanned<f64>,
    tilt_axis: Option<Spanned<Vec3>>,
    tilt_deg: Option<Spanned<f64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FileFireball {
    radius: Option<Spanned<f64>>,
    speed: Option<Spanned<f64>>,
    spawn: Option<Spanned<Vec3>>,
    direction: Option<Spanned<Vec3>>,
    consumes_balls: Option<Spanned<bool>>,
    starts_active: Option<Spanned<bool>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FileGrab {
    stiffness: Option<Spanned<f64>>,
    damping: Option<Spanned<f64>>,
    max_force: Option<Spanned<f64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FileSolver {
    dt: Option<Spanned<f64>>,
    /// Signed so that a negative count is a range error, not a type error.
    iterations: Option<Spanned<i64>>,
    bounce_threshold: Option<Spanned<f64>>,
    event_threshold: Option<Spanned<f64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FileEffects {
    /// Signed so that a negative count is a range error, not a type error.
    capacity: Option<Spanned<i64>>,
    trail: Option<FileTrail>,
    wall_hit: Option<FileWallHit>,
    ball_hit: Option<FileBallHit>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FileTrail {
    interval_min: Option<Spanned<f64>>,
    interval_max: Option<Spanned<f64>>,
    life: Option<Spanned<f64>>,
    size: Option<Spanned<f64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FileWallHit {
    duration: Option<Spanned<f64>>,
    rate: Option<Spanned<f64>>,
    radius: Option<Spanned<f64>>,
    life: Option<Spanned<f64>>,
    size: Option<Spanned<f64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FileBallHit {
    duration: Option<Spanned<f64>>,
    rate: Option<Spanned<f64>>,
    radius: Option<Spanned<f64>>,
    life: Option<Spanned<f64>>,
    size: Option<Spanned<f64>>,
    burst_life: Option<Spanned<f64>>,
    burst_size: Option<Spanned<f64>>,
}

fn rgb(c: Vec3) -> Rgb {
    c.map(|x| x as f32)
}

// ---------------------------------------------------------------------------
// Overlay: copies what the file gives onto the default, remembering the line
// of every key it sets.

struct Overlay<'a> {
    source: &'a str,
    origin: &'a str,
    lines: HashMap<String, usize>,
}

impl Overlay<'_> {
    fn note(&mut self, key: &str, span: Range<usize>) {
        self.lines
            .insert(key.to_owned(), line_of(self.source, span.start));
    }

    /// Copies `value` into `dst` (converted) and records its line.
    fn set<T, U>(
        &mut self,
        key: &str,
        dst: &mut U,
        value: Option<Spanned<T>>,
        convert: impl FnOnce(T) -> U,
    ) {
        if let Some(value) = value {
            self.note(key, value.span());
            *dst = convert(value.into_inner());
        }
    }

    /// Integer keys are read signed; a value that does not fit `usize` is
    /// reported here because it cannot be stored for the later check.
    fn set_count(
        &mut self,
        key: &str,
        dst: &mut usize,
        value: Option<Spanned<i64>>,
        range: (usize, usize),
    ) -> Result<(), SceneError> {
        let Some(value) = value else { return Ok(()) };
        let span = value.span();
        let raw = value.into_inner();
        self.note(key, span.clone());
        match usize::try_from(raw) {
            Ok(n) => {
                *dst = n;
                Ok(())
            }
            Err(_) => Err(SceneError::OutOfRange {
                at: Location {
                    origin: self.origin.to_owned(),
                    line: Some(line_of(self.source, span.start)),
                },
                key: key.to_owned(),
                value: raw.to_string(),
                allowed: format!("{} ..= {}", range.0, range.1),
            }),
        }
    }

    fn apply(&mut self, file: FileScene, scene: &mut Scene) -> Result<(), SceneError> {
        let c = &mut scene.world;
        self.set("gravity", &mut c.gravity, file.gravity, |v| v);

        if let Some(room) = file.room {
            self.set("room.size", &mut c.room.size, room.size, DVec3::from_array);
            self.set(
                "room.restitution",
                &mut c.room.restitution,
                room.restitution,
                |v| v,
            );
            self.set("room.friction", &mut c.room.friction, room.friction, |v| v);
            self.set(
                "room.rolling_resistance",
                &mut c.room.rolling_resistance,
                room.rolling_resistance,
                |v| v,
            );
            if let Some(colors) = room.colors {
                let given = [
                    colors.floor,
                    colors.ceiling,
                    colors.left,
                    colors.right,
                    colors.back,
                    colors.front,
                ];
                for ((name, dst), value) in SURFACE_NAMES.iter().zip(&mut c.room.colors).zip(given)
                {
                    self.set(&format!("room.colors.{name}"), dst, value, rgb);
                }
            }
        }

        if let Some(light) = file.light {
            self.apply_light(light, &mut scene.light);
        }

        if let Some(balls) = file.balls {
            self.set_count(
                "balls.count",
                &mut c.balls.count,
                balls.count,
                (0, MAX_BALLS),
            )?;
            self.set("balls.radius", &mut c.balls.radius, balls.radius, |v| v);
            self.set("balls.mass", &mut c.balls.mass, balls.mass, |v| v);
            self.set(
                "balls.restitution",
                &mut c.balls.restitution,
                balls.restitution,
                |v| v,
            );
            self.set(
                "balls.speed_min",
                &mut c.balls.speed_min,
                balls.speed_min,
                |v| v,
            );
            self.set(
                "balls.speed_max",
                &mut c.balls.speed_max,
                balls.speed_max,
                |v| v,
            );
            self.set(
                "balls.start_fill",
                &mut c.balls.start_fill,
                balls.start_fill,
                |v| v,
            );
            self.set("balls.color", &mut c.balls.color, balls.color, rgb);
        }

        if let Some(t) = file.tumblers {
            let dst = &mut c.tumblers;
            self.set(
                "tumblers.restitution",
                &mut dst.restitution,
                t.restitution,
                |v| v,
            );
            self.set(
                "tumblers.floor_friction",
                &mut dst.floor_friction,
                t.floor_friction,
                |v| v,
            );
            self.set("tumblers.damping", &mut dst.damping, t.damping, |v| v);
            if let Some(colors) = t.colors {
                self.note("tumblers.colors", colors.span());
                dst.colors = colors
                    .into_inner()
                    .into_iter()
                    .enumerate()
                    .map(|(i, color)| {
                        self.note(&format!("tumblers.colors[{i}]"), color.span());
                        rgb(color.into_inner())
                    })
                    .collect();
            }
            if let Some(spheres) = t.spheres {
                self.note("tumblers.spheres", spheres.span());
                dst.spheres = spheres
                    .into_inner()
                    .into_iter()
                    .enumerate()
                    .map(|(i, s)| {
                        let key = format!("tumblers.spheres[{i}]");
                        self.note(&key, s.height.span());
                        self.note(&format!("{key}.height"), s.height.span());
                        self.note(&format!("{key}.radius"), s.radius.span());
                        self.note(&format!("{key}.mass"), s.mass.span());
                        SphereSpec {
                            height: s.height.into_inner(),
                            radius: s.radius.into_inner(),
                            mass: s.mass.into_inner(),
                        }
                    })
                    .collect();
            }
            if let Some(placements) = t.placement {
                dst.placements = placements
                    .into_iter()
                    .enumerate()
                    .map(|(i, p)| {
                        let key = format!("tumblers.placement[{i}]");
                        self.note(&key, p.x.span());
                        let mut placement = TumblerPlacement {
                            x: 0.0,
                            z: 0.0,
                            tilt_axis: DVec3::X,
                            tilt_deg: 0.0,
                        };
                        self.set(&format!("{key}.x"), &mut placement.x, Some(p.x), |v| v);
                        self.set(&format!("{key}.z"), &mut placement.z, Some(p.z), |v| v);
                        self.set(
                            &format!("{key}.tilt_axis"),
                            &mut placement.tilt_axis,
                            p.tilt_axis,
                            DVec3::from_array,
                        );
                        self.set(
                            &format!("{key}.tilt_deg"),
                            &mut placement.tilt_deg,
                            p.tilt_deg,
                            |v| v,
                        );
                        placement
                    })
                    .collect();
            }
        }

        if let Some(f) = file.fireball {
            let dst = &mut c.fireball;
            self.set("fireball.radius", &mut dst.radius, f.radius, |v| v);
            self.set("fireball.speed", &mut dst.speed, f.speed, |v| v);
            self.set("fireball.spawn", &mut dst.spawn, f.spawn, DVec3::from_array);
            self.set(
                "fireball.direction",
                &mut dst.direction,
                f.direction,
                DVec3::from_array,
            );
            self.set(
                "fireball.consumes_balls",
                &mut dst.consumes_balls,
                f.consumes_balls,
                |v| v,
            );
            self.set(
                "fireball.starts_active",
                &mut dst.starts_active,
                f.starts_active,
                |v| v,
            );
        }

        if let Some(g) = file.grab {
            self.set("grab.stiffness", &mut c.grab.stiffness, g.stiffness, |v| v);
            self.set("grab.damping", &mut c.grab.damping, g.damping, |v| v);
            self.set("grab.max_force", &mut c.grab.max_force, g.max_force, |v| v);
        }

        if let Some(s) = file.solver {
            self.set("solver.dt", &mut c.solver.dt, s.dt, |v| v);
            self.set_count(
                "solver.iterations",
                &mut c.solver.iterations,
                s.iterations,
                ITERATIONS,
            )?;
            self.set(
                "solver.bounce_threshold",
                &mut c.solver.bounce_threshold,
                s.bounce_threshold,
                |v| v,
            );
            self.set(
                "solver.event_threshold",
                &mut c.solver.event_threshold,
                s.event_threshold,
                |v| v,
            );
        }

        if let Some(e) = file.effects {
            self.apply_effects(e, &mut scene.effects)?;
        }
        Ok(())
    }

    fn apply_light(&mut self, l: FileLight, c: &mut LightConfig) {
        self.set("light.color", &mut c.color, l.color, rgb);
        self.set("light.intensity", &mut c.intensity, l.intensity, |v| {
            v as f32
        });
        self.set("light.ambient", &mut c.ambient, l.ambient, |v| v as f32);
        self.set(
            "light.bulb_radius",
            &mut c.bulb_radius,
            l.bulb_radius,
            |v| v as f32,
        );
        self.set("light.drop", &mut c.drop, l.drop, |v| v as f32);
    }

    fn apply_effects(&mut self, e: FileEffects, c: &mut EffectsConfig) -> Result<(), SceneError> {
        self.set_count(
            "effects.capacity",
            &mut c.capacity,
            e.capacity,
            PARTICLE_CAPACITY,
        )?;

        if let Some(t) = e.trail {
            let dst = &mut c.trail;
            self.set(
                "effects.trail.interval_min",
                &mut dst.interval_min,
                t.interval_min,
                |v| v,
            );
            self.set(
                "effects.trail.interval_max",
                &mut dst.interval_max,
                t.interval_max,
                |v| v,
            );
            self.set("effects.trail.life", &mut dst.life, t.life, |v| v);
            self.set("effects.trail.size", &mut dst.size, t.size, |v| v);
        }

        if let Some(w) = e.wall_hit {
            let dst = &mut c.wall_hit;
            self.set(
                "effects.wall_hit.duration",
                &mut dst.duration,
                w.duration,
                |v| v,
            );
            self.set("effects.wall_hit.rate", &mut dst.rate, w.rate, |v| v);
            self.set("effects.wall_hit.radius", &mut dst.radius, w.radius, |v| v);
            self.set("effects.wall_hit.life", &mut dst.life, w.life, |v| v);
            self.set("effects.wall_hit.size", &mut dst.size, w.size, |v| v);
        }

        if let Some(b) = e.ball_hit {
            let dst = &mut c.ball_hit;
            self.set(
                "effects.ball_hit.duration",
                &mut dst.duration,
                b.duration,
                |v| v,
            );
            self.set("effects.ball_hit.rate", &mut dst.rate, b.rate, |v| v);
            self.set("effects.ball_hit.radius", &mut dst.radius, b.radius, |v| v);
            self.set("effects.ball_hit.life", &mut dst.life, b.life, |v| v);
            self.set("effects.ball_hit.size", &mut dst.size, b.size, |v| v);
            self.set(
                "effects.ball_hit.burst_life",
                &mut dst.burst_life,
                b.burst_life,
                |v| v,
            );
            self.set(
                "effects.ball_hit.burst_size",
                &mut dst.burst_size,
                b.burst_size,
                |v| v,
            );
        }
        Ok(())
    }
}

// ---------------------------------------------------------------------------
// Range checks on the merged configuration.

const ITERATIONS: (usize, usize) = (1, 256);
const MAX_MASS: f64 = 1e6;
const MAX_SPEED: f64 = 100.0;
const MAX_FRICTION: f64 = 5.0;
/// Longest effect time (seconds) and largest effect radius or size (metres).
const MAX_EFFECT: f64 = 10.0;
/// Most particles an effect may spawn per second.
const MAX_RATE: f64 = 100_000.0;
/// Largest light intensity.
const MAX_INTENSITY: f64 = 100.0;
/// Largest radius (metres) of the light's bulb.
const MAX_BULB_RADIUS: f64 = 1.0;

/// One end of an allowed interval.
#[derive(Clone, Copy)]
enum End {
    Incl(f64),
    Excl(f64),
}

/// An allowed interval, written the way error messages show it.
#[derive(Clone, Copy)]
struct Bounds {
    lo: End,
    hi: End,
}

impl Bounds {
    const fn closed(lo: f64, hi: f64) -> Self {
        Bounds {
            lo: End::Incl(lo),
            hi: End::Incl(hi),
        }
    }

    /// `lo < v <= hi`: for quantities that must be positive.
    const fn positive(hi: f64) -> Self {
        Bounds {
            lo: End::Excl(0.0),
            hi: End::Incl(hi),
        }
    }

    /// `0 < v < hi`.
    const fn open(hi: f64) -> Self {
        Bounds {
            lo: End::Excl(0.0),
            hi: End::Excl(hi),
        }
    }

    /// False for NaN, so a `nan` in a file is always rejected.
    fn contains(self, v: f64) -> bool {
        let above = match self.lo {
            End::Incl(lo) => v >= lo,
            End::Excl(lo) => v > lo,
        };
        let below = match self.hi {
            End::Incl(hi) => v <= hi,
            End::Excl(hi) => v < hi,
        };
        above && below
    }
}

impl fmt::Display for Bounds {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match (self.lo, self.hi) {
            (End::Incl(lo), End::Incl(hi)) => write!(f, "{lo} ..= {hi}"),
            (End::Incl(lo), End::Excl(hi)) => write!(f, ">= {lo} and < {hi}"),
            (End::Excl(lo), End::Incl(hi)) => write!(f, "> {lo} and <= {hi}"),
            (End::Excl(lo), End::Excl(hi)) => write!(f, "> {lo} and < {hi}"),
        }
    }
}

/// Where each key of the merged configuration was set.
struct Sources {
    origin: String,
    from_file: bool,
    /// Key path -> line in the file.
    lines: HashMap<String, usize>,
    /// Key path -> the command-line option that set it.
    options: HashMap<String, String>,
}

impl Sources {
    /// The location to blame for `key`, and whether the value is a default
    /// the file did not mention.
    fn locate(&self, key: &str) -> (Location, bool) {
        if let Some(option) = self.options.get(key) {
            let at = Location {
                origin: format!("command-line option {option}"),
                line: None,
            };
            return (at, false);
        }
        let line = self.lines.get(key).copied();
        let at = Location {
            origin: self.origin.clone(),
            line,
        };
        (at, line.is_none() && self.from_file)
    }
}

fn vec3_text(v: DVec3) -> String {
    format!("[{}, {}, {}]", v.x, v.y, v.z)
}

fn rgb_text(c: Rgb) -> String {
    format!("[{}, {}, {}]", c[0], c[1], c[2])
}

/// The `f64` with the same shortest decimal form as `v`: 0.09 rather than
/// 0.09000000357627869, so that messages and bounds derived from `f32` keys
/// show the numbers as they were written.
fn widen(v: f32) -> f64 {
    v.to_string().parse().unwrap_or(f64::from(v))
}

struct Checker<'a> {
    scene: &'a Scene,
    sources: &'a Sources,
}

impl Checker<'_> {
    fn out_of_range(&self, key: &str, value: String, allowed: String) -> SceneError {
        let (at, default) = self.sources.locate(key);
        let value = if default {
            format!("{value} (built-in default)")
        } else {
            value
        };
        SceneError::OutOfRange {
            at,
            key: key.to_owned(),
            value,
            allowed,
        }
    }

    fn invalid(&self, key: &str, problem: String) -> SceneError {
        SceneError::Invalid {
            at: self.sources.locate(key).0,
            key: key.to_owned(),
            problem,
        }
    }

    fn real(&self, key: &str, v: f64, bounds: Bounds) -> Result<(), SceneError> {
        self.real_why(key, v, bounds, "")
    }

    /// Like [`Self::real`], with a note that explains a derived bound.
    fn real_why(&self, key: &str, v: f64, bounds: Bounds, why: &str) -> Result<(), SceneError> {
        if bounds.contains(v) {
            return Ok(());
        }
        let allowed = if why.is_empty() {
            bounds.to_string()
        } else {
            format!("{bounds} ({why})")
        };
        Err(self.out_of_range(key, v.to_string(), allowed))
    }

    /// [`Self::real_why`] for an `f32` key.
    fn real32(&self, key: &str, v: f32, bounds: Bounds, why: &str) -> Result<(), SceneError> {
        self.real_why(key, widen(v), bounds, why)
    }

    fn count(&self, key: &str, v: usize, (lo, hi): (usize, usize)) -> Result<(), SceneError> {
        if (lo..=hi).contains(&v) {
            Ok(())
        } else {
            Err(self.out_of_range(key, v.to_string(), format!("{lo} ..= {hi}")))
        }
    }

    fn color(&self, key: &str, c: Rgb) -> Result<(), SceneError> {
        if c.iter().all(|&x| (0.0..=1.0).contains(&x)) {
            Ok(())
        } else {
            Err(self.out_of_range(key, rgb_text(c), "each component 0 ..= 1".into()))
        }
    }

    fn direction(&self, key: &str, v: DVec3) -> Result<(), SceneError> {
        if v.is_finite() && v.length_squared() > 1e-18 {
            Ok(())
        } else {
            Err(self.out_of_range(key, vec3_text(v), "any finite non-zero vector".into()))
        }
    }

    fn check(&self) -> Result<(), SceneError> {
        let c = &self.scene.world;
        self.real("gravity", c.gravity, Bounds::closed(0.0, 100.0))?;

        // The room first: other ranges depend on its size.
        let size = c.room.size;
        let size_ok = Bounds::closed(0.5, 1000.0);
        if !size.to_array().iter().all(|&s| size_ok.contains(s)) {
            return Err(self.out_of_range(
                "room.size",
                vec3_text(size),
                format!("each component {size_ok}"),
            ));
        }
        self.real(
            "room.restitution",
            c.room.restitution,
            Bounds::closed(0.0, 1.0),
        )?;
        self.real(
            "room.friction",
            c.room.friction,
            Bounds::closed(0.0, MAX_FRICTION),
        )?;
        self.real(
            "room.rolling_resistance",
            c.room.rolling_resistance,
            Bounds::closed(0.0, 1.0),
        )?;
        for (name, &color) in SURFACE_NAMES.iter().zip(&c.room.colors) {
            self.color(&format!("room.colors.{name}"), color)?;
        }

        self.check_light()?;

        let half_min = size.min_element() / 2.0;
        let fits = Bounds::open(half_min);
        let fits_why = "less than half the smallest room dimension";

        let b = &c.balls;
        self.count("balls.count", b.count, (0, MAX_BALLS))?;
        self.real_why("balls.radius", b.radius, fits, fits_why)?;
        self.real("balls.mass", b.mass, Bounds::positive(MAX_MASS))?;
        self.real("balls.restitution", b.restitution, Bounds::closed(0.0, 1.0))?;
        self.real(
            "balls.speed_min",
            b.speed_min,
            Bounds::closed(0.0, MAX_SPEED),
        )?;
        if b.speed_min.is_finite() {
            self.real_why(
                "balls.speed_max",
                b.speed_max,
                Bounds::closed(b.speed_min, MAX_SPEED),
                "at least balls.speed_min",
            )?;
        }
        self.real("balls.start_fill", b.start_fill, Bounds::positive(1.0))?;
        self.color("balls.color", b.color)?;

        self.check_tumblers(fits, fits_why)?;

        let f = &c.fireball;
        self.real_why("fireball.radius", f.radius, fits, fits_why)?;
        self.real("fireball.speed", f.speed, Bounds::positive(MAX_SPEED))?;
        let inside = [
            Bounds::closed(-size.x / 2.0 + f.radius, size.x / 2.0 - f.radius),
            Bounds::closed(f.radius, size.y - f.radius),
            Bounds::closed(-size.z / 2.0 + f.radius, size.z / 2.0 - f.radius),
        ];
        if !inside
            .iter()
            .zip(f.spawn.to_array())
            .all(|(bounds, v)| bounds.contains(v))
        {
            return Err(self.out_of_range(
                "fireball.spawn",
                vec3_text(f.spawn),
                format!(
                    "x {}, y {}, z {} (inside the room by the fireball's radius)",
                    inside[0], inside[1], inside[2]
                ),
            ));
        }
        self.direction("fireball.direction", f.direction)?;

        let g = &c.grab;
        self.real("grab.stiffness", g.stiffness, Bounds::positive(1e6))?;
        self.real("grab.damping", g.damping, Bounds::closed(0.0, 1e6))?;
        self.real("grab.max_force", g.max_force, Bounds::positive(1e6))?;

        let s = &c.solver;
        self.real("solver.dt", s.dt, Bounds::positive(0.1))?;
        self.count("solver.iterations", s.iterations, ITERATIONS)?;
        self.real(
            "solver.bounce_threshold",
            s.bounce_threshold,
            Bounds::closed(0.0, MAX_SPEED),
        )?;
        self.real(
            "solver.event_threshold",
            s.event_threshold,
            Bounds::closed(0.0, MAX_SPEED),
        )?;

        self.check_effects()
    }

    fn check_light(&self) -> Result<(), SceneError> {
        let l = &self.scene.light;
        self.color("light.color", l.color)?;
        self.real32(
            "light.intensity",
            l.intensity,
            Bounds::closed(0.0, MAX_INTENSITY),
            "",
        )?;
        self.real32("light.ambient", l.ambient, Bounds::closed(0.0, 1.0), "")?;
        let bulb = widen(l.bulb_radius);
        self.real32(
            "light.bulb_radius",
            l.bulb_radius,
            Bounds::positive(MAX_BULB_RADIUS),
            "",
        )?;
        // The bulb hangs below the centre of the ceiling and must not reach
        // through the floor.
        self.real32(
            "light.drop",
            l.drop,
            Bounds::closed(0.0, self.scene.world.room.size.y - bulb),
            "at most the room's height minus light.bulb_radius",
        )
    }

    fn check_effects(&self) -> Result<(), SceneError> {
        let e = &self.scene.effects;
        let time = Bounds::positive(MAX_EFFECT);
        let length = Bounds::positive(MAX_EFFECT);
        let rate = Bounds::closed(0.0, MAX_RATE);
        self.count("effects.capacity", e.capacity, PARTICLE_CAPACITY)?;

        let t = &e.trail;
        self.real("effects.trail.interval_min", t.interval_min, time)?;
        self.real_why(
            "effects.trail.interval_max",
            t.interval_max,
            Bounds::closed(t.interval_min, MAX_EFFECT),
            "at least effects.trail.interval_min",
        )?;
        self.real("effects.trail.life", t.life, time)?;
        self.real("effects.trail.size", t.size, length)?;

        let w = &e.wall_hit;
        self.real("effects.wall_hit.duration", w.duration, time)?;
        self.real("effects.wall_hit.rate", w.rate, rate)?;
        self.real("effects.wall_hit.radius", w.radius, length)?;
        self.real("effects.wall_hit.life", w.life, time)?;
        self.real("effects.wall_hit.size", w.size, length)?;

        let b = &e.ball_hit;
        self.real("effects.ball_hit.duration", b.duration, time)?;
        self.real("effects.ball_hit.rate", b.rate, rate)?;
        self.real("effects.ball_hit.radius", b.radius, length)?;
        self.real("effects.ball_hit.life", b.life, time)?;
        self.real("effects.ball_hit.size", b.size, length)?;
        self.real("effects.ball_hit.burst_life", b.burst_life, time)?;
        self.real("effects.ball_hit.burst_size", b.burst_size, length)?;
        Ok(())
    }

    fn check_tumblers(&self, fits: Bounds, fits_why: &str) -> Result<(), SceneError> {
        let c = &self.scene.world;
        let t = &c.tumblers;
        let size = c.room.size;
        self.real(
            "tumblers.restitution",
            t.restitution,
            Bounds::closed(0.0, 1.0),
        )?;
        self.real(
            "tumblers.floor_friction",
            t.floor_friction,
            Bounds::closed(0.0, MAX_FRICTION),
        )?;
        self.real("tumblers.damping", t.damping, Bounds::closed(0.0, 100.0))?;
        if t.colors.is_empty() && !t.placements.is_empty() {
            return Err(self.invalid(
                "tumblers.colors",
                "at least one colour is needed when there are tumblers".into(),
            ));
        }
        for (i, &color) in t.colors.iter().enumerate() {
            self.color(&format!("tumblers.colors[{i}]"), color)?;
        }

        if t.spheres.len() != TUMBLER_SPHERES {
            return Err(self.invalid(
                "tumblers.spheres",
                format!(
                    "a tumbler is made of exactly {TUMBLER_SPHERES} spheres, found {}",
                    t.spheres.len()
                ),
            ));
        }
        let bottom = t.spheres[0].radius;
        self.real_why("tumblers.spheres[0].radius", bottom, fits, fits_why)?;
        for (i, s) in t.spheres.iter().enumerate() {
            let key = format!("tumblers.spheres[{i}]");
            self.real_why(
                &format!("{key}.height"),
                s.height,
                Bounds::closed(-size.y, size.y),
                "within the room's height of the bottom sphere",
            )?;
            if i > 0 {
                self.real_why(
                    &format!("{key}.radius"),
                    s.radius,
                    Bounds::open(bottom),
                    "smaller than the round bottom, tumblers.spheres[0].radius",
                )?;
            }
            self.real(&format!("{key}.mass"), s.mass, Bounds::positive(MAX_MASS))?;
        }
        // SPEC P6: the centre of mass below the bottom sphere's centre is what
        // rights a tumbler; without it the toy would simply fall over.
        let mass: f64 = t.spheres.iter().map(|s| s.mass).sum();
        let com = t.spheres.iter().map(|s| s.mass * s.height).sum::<f64>() / mass;
        if com >= 0.0 {
            return Err(self.invalid(
                "tumblers.spheres",
                format!(
                    "the centre of mass is {com} above the bottom sphere's centre; it must lie \
                     below it (give the lower spheres more mass) so that the tumbler rights itself"
                ),
            ));
        }

        for (i, p) in t.placements.iter().enumerate() {
            let key = format!("tumblers.placement[{i}]");
            let why = "inside the room by the bottom sphere's radius";
            let reach_x = size.x / 2.0 - bottom;
            let reach_z = size.z / 2.0 - bottom;
            self.real_why(
                &format!("{key}.x"),
                p.x,
                Bounds::closed(-reach_x, reach_x),
                why,
            )?;
            self.real_why(
                &format!("{key}.z"),
                p.z,
                Bounds::closed(-reach_z, reach_z),
                why,
            )?;
            // Round bottoms resting on the floor may touch but not overlap.
            for (j, q) in t.placements.iter().enumerate().take(i) {
                let apart = (p.x - q.x).hypot(p.z - q.z);
                if apart < 2.0 * bottom {
                    return Err(self.invalid(
                        &key,
                        format!(
                            "overlaps tumblers.placement[{j}]: their centres are {apart} apart, \
                             at least {} (twice the bottom radius) is needed",
                            2.0 * bottom
                        ),
                    ));
                }
            }
            self.direction(&format!("{key}.tilt_axis"), p.tilt_axis)?;
            self.real(
                &format!("{key}.tilt_deg"),
                p.tilt_deg,
                Bounds::closed(-180.0, 180.0),
            )?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const DEFAULT_SCENE: &str = include_str!("../../../scenes/default.toml");

    fn parse(source: &str) -> Result<Scene, SceneError> {
        parse_scene(source, "test.toml")
    }

    fn error_text(source: &str) -> String {
        match parse(source) {
            Ok(_) => panic!("expected an error for:\n{source}"),
            Err(e) => e.to_string(),
        }
    }

    #[test]
    fn shipped_default_file_equals_builtin_default() {
        let parsed = parse_scene(DEFAULT_SCENE, "scenes/default.toml").unwrap();
        assert_eq!(
            parsed.world,
            WorldConfig::default(),
            "scenes/default.toml must spell out WorldConfig::default() exactly"
        );
        assert_eq!(
            parsed.effects,
            EffectsConfig::default(),
            "scenes/default.toml must spell out EffectsConfig::default() exactly"
        );
        assert_eq!(
            parsed.light,
            LightConfig::default(),
            "scenes/default.toml must spell out LightConfig::default() exactly"
        );
        assert_eq!(parsed, Scene::default());
    }

    #[test]
    fn builtin_default_is_valid() {
        validate(&Scene::default()).unwrap();
        assert_eq!(load_scene(None).unwrap(), Scene::default());
    }

    #[test]
    fn empty_file_is_the_default() {
        assert_eq!(parse("").unwrap(), Scene::default());
        assert_eq!(parse("# nothing\n").unwrap(), Scene::default());
    }

    #[test]
    fn one_key_changes_only_that_key() {
        let parsed = parse("[balls]\nrestitution = 0.5\n").unwrap();
        let mut expected = Scene::default();
        expected.world.balls.restitution = 0.5;
        assert_eq!(parsed, expected);

        let parsed = parse("gravity = 3.5").unwrap();
        let mut expected = Scene::default();
        expected.world.gravity = 3.5;
        assert_eq!(parsed, expected);

        let parsed = parse("[room.colors]\nleft = [0, 0, 1]\n").unwrap();
        let mut expected = Scene::default();
        expected.world.room.colors[2] = [0.0, 0.0, 1.0];
        assert_eq!(parsed, expected);
    }

    #[test]
    fn one_effects_key_changes_only_that_key() {
        let parsed = parse("[effects.wall_hit]\nrate = 500\n").unwrap();
        let mut expected = Scene::default();
        expected.effects.wall_hit.rate = 500.0;
        assert_eq!(parsed, expected);

        let parsed = parse("[effects]\ncapacity = 100\n").unwrap();
        let mut expected = Scene::default();
        expected.effects.capacity = 100;
        assert_eq!(parsed, expected);

        let parsed = parse("[effects.ball_hit]\nburst_size = 0.25\n").unwrap();
        let mut expected = Scene::default();
        expected.effects.ball_hit.burst_size = 0.25;
        assert_eq!(parsed, expected);
    }

    #[test]
    fn one_light_key_changes_only_that_key() {
        let parsed = parse("[light]\nintensity = 5\n").unwrap();
        let mut expected = Scene::default();
        expected.light.intensity = 5.0;
        assert_eq!(parsed, expected);

        let parsed = parse("[light]\ncolor = [0.5, 0.25, 1]\n").unwrap();
        let mut expected = Scene::default();
        expected.light.color = [0.5, 0.25, 1.0];
        assert_eq!(parsed, expected);

        let parsed = parse("[light]\ndrop = 0\n").unwrap();
        let mut expected = Scene::default();
        expected.light.drop = 0.0;
        assert_eq!(parsed, expected);
    }

    #[test]
    fn light_out_of_range_names_line_key_and_range() {
        let text = error_text("[light]\nambient = 0.1\nintensity = 150\n");
        assert_eq!(
            text,
            "test.toml:3: light.intensity = 150 is out of range: allowed 0 ..= 100"
        );

        let text = error_text("[light]\nambient = 1.5\n");
        assert_eq!(
            text,
            "test.toml:2: light.ambient = 1.5 is out of range: allowed 0 ..= 1"
        );

        let text = error_text("[light]\nbulb_radius = 0\n");
        assert_eq!(
            text,
            "test.toml:2: light.bulb_radius = 0 is out of range: allowed > 0 and <= 1"
        );

        let text = error_text("[light]\ncolor = [1, 1.2, 1]\n");
        assert_eq!(
            text,
            "test.toml:2: light.color = [1, 1.2, 1] is out of range: \
             allowed each component 0 ..= 1"
        );

        let text = error_text("[light]\ndrop = -0.1\n");
        assert_eq!(
            text,
            "test.toml:2: light.drop = -0.1 is out of range: allowed 0 ..= 3.91 \
             (at most the room's height minus light.bulb_radius)"
        );

        // The bulb must stay inside the room: drop depends on the room's
        // height and the bulb's radius.
        let text = error_text("[light]\nbulb_radius = 0.5\ndrop = 3.6\n");
        assert_eq!(
            text,
            "test.toml:3: light.drop = 3.6 is out of range: allowed 0 ..= 3.5 \
             (at most the room's height minus light.bulb_radius)"
        );
        // A value the file did not give is named as the built-in default.
        let text = error_text("[room]\nsize = [8, 0.5, 8]\n[light]\nbulb_radius = 0.3\n");
        assert!(
            text.starts_with("test.toml: light.drop = 0.25 (built-in default) is out of range"),
            "{text}"
        );
        assert!(text.contains("allowed 0 ..= 0.2 "), "{text}");

        let text = error_text("[light]\nglow = 1\n");
        assert!(
            text.starts_with("test.toml:2: unknown key `light.glow`"),
            "{text}"
        );
    }

    #[test]
    fn runtime_light_is_checked() {
        let mut scene = Scene::default();
        scene.light.intensity = -1.0;
        let text = validate(&scene).unwrap_err().to_string();
        assert_eq!(
            text,
            "built-in default scene: light.intensity = -1 is out of range: allowed 0 ..= 100"
        );
    }

    #[test]
    fn consumes_balls_can_be_turned_off() {
        let parsed = parse("[fireball]\nconsumes_balls = false\n").unwrap();
        let mut expected = Scene::default();
        expected.world.fireball.consumes_balls = false;
        assert_eq!(parsed, expected);
        assert!(
            parse("[fireball]\nconsumes_balls = true\n")
                .unwrap()
                .world
                .fireball
                .consumes_balls
        );

        let text = error_text("[fireball]\nconsumes_balls = 0\n");
        assert!(text.starts_with("test.toml:2: "), "{text}");
    }

    #[test]
    fn effects_out_of_range_names_line_key_and_range() {
        let text = error_text("[effects.trail]\nlife = 0.5\nsize = 12\n");
        assert_eq!(
            text,
            "test.toml:3: effects.trail.size = 12 is out of range: allowed > 0 and <= 10"
        );

        let text = error_text("[effects]\ncapacity = 8\n");
        assert_eq!(
            text,
            "test.toml:2: effects.capacity = 8 is out of range: allowed 16 ..= 1000000"
        );

        let text = error_text("[effects]\ncapacity = -5\n");
        assert_eq!(
            text,
            "test.toml:2: effects.capacity = -5 is out of range: allowed 16 ..= 1000000"
        );

        let text = error_text("[effects.ball_hit]\nrate = 200000\n");
        assert_eq!(
            text,
            "test.toml:2: effects.ball_hit.rate = 200000 is out of range: allowed 0 ..= 100000"
        );

        let text = error_text("\n[effects.wall_hit]\nduration = 0\n");
        assert_eq!(
            text,
            "test.toml:3: effects.wall_hit.duration = 0 is out of range: allowed > 0 and <= 10"
        );

        let text = error_text("[effects.trail]\ninterval_min = 0.2\ninterval_max = 0.1\n");
        assert_eq!(
            text,
            "test.toml:3: effects.trail.interval_max = 0.1 is out of range: \
             allowed 0.2 ..= 10 (at least effects.trail.interval_min)"
        );

        let text = error_text("[effects.trail]\ninterval_min = 0.5\n");
        assert!(
            text.starts_with(
                "test.toml: effects.trail.interval_max = 0.03 (built-in default) is out of range"
            ),
            "{text}"
        );

        let text = error_text("[effects.ball_hit]\nglow = 1\n");
        assert!(
            text.starts_with("test.toml:2: unknown key `effects.ball_hit.glow`"),
            "{text}"
        );
    }

    #[test]
    fn integers_are_accepted_for_reals() {
        let parsed = parse("gravity = 10\n[room]\nsize = [6, 3, 8]\n").unwrap();
        assert_eq!(parsed.world.gravity, 10.0);
        assert_eq!(parsed.world.room.size, DVec3::new(6.0, 3.0, 8.0));
    }

    #[test]
    fn unknown_key_names_line_and_key() {
        let text = error_text("gravity = 9.81\n\n[balls]\ncount = 3\ncolour = [1, 0, 0]\n");
        assert!(
            text.starts_with("test.toml:5: unknown key `balls.colour`"),
            "{text}"
        );

        let text = error_text("[lighting]\nintensity = 3\n");
        assert!(text.starts_with("test.toml:1: "), "{text}");
        assert!(text.contains("lighting"), "{text}");

        let text = error_text("[[tumblers.placement]]\nx = 0\nz = 0\nangle = 3\n");
        assert!(
            text.starts_with("test.toml:4: unknown key `tumblers.placement.angle`"),
            "{text}"
        );

        let text = error_text("[room.colors]\nfloor = [0, 0, 0]\nroof = [1, 1, 1]\n");
        assert!(
            text.starts_with("test.toml:3: unknown key `room.colors.roof`"),
            "{text}"
        );
    }

    #[test]
    fn out_of_range_names_line_key_and_range() {
        let text = error_text("# comment\n[balls]\ncount = 3\nrestitution = 1.5\n");
        assert_eq!(
            text,
            "test.toml:4: balls.restitution = 1.5 is out of range: allowed 0 ..= 1"
        );

        let text = error_text("[solver]\ndt = 0.5\n");
        assert_eq!(
            text,
            "test.toml:2: solver.dt = 0.5 is out of range: allowed > 0 and <= 0.1"
        );

        let text = error_text("[balls]\ncount = -1\n");
        assert_eq!(
            text,
            "test.toml:2: balls.count = -1 is out of range: allowed 0 ..= 1000000"
        );

        let text = error_text("[solver]\niterations = 0\n");
        assert!(text.contains("solver.iterations = 0"), "{text}");
        assert!(text.contains("allowed 1 ..= 256"), "{text}");

        let text = error_text("gravity = nan\n");
        assert!(text.starts_with("test.toml:1: gravity = NaN"), "{text}");
    }

    #[test]
    fn range_errors_in_lists_point_at_the_entry() {
        let text = error_text(
            "[[tumblers.placement]]\nx = 0\nz = 0\n\n[[tumblers.placement]]\nx = 1\nz = 9\n",
        );
        assert!(
            text.starts_with("test.toml:7: tumblers.placement[1].z = 9"),
            "{text}"
        );
        assert!(text.contains("allowed -3.7 ..= 3.7"), "{text}");

        let text = error_text("[room.colors]\nfloor = [0.5, 1.2, 0]\n");
        assert!(text.starts_with("test.toml:2: room.colors.floor"), "{text}");
    }

    #[test]
    fn dependent_ranges_follow_other_keys() {
        // A smaller room makes the default placements invalid; the default
        // value is named as such.
        let text = error_text("[room]\nsize = [3, 3, 3]\n");
        assert!(
            text.starts_with("test.toml: tumblers.placement[0].x = -2.2 (built-in default)"),
            "{text}"
        );

        let text = error_text("[balls]\nstart_fill = 1.5\n");
        assert_eq!(
            text,
            "test.toml:2: balls.start_fill = 1.5 is out of range: allowed > 0 and <= 1"
        );

        let text = error_text("[balls]\nspeed_min = 5\nspeed_max = 4\n");
        assert!(
            text.starts_with("test.toml:3: balls.speed_max = 4"),
            "{text}"
        );

        let text = error_text(
            "[tumblers]\nspheres = [\n  { height = 0, radius = 0.3, mass = 2 },\n  \
             { height = -0.1, radius = 0.1, mass = 4 },\n  \
             { height = 0.3, radius = 0.35, mass = 0.4 },\n  \
             { height = 0.5, radius = 0.1, mass = 0.1 },\n  \
             { height = 0.6, radius = 0.1, mass = 0.1 },\n  \
             { height = 0.7, radius = 0.1, mass = 0.1 },\n]\n",
        );
        assert!(
            text.starts_with("test.toml:5: tumblers.spheres[2].radius = 0.35"),
            "{text}"
        );
    }

    #[test]
    fn wrong_sphere_count_is_an_error() {
        let text = error_text("[tumblers]\nspheres = [{ height = 0, radius = 0.3, mass = 2 }]\n");
        assert!(text.starts_with("test.toml:2: tumblers.spheres"), "{text}");
        assert!(text.contains("exactly 6"), "{text}");
    }

    #[test]
    fn wrong_type_names_line() {
        let text = error_text("[room]\nrestitution = 0.5\nfriction = \"high\"\n");
        assert!(text.starts_with("test.toml:3: "), "{text}");

        let text = error_text("[balls]\ncount = 2.5\n");
        assert!(text.starts_with("test.toml:2: "), "{text}");

        let text = error_text("[room]\nsize = [1, 2]\n");
        assert!(text.starts_with("test.toml:2: "), "{text}");
    }

    #[test]
    fn syntax_error_names_line() {
        let text = error_text("gravity = 9.81\n[balls\ncount = 3\n");
        assert!(text.starts_with("test.toml:2: "), "{text}");
    }

    #[test]
    fn zero_balls_and_zero_tumblers_are_valid() {
        let parsed = parse("[balls]\ncount = 0\n[tumblers]\nplacement = []\n").unwrap();
        assert_eq!(parsed.world.balls.count, 0);
        assert!(parsed.world.tumblers.placements.is_empty());
    }

    #[test]
    fn placements_replace_the_default_list() {
        let parsed = parse(
            "[[tumblers.placement]]\nx = 1\nz = -1\ntilt_axis = [0, 0, 1]\ntilt_deg = 20\n\n\
             [[tumblers.placement]]\nx = -1\nz = 0.5\n",
        )
        .unwrap();
        assert_eq!(
            parsed.world.tumblers.placements,
            vec![
                TumblerPlacement {
                    x: 1.0,
                    z: -1.0,
                    tilt_axis: DVec3::Z,
                    tilt_deg: 20.0,
                },
                TumblerPlacement {
                    x: -1.0,
                    z: 0.5,
                    tilt_axis: DVec3::X,
                    tilt_deg: 0.0,
                },
            ]
        );
    }

    #[test]
    fn overlapping_tumblers_are_rejected() {
        let text = error_text(
            "[[tumblers.placement]]\nx = 0\nz = 0\n\n[[tumblers.placement]]\nx = 0.5\nz = 0\n",
        );
        assert!(
            text.starts_with("test.toml:6: tumblers.placement[1]: overlaps"),
            "{text}"
        );
    }

    #[test]
    fn bad_tilt_is_rejected() {
        let text = error_text("[[tumblers.placement]]\nx = 0\nz = 0\ntilt_deg = 200\n");
        assert!(
            text.starts_with("test.toml:4: tumblers.placement[0].tilt_deg = 200"),
            "{text}"
        );
        let text = error_text("[[tumblers.placement]]\nx = 0\nz = 0\ntilt_axis = [0, 0, 0]\n");
        assert!(
            text.starts_with("test.toml:4: tumblers.placement[0].tilt_axis"),
            "{text}"
        );
    }

    #[test]
    fn overrides_are_checked_and_named() {
        let overrides = Overrides {
            balls: Some(7),
            gravity: Some(1.5),
        };
        let parsed = parse_scene_with("gravity = 3\n", "test.toml", &overrides).unwrap();
        assert_eq!(parsed.world.balls.count, 7);
        assert_eq!(parsed.world.gravity, 1.5);

        let overrides = Overrides {
            balls: None,
            gravity: Some(-2.0),
        };
        let text = parse_scene_with("", "test.toml", &overrides)
            .unwrap_err()
            .to_string();
        assert_eq!(
            text,
            "command-line option --gravity: gravity = -2 is out of range: allowed 0 ..= 100"
        );
    }

    #[test]
    fn missing_file_names_the_file() {
        let err = load_scene(Some(Path::new("no/such/scene.toml"))).unwrap_err();
        assert!(matches!(err, SceneError::Read { .. }));
        assert!(err.to_string().contains("no/such/scene.toml"));
    }
}
