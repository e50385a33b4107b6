//! JSON Lines traces of a simulation (A3), for analysis and plots.
//!
//! The first line describes the scene (`"kind":"scene"`); each further line
//! is the state of every body at one step (`"kind":"state"`) with the events
//! since the previous state line. Floats are written by serde_json as the
//! shortest text that reads back to the same bits, so two traces of the same
//! run compare equal byte for byte (P10).

use std::borrow::Cow;
use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::Path;

use rolypoly_physics::{Event, EventKind, Rgb, Surface, Tint, World};
use serde::Serialize;
use serde::ser::{SerializeMap, Serializer};

/// A trace could not be written; names the destination.
#[derive(Debug, thiserror::Error)]
#[error("cannot write trace to {name}")]
pub struct TraceError {
    /// The file, or standard output.
    pub name: String,
    /// Why.
    #[source]
    pub source: io::Error,
}

impl TraceError {
    /// True when the reader of standard output went away (`| head`), which
    /// ends a run quietly rather than as a failure.
    pub fn is_broken_pipe(&self) -> bool {
        self.source.kind() == io::ErrorKind::BrokenPipe
    }
}

/// Writes trace lines to a buffered destination.
pub struct TraceWriter<W: Write> {
    out: BufWriter<W>,
    name: String,
}

/// Opens `path` for a trace; `-` is standard output.
pub fn create(path: &Path) -> Result<TraceWriter<Box<dyn Write>>, TraceError> {
    if path.as_os_str() == "-" {
        return Ok(TraceWriter::new(Box::new(io::stdout()), "standard output"));
    }
    let name = format!("`{}`", path.display());
    match File::create(path) {
        Ok(file) => Ok(TraceWriter::new(Box::new(file), name)),
        Err(source) => Err(TraceError { name, source }),
    }
}

/// `true` when `path` names standard output.
pub fn is_stdout(path: &Path) -> bool {
    path.as_os_str() == "-"
}

impl<W: Write> TraceWriter<W> {
    /// `name` is how error messages refer to `out`.
    pub fn new(out: W, name: impl Into<String>) -> Self {
        TraceWriter {
            out: BufWriter::new(out),
            name: name.into(),
        }
    }

    /// Writes the scene line: the constants a reader needs to interpret the
    /// state lines (sizes, masses, the tumbler's shape).
    pub fn scene(&mut self, world: &World, seed: u64) -> Result<(), TraceError> {
        let config = world.config();
        let balls = world.balls();
        let shape = world.tumbler_shape();
        let line = SceneLine {
            kind: "scene",
            seed,
            dt: config.solver.dt,
            gravity: config.gravity,
            room: RoomLine {
                size: config.room.size.to_array(),
                colors: SurfaceColors(&config.room.colors),
            },
            balls: balls
                .radii()
                .iter()
                .zip(balls.masses())
                .map(|(&radius, &mass)| BallShape { radius, mass })
                .collect(),
            tumbler_shape: ShapeLine {
                spheres: shape
                    .spheres
                    .iter()
                    .map(|s| SphereLine {
                        height: s.height,
                        radius: s.radius,
                        mass: s.mass,
                    })
                    .collect(),
                mass: shape.mass,
                center_of_mass: shape.center_of_mass.to_array(),
                bottom_radius: shape.bottom_radius,
                com_offset: shape.com_offset,
                inertia: [0, 1, 2].map(|row| shape.inertia.row(row).to_array()),
            },
            tumblers: world.tumblers().len(),
            fireball: FireballShape {
                radius: config.fireball.radius,
                speed: config.fireball.speed,
                // P8: the fireball has a ball's mass.
                mass: config.balls.mass,
            },
        };
        self.line(&line)
    }

    /// Writes the state of every body now, with `events` (those since the
    /// previous state line).
    pub fn state(&mut self, world: &World, events: &[Event]) -> Result<(), TraceError> {
        let balls = world.balls();
        let energy = world.energy();
        let line = StateLine {
            kind: "state",
            step: world.step_count(),
            time: world.time(),
            balls: (0..balls.len())
                .map(|i| {
                    let tint = balls.tints()[i];
                    BallState {
                        p: balls.positions()[i].to_array(),
                        v: balls.velocities()[i].to_array(),
                        w: balls.spins()[i].to_array(),
                        color: world.tint_color(tint),
                        tint: tint_name(tint),
                        alive: balls.alive()[i],
                    }
                })
                .collect(),
            tumblers: world
                .tumblers()
                .iter()
                .map(|t| TumblerState {
                    p: t.center_of_mass().to_array(),
                    q: t.orientation().to_array(),
                    v: t.linear_velocity().to_array(),
                    w: t.angular_velocity().to_array(),
                    sliding: t.sliding(),
                })
                .collect(),
            fireball: world.fireball().map(|f| FireballState {
                p: f.position.to_array(),
                v: f.velocity.to_array(),
            }),
            energy: EnergyLine {
                kinetic: energy.kinetic,
                potential: energy.potential,
                total: energy.total(),
            },
            events: events.iter().map(event_line).collect(),
        };
        self.line(&line)
    }

    /// Flushes the buffer; call once at the end so that a late write error
    /// is reported instead of lost in a drop.
    pub fn finish(mut self) -> Result<W, TraceError> {
        self.out.flush().map_err(|source| self.error(source))?;
        let name = self.name;
        self.out.into_inner().map_err(|e| TraceError {
            name,
            source: e.into_error(),
        })
    }

    fn line(&mut self, value: &impl Serialize) -> Result<(), TraceError> {
        serde_json::to_writer(&mut self.out, value)
            .map_err(io::Error::from)
            .and_then(|()| self.out.write_all(b"\n"))
            .map_err(|source| self.error(source))
    }

    fn error(&self, source: io::Error) -> TraceError {
        TraceError {
            name: self.name.clone(),
            source,
        }
    }
}

/// The name of a ball's tint: `white`, a surface name or `tumblerN`.
pub fn tint_name(tint: Tint) -> Cow<'static, str> {
    match tint {
        Tint::White => Cow::Borrowed("white"),
        Tint::Surface(surface) => Cow::Borrowed(surface.name()),
        Tint::Tumbler(i) => Cow::Owned(format!("tumbler{i}")),
        Tint::Placed(k) => Cow::Owned(format!("placed{k}")),
    }
}

#[derive(Serialize)]
struct SceneLine<'a> {
    kind: &'static str,
    seed: u64,
    dt: f64,
    gravity: f64,
    room: RoomLine<'a>,
    balls: Vec<BallShape>,
    tumbler_shape: ShapeLine,
    tumblers: usize,
    fireball: FireballShape,
}

#[derive(Serialize)]
struct RoomLine<'a> {
    size: [f64; 3],
    colors: SurfaceColors<'a>,
}

/// The room's colours as an object keyed by surface name, in
/// `Surface::ALL` order.
struct SurfaceColors<'a>(&'a [Rgb; 6]);

impl Serialize for SurfaceColors<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(Some(6))?;
        for (surface, color) in Surface::ALL.iter().zip(self.0) {
            map.serialize_entry(surface.name(), color)?;
        }
        map.end()
    }
}

#[derive(Serialize)]
struct BallShape {
    radius: f64,
    mass: f64,
}

#[derive(Serialize)]
struct SphereLine {
    height: f64,
    radius: f64,
    mass: f64,
}

#[derive(Serialize)]
struct ShapeLine {
    spheres: Vec<SphereLine>,
    mass: f64,
    center_of_mass: [f64; 3],
    bottom_radius: f64,
    com_offset: f64,
    inertia: [[f64; 3]; 3],
}

#[derive(Serialize)]
struct FireballShape {
    radius: f64,
    speed: f64,
    mass: f64,
}

#[derive(Serialize)]
struct StateLine {
    kind: &'static str,
    step: u64,
    time: f64,
    balls: Vec<BallState>,
    tumblers: Vec<TumblerState>,
    fireball: Option<FireballState>,
    energy: EnergyLine,
    events: Vec<EventLine>,
}

#[derive(Serialize)]
struct BallState {
    p: [f64; 3],
    v: [f64; 3],
    w: [f64; 3],
    color: Rgb,
    tint: Cow<'static, str>,
    alive: bool,
}

#[derive(Serialize)]
struct TumblerState {
    p: [f64; 3],
    /// Orientation quaternion as [x, y, z, w].
    q: [f64; 4],
    v: [f64; 3],
    w: [f64; 3],
    sliding: bool,
}

#[derive(Serialize)]
struct FireballState {
    p: [f64; 3],
    v: [f64; 3],
}

#[derive(Serialize)]
struct EnergyLine {
    kinetic: f64,
    potential: f64,
    total: f64,
}

/// One event; only the fields that its kind has are written.
#[derive(Serialize)]
struct EventLine {
    kind: &'static str,
    #[serde(skip_serializing_if = "Option::is_none")]
    ball: Option<usize>,
    #[serde(skip_serializing_if = "Option::is_none")]
    a: Option<usize>,
    #[serde(skip_serializing_if = "Option::is_none")]
    b: Option<usize>,
    #[serde(skip_serializing_if = "Option::is_none")]
    tumbler: Option<usize>,
    #[serde(skip_serializing_if = "Option::is_none")]
    sphere: Option<usize>,
    #[serde(skip_serializing_if = "Option::is_none")]
    surface: Option<&'static str>,
    point: [f64; 3],
    normal: [f64; 3],
    speed: f64,
}

/// The snake_case name of an event kind, as written in traces and summaries.
pub fn event_kind_name(kind: &EventKind) -> &'static str {
    EVENT_KINDS[match kind {
        EventKind::BallSurface { .. } => 0,
        EventKind::BallBall { .. } => 1,
        EventKind::BallTumbler { .. } => 2,
        EventKind::FireballSurface { .. } => 3,
        EventKind::FireballBall { .. } => 4,
        EventKind::FireballTumbler { .. } => 5,
    }]
}

/// Every kind of event by the name traces (and Python) give it.
pub const EVENT_KINDS: [&str; 6] = [
    "ball_surface",
    "ball_ball",
    "ball_tumbler",
    "fireball_surface",
    "fireball_ball",
    "fireball_tumbler",
];

fn event_line(event: &Event) -> EventLine {
    let mut line = EventLine {
        kind: event_kind_name(&event.kind),
        ball: None,
        a: None,
        b: None,
        tumbler: None,
        sphere: None,
        surface: None,
        point: event.point.to_array(),
        normal: event.normal.to_array(),
        speed: event.speed,
    };
    match event.kind {
        EventKind::BallSurface { ball, surface } => {
            line.ball = Some(ball);
            line.surface = Some(surface.name());
        }
        EventKind::BallBall { a, b } => {
            line.a = Some(a);
            line.b = Some(b);
        }
        EventKind::BallTumbler {
            ball,
            tumbler,
            sphere,
        } => {
            line.ball = Some(ball);
            line.tumbler = Some(tumbler);
            line.sphere = Some(sphere);
        }
        EventKind::FireballSurface { surface } => line.surface = Some(surface.name()),
        EventKind::FireballBall { ball } => line.ball = Some(ball),
        EventKind::FireballTumbler { tumbler, sphere } => {
            line.tumbler = Some(tumbler);
            line.sphere = Some(sphere);
        }
    }
    line
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;
    use rolypoly_physics::WorldConfig;

    fn lines(world: &World, events: &[Event]) -> Vec<serde_json::Value> {
        let mut trace = TraceWriter::new(Vec::new(), "memory");
        trace.scene(world, 5).unwrap();
        trace.state(world, events).unwrap();
        let bytes = trace.finish().unwrap();
        String::from_utf8(bytes)
            .unwrap()
            .lines()
            .map(|l| serde_json::from_str(l).unwrap())
            .collect()
    }

    #[test]
    fn scene_and_state_lines_have_the_documented_fields() {
        let world = World::new(WorldConfig::default(), 1).unwrap();
        let lines = lines(&world, &[]);
        assert_eq!(lines.len(), 2);
        let scene = &lines[0];
        assert_eq!(scene["kind"], "scene");
        assert_eq!(scene["seed"], 5);
        assert_eq!(scene["balls"].as_array().unwrap().len(), 30);
        assert_eq!(scene["tumblers"], 5);
        assert_eq!(
            scene["tumbler_shape"]["spheres"].as_array().unwrap().len(),
            6
        );
        assert_eq!(
            scene["tumbler_shape"]["inertia"].as_array().unwrap().len(),
            3
        );
        assert!(scene["room"]["colors"]["floor"].is_array());
        for key in ["radius", "speed", "mass"] {
            assert!(scene["fireball"][key].is_number(), "{key}");
        }

        let state = &lines[1];
        assert_eq!(state["kind"], "state");
        assert_eq!(state["step"], 0);
        let ball = &state["balls"][0];
        for key in ["p", "v", "w", "color"] {
            assert_eq!(ball[key].as_array().unwrap().len(), 3, "{key}");
        }
        assert_eq!(ball["tint"], "white");
        assert_eq!(ball["alive"], true);
        let tumbler = &state["tumblers"][0];
        assert_eq!(tumbler["q"].as_array().unwrap().len(), 4);
        assert!(tumbler["sliding"].is_boolean());
        assert!(state["fireball"].is_null());
        assert!(state["energy"]["total"].is_number());
    }

    #[test]
    fn events_carry_their_own_fields_only() {
        let world = World::new(WorldConfig::default(), 1).unwrap();
        let events = [
            Event {
                kind: EventKind::BallSurface {
                    ball: 3,
                    surface: Surface::Floor,
                },
                point: DVec3::new(1.0, 0.0, 2.0),
                normal: DVec3::Y,
                speed: 1.5,
                within_step: 0.0,
            },
            Event {
                kind: EventKind::BallBall { a: 1, b: 2 },
                point: DVec3::ZERO,
                normal: DVec3::X,
                speed: 0.25,
                within_step: 0.0,
            },
        ];
        let lines = lines(&world, &events);
        let written = lines[1]["events"].as_array().unwrap();
        assert_eq!(
            written[0],
            serde_json::json!({"kind": "ball_surface", "ball": 3, "surface": "floor",
                "point": [1.0, 0.0, 2.0], "normal": [0.0, 1.0, 0.0], "speed": 1.5})
        );
        assert_eq!(
            written[1],
            serde_json::json!({"kind": "ball_ball", "a": 1, "b": 2,
                "point": [0.0, 0.0, 0.0], "normal": [1.0, 0.0, 0.0], "speed": 0.25})
        );
    }

    #[test]
    fn tint_names() {
        assert_eq!(tint_name(Tint::White), "white");
        assert_eq!(tint_name(Tint::Surface(Surface::Ceiling)), "ceiling");
        assert_eq!(tint_name(Tint::Tumbler(3)), "tumbler3");
        assert_eq!(tint_name(Tint::Placed(2)), "placed2");
    }
}
