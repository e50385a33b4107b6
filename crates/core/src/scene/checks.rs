//! Range checks on the merged configuration.

use std::collections::HashMap;

use glam::DVec3;
use rolypoly_physics::{Rgb, Room, TumblerShape, placement_problem};

use super::bounds::{Bounds, number_text, widen};
use super::keys::{Allowed, KEYS, Key, List, MAX_MASS, MAX_SPEED, Slot};
use super::{Location, MAX_BALLS, Scene, SceneError, TUMBLER_SPHERES};

/// Fastest spin (rad/s) a placed ball may start with.
const MAX_SPIN: f64 = 1000.0;

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

fn vec3_text(v: DVec3) -> String {
    let [x, y, z] = v.to_array().map(number_text);
    format!("[{x}, {y}, {z}]")
}

fn rgb_text(c: Rgb) -> String {
    let [r, g, b] = c.map(|x| number_text(widen(x)));
    format!("[{r}, {g}, {b}]")
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

    /// Every component of a vector or colour within `bounds`; `shown` is
    /// the value as the message shows it.
    fn each(
        &self,
        key: &str,
        values: &[f64],
        shown: String,
        bounds: Bounds,
    ) -> Result<(), SceneError> {
        if values.iter().all(|&x| bounds.contains(x)) {
            Ok(())
        } else {
            Err(self.out_of_range(key, shown, format!("each component {bounds}")))
        }
    }

    /// A colour of a list entry.
    fn color(&self, key: &str, c: Rgb) -> Result<(), SceneError> {
        self.each(key, &c.map(widen), rgb_text(c), Bounds::closed(0.0, 1.0))
    }

    fn direction(&self, key: &str, v: DVec3) -> Result<(), SceneError> {
        if v.is_finite() && v.length_squared() > 1e-18 {
            Ok(())
        } else {
            Err(self.out_of_range(key, vec3_text(v), "any finite non-zero vector".into()))
        }
    }

    /// Every key in the order of the table (a key's range may depend on
    /// the keys above it), then the lists' own rules.
    pub(super) fn check(&self) -> Result<(), SceneError> {
        KEYS.iter().try_for_each(|key| self.check_key(key))
    }

    /// The lists, checked together where the last of them sits in the
    /// table: the tumblers' colours, shape and places, then the balls
    /// placed by hand, which must be clear of the tumblers.
    fn check_lists(&self) -> Result<(), SceneError> {
        let fits = Bounds::open(self.scene.world.room.size.min_element() / 2.0);
        let fits_why = "less than half the smallest room dimension";
        self.check_tumblers(fits, fits_why)?;
        self.check_ball_placements(fits, fits_why)
    }

    fn check_key(&self, key: &Key) -> Result<(), SceneError> {
        let scene = self.scene;
        let name = key.name;
        let (bounds, why) = match key.allowed {
            Allowed::Any => return Ok(()),
            Allowed::ListRules => {
                let last = matches!(key.slot, Slot::List(List::TumblerPlacements));
                return if last { self.check_lists() } else { Ok(()) };
            }
            Allowed::Within(bounds) | Allowed::Each(bounds) => (bounds, ""),
            Allowed::Derived(bounds, why) => (bounds(scene), why),
            Allowed::NonZero => {
                let Slot::Vector(place) = &key.slot else {
                    unreachable!("{name}: only a vector can be non-zero")
                };
                return self.direction(name, *(place.read)(scene));
            }
            Allowed::EachDerived(bounds, why) => {
                let Slot::Vector(place) = &key.slot else {
                    unreachable!("{name}: only a vector has components")
                };
                let v = *(place.read)(scene);
                let [x, y, z] = bounds(scene);
                if [x, y, z]
                    .iter()
                    .zip(v.to_array())
                    .all(|(b, v)| b.contains(v))
                {
                    return Ok(());
                }
                let allowed = format!("x {x}, y {y}, z {z} ({why})");
                return Err(self.out_of_range(name, vec3_text(v), allowed));
            }
        };
        match &key.slot {
            Slot::Real(place) => self.real_why(name, *(place.read)(scene), bounds, why),
            Slot::Single(place) => self.real_why(name, widen(*(place.read)(scene)), bounds, why),
            Slot::Count(place) => self.real_why(name, *(place.read)(scene) as f64, bounds, why),
            Slot::Vector(place) => {
                let v = *(place.read)(scene);
                self.each(name, &v.to_array(), vec3_text(v), bounds)
            }
            Slot::Color(place) => {
                let c = *(place.read)(scene);
                self.each(name, &c.map(widen), rgb_text(c), bounds)
            }
            Slot::Switch(_) | Slot::Word(_) | Slot::List(_) => Ok(()),
        }
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

    /// The tumblers' lists: colours, the shape's spheres, the placements.
    fn check_tumblers(&self, fits: Bounds, fits_why: &str) -> Result<(), SceneError> {
        let c = &self.scene.world;
        let t = &c.tumblers;
        let size = c.room.size;
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
        // P6: the centre of mass below the bottom sphere's centre is what
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
