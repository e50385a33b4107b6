//! A world as the program runs it: the physics and its particle effects
//! (the program's `Simulation`), stepped as `rolypoly render` and
//! `rolypoly simulate` step it, with the balls on the GPU engine where the
//! world was made for it, and the events kept until Python asks for them.

use std::borrow::Cow;

use rolypoly_core::engine::Engine;
use rolypoly_core::simulation::Simulation;
use rolypoly_core::snapshot::{self, SimulationState};
use rolypoly_gpu::{Compute, GpuError, GpuSnapshot};
use rolypoly_physics::{Balls, Event, World as PhysicsWorld};
use serde::{Deserialize, Serialize};

use crate::scene::Scene;

/// Events kept for `World.events()` at most; later ones are counted, not
/// kept, so that a world stepped for hours without being asked does not
/// fill the memory.
pub const MAX_PENDING_EVENTS: usize = 1_000_000;

/// A world, its effects and its events since they were last taken.
pub struct Run {
    /// The physics and its particle effects.
    pub sim: Simulation,
    /// The scene it was made from (its light and quality draw its frames).
    pub scene: Scene,
    /// The seed it was made with.
    pub seed: u64,
    /// The GPU engine's balls as the scene made them, before they moved to
    /// the GPU: their sizes and masses in double precision, as the trace's
    /// scene line gives them.
    made: Option<Balls>,
    /// The events since `World.events()` last took them, with the step
    /// each happened in.
    pub pending: Vec<(u64, Event)>,
    /// Events not kept since then, past [`MAX_PENDING_EVENTS`].
    pub dropped: u64,
}

/// Why a world could not be made.
pub enum MakeError {
    /// The scene does not build (a placement the checks cannot see).
    Build(String),
    /// The GPU engine would not start.
    Gpu(GpuError),
}

impl Run {
    /// `scene`'s world from `seed`, its balls stepped by `engine`.
    pub fn new(scene: Scene, seed: u64, engine: Engine) -> Result<Run, MakeError> {
        let world = PhysicsWorld::new(scene.data.world.clone(), seed)
            .map_err(|e| MakeError::Build(format!("cannot build {}: {e}", scene.name)))?;
        let made = (engine == Engine::Gpu).then(|| world.balls().clone());
        let mut sim = Simulation::new(world, scene.data.effects.clone(), seed);
        if engine == Engine::Gpu {
            let compute = Compute::headless().map_err(MakeError::Gpu)?;
            sim.move_balls_to_compute(&compute)
                .map_err(MakeError::Gpu)?;
        }
        Ok(Run {
            sim,
            scene,
            seed,
            made,
            pending: Vec::new(),
            dropped: 0,
        })
    }

    /// The engine that steps the balls.
    pub fn engine(&self) -> Engine {
        self.sim.engine()
    }

    /// One fixed step, as the program's `Simulation::tick` takes it,
    /// keeping the events.
    pub fn tick(&mut self) -> Result<(), GpuError> {
        self.sim.step()?;
        self.keep_events();
        Ok(())
    }

    /// A run's last step, as `rolypoly simulate` takes it: [`Run::tick`],
    /// with the GPU engine's events still on their way handed on as its
    /// own (see `Simulation::hand_on_events_in_flight`).
    pub fn last_tick(&mut self) -> Result<(), GpuError> {
        self.sim.step()?;
        self.sim.hand_on_events_in_flight()?;
        self.keep_events();
        Ok(())
    }

    /// The last step's events, kept for `World.events()` while there is room.
    fn keep_events(&mut self) {
        let step = self.sim.world.step_count();
        let events = self.sim.last_events();
        let room = MAX_PENDING_EVENTS.saturating_sub(self.pending.len());
        let kept = events.len().min(room);
        self.pending
            .extend(events[..kept].iter().map(|e| (step, *e)));
        self.dropped += (events.len() - kept) as u64;
    }

    /// The last step's events (what the trace writes for it).
    pub fn last_events(&self) -> &[Event] {
        self.sim.last_events()
    }

    /// The balls now: the world's own, or read back from the GPU.
    pub fn balls(&self) -> Result<Cow<'_, Balls>, GpuError> {
        self.sim.balls.read(&self.sim.world)
    }

    /// The balls for the trace's scene line: on the GPU engine, their
    /// sizes and masses as the scene made them (thrown ones as read back),
    /// as `rolypoly simulate` writes them.
    pub fn scene_balls(&self) -> Result<Option<Balls>, GpuError> {
        let (Engine::Gpu, Some(made)) = (self.engine(), &self.made) else {
            return Ok(None);
        };
        let now = self.balls()?;
        let exact = |made: &[f64], now: &[f64]| -> Vec<f64> {
            made.iter()
                .chain(now.iter().skip(made.len()))
                .copied()
                .collect()
        };
        Ok(Some(Balls::from_parts(
            now.positions().to_vec(),
            now.velocities().to_vec(),
            now.spins().to_vec(),
            exact(made.radii(), now.radii()),
            exact(made.masses(), now.masses()),
            now.tints().to_vec(),
            now.alive().to_vec(),
        )))
    }
}

/// What `World.snapshot()` keeps: everything a world steps on from, so that
/// a world restored from it steps on to the same bits.
#[derive(Clone)]
pub struct Saved {
    pub sim: Simulation,
    pub scene: Scene,
    pub seed: u64,
    pub pending: Vec<(u64, Event)>,
    pub dropped: u64,
    /// On the GPU engine, its state copied back, and its balls as the
    /// scene made them.
    gpu: Option<(GpuSnapshot, Option<Balls>)>,
}

/// A [`Saved`] as it travels between processes: the scene as its text and
/// name, the simulation as its state (see [`rolypoly_core::snapshot`]).
#[derive(Serialize, Deserialize)]
struct Carried {
    scene: String,
    name: String,
    seed: u64,
    sim: SimulationState,
    pending: Vec<(u64, Event)>,
    dropped: u64,
    gpu: Option<(GpuSnapshot, Option<Balls>)>,
}

impl Saved {
    /// The engine it was taken on.
    pub fn engine(&self) -> Engine {
        if self.gpu.is_some() {
            Engine::Gpu
        } else {
            Engine::Cpu
        }
    }

    /// As bytes, for another process or machine (see [`Saved::from_bytes`]).
    pub fn to_bytes(&self) -> Vec<u8> {
        snapshot::encode(&Carried {
            scene: self.scene.text(),
            name: self.scene.name.clone(),
            seed: self.seed,
            sim: self.sim.state(),
            pending: self.pending.clone(),
            dropped: self.dropped,
            gpu: self.gpu.clone(),
        })
    }

    /// What [`Saved::to_bytes`] wrote: its simulation made afresh from the
    /// scene and seed, its state then taken on. No graphics adapter is
    /// needed, even for a snapshot of the GPU engine (its state stays bytes
    /// until a world takes it on). Else why not, in a sentence.
    pub fn from_bytes(bytes: &[u8]) -> Result<Saved, String> {
        let carried: Carried = snapshot::decode(bytes).map_err(|e| e.to_string())?;
        let scene = Scene::from_text(&carried.scene, carried.name)
            .map_err(|e| format!("this snapshot's scene does not read: {e}"))?;
        let world = PhysicsWorld::new(scene.data.world.clone(), carried.seed)
            .map_err(|e| format!("this snapshot's scene does not build: {e}"))?;
        let mut sim = Simulation::new(world, scene.data.effects.clone(), carried.seed);
        sim.set_state(carried.sim)
            .map_err(|e| format!("this snapshot cannot be taken on: {e}"))?;
        Ok(Saved {
            sim,
            scene,
            seed: carried.seed,
            pending: carried.pending,
            dropped: carried.dropped,
            gpu: carried.gpu,
        })
    }
}

impl Run {
    /// A copy of the state, the GPU engine's copied back.
    pub fn save(&mut self) -> Result<Saved, GpuError> {
        let gpu = self
            .sim
            .balls
            .snapshot()?
            .map(|snapshot| (snapshot, self.made.clone()));
        Ok(Saved {
            sim: self.sim.clone(),
            scene: self.scene.clone(),
            seed: self.seed,
            pending: self.pending.clone(),
            dropped: self.dropped,
            gpu,
        })
    }

    /// Back to `saved`, taken on the same engine (on the GPU engine, of a
    /// world of the same scene); else refused, the world unchanged.
    pub fn restore(&mut self, saved: &Saved) -> Result<(), GpuError> {
        let (snapshot, made) = match &saved.gpu {
            Some((snapshot, made)) => (Some(snapshot), made.clone()),
            None => (None, None),
        };
        // This world's engine takes the state back (or refuses it); the
        // saved simulation's is another world's, or none.
        self.sim.balls.restore(snapshot)?;
        let balls = std::mem::take(&mut self.sim.balls);
        self.sim = saved.sim.clone();
        self.sim.balls = balls;
        self.made = made;
        self.scene = saved.scene.clone();
        self.seed = saved.seed;
        self.pending.clone_from(&saved.pending);
        self.dropped = saved.dropped;
        Ok(())
    }
}
