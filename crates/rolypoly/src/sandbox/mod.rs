//! The toy as a player drives it, whatever draws it: the running
//! simulation, the settings as the player has left them, pause, single
//! steps and the time scale, thrown balls, and the scene chosen from a list.
//! The window's keys and panel only call into this, so that all of it is
//! tested without a window.

use glam::DVec3;
use rolypoly_physics::{BuildError, World};

use crate::scene::{self, Scene, SceneError};
use crate::simulation::Simulation;

mod fixed_steps;
mod playback;
mod shipped;

pub use fixed_steps::{MAX_CATCH_UP, STEP_BUDGET_PER_FRAME};
pub use playback::{Playback, TIME_SCALES};
pub use shipped::{SHIPPED_SCENES, ShippedScene};

/// Most balls a player may throw into one run of a scene; I (restart)
/// takes them away and the count starts again.
pub const MAX_THROWN: usize = 500;

/// Speed a ball is thrown at unless the player sets another (m/s), and the
/// range they may set.
pub const THROW_SPEED: f64 = 8.0;
pub const THROW_SPEEDS: (f64, f64) = (0.5, 40.0);

/// Why a ball was not thrown.
#[derive(Debug, thiserror::Error, PartialEq, Eq)]
#[error("{MAX_THROWN} balls thrown already: press I to restart and throw again")]
pub struct ThrowRefused;

/// The running toy.
pub struct Sandbox {
    pub sim: Simulation,
    /// The settings as the player left them. The world runs on them, but
    /// for those that wait for a restart ([`Sandbox::restart_pending`]).
    scene: Scene,
    /// What the scene is called: its file or shipped name.
    scene_name: String,
    seed: u64,
    pub playback: Playback,
    /// Speed of a thrown ball (m/s).
    pub throw_speed: f64,
    thrown: usize,
}

impl Sandbox {
    /// The toy on `scene`, its random balls drawn from `seed`.
    pub fn new(scene: Scene, name: &str, seed: u64) -> Result<Sandbox, BuildError> {
        let world = World::new(scene.world.clone(), seed)?;
        Ok(Sandbox::with_world(world, scene, name, seed))
    }

    /// The toy on `world`, built from `scene` with `seed`.
    pub fn with_world(world: World, scene: Scene, name: &str, seed: u64) -> Sandbox {
        Sandbox {
            sim: Simulation::new(world, scene.effects.clone(), seed),
            scene,
            scene_name: name.to_owned(),
            seed,
            playback: Playback::default(),
            throw_speed: THROW_SPEED,
            thrown: 0,
        }
    }

    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    pub fn scene_name(&self) -> &str {
        &self.scene_name
    }

    pub fn seed(&self) -> u64 {
        self.seed
    }

    pub fn world(&self) -> &World {
        &self.sim.world
    }

    /// Takes settings the player changed: checked by the scene file's
    /// rules (and refused whole if one breaks them); those the running
    /// world can take hold from the next step, the rest from the next
    /// restart.
    pub fn set_scene(&mut self, scene: Scene) -> Result<(), SceneError> {
        scene::validate(&scene)?;
        self.sim.world.tune(&scene.world);
        self.scene = scene;
        Ok(())
    }

    /// Whether some changed settings wait for a restart (I).
    pub fn restart_pending(&self) -> bool {
        self.sim.world.needs_rebuild(&self.scene.world)
            || *self.sim.fx.config() != self.scene.effects
    }

    /// I: the balls anew, thrown balls gone; the whole world built anew
    /// from the settings when some wait for it.
    pub fn restart(&mut self) -> Result<(), BuildError> {
        self.thrown = 0;
        if self.restart_pending() {
            let world = World::new(self.scene.world.clone(), self.seed)?;
            self.sim = Simulation::new(world, self.scene.effects.clone(), self.seed);
            Ok(())
        } else {
            self.sim.world.reset_balls()
        }
    }

    /// Another scene at once, from the start; the time scale and pause stay
    /// as they were.
    pub fn load(&mut self, scene: Scene, name: &str) -> Result<(), BuildError> {
        let world = World::new(scene.world.clone(), self.seed)?;
        self.sim = Simulation::new(world, scene.effects.clone(), self.seed);
        self.scene = scene;
        self.scene_name = name.to_owned();
        self.thrown = 0;
        Ok(())
    }

    /// Throws a ball from `from` along `direction` at the throw speed.
    /// Returns its number.
    pub fn throw(&mut self, from: DVec3, direction: DVec3) -> Result<usize, ThrowRefused> {
        if self.thrown >= MAX_THROWN {
            return Err(ThrowRefused);
        }
        self.thrown += 1;
        let velocity = direction.normalize_or(DVec3::NEG_Z) * self.throw_speed;
        Ok(self.sim.world.throw_ball(from, velocity))
    }

    /// Balls thrown since the scene started or restarted.
    pub fn thrown(&self) -> usize {
        self.thrown
    }

    /// Runs the steps a frame of `elapsed` real seconds asks for (see
    /// [`Playback::advance`]); `spent` is the time the frame has spent
    /// stepping. Returns how many ran.
    pub fn frame(&mut self, elapsed: f64, spent: impl FnMut() -> std::time::Duration) -> u32 {
        let dt = self.sim.world.config().solver.dt;
        let sim = &mut self.sim;
        self.playback.advance(elapsed, dt, spent, || sim.tick())
    }
}

#[cfg(test)]
mod tests;
