//! The balls on whichever engine steps them: one type for the program, the
//! sandbox, `simulate`, the sound and the Python package, so that none of
//! them branches on the engine. The CPU engine's balls live in the world
//! and are stepped by its step; the GPU engine's were taken out of the
//! world onto the graphics adapter, and are stepped there after the
//! world's tumblers and fireball.

use std::borrow::Cow;
use std::sync::{Arc, Mutex, MutexGuard, PoisonError};

use glam::DVec3;
use rolypoly_gpu::{GpuBalls, GpuError, GpuSnapshot};
use rolypoly_physics::{Balls, Event, World};
use rolypoly_render::GpuBallBuffer;

use crate::engine::Engine;

/// The balls of a simulation and the engine that steps them. A clone
/// shares the GPU engine's balls (a copy on the GPU is what
/// [`BallEngine::snapshot`] is for).
#[derive(Clone, Default)]
pub enum BallEngine {
    /// The CPU engine: the balls are the world's.
    #[default]
    Cpu,
    /// The GPU engine, listened to: its impacts are reported as the CPU
    /// engine's world reports them, for the effects and the sound.
    Gpu(Arc<Mutex<GpuBalls>>),
}

impl BallEngine {
    /// The GPU engine stepping `balls` (taken out of their world), its
    /// impacts listened to.
    pub fn gpu(mut balls: GpuBalls) -> BallEngine {
        balls.listen(true);
        BallEngine::Gpu(Arc::new(Mutex::new(balls)))
    }

    /// Which engine it is.
    pub fn engine(&self) -> Engine {
        match self {
            BallEngine::Cpu => Engine::Cpu,
            BallEngine::Gpu(_) => Engine::Gpu,
        }
    }

    /// The GPU engine, where it steps the balls.
    pub fn gpu_balls(&self) -> Option<MutexGuard<'_, GpuBalls>> {
        match self {
            BallEngine::Cpu => None,
            BallEngine::Gpu(gpu) => Some(gpu.lock().unwrap_or_else(PoisonError::into_inner)),
        }
    }

    /// One fixed step of `world` and its balls; the step's events (the
    /// world's, then the GPU engine's catches and impacts, which come
    /// [`rolypoly_gpu::REPORT_DELAY`] steps late) into `events`.
    pub fn step(&self, world: &mut World, events: &mut Vec<Event>) -> Result<(), GpuError> {
        world.step();
        world.take_events(events);
        match self.gpu_balls() {
            Some(mut balls) => {
                let stepped = balls.step(world);
                balls.take_events(events);
                stepped
            }
            None => Ok(()),
        }
    }

    /// Balls in `world`, caught and thrown ones included.
    pub fn count(&self, world: &World) -> usize {
        self.gpu_balls()
            .map_or(world.balls().len(), |balls| balls.len())
    }

    /// Throws a ball from `from` at `velocity` (B); its number.
    pub fn throw(
        &self,
        world: &mut World,
        from: DVec3,
        velocity: DVec3,
    ) -> Result<usize, GpuError> {
        match self.gpu_balls() {
            Some(mut balls) => balls.throw_ball(world, from, velocity),
            None => Ok(world.throw_ball(from, velocity)),
        }
    }

    /// The balls anew, as the scene starts them (I).
    pub fn reset(&self, world: &mut World) -> Result<(), GpuError> {
        match self.gpu_balls() {
            Some(mut balls) => balls.restart(world),
            None => world
                .reset_balls()
                .map_err(|e| GpuError::Build(e.to_string())),
        }
    }

    /// Moves ball `ball` to `position` at `velocity`, keeping its spin (the
    /// caller checks it fits there).
    pub fn set_ball(
        &self,
        world: &mut World,
        ball: usize,
        position: DVec3,
        velocity: DVec3,
    ) -> Result<(), GpuError> {
        match self.gpu_balls() {
            Some(mut balls) => balls.set_ball(ball, position, velocity),
            None => {
                let balls = world.balls_mut();
                let spin = balls.spins()[ball];
                balls.set(ball, position, velocity);
                balls.set_spin(ball, spin);
                Ok(())
            }
        }
    }

    /// The balls now: `world`'s own, or read back from the GPU (a wait).
    pub fn read<'w>(&self, world: &'w World) -> Result<Cow<'w, Balls>, GpuError> {
        match self.gpu_balls() {
            Some(balls) => Ok(Cow::Owned(balls.read()?.to_balls())),
            None => Ok(Cow::Borrowed(world.balls())),
        }
    }

    /// What the renderer draws the GPU engine's balls from; none on the
    /// CPU engine, whose balls the renderer reads from the world.
    pub fn instances(&self) -> Option<GpuBallBuffer> {
        self.gpu_balls().map(|balls| GpuBallBuffer {
            buffer: balls.instances().clone(),
            count: balls.len() as u32,
        })
    }

    /// The engine in words, for the HUD: "cpu", or "gpu on ADAPTER".
    pub fn describe(&self) -> String {
        match self.gpu_balls() {
            Some(balls) => format!("gpu on {}", balls.adapter()),
            None => "cpu".into(),
        }
    }

    /// The GPU engine's state copied back (its balls, contacts and reports
    /// on their way); none on the CPU engine, whose balls a clone of the
    /// world keeps.
    pub fn snapshot(&self) -> Result<Option<GpuSnapshot>, GpuError> {
        self.gpu_balls()
            .map(|mut balls| balls.snapshot())
            .transpose()
    }

    /// Puts back what [`BallEngine::snapshot`] copied, taken on the same
    /// engine (on the GPU engine, of a world of the same scene); else
    /// refused, unchanged.
    pub fn restore(&self, snapshot: Option<&GpuSnapshot>) -> Result<(), GpuError> {
        match (self.gpu_balls(), snapshot) {
            (None, None) => Ok(()),
            (Some(mut balls), Some(snapshot)) => balls.restore(snapshot),
            (ours, _) => Err(GpuError::Unsupported(format!(
                "a snapshot of a world on the {} engine cannot be put back into a world on the {} \
                 engine",
                if snapshot.is_some() { "gpu" } else { "cpu" },
                if ours.is_some() { "gpu" } else { "cpu" },
            ))),
        }
    }
}
