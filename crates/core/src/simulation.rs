//! What every run shows: the world and its particle effects, stepped
//! together at the world's fixed step, and the one view of both that the
//! renderer draws. With the GPU engine, the balls are stepped on the GPU
//! after the world's tumblers and fireball, and drawn from there.

use std::sync::{Arc, Mutex, MutexGuard, PoisonError};

use rolypoly_fx::{Effects, EffectsConfig};
use rolypoly_gpu::{GpuBalls, GpuError};
use rolypoly_physics::{Event, StepTimes, World};
use rolypoly_render::{DebugViews, GpuBallBuffer, LightConfig, SceneView};

/// The world and its effects.
#[derive(Clone)]
pub struct Simulation {
    /// The physics.
    pub world: World,
    /// The particle effects.
    pub fx: Effects,
    /// The last tick's events, kept so that ticks allocate nothing.
    events: Vec<Event>,
    /// The steps' stage times since they were last taken, summed, and how
    /// many steps.
    step_times: (StepTimes, u32),
    /// The balls, where the GPU engine steps them (the world then has none).
    gpu: Option<Arc<Mutex<GpuBalls>>>,
    /// Why the GPU engine stopped, if it did.
    gpu_failure: Option<String>,
}

impl Simulation {
    /// `world` with fresh effects of `effects`, their random sequence drawn
    /// from `seed`.
    pub fn new(world: World, effects: EffectsConfig, seed: u64) -> Simulation {
        Simulation {
            world,
            fx: Effects::new(effects, seed),
            events: Vec::new(),
            step_times: (StepTimes::default(), 0),
            gpu: None,
            gpu_failure: None,
        }
    }

    /// Moves the world's balls onto `device`, where the GPU engine steps
    /// them from here on.
    pub fn move_balls_to_gpu(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        adapter: &wgpu::Adapter,
    ) -> Result<(), GpuError> {
        let balls = GpuBalls::new(device.clone(), queue.clone(), adapter, &mut self.world)?;
        self.hand_balls_to(balls);
        Ok(())
    }

    /// As [`Simulation::move_balls_to_gpu`], on a device opened without a
    /// renderer (to hear or count the balls, not to draw them).
    pub fn move_balls_to_compute(
        &mut self,
        compute: &rolypoly_gpu::Compute,
    ) -> Result<(), GpuError> {
        let balls = GpuBalls::on_compute(compute, &mut self.world)?;
        self.hand_balls_to(balls);
        Ok(())
    }

    /// The GPU engine steps the balls from here on, reporting their
    /// impacts as the CPU engine's world does, for the effects and the
    /// sound.
    fn hand_balls_to(&mut self, mut balls: GpuBalls) {
        balls.listen(true);
        self.gpu = Some(Arc::new(Mutex::new(balls)));
    }

    /// `report` on the simulation with every ball in its world: on the GPU
    /// engine the balls are read back (a wait on the GPU) and put into the
    /// world for the while.
    pub fn with_balls<T>(&mut self, report: impl FnOnce(&Simulation) -> T) -> Result<T, GpuError> {
        let Some(gpu) = self.gpu.clone() else {
            return Ok(report(self));
        };
        let balls = gpu
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .read()?
            .to_balls();
        self.world.put_balls(balls);
        let out = report(self);
        self.world.take_balls();
        Ok(out)
    }

    /// Whether the GPU engine steps the balls.
    pub fn on_gpu(&self) -> bool {
        self.gpu.is_some()
    }

    /// Balls in the world, caught and thrown ones included, on either engine.
    pub fn ball_count(&self) -> usize {
        self.gpu_balls()
            .map_or(self.world.balls().len(), |balls| balls.len())
    }

    /// Throws a ball from `from` at `velocity` (B), into whichever engine
    /// steps the balls.
    pub fn throw_ball(&mut self, from: glam::DVec3, velocity: glam::DVec3) -> Result<(), GpuError> {
        match &self.gpu {
            Some(gpu) => {
                let mut balls = gpu.lock().unwrap_or_else(PoisonError::into_inner);
                balls.throw_ball(&mut self.world, from, velocity)?;
            }
            None => {
                self.world.throw_ball(from, velocity);
            }
        }
        Ok(())
    }

    /// The balls anew (I), in whichever engine steps them.
    pub fn reset_balls(&mut self) -> Result<(), GpuError> {
        match &self.gpu {
            Some(gpu) => {
                let mut balls = gpu.lock().unwrap_or_else(PoisonError::into_inner);
                balls.restart(&mut self.world)
            }
            None => self
                .world
                .reset_balls()
                .map_err(|e| GpuError::Build(e.to_string())),
        }
    }

    /// The GPU engine, where it steps the balls.
    pub fn gpu_balls(&self) -> Option<MutexGuard<'_, GpuBalls>> {
        self.gpu
            .as_ref()
            .map(|gpu| gpu.lock().unwrap_or_else(PoisonError::into_inner))
    }

    /// Fails with why the GPU engine stopped, if it did.
    pub fn check_gpu(&self) -> anyhow::Result<()> {
        match &self.gpu_failure {
            Some(why) => anyhow::bail!("{why}"),
            None => Ok(()),
        }
    }

    /// One fixed step: the physics, then the effects its events set off.
    /// A GPU engine that fails stops stepping the balls, and says why in
    /// [`Simulation::check_gpu`].
    pub fn tick(&mut self) {
        let gpu = self.gpu.clone();
        let mut held = gpu
            .as_ref()
            .map(|gpu| gpu.lock().unwrap_or_else(PoisonError::into_inner));
        let balls = held.as_deref_mut().filter(|_| self.gpu_failure.is_none());
        if let Err(e) = self.tick_with(balls) {
            self.gpu_failure = Some(e.to_string());
        }
    }

    /// One fixed step with the balls on `gpu` where one is given (an
    /// engine the caller keeps, as the Python package does; the world
    /// then holds no balls): the world, the balls, the effects.
    pub fn tick_with(&mut self, gpu: Option<&mut GpuBalls>) -> Result<(), GpuError> {
        self.world.step();
        let (sum, steps) = &mut self.step_times;
        let last = self.world.step_times();
        for (total, stage) in sum.stages.iter_mut().zip(last.stages) {
            *total += stage;
        }
        sum.total += last.total;
        (sum.pairs, sum.other_contacts) = (last.pairs, last.other_contacts);
        sum.impacts += last.impacts;
        *steps += 1;
        self.world.take_events(&mut self.events);
        let stepped = match gpu {
            Some(balls) => {
                let stepped = balls.step(&mut self.world);
                balls.take_events(&mut self.events);
                stepped
            }
            None => Ok(()),
        };
        self.fx.consume(&self.events, &self.world);
        self.fx
            .update(self.world.config().solver.dt, self.world.fireball());
        stepped
    }

    /// The last tick's events: the world's, then the balls the GPU engine's
    /// fireball caught and their impacts.
    pub fn last_events(&self) -> &[Event] {
        &self.events
    }

    /// Puts back the last tick's events, as a state taken on had them.
    pub(crate) fn set_last_events(&mut self, events: Vec<Event>) {
        self.events = events;
    }

    /// The steps' stage times since the last call, summed (the counts of
    /// pairs and contacts: the last step's), and how many steps.
    pub fn take_step_times(&mut self) -> (StepTimes, u32) {
        std::mem::take(&mut self.step_times)
    }

    /// `steps` ticks.
    pub fn ticks(&mut self, steps: u64) {
        for _ in 0..steps {
            self.tick();
        }
    }

    /// What the renderer draws now: the bodies (a held tumbler enlarged),
    /// the effects, lit by `light`.
    pub fn view(&self, light: &LightConfig) -> SceneView {
        let mut view = SceneView::from_world(&self.world, self.world.grabbed())
            .with_effects(&self.fx, &self.world)
            .with_light(light);
        if let Some(balls) = self.gpu_balls() {
            view.gpu_balls = Some(GpuBallBuffer {
                buffer: balls.instances().clone(),
                count: balls.len() as u32,
            });
        }
        view
    }

    /// As [`Simulation::view`], with the debug views `debug` shows of the
    /// last step.
    pub fn view_showing(&self, light: &LightConfig, debug: &DebugViews) -> SceneView {
        self.view(light)
            .with_debug(&self.world, &self.events, debug)
    }
}
