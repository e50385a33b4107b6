//! A run's sound, step by step (J1): after each physics step, the
//! step's impacts strike their bodies' voices at their moment within the
//! step, the rolling rumble and the fireball's roar follow the bodies, the
//! bells chime, and the block of samples the step spans is mixed, scaled
//! by the volume and limited.

use glam::DVec3;
use rolypoly_physics::{Balls, Event, EventKind, Surface, World};

use crate::chime::{CLAPPER_MASS, Chime, Chimes};
use crate::config::{SAMPLE_RATE, SoundConfig};
use crate::hertz::Contact;
use crate::limiter::Limiter;
use crate::listener::Listener;
use crate::material::Properties;
use crate::modes::{self, Mode};
use crate::resonator::ModalBank;
use crate::roar::Roar;
use crate::rolling::Rolling;
use crate::voices::{Body, Strike, Voices};

/// The characteristic impedance of air, ρ c (Pa s/m): the pressure a
/// surface moving at 1 m/s radiates, before spreading.
const AIR_IMPEDANCE: f64 = 413.0;
/// The fireball's side of an impact: it roars, but is not struck.
const FIREBALL: Body = Body::Ball(usize::MAX);
/// The pressure (Pa) a sample of 1.0 stands for.
const FULL_SCALE_PASCALS: f64 = 400.0;
/// The floor's boards: side (m) and thickness (m).
const FLOOR_BOARD: (f64, f64) = (1.0, 0.022);
/// The walls' and ceiling's boards, between studs.
const WALL_BOARD: (f64, f64) = (0.6, 0.0125);
/// The bell: its strike note (Hz, C7), mass (kg) and size (m).
const BELL_NOTE: f64 = 2093.0;
const BELL_MASS: f64 = 0.05;
const BELL_RADIUS: f64 = 0.025;
/// The clapper's ball's radius (m); it is steel.
const CLAPPER_RADIUS: f64 = 0.004;

/// The sound of a run, made a step at a time.
pub struct Soundtrack {
    config: SoundConfig,
    sample_rate: f64,
    voices: Voices,
    rolling: Rolling,
    roar: Roar,
    chimes: Chimes,
    limiter: Limiter,
    /// Steps heard, and samples made.
    steps: u64,
    made: u64,
    frames: Vec<[f32; 2]>,
    chimed: Vec<Chime>,
    /// The loudest sample before the limiter, of all made (full scale).
    pub loudest: f32,
}

impl Soundtrack {
    /// The sound of `world`'s run from its current step on, as `config`
    /// says, at [`SAMPLE_RATE`].
    pub fn new(config: &SoundConfig, world: &World) -> Soundtrack {
        let sample_rate = f64::from(SAMPLE_RATE);
        let balls = config.balls.properties();
        // The bed sounds like the scene's ball ringing.
        let ball = modes::sphere(world.config().balls.radius, &balls)[0];
        Soundtrack {
            config: config.clone(),
            sample_rate,
            voices: Voices::new(sample_rate, ball.frequency, ball.decay),
            rolling: Rolling::new(sample_rate),
            roar: Roar::new(sample_rate),
            chimes: Chimes::default(),
            limiter: Limiter::new(sample_rate),
            steps: 0,
            made: 0,
            frames: Vec::new(),
            chimed: Vec::new(),
            loudest: 0.0,
        }
    }

    /// The settings it sounds with now.
    pub fn config(&self) -> &SoundConfig {
        &self.config
    }

    /// Takes new settings: the volume and on/off at once, the materials
    /// with the next body struck.
    pub fn set_config(&mut self, config: &SoundConfig) {
        self.config = config.clone();
    }

    /// Strikes struck so far with a voice of their own, and merged into
    /// the crowd's bed.
    pub fn strikes(&self) -> (u64, u64) {
        (self.voices.voiced, self.voices.bedded)
    }

    /// The bells' strikes so far.
    pub fn chimes(&self) -> u64 {
        self.chimes.count
    }

    /// The voices ringing now.
    pub fn voices(&self) -> usize {
        self.voices.ringing()
    }

    /// Makes the samples of the step `world` just took, whose impacts are
    /// `events`, heard by `listener`.
    pub fn hear_step(&mut self, world: &World, events: &[Event], listener: &Listener) {
        self.hear_step_among(world, world.balls(), events, listener);
    }

    /// As [`Soundtrack::hear_step`], the balls struck being `balls` and not
    /// the world's: those of balls stepped elsewhere (the GPU engine's,
    /// stood in for by their sizes and masses where they last struck).
    pub fn hear_step_among(
        &mut self,
        world: &World,
        balls: &Balls,
        events: &[Event],
        listener: &Listener,
    ) {
        let dt = world.config().solver.dt;
        self.steps += 1;
        let end = (self.steps as f64 * dt * self.sample_rate).round() as u64;
        let n = end.saturating_sub(self.made) as usize;
        // The step began this long after the block's first sample.
        let offset = (self.steps - 1) as f64 * dt - self.made as f64 / self.sample_rate;
        self.made += n as u64;
        let first = self.frames.len();
        self.frames.resize(first + n, [0.0; 2]);
        if !self.config.enabled {
            return;
        }
        for event in events {
            for strike in self
                .strikes_of(world, balls, event, offset)
                .iter()
                .flatten()
            {
                self.strike(world, balls, strike, listener);
            }
        }
        let mut chimed = std::mem::take(&mut self.chimed);
        chimed.clear();
        self.chimes.strikes(world, &mut chimed);
        for chime in &chimed {
            let strike = self.chime_strike(world, balls, chime, offset + dt);
            self.strike(world, balls, &strike, listener);
        }
        self.chimed = chimed;
        let block = &mut self.frames[first..];
        let at = |body: Body| match body {
            Body::Ball(i) => balls.positions().get(i).copied(),
            Body::Shell(t) | Body::Bell(t) => world.tumblers().get(t).map(|t| t.center_of_mass()),
            Body::Board(..) => None,
        };
        self.voices.render(block, listener, at);
        self.rolling.render(block, world, balls, listener);
        self.roar.render(block, world.fireball(), listener);
        let volume = self.config.volume as f32;
        for frame in block.iter_mut() {
            frame[0] *= volume;
            frame[1] *= volume;
            self.loudest = self.loudest.max(frame[0].abs()).max(frame[1].abs());
        }
        self.limiter.run(block);
    }

    /// The samples made and not yet taken, left and right.
    pub fn frames(&self) -> &[[f32; 2]] {
        &self.frames
    }

    /// Takes the samples made so far.
    pub fn take_frames(&mut self) -> Vec<[f32; 2]> {
        std::mem::take(&mut self.frames)
    }

    /// Sounds `strike`, making its body's voice if need be.
    fn strike(&mut self, world: &World, balls: &Balls, strike: &Strike, listener: &Listener) {
        let sample_rate = self.sample_rate;
        let config = &self.config;
        self.voices.strike(strike, listener, || {
            let modes = modes_of(config, world, balls, strike.body);
            ModalBank::new(&modes, strike.loudness, sample_rate)
        });
    }

    /// The strikes of `event`, a step that began `offset` seconds after the
    /// block's start.
    fn strikes_of(
        &self,
        world: &World,
        balls: &Balls,
        event: &Event,
        offset: f64,
    ) -> [Option<Strike>; 2] {
        let at = offset + event.within_step;
        let config = world.config();
        let ball = |i: usize| {
            let r = *balls.radii().get(i)?;
            Some(Side {
                body: Body::Ball(i),
                mass: balls.masses()[i],
                radius: r,
                material: self.config.balls.properties(),
                point: balls.positions()[i],
            })
        };
        let board = |s: Surface| Side {
            body: board_of(s, event.point),
            mass: f64::INFINITY,
            radius: f64::INFINITY,
            material: surface_material(s, &self.config),
            point: event.point,
        };
        let shape = world.tumbler_shape();
        let shell = |t: usize, sphere: usize| Side {
            body: Body::Shell(t),
            mass: shape.mass,
            radius: shape
                .spheres
                .get(sphere)
                .map_or(shape.bottom_radius, |s| s.radius),
            material: self.config.tumblers.properties(),
            point: event.point,
        };
        let fireball = world.fireball().map(|f| Side {
            body: FIREBALL,
            mass: f.mass,
            radius: f.radius,
            material: self.config.balls.properties(),
            point: f.position,
        });
        let (first, second, restitution) = match event.kind {
            EventKind::BallSurface { ball: i, surface } => {
                (ball(i), Some(board(surface)), config.room.restitution)
            }
            EventKind::BallBall { a, b } => (ball(a), ball(b), config.balls.restitution),
            EventKind::BallTumbler {
                ball: i,
                tumbler,
                sphere,
            } => (
                ball(i),
                Some(shell(tumbler, sphere)),
                config.tumblers.restitution,
            ),
            // The fireball keeps its speed: it reflects, as if e = 1.
            EventKind::FireballSurface { surface } => (fireball, Some(board(surface)), 1.0),
            EventKind::FireballBall { ball: i } => (fireball, ball(i), 1.0),
            EventKind::FireballTumbler { tumbler, sphere } => {
                (fireball, Some(shell(tumbler, sphere)), 1.0)
            }
        };
        let (Some(a), Some(b)) = (first, second) else {
            return [None, None];
        };
        let mass = reduced(a.mass, b.mass);
        let contact = Contact {
            mass,
            radius: reduced(a.radius, b.radius),
            modulus: 1.0 / (a.material.compliance() + b.material.compliance()),
        };
        let impulse = mass * (1.0 + restitution) * event.speed;
        let duration = contact.duration(event.speed);
        [a, b].map(|body| {
            (body.body != FIREBALL).then(|| Strike {
                body: body.body,
                point: body.point,
                at,
                duration,
                impulse,
                loudness: loudness(&self.config, world, balls, body.body),
            })
        })
    }

    /// The strike of a bell's clapper, at `at` seconds from the block's
    /// start.
    fn chime_strike(&self, world: &World, balls: &Balls, chime: &Chime, at: f64) -> Strike {
        let contact = Contact {
            mass: reduced(CLAPPER_MASS, BELL_MASS),
            radius: CLAPPER_RADIUS,
            modulus: 1.0
                / (crate::Material::Steel.properties().compliance()
                    + crate::Material::Brass.properties().compliance()),
        };
        let body = Body::Bell(chime.tumbler);
        Strike {
            body,
            point: world.tumblers()[chime.tumbler].center_of_mass(),
            at,
            duration: contact.duration(chime.speed),
            impulse: chime.impulse,
            loudness: loudness(&self.config, world, balls, body),
        }
    }
}

/// One side of an impact as the sound sees it.
struct Side {
    body: Body,
    mass: f64,
    radius: f64,
    material: Properties,
    point: DVec3,
}

/// x y / (x + y), which leaves x where y is infinite.
fn reduced(x: f64, y: f64) -> f64 {
    if y.is_infinite() {
        x
    } else if x.is_infinite() {
        y
    } else {
        x * y / (x + y)
    }
}

/// The floor's material, or the walls' (the ceiling is a wall's).
fn surface_material(s: Surface, config: &SoundConfig) -> Properties {
    match s {
        Surface::Floor => config.floor.properties(),
        _ => config.walls.properties(),
    }
}

/// The board of `s` and its size: (side, thickness).
fn board_size(s: Surface) -> (f64, f64) {
    match s {
        Surface::Floor => FLOOR_BOARD,
        _ => WALL_BOARD,
    }
}

/// The board of surface `s` that `point` lies on.
fn board_of(s: Surface, point: DVec3) -> Body {
    let n = s.inward_normal().abs();
    let (side, _) = board_size(s);
    // The two axes in the surface's plane.
    let (u, v) = if n.y > 0.5 {
        (point.x, point.z)
    } else if n.x > 0.5 {
        (point.y, point.z)
    } else {
        (point.x, point.y)
    };
    Body::Board(
        s.index(),
        (u / side).floor() as i64,
        (v / side).floor() as i64,
    )
}

/// The mass (kg) and radiating size (m) of `body`.
fn mass_and_size(config: &SoundConfig, world: &World, balls: &Balls, body: Body) -> (f64, f64) {
    match body {
        Body::Ball(i) => (balls.masses()[i], balls.radii()[i]),
        Body::Board(s, ..) => {
            let s = Surface::ALL[s];
            let (side, thickness) = board_size(s);
            let density = surface_material(s, config).density;
            (density * thickness * side * side, 0.5 * side)
        }
        Body::Shell(_) => {
            let shape = world.tumbler_shape();
            (shape.mass, shape.bottom_radius)
        }
        Body::Bell(_) => (BELL_MASS, BELL_RADIUS),
    }
}

/// The output a unit impulse gives a mode of weight 1 of `body` at 1 m
/// (full scale per N s): its surface's velocity 1/m radiated from its
/// size, spreading as size / distance.
fn loudness(config: &SoundConfig, world: &World, balls: &Balls, body: Body) -> f64 {
    let (mass, size) = mass_and_size(config, world, balls, body);
    AIR_IMPEDANCE * size / (mass * FULL_SCALE_PASCALS)
}

/// `body`'s modes, from the world's sizes and `config`'s materials.
fn modes_of(config: &SoundConfig, world: &World, balls: &Balls, body: Body) -> Vec<Mode> {
    match body {
        Body::Ball(i) => modes::sphere(balls.radii()[i], &config.balls.properties()),
        Body::Board(s, ..) => {
            let s = Surface::ALL[s];
            let (side, thickness) = board_size(s);
            modes::plate(side, thickness, &surface_material(s, config))
        }
        Body::Shell(_) => modes::shell(
            world.tumbler_shape().bottom_radius,
            &config.tumblers.properties(),
        ),
        Body::Bell(_) => modes::bell(BELL_NOTE, &crate::Material::Brass.properties()),
    }
}
