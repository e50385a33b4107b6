//! Range checks on the merged configuration.

use std::collections::HashMap;
use std::fmt;

use glam::DVec3;
use rolypoly_physics::{Rgb, Room, TumblerShape, placement_problem};

use super::{
    Location, MAX_BALLS, PARTICLE_CAPACITY, SURFACE_NAMES, Scene, SceneError, TUMBLER_SPHERES,
};

pub(super) const ITERATIONS: (usize, usize) = (1, 256);
const MAX_MASS: f64 = 1e6;
const MAX_SPEED: f64 = 100.0;
/// Fastest spin (rad/s) a placed ball may start with.
const MAX_SPIN: f64 = 1000.0;
const MAX_FRICTION: f64 = 5.0;
/// Longest effect time (seconds) and largest effect radius or size (metres).
const MAX_EFFECT: f64 = 10.0;
/// Most particles an effect may spawn per second.
const MAX_RATE: f64 = 100_000.0;
/// Largest light intensity.
const MAX_INTENSITY: f64 = 100.0;
/// Largest radius (metres) of the light's bulb.
const MAX_BULB_RADIUS: f64 = 1.0;
/// Largest strength of the bloom's glow.
const MAX_BLOOM_STRENGTH: f64 = 4.0;

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
        let value = |end: End| match end {
            End::Incl(v) | End::Excl(v) => number_text(v),
        };
        let (lo, hi) = (value(self.lo), value(self.hi));
        match (self.lo, self.hi) {
            (End::Incl(_), End::Incl(_)) => write!(f, "{lo} ..= {hi}"),
            (End::Incl(_), End::Excl(_)) => write!(f, ">= {lo} and < {hi}"),
            (End::Excl(_), End::Incl(_)) => write!(f, "> {lo} and <= {hi}"),
            (End::Excl(_), End::Excl(_)) => write!(f, "> {lo} and < {hi}"),
        }
    }
}

/// Where each key of the merged configuration was set.
pub(super) struct Sources {
    pub(super) origin: String,
    pub(super) from_file: bool,
    /// Key path -> line in the file.
    pub(super) lines: HashMap<String, usize>,
    /// Key path -> its number as written in the file, for keys of one number.
    pub(super) written: HashMap<String, String>,
    /// Key path -> the command-line option that set it.
    pub(super) options: HashMap<String, String>,
}

impl Sources {
    /// Nothing set yet, for a scene from `origin` (a file or not).
    pub(super) fn new(origin: &str, from_file: bool) -> Sources {
        Sources {
            origin: origin.to_owned(),
            from_file,
            lines: HashMap::new(),
            written: HashMap::new(),
            options: HashMap::new(),
        }
    }

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

/// A number as a message shows it: in full where that is short, else in
/// exponent form (`1e308`, not 309 digits).
fn number_text(v: f64) -> String {
    let huge_or_tiny = v.abs() >= 1e16 || (v != 0.0 && v.abs() < 1e-6);
    if v.is_finite() && huge_or_tiny {
        format!("{v:e}")
    } else {
        v.to_string()
    }
}

fn vec3_text(v: DVec3) -> String {
    let [x, y, z] = v.to_array().map(number_text);
    format!("[{x}, {y}, {z}]")
}

fn rgb_text(c: Rgb) -> String {
    let [r, g, b] = c.map(|x| number_text(widen(x)));
    format!("[{r}, {g}, {b}]")
}

/// The `f64` with the same shortest decimal form as `v`: 0.09 rather than
/// 0.09000000357627869, so that messages and bounds derived from `f32` keys
/// show the numbers as they were written.
fn widen(v: f32) -> f64 {
    v.to_string().parse().unwrap_or(f64::from(v))
}

pub(super) struct Checker<'a> {
    pub(super) scene: &'a Scene,
    pub(super) sources: &'a Sources,
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

    /// The value of the one-number key `key` as the message shows it: as
    /// written in the file, if it was, since the value kept may have been
    /// rounded to `inf` in single precision.
    fn number_shown(&self, key: &str, v: f64) -> String {
        let from_option = self.sources.options.contains_key(key);
        match self.sources.written.get(key) {
            Some(text) if !from_option => text.clone(),
            _ => number_text(v),
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
        Err(self.out_of_range(key, self.number_shown(key, v), allowed))
    }

    /// [`Self::real_why`] for an `f32` key.
    fn real32(&self, key: &str, v: f32, bounds: Bounds, why: &str) -> Result<(), SceneError> {
        self.real_why(key, widen(v), bounds, why)
    }

    fn count(&self, key: &str, v: usize, (lo, hi): (usize, usize)) -> Result<(), SceneError> {
        if (lo..=hi).contains(&v) {
            Ok(())
        } else {
            let shown = self.number_shown(key, v as f64);
            Err(self.out_of_range(key, shown, format!("{lo} ..= {hi}")))
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

    pub(super) fn check(&self) -> Result<(), SceneError> {
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
        self.check_ball_placements(fits, fits_why)?;

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
        )?;
        self.real32(
            "light.bloom_strength",
            l.bloom_strength,
            Bounds::closed(0.0, MAX_BLOOM_STRENGTH),
            "",
        )?;
        self.real32(
            "light.bloom_threshold",
            l.bloom_threshold,
            Bounds::positive(MAX_INTENSITY),
            "",
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

    /// Each placed ball's own values, then where it lies: in the room, clear
    /// of the other balls and the tumblers (as the world checks it).
    fn check_ball_placements(&self, fits: Bounds, fits_why: &str) -> Result<(), SceneError> {
        let c = &self.scene.world;
        let b = &c.balls;
        if b.total() > MAX_BALLS {
            return Err(self.out_of_range(
                "balls.count",
                format!("{} (and {} placed)", b.count, b.placements.len()),
                format!("at most {MAX_BALLS} balls in all"),
            ));
        }
        for (i, p) in b.placements.iter().enumerate() {
            let key = format!("balls.placement[{i}]");
            let at = |name: &str| format!("{key}.{name}");
            for (name, v) in [
                ("position", p.position),
                ("velocity", p.velocity),
                ("spin", p.spin),
            ] {
                if !v.is_finite() {
                    return Err(self.out_of_range(
                        &at(name),
                        vec3_text(v),
                        "finite numbers".into(),
                    ));
                }
            }
            let speed = p.velocity.length();
            if speed > MAX_SPEED {
                return Err(self.out_of_range(
                    &at("velocity"),
                    vec3_text(p.velocity),
                    format!("a speed of at most {MAX_SPEED} m/s (this is {speed})"),
                ));
            }
            if p.spin.length() > MAX_SPIN {
                return Err(self.out_of_range(
                    &at("spin"),
                    vec3_text(p.spin),
                    format!("at most {MAX_SPIN} rad/s"),
                ));
            }
            if let Some(color) = p.color {
                self.color(&at("color"), color)?;
            }
            if let Some(radius) = p.radius {
                self.real_why(&at("radius"), radius, fits, fits_why)?;
            }
            if let Some(mass) = p.mass {
                self.real(&at("mass"), mass, Bounds::positive(MAX_MASS))?;
            }
        }
        let room = Room::new(c.room.size);
        let shape = TumblerShape::new(&c.tumblers.spheres);
        for i in 0..b.placements.len() {
            if let Some(problem) = placement_problem(c, &room, &shape, i) {
                let key = format!("balls.placement[{i}]");
                return Err(self.invalid(&key, format!("ball {i} {problem}")));
            }
        }
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
