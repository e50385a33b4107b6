//! The one table of scene keys: for every key a scene file may set, its
//! name, where its value lives in a [`Scene`], the range it must lie in,
//! when a running sandbox takes a change of it, how the panel shows it,
//! and a line that says what it is for. The reader of scene files, the
//! range checks, the panel, the saver and the key reference in
//! `docs/scenes.md` all walk this table; a key's default is the value
//! [`Scene::default`] holds.

use crate::engine::Engine;
use glam::DVec3;
use rolypoly_physics::Rgb;
use rolypoly_render::QualityChoice;
use rolypoly_sound::Material;

use super::bounds::{Bounds, widen};
use super::{MAX_BALLS, PARTICLE_CAPACITY, Scene};

/// Largest mass (kg) of a ball or a tumbler's sphere.
pub const MAX_MASS: f64 = 1e6;
/// Largest speed (m/s) anything may be given.
pub const MAX_SPEED: f64 = 100.0;
/// Largest friction coefficient.
const MAX_FRICTION: f64 = 5.0;
/// Longest effect time (seconds) and largest effect radius or size (metres).
const MAX_EFFECT: f64 = 10.0;
/// Most particles an effect may spawn, or balls a spout may pour, per second.
const MAX_RATE: f64 = 100_000.0;
/// Largest light intensity.
const MAX_INTENSITY: f64 = 100.0;
/// Largest spring, damping or force of the hand that drags.
const MAX_GRAB: f64 = 1e6;
/// Largest master volume of the sound (a gain: +12 dB).
const MAX_VOLUME: f64 = 4.0;
/// Largest frame rate the window may be asked to hold.
const MAX_TARGET_FPS: f64 = 1000.0;

/// Where a value of type `T` lives in a [`Scene`].
pub struct Place<T: 'static> {
    /// The value, to read.
    pub read: fn(&Scene) -> &T,
    /// The value, to change.
    pub write: fn(&mut Scene) -> &mut T,
}

/// Where a key that names one of a few choices lives: its value read as
/// its name, and written from one.
pub struct WordPlace {
    /// The names allowed, in the order the panel lists them.
    pub names: &'static [&'static str],
    /// The value's name.
    pub read: fn(&Scene) -> &'static str,
    /// Sets the value named (one of `names`).
    pub write: fn(&mut Scene, &str),
}

/// `material!(balls)`: the material `scene.sound.balls`, by its name.
macro_rules! material {
    ($field:ident) => {
        Word(WordPlace {
            names: &Material::NAMES,
            read: |scene| scene.sound.$field.name(),
            write: |scene, name| {
                scene.sound.$field = Material::from_name(name).unwrap_or(scene.sound.$field);
            },
        })
    };
}

/// `place!(world.gravity)`: the field `scene.world.gravity`.
macro_rules! place {
    ($($field:tt)+) => {
        Place {
            read: |scene| &scene.$($field)+,
            write: |scene| &mut scene.$($field)+,
        }
    };
}

/// A key's type, and where its value lives.
pub enum Slot {
    /// A number.
    Real(Place<f64>),
    /// A number kept in single precision (the light's, which the GPU reads).
    Single(Place<f32>),
    /// A whole number.
    Count(Place<usize>),
    /// `true` or `false`.
    Switch(Place<bool>),
    /// Three numbers, `[x, y, z]`.
    Vector(Place<DVec3>),
    /// A colour, `[r, g, b]` in linear light.
    Color(Place<Rgb>),
    /// One of a few names, written as a string.
    Word(WordPlace),
    /// A list of entries with keys of their own, read and checked by the
    /// code of each list.
    List(List),
}

/// The keys that hold lists.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum List {
    /// `[[balls.placement]]`: balls placed by hand.
    BallPlacements,
    /// `tumblers.colors`: a colour per tumbler.
    TumblerColors,
    /// `tumblers.spheres`: the shape every tumbler shares.
    TumblerSpheres,
    /// `[[tumblers.placement]]`: where the tumblers stand.
    TumblerPlacements,
}

/// The values a key allows.
pub enum Allowed {
    /// Any value of its type.
    Any,
    /// A fixed interval.
    Within(Bounds),
    /// An interval that depends on other keys (checked earlier in the
    /// table), and the reason, as the error message gives it.
    Derived(fn(&Scene) -> Bounds, &'static str),
    /// Every component within a fixed interval.
    Each(Bounds),
    /// Each component within its own interval, which depends on other keys.
    EachDerived(fn(&Scene) -> [Bounds; 3], &'static str),
    /// Any finite vector that is not zero.
    NonZero,
    /// A list's own rules.
    ListRules,
}

/// When a running sandbox takes a changed value.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Takes {
    /// The world reads it afresh from its next step (or its next use of it).
    NextStep,
    /// The renderer draws with it from the next frame.
    NextFrame,
    /// Only a world built anew takes it: on the next restart (I).
    Restart,
}

/// How the sandbox panel shows a key.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Control {
    /// Not in the panel: a scene file sets it.
    Hidden,
    /// A slider with this label over this span (narrower than the allowed
    /// range: the span a player wants to sweep).
    Slider(&'static str, f64, f64),
    /// A check box with this label.
    Checkbox(&'static str),
    /// A drop-down list of the key's names with this label.
    Choice(&'static str),
}

/// One key of a scene file.
pub struct Key {
    /// Its dotted path in the file, such as `balls.restitution`.
    pub name: &'static str,
    /// Its type, and where its value lives.
    pub slot: Slot,
    /// The values it allows.
    pub allowed: Allowed,
    /// When a running sandbox takes a change of it.
    pub takes: Takes,
    /// How the panel shows it.
    pub control: Control,
    /// What it is for, in one line.
    pub doc: &'static str,
}

impl Key {
    /// The table the key sits in (`""` for the top level), and its own name.
    pub fn table_and_leaf(&self) -> (&'static str, &'static str) {
        self.name.rsplit_once('.').unwrap_or(("", self.name))
    }
}

/// The key named `name`, if there is one.
pub fn key(name: &str) -> Option<&'static Key> {
    KEYS.iter().find(|k| k.name == name)
}

/// Less than half the smallest dimension of the room: what a sphere must
/// be to fit in it.
fn fits_in_room(scene: &Scene) -> Bounds {
    Bounds::open(scene.world.room.size.min_element() / 2.0)
}
const FITS_WHY: &str = "less than half the smallest room dimension";

const UNIT: Bounds = Bounds::closed(0.0, 1.0);
const EFFECT_TIME: Bounds = Bounds::positive(MAX_EFFECT);
const EFFECT_LENGTH: Bounds = Bounds::positive(MAX_EFFECT);
const EFFECT_RATE: Bounds = Bounds::closed(0.0, MAX_RATE);

/// A key shorthand: name, slot, allowed, takes, control, doc.
const fn key_of(
    name: &'static str,
    slot: Slot,
    allowed: Allowed,
    takes: Takes,
    control: Control,
    doc: &'static str,
) -> Key {
    Key {
        name,
        slot,
        allowed,
        takes,
        control,
        doc,
    }
}

use Allowed::{Any, Derived, Each, EachDerived, ListRules, NonZero, Within};
use Control::{Checkbox, Choice, Hidden, Slider};
use Slot::{Color, Count, Real, Single, Switch, Vector, Word};
use Takes::{NextFrame, NextStep, Restart};

/// Every key a scene file may set, in the order of `scenes/default.toml`.
/// A key's range may depend only on keys above it: they are checked in
/// this order, the room first.
pub static KEYS: &[Key] = &[
    key_of(
        "gravity",
        Real(place!(world.gravity)),
        Within(Bounds::closed(0.0, 100.0)),
        NextStep,
        Slider("gravity, m/s²", 0.0, 30.0),
        "Gravitational acceleration in m/s², pulling along -y.",
    ),
    key_of(
        "room.size",
        Vector(place!(world.room.size)),
        Each(Bounds::closed(0.5, 1000.0)),
        Restart,
        Hidden,
        "Inner size [x, y, z] of the box in metres; the floor is y = 0, the room centred on x = z = 0.",
    ),
    key_of(
        "room.restitution",
        Real(place!(world.room.restitution)),
        Within(UNIT),
        NextStep,
        Slider("wall restitution", 0.0, 1.0),
        "Restitution of a ball bouncing on any surface: 0 is dead, 1 perfectly elastic.",
    ),
    key_of(
        "room.friction",
        Real(place!(world.room.friction)),
        Within(Bounds::closed(0.0, MAX_FRICTION)),
        NextStep,
        Slider("wall friction", 0.0, 1.5),
        "Coulomb friction between a ball and a surface.",
    ),
    key_of(
        "room.rolling_resistance",
        Real(place!(world.room.rolling_resistance)),
        Within(UNIT),
        NextStep,
        Slider("wall rolling resistance", 0.0, 0.2),
        "A rolling ball's deceleration as a share of its normal acceleration.",
    ),
    key_of(
        "room.colors.floor",
        Color(place!(world.room.colors[0])),
        Each(UNIT),
        NextStep,
        Hidden,
        "Colour of the floor; a ball that hits it takes it.",
    ),
    key_of(
        "room.colors.ceiling",
        Color(place!(world.room.colors[1])),
        Each(UNIT),
        NextStep,
        Hidden,
        "Colour of the ceiling.",
    ),
    key_of(
        "room.colors.left",
        Color(place!(world.room.colors[2])),
        Each(UNIT),
        NextStep,
        Hidden,
        "Colour of the -x wall.",
    ),
    key_of(
        "room.colors.right",
        Color(place!(world.room.colors[3])),
        Each(UNIT),
        NextStep,
        Hidden,
        "Colour of the +x wall.",
    ),
    key_of(
        "room.colors.back",
        Color(place!(world.room.colors[4])),
        Each(UNIT),
        NextStep,
        Hidden,
        "Colour of the -z wall.",
    ),
    key_of(
        "room.colors.front",
        Color(place!(world.room.colors[5])),
        Each(UNIT),
        NextStep,
        Hidden,
        "Colour of the +z wall (behind the camera).",
    ),
    key_of(
        "light.color",
        Color(place!(light.color)),
        Each(UNIT),
        NextFrame,
        Hidden,
        "Colour of the point light below the ceiling's centre.",
    ),
    key_of(
        "light.intensity",
        Single(place!(light.intensity)),
        Within(Bounds::closed(0.0, MAX_INTENSITY)),
        NextFrame,
        Slider("intensity", 0.0, 40.0),
        "Brightness: the light's colour is multiplied by this.",
    ),
    key_of(
        "light.ambient",
        Single(place!(light.ambient)),
        Within(UNIT),
        NextFrame,
        Slider("ambient", 0.0, 1.0),
        "Strength of the even light that reaches what is in shadow where light.indirect is off (the bounce, on, is worked out from the lights).",
    ),
    key_of(
        "light.bulb_radius",
        Single(place!(light.bulb_radius)),
        Within(Bounds::positive(1.0)),
        NextFrame,
        Hidden,
        "Radius in metres of the visible, glowing bulb.",
    ),
    key_of(
        "light.drop",
        Single(place!(light.drop)),
        Derived(
            |scene| {
                let bulb = widen(scene.light.bulb_radius);
                Bounds::closed(0.0, scene.world.room.size.y - bulb)
            },
            "at most the room's height minus light.bulb_radius",
        ),
        NextFrame,
        Hidden,
        "How far below the ceiling's centre the light hangs, in metres.",
    ),
    key_of(
        "light.bloom",
        Switch(place!(light.bloom)),
        Any,
        NextFrame,
        Checkbox("bloom"),
        "What is brighter than white glows: the bulb, the fireball and its particles (--no-bloom).",
    ),
    key_of(
        "light.bloom_strength",
        Single(place!(light.bloom_strength)),
        Within(Bounds::closed(0.0, 4.0)),
        NextFrame,
        Slider("bloom strength", 0.0, 4.0),
        "How strongly the glow is added.",
    ),
    key_of(
        "light.bloom_threshold",
        Single(place!(light.bloom_threshold)),
        Within(Bounds::positive(MAX_INTENSITY)),
        NextFrame,
        Slider("bloom threshold", 0.1, 20.0),
        "Linear brightness above which things glow; lit walls stay below 2.",
    ),
    key_of(
        "light.fireball_light",
        Switch(place!(light.fireball_light)),
        Any,
        NextFrame,
        Checkbox("fireball light"),
        "The flying fireball lights what it passes and its hits flash; it casts no shadow (--no-fireball-light).",
    ),
    key_of(
        "light.indirect",
        Switch(place!(light.indirect)),
        Any,
        NextFrame,
        Checkbox("bounce light"),
        "Light bounces once off the floor, walls and ceiling, in their colours (--no-indirect).",
    ),
    key_of(
        "light.occlusion",
        Switch(place!(light.occlusion)),
        Any,
        NextFrame,
        Checkbox("contact occlusion"),
        "Darkening where things meet: under a ball, round a tumbler's base (--no-occlusion).",
    ),
    key_of(
        "render.quality",
        Word(WordPlace {
            names: &QualityChoice::NAMES,
            read: |scene| scene.quality.name(),
            write: |scene, name| {
                scene.quality = QualityChoice::from_name(name).unwrap_or(scene.quality);
            },
        }),
        Any,
        NextFrame,
        Choice("quality"),
        "How finely frames are drawn; auto lowers the window's render scale, then steps down, while frames are slower than render.target_fps; render and record draw auto as high (--quality).",
    ),
    key_of(
        "render.target_fps",
        Real(place!(target_fps)),
        Within(Bounds::closed(0.0, MAX_TARGET_FPS)),
        NextFrame,
        Slider("target fps", 0.0, 240.0),
        "The frames a second auto quality holds the window to, by its render scale first; 0: the display's rate with a GPU, 30 on a software renderer (--fps).",
    ),
    key_of(
        "sound.enabled",
        Switch(place!(sound.enabled)),
        Any,
        NextFrame,
        Checkbox("sound"),
        "Whether the room sounds: impacts, rolling, the fireball and the bells, live in the window (M mutes) and in record's MP4s.",
    ),
    key_of(
        "sound.volume",
        Real(place!(sound.volume)),
        Within(Bounds::closed(0.0, MAX_VOLUME)),
        NextFrame,
        Slider("volume", 0.0, 2.0),
        "The sound's master volume, a gain: 1 is as calibrated, 0 silent; a limiter keeps every sample below full scale.",
    ),
    key_of(
        "sound.balls",
        material!(balls),
        Any,
        NextFrame,
        Choice("balls' material"),
        "What the balls sound made of (plastic, rubber, wood, plaster, steel, glass, brass, ceramic): their modes' pitch and ring.",
    ),
    key_of(
        "sound.floor",
        material!(floor),
        Any,
        NextFrame,
        Choice("floor's material"),
        "What the floor's boards sound made of (the same materials as sound.balls).",
    ),
    key_of(
        "sound.walls",
        material!(walls),
        Any,
        NextFrame,
        Choice("walls' material"),
        "What the walls' and the ceiling's boards sound made of (the same materials as sound.balls).",
    ),
    key_of(
        "sound.tumblers",
        material!(tumblers),
        Any,
        NextFrame,
        Choice("tumblers' material"),
        "What the tumblers' shells sound made of (the same materials as sound.balls); their bells are brass.",
    ),
    key_of(
        "balls.count",
        Count(place!(world.balls.count)),
        Within(Bounds::closed(0.0, MAX_BALLS as f64)),
        Restart,
        Slider("balls", 0.0, 20_000.0),
        "Number of balls placed at random (from the seed), besides the placed ones.",
    ),
    key_of(
        "balls.radius",
        Real(place!(world.balls.radius)),
        Derived(fits_in_room, FITS_WHY),
        Restart,
        Slider("ball radius, m", 0.02, 0.5),
        "Radius of a ball in metres.",
    ),
    key_of(
        "balls.mass",
        Real(place!(world.balls.mass)),
        Within(Bounds::positive(MAX_MASS)),
        Restart,
        Slider("ball mass, kg", 0.01, 20.0),
        "Mass of a ball in kg; the fireball has the same.",
    ),
    key_of(
        "balls.restitution",
        Real(place!(world.balls.restitution)),
        Within(UNIT),
        NextStep,
        Slider("ball restitution", 0.0, 1.0),
        "Restitution of a ball-ball collision.",
    ),
    key_of(
        "balls.friction",
        Real(place!(world.balls.friction)),
        Within(Bounds::closed(0.0, MAX_FRICTION)),
        NextStep,
        Slider("ball friction", 0.0, 1.5),
        "Coulomb friction between two balls, and between a ball and a tumbler.",
    ),
    key_of(
        "balls.rolling_resistance",
        Real(place!(world.balls.rolling_resistance)),
        Within(UNIT),
        NextStep,
        Slider("ball rolling resistance", 0.0, 0.2),
        "As room.rolling_resistance, for a ball rolling on another ball (not on a tumbler).",
    ),
    key_of(
        "balls.speed_min",
        Real(place!(world.balls.speed_min)),
        Within(Bounds::closed(0.0, MAX_SPEED)),
        NextStep,
        Hidden,
        "Slowest starting speed (m/s) of a random ball, in a random direction.",
    ),
    key_of(
        "balls.speed_max",
        Real(place!(world.balls.speed_max)),
        Derived(
            |scene| Bounds::closed(scene.world.balls.speed_min, MAX_SPEED),
            "at least balls.speed_min",
        ),
        NextStep,
        Hidden,
        "Fastest starting speed (m/s) of a random ball.",
    ),
    key_of(
        "balls.start_fill",
        Real(place!(world.balls.start_fill)),
        Within(Bounds::positive(1.0)),
        NextStep,
        Hidden,
        "The share of the room's height, from the floor up, the random balls start in.",
    ),
    key_of(
        "balls.color",
        Color(place!(world.balls.color)),
        Each(UNIT),
        NextStep,
        Hidden,
        "Colour of a ball that has not hit anything yet.",
    ),
    key_of(
        "balls.placement",
        Slot::List(List::BallPlacements),
        ListRules,
        Restart,
        Hidden,
        "Balls placed by hand, one [[balls.placement]] each: a position inside the room and clear of \
         the rest, and optionally velocity, spin (rad/s, at most 1000), color, radius and mass.",
    ),
    key_of(
        "balls.pour.rate",
        Real(place!(world.balls.pour.rate)),
        Within(Bounds::closed(0.0, MAX_RATE)),
        NextStep,
        Hidden,
        "Random balls poured per second, each dropped from a clear point of the spout's mouth; 0 \
         starts them all at once, placed at random.",
    ),
    key_of(
        "balls.pour.radius",
        Real(place!(world.balls.pour.radius)),
        Derived(
            |scene| {
                let (size, r) = (scene.world.room.size, scene.world.balls.radius);
                if scene.world.balls.pour.rate > 0.0 {
                    Bounds::positive(size.x.min(size.z) / 2.0 - r)
                } else {
                    Bounds::positive(f64::INFINITY)
                }
            },
            "at most half the room's width and depth less balls.radius, when balls.pour.rate > 0",
        ),
        NextStep,
        Hidden,
        "Radius in metres of the spout's mouth, the horizontal disc the balls are let go from.",
    ),
    key_of(
        "balls.pour.spout",
        Vector(place!(world.balls.pour.spout)),
        EachDerived(
            |scene| {
                let (size, balls) = (scene.world.room.size, &scene.world.balls);
                let (r, reach) = (balls.radius, balls.pour.radius + balls.radius);
                if balls.pour.rate <= 0.0 {
                    // Nothing is poured: the spout may be anywhere.
                    return [Bounds::closed(f64::NEG_INFINITY, f64::INFINITY); 3];
                }
                [
                    Bounds::closed(-size.x / 2.0 + reach, size.x / 2.0 - reach),
                    Bounds::closed(r, size.y - r),
                    Bounds::closed(-size.z / 2.0 + reach, size.z / 2.0 - reach),
                ]
            },
            "the mouth, and a ball let go from it, inside the room, when balls.pour.rate > 0",
        ),
        NextStep,
        Hidden,
        "The centre of the spout's mouth.",
    ),
    key_of(
        "tumblers.restitution",
        Real(place!(world.tumblers.restitution)),
        Within(UNIT),
        NextStep,
        Slider("tumbler restitution", 0.0, 1.0),
        "Restitution of impacts between a tumbler and anything.",
    ),
    key_of(
        "tumblers.floor_friction",
        Real(place!(world.tumblers.floor_friction)),
        Within(Bounds::closed(0.0, MAX_FRICTION)),
        NextStep,
        Slider("tumbler floor friction", 0.0, 1.5),
        "Coulomb friction between a tumbler's round bottom and the floor.",
    ),
    key_of(
        "tumblers.damping",
        Real(place!(world.tumblers.damping)),
        Within(Bounds::closed(0.0, 100.0)),
        NextStep,
        Slider("tumbler damping", 0.0, 10.0),
        "Rate (1/s) at which rocking and spinning lose energy; 0 rocks for ever.",
    ),
    key_of(
        "tumblers.colors",
        Slot::List(List::TumblerColors),
        ListRules,
        NextStep,
        Hidden,
        "Tumbler i gets colour i, cycling; at least one colour when there are tumblers.",
    ),
    key_of(
        "tumblers.spheres",
        Slot::List(List::TumblerSpheres),
        ListRules,
        Restart,
        Hidden,
        "The shape every tumbler shares: exactly 6 spheres { height, radius, mass } on its axis, the \
         round bottom first and largest, the centre of mass below the bottom's centre.",
    ),
    key_of(
        "tumblers.placement",
        Slot::List(List::TumblerPlacements),
        ListRules,
        Restart,
        Hidden,
        "One [[tumblers.placement]] per tumbler: x and z of its bottom on the floor, and optionally \
         tilt_axis and tilt_deg (-180 ..= 180); `placement = []` means none.",
    ),
    key_of(
        "fireball.radius",
        Real(place!(world.fireball.radius)),
        Derived(fits_in_room, FITS_WHY),
        NextStep,
        Hidden,
        "Radius of the fireball in metres, from its next launch.",
    ),
    key_of(
        "fireball.speed",
        Real(place!(world.fireball.speed)),
        Within(Bounds::positive(MAX_SPEED)),
        NextStep,
        Slider("fireball speed, m/s (F)", 0.5, 30.0),
        "The constant speed the fireball flies at, in m/s.",
    ),
    key_of(
        "fireball.spawn",
        Vector(place!(world.fireball.spawn)),
        EachDerived(
            |scene| {
                let (size, r) = (scene.world.room.size, scene.world.fireball.radius);
                [
                    Bounds::closed(-size.x / 2.0 + r, size.x / 2.0 - r),
                    Bounds::closed(r, size.y - r),
                    Bounds::closed(-size.z / 2.0 + r, size.z / 2.0 - r),
                ]
            },
            "inside the room by the fireball's radius",
        ),
        NextStep,
        Hidden,
        "Where the fireball is launched from.",
    ),
    key_of(
        "fireball.direction",
        Vector(place!(world.fireball.direction)),
        NonZero,
        NextStep,
        Hidden,
        "The direction the fireball flies in (normalised).",
    ),
    key_of(
        "fireball.consumes_balls",
        Switch(place!(world.fireball.consumes_balls)),
        Any,
        NextStep,
        Hidden,
        "true: a ball the fireball hits is caught, until the balls are re-initialised; false: it is knocked away.",
    ),
    key_of(
        "fireball.starts_active",
        Switch(place!(world.fireball.starts_active)),
        Any,
        Restart,
        Hidden,
        "Whether the fireball is flying from the start rather than from the first F.",
    ),
    key_of(
        "grab.stiffness",
        Real(place!(world.grab.stiffness)),
        Within(Bounds::positive(MAX_GRAB)),
        NextStep,
        Slider("grab spring, N/m", 1.0, 2000.0),
        "Stiffness in N/m of the spring by which the mouse drags a tumbler.",
    ),
    key_of(
        "grab.damping",
        Real(place!(world.grab.damping)),
        Within(Bounds::closed(0.0, MAX_GRAB)),
        NextStep,
        Slider("grab damping, N s/m", 0.0, 200.0),
        "Damping in N s/m on the grab point's velocity.",
    ),
    key_of(
        "grab.max_force",
        Real(place!(world.grab.max_force)),
        Within(Bounds::positive(MAX_GRAB)),
        NextStep,
        Hidden,
        "The largest force in N the hand applies.",
    ),
    key_of(
        "solver.dt",
        Real(place!(world.solver.dt)),
        Within(Bounds::positive(0.1)),
        Restart,
        Hidden,
        "The fixed time step in seconds.",
    ),
    key_of(
        "solver.iterations",
        Count(place!(world.solver.iterations)),
        Within(Bounds::closed(1.0, 256.0)),
        NextStep,
        Slider("solver iterations", 1.0, 64.0),
        "Contact-solver iterations per step.",
    ),
    key_of(
        "solver.bounce_threshold",
        Real(place!(world.solver.bounce_threshold)),
        Within(Bounds::closed(0.0, MAX_SPEED)),
        NextStep,
        Slider("bounce threshold, m/s", 0.0, 2.0),
        "Below this approach speed (m/s) an impact does not bounce but rests.",
    ),
    key_of(
        "solver.event_threshold",
        Real(place!(world.solver.event_threshold)),
        Within(Bounds::closed(0.0, MAX_SPEED)),
        NextStep,
        Slider("event threshold, m/s", 0.0, 5.0),
        "Below this approach speed (m/s) a contact emits no event and changes no colour.",
    ),
    key_of(
        "solver.engine",
        Word(WordPlace {
            names: &Engine::NAMES,
            read: |scene| scene.engine.name(),
            write: |scene, name| {
                scene.engine = Engine::from_name(name).unwrap_or(scene.engine);
            },
        }),
        Any,
        Restart,
        Choice("engine"),
        "Which engine steps the balls: cpu (the reference) or gpu (compute shaders on the graphics adapter; an adapter without them is an error) (--engine).",
    ),
    key_of(
        "effects.capacity",
        Count(place!(effects.capacity)),
        Within(Bounds::closed(
            PARTICLE_CAPACITY.0 as f64,
            PARTICLE_CAPACITY.1 as f64,
        )),
        Restart,
        Hidden,
        "Most particles alive at once; spawning beyond that is skipped.",
    ),
    key_of(
        "effects.trail.interval_min",
        Real(place!(effects.trail.interval_min)),
        Within(EFFECT_TIME),
        Restart,
        Hidden,
        "Shortest wait in seconds between two cubes of the fireball's trail.",
    ),
    key_of(
        "effects.trail.interval_max",
        Real(place!(effects.trail.interval_max)),
        Derived(
            |scene| Bounds::closed(scene.effects.trail.interval_min, MAX_EFFECT),
            "at least effects.trail.interval_min",
        ),
        Restart,
        Hidden,
        "Longest wait in seconds between two cubes of the trail.",
    ),
    key_of(
        "effects.trail.life",
        Real(place!(effects.trail.life)),
        Within(EFFECT_TIME),
        Restart,
        Hidden,
        "How long in seconds a trail cube lives.",
    ),
    key_of(
        "effects.trail.size",
        Real(place!(effects.trail.size)),
        Within(EFFECT_LENGTH),
        Restart,
        Hidden,
        "A trail cube's size at birth, as a share of the fireball's radius.",
    ),
    key_of(
        "effects.wall_hit.duration",
        Real(place!(effects.wall_hit.duration)),
        Within(EFFECT_TIME),
        Restart,
        Hidden,
        "How long in seconds the ring of a fireball's wall hit keeps spawning cubes.",
    ),
    key_of(
        "effects.wall_hit.rate",
        Real(place!(effects.wall_hit.rate)),
        Within(EFFECT_RATE),
        Restart,
        Hidden,
        "Cubes the wall hit spawns per second.",
    ),
    key_of(
        "effects.wall_hit.radius",
        Real(place!(effects.wall_hit.radius)),
        Within(EFFECT_LENGTH),
        Restart,
        Hidden,
        "Radius in metres the ring reaches at the end of the wall hit.",
    ),
    key_of(
        "effects.wall_hit.life",
        Real(place!(effects.wall_hit.life)),
        Within(EFFECT_TIME),
        Restart,
        Hidden,
        "How long in seconds a cube of the wall hit lives.",
    ),
    key_of(
        "effects.wall_hit.size",
        Real(place!(effects.wall_hit.size)),
        Within(EFFECT_LENGTH),
        Restart,
        Hidden,
        "Size in metres of a cube of the wall hit at its largest.",
    ),
    key_of(
        "effects.ball_hit.duration",
        Real(place!(effects.ball_hit.duration)),
        Within(EFFECT_TIME),
        Restart,
        Hidden,
        "How long in seconds cubes keep collapsing onto a ball the fireball hits.",
    ),
    key_of(
        "effects.ball_hit.rate",
        Real(place!(effects.ball_hit.rate)),
        Within(EFFECT_RATE),
        Restart,
        Hidden,
        "Cubes the ball hit spawns per second.",
    ),
    key_of(
        "effects.ball_hit.radius",
        Real(place!(effects.ball_hit.radius)),
        Within(EFFECT_LENGTH),
        Restart,
        Hidden,
        "Radius in metres of the shell the cubes start on; it shrinks to nothing.",
    ),
    key_of(
        "effects.ball_hit.life",
        Real(place!(effects.ball_hit.life)),
        Within(EFFECT_TIME),
        Restart,
        Hidden,
        "How long in seconds a cube of the ball hit lives.",
    ),
    key_of(
        "effects.ball_hit.size",
        Real(place!(effects.ball_hit.size)),
        Within(EFFECT_LENGTH),
        Restart,
        Hidden,
        "Size in metres of a cube of the ball hit at its largest.",
    ),
    key_of(
        "effects.ball_hit.burst_life",
        Real(place!(effects.ball_hit.burst_life)),
        Within(EFFECT_TIME),
        Restart,
        Hidden,
        "How long in seconds the burst at the end of a ball hit lives.",
    ),
    key_of(
        "effects.ball_hit.burst_size",
        Real(place!(effects.ball_hit.burst_size)),
        Within(EFFECT_LENGTH),
        Restart,
        Hidden,
        "Size in metres of the burst at its largest.",
    ),
];

/// `scene` with the value of `key` changed to the nearest other value the
/// scene's rules accept, or `None` for a list: how the tests of the table
/// change one key at a time.
pub fn nearby_change(key: &Key, scene: &Scene) -> Option<Scene> {
    let near = |x: f64| [0.9 * x, 1.1 * x, x + 0.05, x - 0.05, 0.5, 0.01];
    let mut candidates: Vec<Scene> = Vec::new();
    let mut with = |edit: &dyn Fn(&mut Scene)| {
        let mut s = scene.clone();
        edit(&mut s);
        candidates.push(s);
    };
    match &key.slot {
        Slot::Real(p) => near(*(p.read)(scene)).map(|x| with(&|s| *(p.write)(s) = x)),
        Slot::Single(p) => {
            near(f64::from(*(p.read)(scene))).map(|x| with(&|s| *(p.write)(s) = x as f32))
        }
        Slot::Count(p) => {
            let n = *(p.read)(scene);
            [n + 1, n.saturating_sub(1), n, n, n, n].map(|n| with(&|s| *(p.write)(s) = n))
        }
        Slot::Switch(p) => {
            let b = *(p.read)(scene);
            [!b; 6].map(|b| with(&|s| *(p.write)(s) = b))
        }
        Slot::Vector(p) => {
            let v = *(p.read)(scene);
            near(1.0).map(|k| with(&|s| *(p.write)(s) = v * k))
        }
        Slot::Color(p) => {
            let c = *(p.read)(scene);
            near(1.0).map(|k| with(&|s| *(p.write)(s) = c.map(|x| (x * k as f32).min(1.0))))
        }
        Slot::Word(p) => {
            let now = (p.read)(scene);
            let other = p
                .names
                .iter()
                .find(|n| **n != now)
                .expect("two names or more");
            [other; 6].map(|name| with(&|s| (p.write)(s, name)))
        }
        Slot::List(_) => return None,
    };
    candidates
        .into_iter()
        .find(|s| s != scene && super::validate(s).is_ok())
}

#[cfg(test)]
mod tests;
