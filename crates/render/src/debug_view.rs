//! The debug views: what happens inside the step, drawn as marks over the
//! finished frame: the contacts and their impulses, the bodies' velocities
//! and spins, the broadphase's occupied cells, which bodies are at rest,
//! and why a tumbler rights itself.
//!
//! Built each frame on the processor from the world and the last step's
//! events, as plain marks (lines, dots, arrowheads) between points of the
//! world; the renderer draws them all in one call, at the output's
//! resolution, each a screen-facing quad sized in pixels with a dark
//! outline, so that it reads on the white wall, the wood floor and a
//! coloured ball alike and at any distance (as Box2D's, Jolt's and MuJoCo's
//! debug draws do). Marks hidden behind a body are drawn faintly, not lost.

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

/// Gravity (m/s²) of the reference impulse: a ball's weight over a step on
/// Earth, whatever the scene's gravity.
const STANDARD_GRAVITY: f64 = 9.81;
/// An impulse's line, in ball radii, at the reference impulse (a ball's
/// weight over a step); each tenfold more adds [`RADII_PER_DECADE`], so
/// that a tumbler's weight and a hard impact fit the scene as well as a
/// ball resting on the floor. An impulse too small to reach a length is
/// not drawn.
const REFERENCE_RADII: f64 = 3.0;
/// Ball radii an impulse's line grows by for each tenfold of impulse.
const RADII_PER_DECADE: f64 = 1.0;
/// Seconds of travel a velocity arrow shows.
const VELOCITY_SECONDS: f32 = 0.1;

/// The marks' sizes, in pixels of a frame 360 pixels high: a taller frame
/// draws them larger in proportion (see [`mark_scale`]), so that they look
/// alike at any resolution and quality level.
pub mod mark_size {
    /// A contact's dot, across.
    pub const DOT: f32 = 15.0;
    /// An impact's dot, across.
    pub const IMPACT_DOT: f32 = 19.0;
    /// A contact's normal, drawn from its dot.
    pub const NORMAL: f32 = 22.0;
    /// Where an impulse acts, across.
    pub const IMPULSE_DOT: f32 = 12.0;
    /// A spike's width (see debug_marks.wgsl's `SPIKE_WIDTH`).
    pub const SPIKE: f32 = 2.5;
    /// A centre of mass's dot, across.
    pub const COM_DOT: f32 = 14.0;
    /// A line's width.
    pub const LINE: f32 = 2.0;
    /// A vector's width (impulses, a tumbler's velocity; a ball's, one of
    /// thousands in a crowd, is a line's).
    pub const VECTOR: f32 = 3.0;
    /// An arrowhead's length over its line's width: a vector's head is
    /// 13.5 long, the head of a ball's line (one of thousands) 9.
    pub const HEAD_PER_WIDTH: f32 = 4.5;
    /// The dark outline around every mark.
    pub const OUTLINE: f32 = 1.0;
}

/// Pixels of the output per pixel of [`mark_size`]: its height over 360, and
/// never below one.
pub fn mark_scale(output_height: u32) -> f32 {
    (output_height as f32 / 360.0).max(1.0)
}
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

/// What a debug mark is drawn as.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MarkShape {
    /// A line from `from` to `to`, round-ended.
    Line,
    /// A dot at `from`.
    Dot,
    /// An arrow from `from` to `to`: a line of its width with a head at
    /// `to`, one mark (a crowd's arrows are thousands).
    Arrow,
    /// A line of a fixed length on screen (its size) from `from`, towards
    /// where `to` shows: a direction, such as a contact's normal.
    Spike,
}

/// One mark of a debug view (see `MarkIn` in debug_marks.wgsl): between two
/// points of the world, sized in pixels (see [`mark_size`]).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct DebugMark {
    /// Where it starts (m).
    pub from: [f32; 3],
    /// Its [`MarkShape`], as 0, 1, 2 or 3.
    pub shape: f32,
    /// Where it ends (m); a dot's is its `from`.
    pub to: [f32; 3],
    /// A line's or an arrow's width, a dot's diameter, a spike's length
    /// (pixels of a 360-pixel frame).
    pub size: f32,
    /// Its colour (linear RGB), and 1 in alpha to be drawn over everything,
    /// 0 to be drawn faint where a body hides it.
    pub color: [f32; 4],
    /// x: the most its size (an arrow's: its head's length) may be, in
    /// metres seen where it is (0: no most): a contact's dot is never
    /// larger than its ball, an arrowhead never longer than half its
    /// arrow, so that a crowd far off stays legible (and cheap to draw).
    /// y: an arrow's head length (pixels of a 360-pixel frame). Then a pad.
    pub cap: [f32; 4],
}

impl DebugMark {
    const ATTRIBUTES: [wgpu::VertexAttribute; 4] = wgpu::vertex_attr_array![
        0 => Float32x4, 1 => Float32x4, 2 => Float32x4, 3 => Float32x4
    ];

    /// The instance buffer's layout.
    pub fn layout() -> wgpu::VertexBufferLayout<'static> {
        wgpu::VertexBufferLayout {
            array_stride: std::mem::size_of::<DebugMark>() as u64,
            step_mode: wgpu::VertexStepMode::Instance,
            attributes: &Self::ATTRIBUTES,
        }
    }

    /// What it is drawn as.
    pub fn shape(&self) -> MarkShape {
        match self.shape as u32 {
            0 => MarkShape::Line,
            1 => MarkShape::Dot,
            2 => MarkShape::Arrow,
            _ => MarkShape::Spike,
        }
    }

    /// Whether it is drawn over everything.
    pub fn over(&self) -> bool {
        self.color[3] > 0.5
    }
}

/// An impulse along a contact's normal.
const IMPULSE_COLOR: Vec3 = Vec3::new(1.0, 1.0, 0.3);
/// Friction's impulse, along the contact.
const FRICTION_COLOR: Vec3 = Vec3::new(1.0, 0.35, 0.1);
/// A body's velocity.
const VELOCITY_COLOR: Vec3 = Vec3::new(1.0, 0.45, 0.1);
/// A body's spin, along its axis.
const SPIN_COLOR: Vec3 = Vec3::new(0.3, 0.6, 1.0);
/// An occupied cell's edges.
const GRID_COLOR: Vec3 = Vec3::new(0.25, 0.85, 0.4);
/// A tumbler's centre of mass.
const COM_COLOR: Vec3 = Vec3::ONE;
/// From the centre of mass to the rolling contact.
const LEVER_COLOR: Vec3 = Vec3::new(1.0, 0.9, 0.2);
/// The weight's line, straight down from the centre of mass.
const WEIGHT_COLOR: Vec3 = Vec3::splat(0.8);
/// The righting arm: from under the centre of mass to the contact.
const ARM_COLOR: Vec3 = Vec3::new(1.0, 0.3, 0.2);

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
            State::New => color,
            State::Kept => color * 0.6,
            State::Impact => color.lerp(Vec3::ONE, 0.5),
        }
    }
}

/// The marks being built, and whether new ones are drawn over everything.
#[derive(Default)]
struct Marks {
    marks: Vec<DebugMark>,
    over: bool,
}

impl Marks {
    /// A mark at most `cap` metres large where it is (0: no most).
    #[allow(clippy::too_many_arguments)]
    fn push_capped(
        &mut self,
        shape: MarkShape,
        from: Vec3,
        to: Vec3,
        size: f32,
        cap: f32,
        color: Vec3,
    ) {
        self.push_mark(shape, from, to, size, [cap, 0.0, 0.0, 0.0], color);
    }

    fn push_mark(
        &mut self,
        shape: MarkShape,
        from: Vec3,
        to: Vec3,
        size: f32,
        cap: [f32; 4],
        color: Vec3,
    ) {
        let color = color.min(Vec3::ONE);
        self.marks.push(DebugMark {
            from: from.to_array(),
            shape: shape as u32 as f32,
            to: to.to_array(),
            size,
            color: [color.x, color.y, color.z, if self.over { 1.0 } else { 0.0 }],
            cap,
        });
    }

    fn push(&mut self, shape: MarkShape, from: Vec3, to: Vec3, size: f32, color: Vec3) {
        self.push_capped(shape, from, to, size, 0.0, color);
    }

    fn segment(&mut self, a: Vec3, b: Vec3, color: Vec3) {
        self.push(MarkShape::Line, a, b, mark_size::LINE, color);
    }

    fn dot(&mut self, at: Vec3, across: f32, color: Vec3) {
        self.push(MarkShape::Dot, at, at, across, color);
    }

    /// An arrow from `from` along `along`, `width` wide, its head in
    /// proportion to its width and never longer than half the arrow.
    fn arrow(&mut self, from: Vec3, along: Vec3, width: f32, color: Vec3) {
        let length = along.length();
        if length < 1e-4 {
            return;
        }
        let cap = [0.5 * length, mark_size::HEAD_PER_WIDTH * width, 0.0, 0.0];
        self.push_mark(MarkShape::Arrow, from, from + along, width, cap, color);
    }

    /// The edges of boxes of side `size` with their lowest corners at
    /// `corners`: each edge once however many boxes share it (in a crowd,
    /// up to four do), and edges end to end along one line as one segment,
    /// so that a crowd's grid is a few long lines, cheap to draw.
    fn boxes(&mut self, corners: &[DVec3], size: f64, color: Vec3) {
        let Some(&origin) = corners.first() else {
            return;
        };
        // Each edge of unit length on the cells' lattice: its axis, the
        // line it lies on (its other two coordinates), where along it.
        let mut edges: Vec<(usize, [i64; 2], i64)> = Vec::with_capacity(12 * corners.len());
        for lo in corners {
            let cell = ((*lo - origin) / size).round().as_i64vec3().to_array();
            for axis in 0..3 {
                let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
                for (a, b) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                    edges.push((axis, [cell[u] + a, cell[v] + b], cell[axis]));
                }
            }
        }
        edges.sort_unstable();
        edges.dedup();
        let corner = |axis: usize, line: [i64; 2], along: i64| {
            let mut at = [0; 3];
            at[axis] = along;
            at[(axis + 1) % 3] = line[0];
            at[(axis + 2) % 3] = line[1];
            (origin + glam::I64Vec3::from_array(at).as_dvec3() * size).as_vec3()
        };
        let mut rest = edges.as_slice();
        while let Some(&(axis, line, first)) = rest.first() {
            let run = rest
                .iter()
                .zip(first..)
                .take_while(|&(&(a, l, along), next)| a == axis && l == line && along == next)
                .count();
            let last = first + run as i64;
            self.segment(corner(axis, line, first), corner(axis, line, last), color);
            rest = &rest[run..];
        }
    }
}

/// How long an impulse's line is (m): [`REFERENCE_RADII`] ball radii at
/// `reference` (a ball's weight over a step), one radius more for each
/// tenfold (times the panel's `scale`), none where that is no length.
fn impulse_length(impulse: f64, reference: f64, radius: f64, scale: f32) -> f64 {
    if impulse <= 0.0 || reference <= 0.0 {
        return 0.0;
    }
    let radii = REFERENCE_RADII + RADII_PER_DECADE * (impulse / reference).log10();
    radii.max(0.0) * radius * f64::from(scale)
}

/// One line of the debug views' legend: a mark, its colour, what it means.
#[derive(Clone, Debug, PartialEq)]
pub struct LegendEntry {
    /// How it is drawn.
    pub shape: MarkShape,
    /// Its colour (linear RGB).
    pub color: [f32; 3],
    /// What it means.
    pub text: String,
}

impl DebugLayer {
    /// What this view draws, mark by mark: the legend's lines for it.
    pub fn legend(self) -> Vec<LegendEntry> {
        let entry = |shape, color: Vec3, text: &str| LegendEntry {
            shape,
            color: color.min(Vec3::ONE).to_array(),
            text: text.to_string(),
        };
        let dot = MarkShape::Dot;
        match self {
            DebugLayer::Contacts => vec![
                entry(
                    MarkShape::Spike,
                    Vec3::ONE,
                    "a contact and the normal it pushes along",
                ),
                entry(
                    dot,
                    kind_color(ContactKind::BallBall),
                    "ball - ball contact",
                ),
                entry(
                    dot,
                    kind_color(ContactKind::BallWall),
                    "ball - wall or floor",
                ),
                entry(dot, kind_color(ContactKind::BallTumbler), "ball - tumbler"),
                entry(
                    dot,
                    kind_color(ContactKind::TumblerFloor),
                    "tumbler - floor",
                ),
                entry(
                    dot,
                    kind_color(ContactKind::TumblerTumbler),
                    "tumbler - tumbler",
                ),
                entry(
                    dot,
                    State::Kept.tint(Vec3::ONE),
                    "darker: kept from the last step; large and pale: an impact",
                ),
            ],
            DebugLayer::Impulses => vec![
                entry(MarkShape::Arrow, IMPULSE_COLOR, "impulse along the normal"),
                entry(MarkShape::Arrow, FRICTION_COLOR, "friction's impulse"),
                entry(
                    MarkShape::Line,
                    Vec3::splat(0.8),
                    &format!(
                        "log length: {REFERENCE_RADII} ball radii at a ball's weight over a step, \
                         {RADII_PER_DECADE} more for each tenfold (times the panel's scale)"
                    ),
                ),
            ],
            DebugLayer::Velocities => vec![
                entry(
                    MarkShape::Arrow,
                    VELOCITY_COLOR,
                    &format!("velocity: where it goes in {VELOCITY_SECONDS} s"),
                ),
                entry(MarkShape::Arrow, SPIN_COLOR, "spin, along its axis"),
            ],
            DebugLayer::Grid => vec![entry(
                MarkShape::Line,
                GRID_COLOR,
                "cells of the broadphase that hold a ball",
            )],
            DebugLayer::Rest => vec![
                entry(dot, speed_color(0.0), "at rest"),
                entry(dot, speed_color(0.5), "slow"),
                entry(dot, speed_color(2.0), "faster"),
                entry(dot, speed_color(FAST), &format!("{FAST} m/s and over")),
            ],
            DebugLayer::Com => vec![
                entry(dot, COM_COLOR, "centre of mass"),
                entry(MarkShape::Arrow, WEIGHT_COLOR, "its weight, straight down"),
                entry(
                    dot,
                    kind_color(ContactKind::TumblerFloor),
                    "rolling contact",
                ),
                entry(
                    MarkShape::Line,
                    ARM_COLOR,
                    "righting arm: the weight's lever",
                ),
            ],
        }
    }
}

/// A contact to draw: the world's probe, and its state this step.
struct Shown {
    probe: ContactProbe,
    state: State,
}

/// The radius of the smaller body a contact joins: its ball's, or a
/// tumbler's round bottom for a tumbler's.
fn contact_radius(world: &World, probe: &ContactProbe) -> f64 {
    let radii = world.balls().radii();
    probe
        .balls
        .iter()
        .flatten()
        .map(|&ball| radii[ball])
        .fold(world.tumbler_shape().bottom_radius, f64::min)
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
    // The GPU engine's balls are not the world's: their impacts have no
    // contact of the world's to mark.
    let ours = |ball: usize| ball < balls.len();
    for e in events {
        let (kind, pair, mass, restitution) = match e.kind {
            EventKind::BallBall { a, b } if !(ours(a) && ours(b)) => continue,
            EventKind::BallSurface { ball, .. } | EventKind::BallTumbler { ball, .. }
                if !ours(ball) =>
            {
                continue;
            }
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
        let mut lines = Marks {
            marks: std::mem::take(&mut self.debug_marks),
            over: false,
        };
        if views.shows(DebugLayer::Contacts) || views.shows(DebugLayer::Impulses) {
            let balls = &world.config().balls;
            let reference = balls.mass * STANDARD_GRAVITY * world.config().solver.dt;
            let length = |impulse: f64| {
                impulse_length(impulse, reference, balls.radius, views.impulse_scale)
            };
            for s in contacts(world, events) {
                let p = &s.probe;
                let point = p.point.as_vec3();
                if views.shows(DebugLayer::Impulses) {
                    let normal = (p.normal * length(p.impulse)).as_vec3();
                    if normal != Vec3::ZERO {
                        lines.dot(point, mark_size::IMPULSE_DOT, IMPULSE_COLOR);
                    }
                    lines.arrow(point, normal, mark_size::VECTOR, IMPULSE_COLOR);
                    let friction = p.friction.length();
                    if friction > 0.0 {
                        let along = (p.friction / friction * length(friction)).as_vec3();
                        lines.arrow(point, along, mark_size::VECTOR, FRICTION_COLOR);
                    }
                }
                if views.shows(DebugLayer::Contacts) {
                    let across = if s.state == State::Impact {
                        mark_size::IMPACT_DOT
                    } else {
                        mark_size::DOT
                    };
                    let color = s.state.tint(kind_color(p.kind));
                    // No larger than the ball it touches, seen from here;
                    // the normal it pushes along as long again, as Box2D
                    // draws it.
                    let cap = 2.0 * contact_radius(world, p) as f32;
                    let towards = point + p.normal.as_vec3() * 0.1;
                    lines.push_capped(
                        MarkShape::Spike,
                        point,
                        towards,
                        mark_size::NORMAL,
                        2.0 * cap,
                        color,
                    );
                    lines.push_capped(MarkShape::Dot, point, point, across, cap, color);
                }
            }
        }
        let balls = world.balls();
        let live = || (0..balls.len()).filter(|&i| balls.alive()[i]);
        if views.shows(DebugLayer::Velocities) {
            let (velocity_color, spin_color) = (VELOCITY_COLOR, SPIN_COLOR);
            for i in live() {
                let centre = balls.positions()[i].as_vec3();
                let r = balls.radii()[i] as f32;
                lines.arrow(
                    centre,
                    balls.velocities()[i].as_vec3() * VELOCITY_SECONDS,
                    mark_size::LINE,
                    velocity_color,
                );
                // The spin's axis, as long as the surface's speed would carry it.
                lines.arrow(
                    centre,
                    balls.spins()[i].as_vec3() * r * VELOCITY_SECONDS,
                    mark_size::LINE,
                    spin_color,
                );
            }
            for t in world.tumblers() {
                let com = t.center_of_mass().as_vec3();
                lines.arrow(
                    com,
                    t.linear_velocity().as_vec3() * VELOCITY_SECONDS,
                    mark_size::VECTOR,
                    velocity_color,
                );
                lines.arrow(
                    com,
                    t.angular_velocity().as_vec3() * 0.2 * VELOCITY_SECONDS,
                    mark_size::VECTOR,
                    spin_color,
                );
            }
        }
        if views.shows(DebugLayer::Grid) {
            let (cells, edge) = world.occupied_cells();
            lines.boxes(&cells, edge, GRID_COLOR);
        }
        // The centre of mass lies inside the tumbler: drawn over it.
        if views.shows(DebugLayer::Com) {
            lines.over = true;
            for t in world.tumblers() {
                let com = t.center_of_mass().as_vec3();
                let contact = t.contact_point().as_vec3();
                let below = Vec3::new(com.x, contact.y, com.z);
                // The lever: the weight acts straight down from the centre of
                // mass; its horizontal distance from the contact turns the
                // tumbler back upright.
                lines.push(
                    MarkShape::Line,
                    com,
                    contact,
                    mark_size::VECTOR,
                    LEVER_COLOR,
                );
                lines.arrow(com, below - com, mark_size::VECTOR, WEIGHT_COLOR);
                lines.push(
                    MarkShape::Line,
                    below,
                    contact,
                    mark_size::VECTOR,
                    ARM_COLOR,
                );
                lines.dot(com, mark_size::COM_DOT, COM_COLOR);
                lines.dot(
                    contact,
                    mark_size::COM_DOT,
                    kind_color(ContactKind::TumblerFloor),
                );
            }
            lines.over = false;
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
        self.debug_marks = lines.marks;
        self
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashSet;

    /// The segments `boxes` draws, in steps of `size` from `origin`:
    /// (axis, its start, its length).
    fn segments(corners: &[DVec3], size: f64, origin: DVec3) -> Vec<(usize, [i64; 3], i64)> {
        let mut marks = Marks::default();
        marks.boxes(corners, size, Vec3::ONE);
        let steps = |p: [f32; 3]| {
            let steps = (Vec3::from(p).as_dvec3() - origin) / size;
            assert!(
                (steps - steps.round()).abs().max_element() < 1e-3,
                "{steps} off the lattice"
            );
            steps.round().as_i64vec3().to_array()
        };
        marks
            .marks
            .iter()
            .map(|m| {
                let (a, b) = (steps(m.from), steps(m.to));
                let axis = (0..3)
                    .find(|&k| a[k] != b[k])
                    .expect("a segment has a length");
                let along: Vec<usize> = (0..3).filter(|&k| a[k] != b[k]).collect();
                assert_eq!(along, [axis], "a segment lies along one axis");
                (axis, a.min(b), (b[axis] - a[axis]).abs())
            })
            .collect()
    }

    /// The cells' edges of unit length, each once.
    fn unit_edges(cells: &[[i64; 3]]) -> HashSet<(usize, [i64; 3])> {
        let mut out = HashSet::new();
        for cell in cells {
            for axis in 0..3 {
                let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
                for (a, b) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                    let mut start = *cell;
                    start[u] += a;
                    start[v] += b;
                    out.insert((axis, start));
                }
            }
        }
        out
    }

    #[test]
    fn boxes_draw_each_edge_once_and_edges_in_line_as_one() {
        let origin = DVec3::new(-0.35, 0.05, 1.1);
        let size = 0.25;
        let block: Vec<[i64; 3]> = (0..8).map(|k| [k & 1, (k >> 1) & 1, k >> 2]).collect();
        let crowd: Vec<[i64; 3]> = (0..60)
            .map(|k: i64| [(k * 7) % 5, (k * 3) % 4, (k * 11) % 6])
            .collect();
        // One box: its twelve edges; two side by side: four lines of two
        // along x and six of one either way; a 2 x 2 x 2 block: 3 axes x
        // 3 x 3 lines.
        for (cells, count) in [
            (vec![[0, 0, 0]], Some(12)),
            (vec![[0, 0, 0], [1, 0, 0]], Some(16)),
            (block, Some(27)),
            (crowd, None),
        ] {
            let corners: Vec<DVec3> = cells
                .iter()
                .map(|c| origin + glam::I64Vec3::from_array(*c).as_dvec3() * size)
                .collect();
            let drawn = segments(&corners, size, origin);
            if let Some(count) = count {
                assert_eq!(drawn.len(), count, "{cells:?}");
            }
            // Together they are the cells' edges, none twice.
            let mut covered = HashSet::new();
            for &(axis, start, length) in &drawn {
                for k in 0..length {
                    let mut at = start;
                    at[axis] += k;
                    assert!(
                        covered.insert((axis, at)),
                        "{at:?} along {axis} drawn twice"
                    );
                }
            }
            assert_eq!(covered, unit_edges(&cells));
            // No segment ends where another on its line starts.
            for &(axis, start, length) in &drawn {
                let mut end = start;
                end[axis] += length;
                assert!(
                    !drawn.iter().any(|&(a, s, _)| a == axis && s == end),
                    "{start:?} along {axis} not joined to the next"
                );
            }
        }
    }

    #[test]
    fn impulse_lines_grow_by_a_radius_each_tenfold() {
        let r = 0.1;
        let at = |impulse: f64| impulse_length(impulse, 2.0, r, 1.0);
        assert!((at(2.0) - REFERENCE_RADII * r).abs() < 1e-12);
        assert!((at(20.0) - at(2.0) - RADII_PER_DECADE * r).abs() < 1e-12);
        assert_eq!(at(0.0), 0.0);
        assert_eq!(at(2.0 * 1e-4), 0.0);
    }
}
