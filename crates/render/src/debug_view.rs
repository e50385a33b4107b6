//! The debug views: what happens inside the step, drawn as lines in the
//! scene (depth-tested, over what is lit): the contacts and their impulses,
//! the bodies' velocities and spins, the broadphase's occupied cells, which
//! bodies are at rest, and why a tumbler rights itself.
//!
//! Built each frame on the processor from the world and the last step's
//! events, as plain line segments; the renderer draws them all in one call.

use std::collections::HashMap;
use std::fmt;

use glam::{DVec3, Vec3};
use rolypoly_physics::{ContactKind, ContactProbe, Event, EventKind, World};

use crate::view::SceneView;

/// One debug view.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DebugLayer {
    /// A dot at each contact, coloured by what it joins and whether it is
    /// new, kept from the last step, or an impact.
    Contacts,
    /// Each contact's impulse over the step along its normal, and its
    /// friction along the tangent.
    Impulses,
    /// An arrow per body for its velocity, one for its spin.
    Velocities,
    /// The broadphase's occupied cells.
    Grid,
    /// The bodies coloured by speed, those at rest in grey.
    Rest,
    /// Each tumbler's centre of mass, its rolling contact and the lever
    /// between them.
    Com,
}

impl DebugLayer {
    /// Every view, in the order of their keys (1 to 6).
    pub const ALL: [DebugLayer; 6] = [
        DebugLayer::Contacts,
        DebugLayer::Impulses,
        DebugLayer::Velocities,
        DebugLayer::Grid,
        DebugLayer::Rest,
        DebugLayer::Com,
    ];

    /// Its name, as `--show` takes it.
    pub fn name(self) -> &'static str {
        match self {
            DebugLayer::Contacts => "contacts",
            DebugLayer::Impulses => "impulses",
            DebugLayer::Velocities => "velocities",
            DebugLayer::Grid => "grid",
            DebugLayer::Rest => "rest",
            DebugLayer::Com => "com",
        }
    }

    fn bit(self) -> u8 {
        1 << DebugLayer::ALL.iter().position(|&l| l == self).unwrap_or(0)
    }
}

/// Gravity (m/s²) of the impulse that draws a ball's radius long: a ball's
/// weight over a step on Earth, whatever the scene's gravity.
const STANDARD_GRAVITY: f64 = 9.81;
/// Seconds of travel a velocity arrow shows.
const VELOCITY_SECONDS: f32 = 0.25;
/// Half the width of a contact's dot (m); an impact's is twice as wide.
const DOT: f32 = 0.04;
/// Lines are drawn this much brighter than their colour: above the bloom's
/// threshold, so that one pixel wide they still show from across the room.
const GLOW: f32 = 2.5;
/// Below this speed (m/s), and turning its surface slower, a body is at rest.
pub const REST_SPEED: f32 = 0.05;
/// The speed (m/s) the rest view's colours run up to.
const FAST: f32 = 4.0;

/// Which debug views are shown, and the impulses' scale.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DebugViews {
    shown: u8,
    /// How long an impulse's line is: at 1, the impulse that carries a
    /// ball's weight over a step (m g dt, at 9.81 m/s²) is as long as the
    /// ball's radius, so that the lines fit the scene's balls.
    pub impulse_scale: f32,
}

impl Default for DebugViews {
    fn default() -> Self {
        DebugViews {
            shown: 0,
            impulse_scale: 1.0,
        }
    }
}

impl DebugViews {
    /// Whether `layer` is shown.
    pub fn shows(&self, layer: DebugLayer) -> bool {
        self.shown & layer.bit() != 0
    }

    /// Shows `layer`, or hides it.
    pub fn set(&mut self, layer: DebugLayer, on: bool) {
        if on {
            self.shown |= layer.bit();
        } else {
            self.shown &= !layer.bit();
        }
    }

    /// Whether any view is shown.
    pub fn any(&self) -> bool {
        self.shown != 0
    }

    /// The views a comma-separated list names (`contacts,grid`); an
    /// unknown name is an error that lists the names.
    pub fn parse(list: &str) -> Result<DebugViews, String> {
        let mut views = DebugViews::default();
        for name in list.split(',').map(str::trim).filter(|n| !n.is_empty()) {
            let layer = DebugLayer::ALL
                .into_iter()
                .find(|l| l.name() == name)
                .ok_or_else(|| {
                    format!(
                        "`{name}` is not a debug view: use some of {}",
                        DebugViews::names()
                    )
                })?;
            views.set(layer, true);
        }
        Ok(views)
    }

    /// Every view's name, comma-separated.
    pub fn names() -> String {
        DebugLayer::ALL.map(DebugLayer::name).join(", ")
    }
}

impl fmt::Display for DebugViews {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let shown: Vec<&str> = DebugLayer::ALL
            .into_iter()
            .filter(|&l| self.shows(l))
            .map(DebugLayer::name)
            .collect();
        f.write_str(&shown.join(","))
    }
}

/// One end of a line segment of a debug view (see `LineIn` in scene.wgsl).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct LineVertex {
    /// Where it is (m).
    pub position: [f32; 3],
    /// Its colour (linear RGB).
    pub color: [f32; 3],
}

impl LineVertex {
    const ATTRIBUTES: [wgpu::VertexAttribute; 2] =
        wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3];

    /// The vertex buffer's layout.
    pub fn layout() -> wgpu::VertexBufferLayout<'static> {
        wgpu::VertexBufferLayout {
            array_stride: std::mem::size_of::<LineVertex>() as u64,
            step_mode: wgpu::VertexStepMode::Vertex,
            attributes: &Self::ATTRIBUTES,
        }
    }
}

/// Colours of a contact's kind.
fn kind_color(kind: ContactKind) -> Vec3 {
    match kind {
        ContactKind::BallBall => Vec3::new(1.0, 0.85, 0.1),
        ContactKind::BallWall => Vec3::new(0.1, 0.8, 1.0),
        ContactKind::BallTumbler => Vec3::new(1.0, 0.2, 0.8),
        ContactKind::TumblerFloor => Vec3::new(0.2, 1.0, 0.3),
        ContactKind::TumblerTumbler => Vec3::new(1.0, 0.5, 0.1),
    }
}

/// Where a contact stands: it shows in the dot's brightness and size.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum State {
    /// It first pushed this step.
    New,
    /// It pushed in the step before too.
    Kept,
    /// Its bodies met in an impact this step.
    Impact,
}

impl State {
    fn tint(self, color: Vec3) -> Vec3 {
        match self {
            State::New => color * 1.4,
            State::Kept => color * 0.55,
            State::Impact => color.lerp(Vec3::ONE, 0.5) * 1.6,
        }
    }
}

/// Line segments, two vertices each.
#[derive(Default)]
struct Lines(Vec<LineVertex>);

impl Lines {
    fn segment(&mut self, a: Vec3, b: Vec3, color: Vec3) {
        let color = (color * GLOW).to_array();
        self.0.push(LineVertex {
            position: a.to_array(),
            color,
        });
        self.0.push(LineVertex {
            position: b.to_array(),
            color,
        });
    }

    /// A dot: three short crossing lines.
    fn dot(&mut self, at: Vec3, half: f32, color: Vec3) {
        for axis in [Vec3::X, Vec3::Y, Vec3::Z] {
            self.segment(at - axis * half, at + axis * half, color);
        }
    }

    /// An arrow from `from` along `along`, with a head.
    fn arrow(&mut self, from: Vec3, along: Vec3, color: Vec3) {
        let length = along.length();
        if length < 1e-4 {
            return;
        }
        let to = from + along;
        self.segment(from, to, color);
        let dir = along / length;
        let side = dir.any_orthonormal_vector();
        let head = (0.25 * length).min(0.06);
        for s in [side, -side] {
            self.segment(to, to - dir * head + s * head * 0.5, color);
        }
    }

    /// The twelve edges of the box `lo..lo + size`.
    fn cube(&mut self, lo: Vec3, size: f32, color: Vec3) {
        let c = |x: f32, y: f32, z: f32| lo + Vec3::new(x, y, z) * size;
        for (a, b) in [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)] {
            self.segment(c(0.0, a, b), c(1.0, a, b), color);
            self.segment(c(a, 0.0, b), c(a, 1.0, b), color);
            self.segment(c(a, b, 0.0), c(a, b, 1.0), color);
        }
    }
}

/// A contact to draw: the world's probe, and its state this step.
struct Shown {
    probe: ContactProbe,
    state: State,
}

/// The step's contacts: the solver's, marked where this step's events say
/// their bodies met in an impact, and the impacts the solver never saw
/// (resolved one by one before it), their impulse taken as
/// (1 + e) m v with the pair's reduced mass.
fn contacts(world: &World, events: &[Event]) -> Vec<Shown> {
    let mut shown: Vec<Shown> = world
        .contact_probes()
        .into_iter()
        .map(|probe| Shown {
            state: if probe.kept { State::Kept } else { State::New },
            probe,
        })
        .collect();
    // The contacts by what they join, so that each event finds its own
    // without a walk over every contact (a crowd has tens of thousands).
    let mut by_bodies: HashMap<(ContactKind, [Option<usize>; 2]), Vec<usize>> = HashMap::new();
    for (k, s) in shown.iter().enumerate() {
        by_bodies
            .entry((s.probe.kind, s.probe.balls))
            .or_default()
            .push(k);
    }
    let balls = world.balls();
    let config = world.config();
    for e in events {
        let (kind, pair, mass, restitution) = match e.kind {
            EventKind::BallBall { a, b } => {
                let (ma, mb) = (balls.masses()[a], balls.masses()[b]);
                let pair = [Some(a.min(b)), Some(a.max(b))];
                (
                    ContactKind::BallBall,
                    pair,
                    ma * mb / (ma + mb),
                    config.balls.restitution,
                )
            }
            EventKind::BallSurface { ball, .. } => (
                ContactKind::BallWall,
                [Some(ball), None],
                balls.masses()[ball],
                config.room.restitution,
            ),
            EventKind::BallTumbler { ball, .. } => (
                ContactKind::BallTumbler,
                [Some(ball), None],
                balls.masses()[ball],
                config.tumblers.restitution,
            ),
            _ => continue,
        };
        // A ball's walls are told apart by their normals.
        let candidates = by_bodies.entry((kind, pair)).or_default();
        let same = candidates
            .iter()
            .copied()
            .find(|&k| kind != ContactKind::BallWall || shown[k].probe.normal.dot(e.normal) > 0.9);
        match same {
            Some(k) => shown[k].state = State::Impact,
            None => {
                candidates.push(shown.len());
                shown.push(Shown {
                    probe: ContactProbe {
                        kind,
                        balls: pair,
                        kept: false,
                        point: e.point,
                        normal: e.normal,
                        impulse: (1.0 + restitution) * mass * e.speed,
                        friction: DVec3::ZERO,
                    },
                    state: State::Impact,
                });
            }
        }
    }
    shown
}

/// A colour for `speed` (m/s): grey at rest, then blue through green to
/// red at 4 m/s and over.
pub fn speed_color(speed: f32) -> Vec3 {
    if speed < REST_SPEED {
        return Vec3::splat(0.35);
    }
    let t = (speed / FAST).clamp(0.0, 1.0);
    let (blue, green, red) = (
        Vec3::new(0.1, 0.3, 1.0),
        Vec3::new(0.1, 0.9, 0.2),
        Vec3::new(1.0, 0.15, 0.05),
    );
    if t < 0.5 {
        blue.lerp(green, t * 2.0)
    } else {
        green.lerp(red, t * 2.0 - 1.0)
    }
}

impl SceneView {
    /// Adds the debug views `views` shows of `world`, whose last step's
    /// events are `events`: lines for the contacts, impulses, velocities,
    /// grid and centres of mass, the bodies recoloured for the rest view.
    pub fn with_debug(mut self, world: &World, events: &[Event], views: &DebugViews) -> SceneView {
        if !views.any() {
            return self;
        }
        let mut lines = Lines(std::mem::take(&mut self.debug_lines));
        if views.shows(DebugLayer::Contacts) || views.shows(DebugLayer::Impulses) {
            // Metres of line per newton-second.
            let balls = &world.config().balls;
            let weight = balls.mass * STANDARD_GRAVITY * world.config().solver.dt;
            let scale = f64::from(views.impulse_scale) * balls.radius / weight;
            for s in contacts(world, events) {
                let p = &s.probe;
                let point = p.point.as_vec3();
                if views.shows(DebugLayer::Contacts) {
                    let half = if s.state == State::Impact {
                        2.0 * DOT
                    } else {
                        DOT
                    };
                    lines.dot(point, half, s.state.tint(kind_color(p.kind)));
                }
                if views.shows(DebugLayer::Impulses) {
                    let normal = (p.normal * p.impulse * scale).as_vec3();
                    lines.segment(point, point + normal, Vec3::new(1.0, 1.0, 0.3));
                    let friction = (p.friction * scale).as_vec3();
                    if friction.length() > 1e-4 {
                        lines.segment(point, point + friction, Vec3::new(1.0, 0.35, 0.1));
                    }
                }
            }
        }
        let balls = world.balls();
        let live = || (0..balls.len()).filter(|&i| balls.alive()[i]);
        if views.shows(DebugLayer::Velocities) {
            let (velocity_color, spin_color) =
                (Vec3::new(1.0, 0.45, 0.1), Vec3::new(0.3, 0.6, 1.0));
            for i in live() {
                let centre = balls.positions()[i].as_vec3();
                let r = balls.radii()[i] as f32;
                lines.arrow(
                    centre,
                    balls.velocities()[i].as_vec3() * VELOCITY_SECONDS,
                    velocity_color,
                );
                // The spin's axis, as long as the surface's speed would carry it.
                lines.arrow(
                    centre,
                    balls.spins()[i].as_vec3() * r * VELOCITY_SECONDS,
                    spin_color,
                );
            }
            for t in world.tumblers() {
                let com = t.center_of_mass().as_vec3();
                lines.arrow(
                    com,
                    t.linear_velocity().as_vec3() * VELOCITY_SECONDS,
                    velocity_color,
                );
                lines.arrow(
                    com,
                    t.angular_velocity().as_vec3() * 0.2 * VELOCITY_SECONDS,
                    spin_color,
                );
            }
        }
        if views.shows(DebugLayer::Grid) {
            let (cells, edge) = world.occupied_cells();
            for c in cells {
                lines.cube(c.as_vec3(), edge as f32, Vec3::new(0.25, 0.7, 0.35));
            }
        }
        // The centre of mass lies inside the tumbler: drawn over it.
        let mut over = Lines(std::mem::take(&mut self.debug_lines_over));
        if views.shows(DebugLayer::Com) {
            let lines = &mut over;
            for t in world.tumblers() {
                let com = t.center_of_mass().as_vec3();
                let contact = t.contact_point().as_vec3();
                let below = Vec3::new(com.x, contact.y, com.z);
                lines.dot(com, 2.0 * DOT, Vec3::ONE * 1.5);
                lines.dot(
                    contact,
                    2.0 * DOT,
                    kind_color(ContactKind::TumblerFloor) * 1.4,
                );
                // The lever: the weight acts straight down from the centre of
                // mass; its horizontal distance from the contact turns the
                // tumbler back upright.
                lines.segment(com, contact, Vec3::new(1.0, 0.9, 0.2) * 1.4);
                lines.segment(com, below, Vec3::splat(0.8));
                lines.segment(below, contact, Vec3::new(1.0, 0.3, 0.2) * 1.4);
            }
        }
        if views.shows(DebugLayer::Rest) {
            for (view, i) in self.balls.iter_mut().zip(live()) {
                let speed = balls.velocities()[i].length() as f32;
                let turning = (balls.spins()[i].length() * balls.radii()[i]) as f32;
                view.color = speed_color(speed.max(turning));
            }
            for (view, t) in self.tumblers.iter_mut().zip(world.tumblers()) {
                // Rocking turns it about its contact; a tenth of a metre is
                // about its centre of mass's lever.
                let rocking = t.angular_velocity().length() * 0.1;
                view.color = speed_color(t.linear_velocity().length().max(rocking) as f32);
            }
        }
        self.debug_lines = lines.0;
        self.debug_lines_over = over.0;
        self
    }
}
