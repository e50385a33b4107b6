//! The effects as a whole: the trail behind the fireball, and the hit events
//! that emit particles every update until they expire (X2-X5).
//!
//! It consumes the physics' events and knows nothing of how it is drawn.
//! Nothing updates while the world is paused: the caller simply does not
//! call [`Effects::update`].

use crate::config::EffectsConfig;
use crate::particle::{Particle, ParticleKind};
use crate::ring::ParticleRing;
use glam::Vec3;
use rolypoly_physics::{Event, EventKind, Fireball, Rng, World};
use serde::{Deserialize, Serialize};
use std::collections::VecDeque;

/// A fireball hit on a wall (or a tumbler): a ring spreading in its plane.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct WallHit {
    /// Where it hit (m).
    pub centre: Vec3,
    /// The surface's normal there.
    pub normal: Vec3,
    /// Seconds since the hit.
    pub age: f32,
    debt: f32,
}

/// A fireball hit on a ball: the ball and the space around it collapse into
/// its centre, then burst.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct BallHit {
    /// The struck ball's centre (m).
    pub centre: Vec3,
    /// Its radius as it was (m).
    pub ball_radius: f32,
    /// Its colour as it was.
    pub ball_color: Vec3,
    /// Seconds since the hit.
    pub age: f32,
    debt: f32,
}

/// The flash of the fireball's latest hit: where, and how strong now (1 at
/// the hit, fading to 0 over [`FLASH_SECONDS`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Flash {
    /// Where the hit was (m).
    pub position: Vec3,
    /// How strong the flash is now, 1 down to 0.
    pub strength: f32,
}

/// How long the flash of a hit lasts.
pub const FLASH_SECONDS: f32 = 0.3;

/// Counts for a HUD.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EffectsStats {
    /// Particles alive now.
    pub live: usize,
    /// Most alive at once.
    pub capacity: usize,
    /// Spawns refused so far because the ring was full.
    pub dropped: u64,
    /// Wall hits still spawning or alive.
    pub wall_hits: usize,
    /// Ball hits still collapsing or bursting.
    pub ball_hits: usize,
}

/// The particle effects of the fireball: its trail and its hits, driven by the world's events.
#[derive(Clone, Serialize, Deserialize)]
pub struct Effects {
    config: EffectsConfig,
    ring: ParticleRing,
    wall_hits: VecDeque<WallHit>,
    ball_hits: VecDeque<BallHit>,
    rng: Rng,
    /// Seconds of effects time (drives the fireball's breathing).
    time: f64,
    /// Seconds until the next trail cube.
    trail_wait: f64,
    /// The fireball's position at the previous update.
    last_fireball: Option<Vec3>,
}

const QUEUE_CAPACITY: usize = 64;

impl Effects {
    /// No particles yet, the random sequence drawn from `seed`.
    pub fn new(config: EffectsConfig, seed: u64) -> Effects {
        let blank = Particle::new(ParticleKind::Trail, Vec3::ZERO, 0.0, 0.0, 0.0);
        Effects {
            ring: ParticleRing::new(config.capacity, blank),
            wall_hits: VecDeque::with_capacity(QUEUE_CAPACITY),
            ball_hits: VecDeque::with_capacity(QUEUE_CAPACITY),
            rng: Rng::new(seed ^ 0x5EED_F1AE_u64),
            time: 0.0,
            trail_wait: 0.0,
            last_fireball: None,
            config,
        }
    }

    /// The constants it runs on.
    pub fn config(&self) -> &EffectsConfig {
        &self.config
    }

    /// Starts hit events for the fireball's impacts among `events`. `world`
    /// tells the struck ball's size and colour.
    pub fn consume(&mut self, events: &[Event], world: &World) {
        for e in events {
            match e.kind {
                EventKind::FireballSurface { .. } | EventKind::FireballTumbler { .. } => {
                    self.wall_hits.push_back(WallHit {
                        centre: e.point.as_vec3(),
                        normal: e.normal.as_vec3(),
                        age: 0.0,
                        debt: 0.0,
                    });
                }
                EventKind::FireballBall { ball } => {
                    let balls = world.balls();
                    let radius = balls.radii().get(ball).copied().unwrap_or(0.0);
                    let tint = balls.tints().get(ball).copied();
                    self.ball_hits.push_back(BallHit {
                        centre: (e.point - e.normal * radius).as_vec3(),
                        ball_radius: radius as f32,
                        ball_color: tint
                            .map_or(Vec3::ONE, |t| Vec3::from_array(world.tint_color(t))),
                        age: 0.0,
                        debt: 0.0,
                    });
                }
                _ => {}
            }
        }
    }

    /// Advances everything by `dt` seconds. `fireball` is the fireball now,
    /// if it flies.
    pub fn update(&mut self, dt: f64, fireball: Option<&Fireball>) {
        self.time += dt;
        self.ring.update(dt as f32);
        self.emit_trail(dt, fireball);
        self.emit_wall_hits(dt as f32);
        self.emit_ball_hits(dt as f32);
    }

    fn random_direction(&mut self) -> Vec3 {
        self.rng.direction().as_vec3()
    }

    fn spin(&mut self) -> Vec3 {
        self.random_direction() * self.rng.range(0.0, std::f64::consts::PI) as f32
    }

    /// X2: cubes at random intervals along the path flown since the last update.
    fn emit_trail(&mut self, dt: f64, fireball: Option<&Fireball>) {
        let Some(f) = fireball else {
            self.last_fireball = None;
            return;
        };
        let now = f.position.as_vec3();
        let before = self.last_fireball.unwrap_or(now);
        self.last_fireball = Some(now);
        let cfg = self.config.trail.clone();
        let radius = f.radius as f32;
        let mut waited = dt;
        while self.trail_wait <= waited {
            waited -= self.trail_wait.max(0.0);
            // Where the fireball was when this cube was due.
            let along = if dt > 0.0 {
                1.0 - (waited / dt) as f32
            } else {
                1.0
            };
            let jitter = self.random_direction() * radius * 0.4;
            let mut p = Particle::new(
                ParticleKind::Trail,
                before.lerp(now, along) + jitter,
                cfg.life as f32,
                (cfg.size * self.rng.range(0.6, 1.2)) as f32 * radius,
                self.rng.range(0.6, 1.0) as f32,
            );
            p.spin = self.spin();
            let _ = self.ring.spawn(p);
            self.trail_wait = self.rng.range(cfg.interval_min, cfg.interval_max);
        }
        self.trail_wait -= waited;
    }

    /// X3: every update, cubes on a ring in the wall's plane whose radius
    /// grows over the event's life.
    fn emit_wall_hits(&mut self, dt: f32) {
        let cfg = self.config.wall_hit.clone();
        let mut hits = std::mem::take(&mut self.wall_hits);
        for hit in hits.iter_mut() {
            hit.age += dt;
            let t = (hit.age / cfg.duration as f32).min(1.0);
            let radius = cfg.radius as f32 * t.sqrt();
            let (t1, t2) = hit.normal.any_orthonormal_pair();
            hit.debt += cfg.rate as f32 * dt;
            while hit.debt >= 1.0 {
                hit.debt -= 1.0;
                let angle = self.rng.range(0.0, std::f64::consts::TAU) as f32;
                let r = radius * self.rng.range(0.85, 1.0) as f32;
                let at = hit.centre + hit.normal * 0.02 + (t1 * angle.cos() + t2 * angle.sin()) * r;
                let mut p = Particle::new(
                    ParticleKind::WallHit,
                    at,
                    cfg.life as f32,
                    (cfg.size * self.rng.range(0.7, 1.3)) as f32,
                    1.0,
                );
                p.spin = self.spin();
                let _ = self.ring.spawn(p);
            }
        }
        while hits.front().is_some_and(|h| h.age >= cfg.duration as f32) {
            hits.pop_front();
        }
        self.wall_hits = hits;
    }

    /// X4: every update, cubes on a shrinking shell around the ball that fall
    /// to its centre, arriving as their lives end; then the burst.
    fn emit_ball_hits(&mut self, dt: f32) {
        let cfg = self.config.ball_hit.clone();
        let duration = cfg.duration as f32;
        let mut hits = std::mem::take(&mut self.ball_hits);
        for hit in hits.iter_mut() {
            hit.age += dt;
            let t = (hit.age / duration).min(1.0);
            let remaining = duration - hit.age;
            if remaining > 0.0 {
                let radius = cfg.radius as f32 * (1.0 - t) + hit.ball_radius * (1.0 - t);
                hit.debt += cfg.rate as f32 * dt;
                while hit.debt >= 1.0 {
                    hit.debt -= 1.0;
                    let from = hit.centre + self.random_direction() * radius;
                    // It must reach the centre by the time the collapse ends.
                    let life = (cfg.life as f32).min(remaining);
                    let mut p = Particle::new(
                        ParticleKind::Collapse,
                        from,
                        life,
                        (cfg.size * self.rng.range(0.7, 1.3)) as f32,
                        1.0,
                    );
                    p.target = hit.centre;
                    p.spin = self.spin();
                    let _ = self.ring.spawn(p);
                }
            } else {
                // The collapse is over: two particles burst from the centre.
                for share in [1.0f32, 0.6] {
                    let mut p = Particle::new(
                        ParticleKind::Burst,
                        hit.centre,
                        cfg.burst_life as f32,
                        cfg.burst_size as f32 * share,
                        1.0,
                    );
                    p.spin = self.spin();
                    let _ = self.ring.spawn(p);
                }
            }
        }
        hits.retain(|h| h.age < duration);
        self.ball_hits = hits;
    }

    /// The living particles, oldest first.
    pub fn particles(&self) -> impl Iterator<Item = &Particle> {
        self.ring.live()
    }

    /// The wall hits still going, oldest first.
    pub fn wall_hits(&self) -> impl Iterator<Item = &WallHit> {
        self.wall_hits.iter()
    }

    /// Balls caught in a collapse, as they are to be drawn: centre, radius
    /// (shrinking with the collapse) and colour.
    pub fn captured_balls(&self) -> impl Iterator<Item = (Vec3, f32, Vec3)> + '_ {
        let duration = self.config.ball_hit.duration as f32;
        self.ball_hits.iter().map(move |h| {
            (
                h.centre,
                h.ball_radius * (1.0 - h.age / duration).max(0.0),
                h.ball_color,
            )
        })
    }

    /// The flash of the youngest hit, while it lasts: it fades as the
    /// square of the time left, quickly at first like a spark.
    pub fn flash(&self) -> Option<Flash> {
        let walls = self.wall_hits.iter().map(|h| (h.centre, h.age));
        let balls = self.ball_hits.iter().map(|h| (h.centre, h.age));
        walls
            .chain(balls)
            .filter(|&(_, age)| age < FLASH_SECONDS)
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(position, age)| Flash {
                position,
                strength: (1.0 - age / FLASH_SECONDS).powi(2),
            })
    }

    /// Seconds of effects time so far.
    pub fn time(&self) -> f64 {
        self.time
    }

    /// Counts for a HUD.
    pub fn stats(&self) -> EffectsStats {
        EffectsStats {
            live: self.ring.live().count(),
            capacity: self.ring.capacity(),
            dropped: self.ring.dropped(),
            wall_hits: self.wall_hits.len(),
            ball_hits: self.ball_hits.len(),
        }
    }

    /// Forgets every particle and event (a fresh start).
    pub fn clear(&mut self) {
        self.ring.clear();
        self.wall_hits.clear();
        self.ball_hits.clear();
        self.last_fireball = None;
    }
}
