//! Scene files (S6, A4): the built-in default scene overridden by a
//! user's TOML file, then range-checked.
//!
//! A scene is the physics ([`WorldConfig`]), the particle effects
//! ([`EffectsConfig`], the file's `[effects]`) and the ceiling light
//! ([`LightConfig`], the file's `[light]`). A file may set any subset of
//! keys; everything it leaves out keeps the value of [`WorldConfig::default`],
//! [`EffectsConfig::default`] or [`LightConfig::default`]. Every key is in
//! one table, [`keys::KEYS`]: its name, where its value lives, its range,
//! when a running sandbox takes a change, its panel control and its doc
//! line. A key the table does not know is an error instead of a silently
//! ignored setting, and every value read keeps its line, so that a range
//! error can point at where it was written.
//!
//! The parts, a file each: `keys`, the table; `read`, which walks a file
//! against it and lays the values over the defaults (`lists`, the keys
//! that hold lists of entries); `checks`, the ranges every value must lie
//! in (`bounds`, an interval as messages show it); `save`, a scene written
//! back as a file of the keys that differ from the default; `reference`,
//! the table as the Markdown of `docs/scenes.md`.

use std::fmt;
use std::path::Path;

use crate::engine::Engine;
use rolypoly_fx::EffectsConfig;
use rolypoly_physics::WorldConfig;
use rolypoly_render::{LightConfig, QualityChoice};
use rolypoly_sound::SoundConfig;

mod bounds;
mod checks;
pub mod keys;
mod lists;
mod read;
pub mod reference;
mod save;
mod shipped;

use checks::{Checker, Sources};
use read::Reader;
pub use save::scene_file_text;
pub use shipped::{SHIPPED_SCENES, ShippedScene};

/// Where the configuration comes from when no scene file is given.
pub const BUILTIN_ORIGIN: &str = "built-in default scene";

/// Largest number of balls a scene may ask for.
pub const MAX_BALLS: usize = 1_000_000;

/// The number of spheres in a tumbler's compound shape (P6).
pub const TUMBLER_SPHERES: usize = 6;

/// Smallest and largest particle capacity a scene may ask for.
pub const PARTICLE_CAPACITY: (usize, usize) = (16, 1_000_000);

/// Where a value came from: a file (with the line, when known) or a
/// command-line option.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Location {
    /// The file, or the option.
    pub origin: String,
    /// The line in the file, when known.
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
        /// The file.
        path: String,
        /// Why.
        #[source]
        source: std::io::Error,
    },
    /// Malformed TOML, an unknown key or a value of the wrong type.
    #[error("{at}: {message}")]
    Syntax {
        /// Where.
        at: Location,
        /// What is wrong, in one line.
        message: String,
    },
    /// A value outside the range the simulation can handle.
    #[error("{at}: {key} = {value} is out of range: allowed {allowed}")]
    OutOfRange {
        /// Where the value was given.
        at: Location,
        /// Its key.
        key: String,
        /// The value, as written.
        value: String,
        /// The range allowed, in words.
        allowed: String,
    },
    /// A structural rule that is not a numeric range (list lengths and such).
    #[error("{at}: {key}: {problem}")]
    Invalid {
        /// Where.
        at: Location,
        /// The key.
        key: String,
        /// What is wrong.
        problem: String,
    },
}

/// A loaded scene: the physics, the particle effects and the light.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Scene {
    /// The physics.
    pub world: WorldConfig,
    /// The particle effects (`[effects]`).
    pub effects: EffectsConfig,
    /// The light (`[light]`).
    pub light: LightConfig,
    /// How finely frames are drawn (`render.quality`).
    pub quality: QualityChoice,
    /// The frames a second the window's auto quality holds
    /// (`render.target_fps`); 0: the display's rate with a GPU, 30 on a
    /// software renderer.
    pub target_fps: f64,
    /// Which engine steps the balls (`solver.engine`).
    pub engine: Engine,
    /// The sound (`[sound]`).
    pub sound: SoundConfig,
}

/// Settings given on the command line; they win over the scene file and are
/// range-checked with the same rules.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Overrides {
    /// `balls.count`, from `--balls`.
    pub balls: Option<usize>,
    /// `gravity`, from `--gravity`.
    pub gravity: Option<f64>,
    /// `solver.engine`, from `--engine`.
    pub engine: Option<Engine>,
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
    let sources = Sources::new(BUILTIN_ORIGIN, false);
    Checker {
        scene,
        sources: &sources,
    }
    .check()
}

fn build(source: Option<&str>, origin: &str, overrides: &Overrides) -> Result<Scene, SceneError> {
    let mut scene = Scene::default();
    let mut sources = Sources::new(origin, source.is_some());
    if let Some(source) = source {
        let mut reader = Reader::new(source, origin);
        reader.read(&mut scene)?;
        sources.lines = reader.lines;
        sources.written = reader.written;
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
    if let Some(engine) = overrides.engine {
        scene.engine = engine;
        sources
            .options
            .insert("solver.engine".into(), "--engine".into());
    }
    Checker {
        scene: &scene,
        sources: &sources,
    }
    .check()?;
    Ok(scene)
}

/// The 1-based line of a byte offset in a scene file's `source`, as its
/// errors name it.
pub fn line_of(source: &str, offset: usize) -> usize {
    let end = offset.min(source.len());
    source.as_bytes()[..end]
        .iter()
        .filter(|&&b| b == b'\n')
        .count()
        + 1
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;
    use rolypoly_physics::{BallPlacement, TumblerPlacement};

    const DEFAULT_SCENE: &str = include_str!("../../../../scenes/default.toml");

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
    fn a_quality_level_is_read_by_name_and_another_word_is_a_clear_error() {
        for name in QualityChoice::NAMES {
            let parsed = parse(&format!("[render]\nquality = \"{name}\"\n")).unwrap();
            assert_eq!(parsed.quality.name(), name);
        }
        let error = error_text("[render]\nquality = \"ultra\"\n");
        assert!(
            error.contains("test.toml:2")
                && error.contains("render.quality")
                && error.contains("`ultra`")
                && error.contains("high, medium, low, auto"),
            "{error}"
        );
        let error = error_text("[render]\nquality = 3\n");
        assert!(error.contains("a string"), "{error}");
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
        assert!(
            text.starts_with("test.toml:1: gravity = nan is out"),
            "{text}"
        );
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
    fn a_spout_must_pour_inside_the_room() {
        let text = error_text("[balls.pour]\nrate = 10\nspout = [0, 9, 0]\n");
        assert_eq!(
            text,
            "test.toml:3: balls.pour.spout = [0, 9, 0] is out of range: allowed x -3.63 ..= 3.63, \
             y 0.12 ..= 3.88, z -3.63 ..= 3.63 (the mouth, and a ball let go from it, inside the \
             room, when balls.pour.rate > 0)"
        );
        let text = error_text("[balls.pour]\nrate = 10\nradius = 3.9\n");
        assert!(
            text.starts_with("test.toml:3: balls.pour.radius = 3.9 is out of range: allowed > 0"),
            "{text}"
        );
        // A wider mouth, or a smaller room, leaves its centre less room.
        let text = error_text("[balls.pour]\nrate = 10\nradius = 3\nspout = [1, 2, 0]\n");
        assert!(text.starts_with("test.toml:4: balls.pour.spout"), "{text}");
        let low_room = "[room]\nsize = [3, 1.5, 3]\n[tumblers]\nplacement = []\n";
        let text = error_text(&format!("{low_room}[balls.pour]\nrate = 10\n"));
        assert!(
            text.starts_with("test.toml: balls.pour.spout = [0, 2, 0] (built-in default)"),
            "{text}"
        );
        // Nothing poured: the spout is not looked at.
        assert!(parse("[balls.pour]\nspout = [0, 9, 0]\nradius = 9\n").is_ok());
        let parsed =
            parse("[balls.pour]\nrate = 50\nspout = [1, 0.5, -1]\nradius = 0.1\n").unwrap();
        let pour = &parsed.world.balls.pour;
        assert_eq!(
            (pour.rate, pour.spout, pour.radius),
            (50.0, DVec3::new(1.0, 0.5, -1.0), 0.1)
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
    fn a_value_of_the_wrong_type_is_named_in_scene_words() {
        for (text, expect) in [
            (
                "gravity = \"x\"\n",
                "test.toml:1: invalid type: string \"x\", expected a number",
            ),
            (
                "[solver]\niterations = 1.5\n",
                "test.toml:2: invalid type: floating point `1.5`, expected a whole number",
            ),
            (
                "room = 3\n",
                "test.toml:1: invalid type: integer `3`, expected a table of keys",
            ),
            (
                "[tumblers]\nplacement = 3\n",
                "test.toml:2: invalid type: integer `3`, expected an array",
            ),
            (
                "[room]\nsize = [1, 2]\n",
                "test.toml:2: invalid length 2, expected an array of length 3",
            ),
        ] {
            assert_eq!(error_text(text), expect);
        }
    }

    #[test]
    fn a_number_out_of_range_is_shown_as_written() {
        for (text, expect) in [
            // Not 309 digits.
            (
                "gravity = 1e308\n",
                "test.toml:1: gravity = 1e308 is out of range: allowed 0 ..= 100",
            ),
            // Not `inf`: single precision cannot hold it.
            (
                "[light]\nintensity = 1e308\n",
                "test.toml:2: light.intensity = 1e308 is out of range: allowed 0 ..= 100",
            ),
            (
                "[balls]\ncount = 2_000_000\n",
                "test.toml:2: balls.count = 2_000_000 is out of range: allowed 0 ..= 1000000",
            ),
            // An array's numbers are shown short.
            (
                "[room]\nsize = [1e300, 4, 4]\n",
                "test.toml:2: room.size = [1e300, 4, 4] is out of range: \
                 allowed each component 0.5 ..= 1000",
            ),
        ] {
            assert_eq!(error_text(text), expect);
        }
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
    fn placed_balls_are_read_with_every_optional_key() {
        let parsed = parse(
            "[balls]\ncount = 0\n\n[[balls.placement]]\nposition = [0, 1, 0]\n\n\
             [[balls.placement]]\nposition = [1, 2, 0.5]\nvelocity = [1, 0, 0]\n\
             spin = [0, 0, -8]\ncolor = [1, 0, 0]\nradius = 0.2\nmass = 3\n",
        )
        .unwrap();
        let b = &parsed.world.balls;
        assert_eq!(b.count, 0);
        let mut second = BallPlacement::new(DVec3::new(1.0, 2.0, 0.5), DVec3::X);
        second.spin = DVec3::new(0.0, 0.0, -8.0);
        second.color = Some([1.0, 0.0, 0.0]);
        second.radius = Some(0.2);
        second.mass = Some(3.0);
        let first = BallPlacement::new(DVec3::Y, DVec3::ZERO);
        assert_eq!(b.placements, vec![first, second]);
    }

    #[test]
    fn a_placed_ball_out_of_the_room_or_in_another_is_named_with_its_line() {
        let text = error_text(
            "[[balls.placement]]\nposition = [0, 1, 0]\n\n[[balls.placement]]\nposition = [0.1, 1, 0]\n",
        );
        assert!(
            text.starts_with("test.toml:5: balls.placement[1]: ball 1 at ")
                && text.contains("overlaps ball 0"),
            "{text}"
        );
        let text = error_text("[[balls.placement]]\nposition = [0, 9, 0]\n");
        assert!(
            text.starts_with("test.toml:2: balls.placement[0]: ball 0 at ")
                && text.contains("inside the room"),
            "{text}"
        );
        let text = error_text("[[balls.placement]]\nposition = [-2.2, 0.3, -1.2]\n");
        assert!(
            text.starts_with("test.toml:2: balls.placement[0]: ball 0")
                && text.contains("tumbler 0"),
            "{text}"
        );
        let text = error_text("[[balls.placement]]\nposition = [0, 1, 0]\nradius = -1\n");
        assert!(
            text.starts_with("test.toml:3: balls.placement[0].radius = -1 is out of range"),
            "{text}"
        );
        let text = error_text("[[balls.placement]]\nvelocity = [0, 1, 0]\n");
        assert!(text.contains("missing key `position`"), "{text}");
        let text = error_text("[[balls.placement]]\nposition = [0, 1, 0]\nspeed = 3\n");
        assert!(
            text.starts_with("test.toml:3: unknown key `balls.placement.speed`"),
            "{text}"
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
            engine: Some(Engine::Gpu),
        };
        let parsed = parse_scene_with(
            "gravity = 3\n[solver]\nengine = \"cpu\"\n",
            "test.toml",
            &overrides,
        )
        .unwrap();
        assert_eq!(parsed.world.balls.count, 7);
        assert_eq!(parsed.world.gravity, 1.5);
        assert_eq!(parsed.engine, Engine::Gpu, "--engine wins over the file");

        let overrides = Overrides {
            gravity: Some(-2.0),
            ..Overrides::default()
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
