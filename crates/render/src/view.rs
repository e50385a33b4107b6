//! What the renderer draws: plain data, read from the physics world.
//!
//! The renderer never reaches into the physics; it is handed a `SceneView`.

use glam::{Mat4, Quat, Vec3};
use rolypoly_fx::{Effects, FireballLook, ParticleKind};
use rolypoly_fx::{Flash, SHELL_COLORS};
use rolypoly_physics::World;

use crate::debug_view::DebugMark;

/// The point light's constants (a scene file's `[light]`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightConfig {
    /// Linear RGB colour, each component 0..=1.
    pub color: [f32; 3],
    /// Brightness multiplier of the colour.
    pub intensity: f32,
    /// Strength of the even light that reaches what is in shadow where the
    /// bounce light (`indirect`) is off; the bounce, on, is worked out from
    /// the lights.
    pub ambient: f32,
    /// Radius of the visible bulb (metres).
    pub bulb_radius: f32,
    /// How far below the ceiling's centre the light hangs (metres).
    pub drop: f32,
    /// Glow around what is brighter than white.
    pub bloom: bool,
    /// How much of the glow is added to the picture.
    pub bloom_strength: f32,
    /// How bright (linear, before exposure) a pixel must be to glow.
    pub bloom_threshold: f32,
    /// The flying fireball, and the flash of its hits, light the room.
    pub fireball_light: bool,
    /// One bounce of diffuse light from the room's six surfaces.
    pub indirect: bool,
    /// Darkening where surfaces meet: under a ball, between two balls.
    pub occlusion: bool,
}

impl Default for LightConfig {
    fn default() -> Self {
        LightConfig {
            color: [1.0, 0.86, 0.68],
            intensity: 3.2,
            ambient: 0.22,
            bulb_radius: 0.09,
            drop: 0.25,
            bloom: true,
            bloom_strength: 1.0,
            bloom_threshold: 2.0,
            fireball_light: true,
            indirect: true,
            occlusion: true,
        }
    }
}

/// The point light at the centre of the ceiling (S2).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Light {
    /// Where the bulb is (m).
    pub position: Vec3,
    /// Linear RGB colour times intensity.
    pub color: Vec3,
    /// Strength of the even light that reaches what is in shadow where the
    /// bounce light (`indirect`) is off; the bounce, on, is worked out from
    /// the lights.
    pub ambient: f32,
    /// Radius of the visible bulb.
    pub bulb_radius: f32,
    /// The glow: its strength and threshold, or none.
    pub bloom: Option<Bloom>,
    /// Whether the fireball's light, when there is one, is drawn.
    pub fireball_light: bool,
    /// Whether one bounce of light off the room's surfaces is drawn.
    pub indirect: bool,
    /// Whether contact occlusion is drawn.
    pub occlusion: bool,
}

/// Glow around what is brighter than `threshold`, added at `strength`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bloom {
    /// How much of the glow is added.
    pub strength: f32,
    /// Linear brightness above which things glow.
    pub threshold: f32,
}

/// A point light: the ceiling light, or the fireball's glow and its hits'
/// flashes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointLight {
    /// Where it is (m).
    pub position: Vec3,
    /// Linear RGB colour times intensity.
    pub color: Vec3,
    /// It falls off as `1 / (c0 + c1 d + c2 d^2)` at distance `d`.
    pub falloff: [f32; 3],
    /// Where given, it fades smoothly to nothing at this distance (m), so
    /// that a bright light near lights nothing far.
    pub reach: Option<f32>,
}

/// The ceiling light's falloff: gentler than the inverse square near the
/// light, so the floor under it is not burnt white, and like it far away.
pub const CEILING_FALLOFF: [f32; 3] = [1.0, 0.05, 0.04];

/// The fireball's falloff: at half strength a metre away, bright on the
/// floor and walls it passes ...
const FIREBALL_FALLOFF: [f32; 3] = [1.0, 0.0, 1.0];
/// ... and nothing beyond three metres: it lights what it passes, not the
/// whole room.
const FIREBALL_REACH: f32 = 3.0;

/// How bright the flash of a hit is at its start, in units of the
/// fireball's inner shell colour.
const FLASH_BRIGHTNESS: f32 = 3.0;

impl PointLight {
    /// The fireball's light: its glow while it flies, and the flash of its
    /// latest hit, from where the fireball is or, once it is gone, from
    /// where it hit.
    pub fn of_fireball(look: Option<&FireballLook>, flash: Option<Flash>) -> Option<PointLight> {
        let flash_color = |f: Flash| SHELL_COLORS[0] * (FLASH_BRIGHTNESS * f.strength);
        match (look, flash) {
            (Some(look), flash) => Some(PointLight {
                position: look.centre,
                color: look.light() + flash.map_or(Vec3::ZERO, flash_color),
                falloff: FIREBALL_FALLOFF,
                reach: Some(FIREBALL_REACH),
            }),
            (None, Some(f)) => Some(PointLight {
                position: f.position,
                color: flash_color(f),
                falloff: FIREBALL_FALLOFF,
                reach: Some(FIREBALL_REACH),
            }),
            (None, None) => None,
        }
    }
}

impl Light {
    /// The ceiling light as a point light.
    pub fn point(&self) -> PointLight {
        PointLight {
            position: self.position,
            color: self.color,
            falloff: CEILING_FALLOFF,
            reach: None,
        }
    }

    /// The light of `config`, hanging below the centre of the ceiling of a
    /// room of `room_size`.
    pub fn ceiling_centre(room_size: Vec3, config: &LightConfig) -> Light {
        Light {
            position: Vec3::new(0.0, room_size.y - config.drop, 0.0),
            color: Vec3::from_array(config.color) * config.intensity,
            ambient: config.ambient,
            bulb_radius: config.bulb_radius,
            bloom: config.bloom.then_some(Bloom {
                strength: config.bloom_strength,
                threshold: config.bloom_threshold,
            }),
            fireball_light: config.fireball_light,
            indirect: config.indirect,
            occlusion: config.occlusion,
        }
    }
}

/// A ball as it is drawn.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BallView {
    /// Its centre (m).
    pub position: Vec3,
    /// Its radius (m).
    pub radius: f32,
    /// Its colour (linear RGB).
    pub color: Vec3,
}

/// A tumbler as it is drawn.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TumblerView {
    /// Centre of the bottom sphere (the mesh's origin).
    pub position: Vec3,
    /// How it is turned.
    pub orientation: Quat,
    /// 1 normally; larger to show that it is held.
    pub scale: f32,
    /// Its paint's base colour (linear RGB).
    pub color: Vec3,
}

impl TumblerView {
    /// Mesh space to world space.
    pub fn model(&self) -> Mat4 {
        Mat4::from_scale_rotation_translation(
            Vec3::splat(self.scale),
            self.orientation,
            self.position,
        )
    }
}

/// A glowing cube of the particle effects.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ParticleView {
    /// Its centre (m).
    pub position: Vec3,
    /// Edge length in metres.
    pub size: f32,
    /// How it is turned.
    pub rotation: Quat,
    /// Linear HDR colour (brighter than 1 glows).
    pub color: Vec3,
    /// Its opacity.
    pub alpha: f32,
}

/// The glow colour of each kind of particle: linear HDR, bright enough
/// (above the default bloom threshold of 2) to glow.
pub fn particle_color(kind: ParticleKind) -> Vec3 {
    match kind {
        ParticleKind::Trail => Vec3::new(1.0, 0.3, 0.04) * 3.2,
        ParticleKind::WallHit => Vec3::new(0.05, 0.7, 1.0) * 3.2,
        ParticleKind::Collapse => Vec3::new(0.65, 0.15, 1.0) * 3.2,
        ParticleKind::Burst => Vec3::new(1.0, 0.5, 1.0) * 4.0,
    }
}

/// The balls as the GPU engine wrote them, on the GPU: `count` instances
/// of 32 bytes (centre and radius, colour, a pad), as the renderer's own
/// ball instances are laid out, in a vertex buffer of the renderer's
/// device.
#[derive(Clone, Debug)]
pub struct GpuBallBuffer {
    /// The instances.
    pub buffer: wgpu::Buffer,
    /// How many are in use.
    pub count: u32,
}

impl PartialEq for GpuBallBuffer {
    /// The same buffer, as many balls.
    fn eq(&self, other: &GpuBallBuffer) -> bool {
        self.buffer == other.buffer && self.count == other.count
    }
}

/// Everything a frame draws: plain data read from the world and the effects.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneView {
    /// The room's inner size (m).
    pub room_size: Vec3,
    /// Floor, ceiling, left, right, back, front.
    pub room_colors: [Vec3; 6],
    /// The ceiling light.
    pub light: Light,
    /// The balls in play.
    pub balls: Vec<BallView>,
    /// The tumblers.
    pub tumblers: Vec<TumblerView>,
    /// The particle effects' cubes.
    pub particles: Vec<ParticleView>,
    /// The fireball's look, while it flies.
    pub fireball: Option<FireballLook>,
    /// The fireball's light (drawn where `light.fireball_light` says so).
    pub fireball_light: Option<PointLight>,
    /// The debug views' marks (see [`SceneView::with_debug`]).
    pub debug_marks: Vec<DebugMark>,
    /// The balls on the GPU, drawn from there instead of `balls` (which is
    /// then empty), where the GPU engine steps them.
    pub gpu_balls: Option<GpuBallBuffer>,
}

impl SceneView {
    /// Reads the world as it is now. `held` is the tumbler to draw enlarged.
    pub fn from_world(world: &World, held: Option<usize>) -> SceneView {
        let config = world.config();
        let room_size = config.room.size.as_vec3();
        let b = world.balls();
        let balls = (0..b.len())
            .filter(|&i| b.alive()[i])
            .map(|i| BallView {
                position: b.positions()[i].as_vec3(),
                radius: b.radii()[i] as f32,
                color: Vec3::from_array(world.tint_color(b.tints()[i])),
            })
            .collect();
        let colors = &config.tumblers.colors;
        let tumblers = world
            .tumblers()
            .iter()
            .enumerate()
            .map(|(i, t)| TumblerView {
                position: t.bottom_center().as_vec3(),
                orientation: t.orientation().as_quat(),
                scale: if held == Some(i) { 1.15 } else { 1.0 },
                color: colors
                    .get(i % colors.len().max(1))
                    .map_or(Vec3::ONE, |c| Vec3::from_array(*c)),
            })
            .collect();
        let fireball = world
            .fireball()
            .map(|f| FireballLook::at(f.position.as_vec3(), f.radius as f32, world.time()));
        SceneView {
            room_size,
            room_colors: config.room.colors.map(Vec3::from_array),
            light: Light::ceiling_centre(room_size, &LightConfig::default()),
            balls,
            tumblers,
            particles: Vec::new(),
            fireball_light: PointLight::of_fireball(fireball.as_ref(), None),
            fireball,
            debug_marks: Vec::new(),
            gpu_balls: None,
        }
    }

    /// Lights the view with `config` instead of the default light.
    pub fn with_light(mut self, config: &LightConfig) -> SceneView {
        self.light = Light::ceiling_centre(self.room_size, config);
        self
    }

    /// Adds what the effects show: the particles, the balls caught in a
    /// collapse, and the fireball's look at the effects' own time.
    pub fn with_effects(mut self, effects: &Effects, world: &World) -> SceneView {
        self.particles
            .extend(effects.particles().map(|p| ParticleView {
                position: p.position(),
                size: p.size(),
                rotation: Quat::from_scaled_axis(p.spin),
                color: particle_color(p.kind),
                alpha: p.alpha(),
            }));
        self.balls.extend(
            effects
                .captured_balls()
                .map(|(position, radius, color)| BallView {
                    position,
                    radius,
                    color,
                }),
        );
        if let Some(f) = world.fireball() {
            self.fireball = Some(FireballLook::at(
                f.position.as_vec3(),
                f.radius as f32,
                effects.time(),
            ));
        }
        self.fireball_light = PointLight::of_fireball(self.fireball.as_ref(), effects.flash());
        self
    }
}
