//! Every constant of a physics scene, as plain data.
//!
//! The values of [`WorldConfig::default`] are the built-in default scene. The
//! scene-file loader of the program overlays a user's TOML on top of them and
//! checks ranges; [`crate::World::new`] only rejects what cannot be built
//! (bodies that do not fit in the room).

use glam::DVec3;

/// An RGB colour with components in 0..=1 (linear).
pub type Rgb = [f32; 3];

/// The closed room: an axis-aligned box with the floor at y = 0, centred on x = z = 0.
#[derive(Clone, Debug, PartialEq)]
pub struct RoomConfig {
    /// Inner size along x, y and z in metres.
    pub size: DVec3,
    /// Colours of the six surfaces, in [`crate::Surface::ALL`] order:
    /// floor, ceiling, left (-x), right (+x), back (-z), front (+z).
    pub colors: [Rgb; 6],
    /// Coefficient of restitution of a ball bouncing on any surface.
    pub restitution: f64,
    /// Coulomb friction coefficient between a ball and a surface.
    pub friction: f64,
    /// Rolling resistance coefficient of a ball rolling on a surface
    /// (deceleration = coefficient x the normal acceleration).
    pub rolling_resistance: f64,
}

/// A ball placed by hand (E3): where it starts and how it moves. What it
/// leaves out is the scene's: the balls' radius, mass and colour.
#[derive(Clone, Debug, PartialEq)]
pub struct BallPlacement {
    /// Where its centre starts (m).
    pub position: DVec3,
    /// Its velocity at the start (m/s).
    pub velocity: DVec3,
    /// Angular velocity in rad/s (a ball sent rolling spins at v / r).
    pub spin: DVec3,
    /// Its colour, if not the scene's ball colour.
    pub color: Option<Rgb>,
    /// Its radius, if not the scene's (m).
    pub radius: Option<f64>,
    /// Its mass, if not the scene's (kg).
    pub mass: Option<f64>,
}

impl BallPlacement {
    /// A ball of the scene's kind at `position`, moving at `velocity`.
    pub fn new(position: DVec3, velocity: DVec3) -> BallPlacement {
        BallPlacement {
            position,
            velocity,
            spin: DVec3::ZERO,
            color: None,
            radius: None,
            mass: None,
        }
    }
}

/// The balls and how they are started.
#[derive(Clone, Debug, PartialEq)]
pub struct BallsConfig {
    /// How many balls start at random (from the seed), besides the placed ones.
    pub count: usize,
    /// Radius of every random ball (m).
    pub radius: f64,
    /// Mass of every random ball (kg).
    pub mass: f64,
    /// Coefficient of restitution of a ball-ball collision (P2's damping factor).
    pub restitution: f64,
    /// Coulomb friction coefficient between two balls, and between a ball
    /// and a tumbler (see docs/physics.md on which coefficient rules a pair).
    pub friction: f64,
    /// Rolling resistance between two balls (not between a ball and a
    /// tumbler): the resisting torque is this times the normal force times
    /// the pair's rolling radius (r1 r2 / (r1 + r2)), the room's coefficient
    /// for a ball on a wall, where the rolling radius is the ball's.
    pub rolling_resistance: f64,
    /// Initial speeds are drawn uniformly from this range (m/s).
    pub speed_min: f64,
    /// Fastest start of a random ball (m/s).
    pub speed_max: f64,
    /// The balls start in this share of the room's height, from the floor
    /// up (0 < share <= 1): a crowded room can start below the eye.
    pub start_fill: f64,
    /// Colour of a ball that has not hit anything yet.
    pub color: Rgb,
    /// Whether the random balls are poured from a spout instead of all
    /// starting at once.
    pub pour: PourConfig,
    /// Balls placed by hand, in addition to the `count` random ones (which
    /// start in the space they leave free): a scene of placed balls alone
    /// sets `count` to 0, and a scene may also rain random balls on a
    /// placed arrangement. They are the world's first balls, in this order.
    pub placements: Vec<BallPlacement>,
}

/// A spout that pours the random balls into the room one after another, as
/// sand from a funnel: each is let go, falling, from a random point of the
/// spout's mouth (a horizontal disc) as soon as that point is clear.
#[derive(Clone, Debug, PartialEq)]
pub struct PourConfig {
    /// Balls let go per second; 0 pours nothing and every random ball
    /// starts at once, placed at random.
    pub rate: f64,
    /// The centre of the spout's mouth (m).
    pub spout: DVec3,
    /// The radius of the spout's mouth (m).
    pub radius: f64,
}

impl BallsConfig {
    /// All the balls: the placed ones and the random ones.
    pub fn total(&self) -> usize {
        self.placements.len() + self.count
    }

    /// The radius of placed ball `k`.
    pub fn placed_radius(&self, k: usize) -> f64 {
        self.placements[k].radius.unwrap_or(self.radius)
    }

    /// The largest radius of any ball.
    pub fn largest_radius(&self) -> f64 {
        (0..self.placements.len()).fold(self.radius, |r, k| r.max(self.placed_radius(k)))
    }
}

/// One sphere of a tumbler's compound shape, in the tumbler's body frame.
///
/// The body frame has its origin at the centre of the bottom sphere and its
/// +y axis along the tumbler's axis of symmetry, so a sphere is placed by its
/// height on that axis alone.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SphereSpec {
    /// Height of the sphere's centre above the bottom sphere's centre, along the axis (m).
    pub height: f64,
    /// Its radius (m).
    pub radius: f64,
    /// Its mass (kg).
    pub mass: f64,
}

/// Where a tumbler starts: its position on the floor and an initial tilt.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TumblerPlacement {
    /// x and z of the bottom sphere's centre.
    pub x: f64,
    /// Where it stands along z (m).
    pub z: f64,
    /// Tilt axis (horizontal; normalised when used) and angle in degrees.
    pub tilt_axis: DVec3,
    /// How far it leans at the start, about `tilt_axis` (degrees).
    pub tilt_deg: f64,
}

/// The tumblers: one shared shape, several placements.
#[derive(Clone, Debug, PartialEq)]
pub struct TumblersConfig {
    /// The compound shape. The first sphere is the round bottom, which rests
    /// on the floor; every other sphere must be smaller than it.
    pub spheres: Vec<SphereSpec>,
    /// Where each tumbler stands.
    pub placements: Vec<TumblerPlacement>,
    /// Restitution of impacts between a tumbler and anything.
    pub restitution: f64,
    /// Coulomb friction between the round bottom and the floor.
    pub floor_friction: f64,
    /// Rate (1/s) at which rocking and spinning lose energy; 0 rocks forever.
    pub damping: f64,
    /// The tumblers' colours, in turn.
    pub colors: Vec<Rgb>,
}

/// The fireball (P8): constant speed, no gravity, a ball's mass.
#[derive(Clone, Debug, PartialEq)]
pub struct FireballConfig {
    /// Its radius (m).
    pub radius: f64,
    /// The speed it keeps (m/s).
    pub speed: f64,
    /// Where `F` launches it from when the caller does not pass a position.
    pub spawn: DVec3,
    /// Where it flies from the spawn point.
    pub direction: DVec3,
    /// What a hit does to a ball: `true`, the ball is caught (it leaves the
    /// simulation at once; the effects draw it collapsing) and comes back
    /// when the balls are re-initialised; `false`, it is knocked away.
    pub consumes_balls: bool,
    /// Launched from `spawn` when the world is built, rather than by the user.
    pub starts_active: bool,
}

/// The hand that drags a grabbed tumbler: a spring-damper at the grab point.
#[derive(Clone, Debug, PartialEq)]
pub struct GrabConfig {
    /// Spring stiffness in N/m.
    pub stiffness: f64,
    /// Damping in N s/m, on the grab point's velocity.
    pub damping: f64,
    /// The largest force the hand applies, in N.
    pub max_force: f64,
}

/// Time stepping and contact solving.
#[derive(Clone, Debug, PartialEq)]
pub struct SolverConfig {
    /// Fixed time step in seconds.
    pub dt: f64,
    /// Gauss-Seidel iterations per contact stage.
    pub iterations: usize,
    /// Below this approach speed (m/s) an impact does not bounce: it rests.
    pub bounce_threshold: f64,
    /// Below this approach speed (m/s) a contact emits no event and changes no colour.
    pub event_threshold: f64,
}

/// Everything the physics needs to build a [`crate::World`].
#[derive(Clone, Debug, PartialEq)]
pub struct WorldConfig {
    /// Gravitational acceleration in m/s^2, acting along -y.
    pub gravity: f64,
    /// The room's size, materials and colours.
    pub room: RoomConfig,
    /// The balls.
    pub balls: BallsConfig,
    /// The tumblers.
    pub tumblers: TumblersConfig,
    /// The fireball.
    pub fireball: FireballConfig,
    /// The hand that drags tumblers.
    pub grab: GrabConfig,
    /// The fixed step and the contact solver.
    pub solver: SolverConfig,
}

impl Default for WorldConfig {
    fn default() -> Self {
        let placements = [
            (-2.2, -1.2),
            (2.2, -1.2),
            (0.0, -2.4),
            (-1.4, 1.6),
            (1.4, 1.6),
        ]
        .map(|(x, z)| TumblerPlacement {
            x,
            z,
            tilt_axis: DVec3::X,
            tilt_deg: 0.0,
        })
        .to_vec();
        WorldConfig {
            gravity: 9.81,
            room: RoomConfig {
                size: DVec3::new(8.0, 4.0, 8.0),
                colors: [
                    [0.62, 0.42, 0.24], // floor: wood
                    [0.92, 0.91, 0.88], // ceiling: white
                    [0.78, 0.12, 0.10], // left: red
                    [0.16, 0.62, 0.22], // right: green
                    [0.90, 0.86, 0.74], // back: cream
                    [0.20, 0.32, 0.78], // front: blue
                ],
                restitution: 0.75,
                friction: 0.4,
                rolling_resistance: 0.02,
            },
            balls: BallsConfig {
                count: 30,
                radius: 0.12,
                mass: 0.25,
                restitution: 0.85,
                friction: 0.4,
                rolling_resistance: 0.02,
                speed_min: 2.0,
                speed_max: 6.0,
                start_fill: 1.0,
                color: [0.95, 0.95, 0.95],
                pour: PourConfig {
                    rate: 0.0,
                    spout: DVec3::new(0.0, 2.0, 0.0),
                    radius: 0.25,
                },
                placements: Vec::new(),
            },
            tumblers: TumblersConfig {
                spheres: vec![
                    SphereSpec {
                        height: 0.0,
                        radius: 0.30,
                        mass: 1.0,
                    }, // round bottom
                    SphereSpec {
                        height: -0.19,
                        radius: 0.10,
                        mass: 7.0,
                    }, // ballast
                    SphereSpec {
                        height: 0.28,
                        radius: 0.22,
                        mass: 0.25,
                    }, // belly
                    SphereSpec {
                        height: 0.46,
                        radius: 0.18,
                        mass: 0.15,
                    }, // chest
                    SphereSpec {
                        height: 0.62,
                        radius: 0.16,
                        mass: 0.12,
                    }, // head
                    SphereSpec {
                        height: 0.78,
                        radius: 0.05,
                        mass: 0.02,
                    }, // top knot
                ],
                placements,
                restitution: 0.5,
                floor_friction: 0.6,
                damping: 0.35,
                colors: vec![
                    [0.85, 0.15, 0.12],
                    [0.95, 0.65, 0.10],
                    [0.20, 0.55, 0.85],
                    [0.55, 0.25, 0.70],
                    [0.10, 0.65, 0.55],
                ],
            },
            fireball: FireballConfig {
                radius: 0.2,
                speed: 6.0,
                spawn: DVec3::new(-1.5, 1.6, -3.0),
                direction: DVec3::new(0.3, -0.1, 1.0),
                consumes_balls: true,
                starts_active: false,
            },
            grab: GrabConfig {
                stiffness: 250.0,
                damping: 70.0,
                max_force: 100.0,
            },
            solver: SolverConfig {
                dt: 1.0 / 120.0,
                iterations: 8,
                bounce_threshold: 0.2,
                event_threshold: 0.05,
            },
        }
    }
}
