//! What every run shows: the world and its particle effects, stepped
//! together at the world's fixed step, and the one view of both that the
//! renderer draws. The balls are stepped by either engine
//! ([`BallEngine`]): in the world on the CPU engine, on the GPU after the
//! world's tumblers and fireball, and drawn from there, on the GPU engine.

use rolypoly_fx::{Effects, EffectsConfig};
use rolypoly_gpu::{GpuBalls, GpuError};
use rolypoly_physics::{Event, StepTimes, World};
use rolypoly_render::{DebugViews, LightConfig, SceneView};

use crate::balls::BallEngine;
use crate::engine::Engine;

/// The world and its effects.
#[derive(Clone)]
pub struct Simulation {
    /// The physics.
    pub world: World,
    /// The particle effects.
    pub fx: Effects,
    /// The balls' engine (on the GPU engine, the world holds no balls).
    pub balls: BallEngine,
    /// The last tick's events, kept so that ticks allocate nothing.
    events: Vec<Event>,
    /// The steps' stage times since they were last taken, summed, and how
    /// many steps.
    step_times: (StepTimes, u32),
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
            balls: BallEngine::Cpu,
            events: Vec::new(),
            step_times: (StepTimes::default(), 0),
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
        self.balls = BallEngine::gpu(balls);
        Ok(())
    }

    /// As [`Simulation::move_balls_to_gpu`], on a device opened without a
    /// renderer (to hear, count or trace the balls, not to draw them).
    pub fn move_balls_to_compute(
        &mut self,
        compute: &rolypoly_gpu::Compute,
    ) -> Result<(), GpuError> {
        let balls = GpuBalls::on_compute(compute, &mut self.world)?;
        self.balls = BallEngine::gpu(balls);
        Ok(())
    }

    /// `report` on the simulation with every ball in its world: on the GPU
    /// engine the balls are read back (a wait on the GPU) and put into the
    /// world for the while.
    pub fn with_balls<T>(
        &mut self,
        report: impl FnOnce(&mut Simulation) -> T,
    ) -> Result<T, GpuError> {
        let read = self.balls.gpu_balls().map(|gpu| gpu.read()).transpose()?;
        let Some(state) = read else {
            return Ok(report(self));
        };
        self.world.put_balls(state.to_balls());
        let out = report(self);
        self.world.take_balls();
        Ok(out)
    }

    /// The engine that steps the balls.
    pub fn engine(&self) -> Engine {
        self.balls.engine()
    }

    /// Balls in the world, caught and thrown ones included, on either engine.
    pub fn ball_count(&self) -> usize {
        self.balls.count(&self.world)
    }

    /// Throws a ball from `from` at `velocity` (B), into whichever engine
    /// steps the balls; its number.
    pub fn throw_ball(
        &mut self,
        from: glam::DVec3,
        velocity: glam::DVec3,
    ) -> Result<usize, GpuError> {
        self.balls.throw(&mut self.world, from, velocity)
    }

    /// The balls anew (I), in whichever engine steps them.
    pub fn reset_balls(&mut self) -> Result<(), GpuError> {
        self.balls.reset(&mut self.world)
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
        if self.gpu_failure.is_some() {
            // The world steps on without its balls.
            let engine = std::mem::take(&mut self.balls);
            let _ = self.step();
            self.balls = engine;
        } else if let Err(e) = self.step() {
            self.gpu_failure = Some(e.to_string());
        }
    }

    /// One fixed step, as [`Simulation::tick`], failing with the GPU
    /// engine's error (the world and effects stepped all the same).
    pub fn step(&mut self) -> Result<(), GpuError> {
        let stepped = self.balls.step(&mut self.world, &mut self.events);
        let (sum, steps) = &mut self.step_times;
        let last = self.world.step_times();
        for (total, stage) in sum.stages.iter_mut().zip(last.stages) {
            *total += stage;
        }
        sum.total += last.total;
        (sum.pairs, sum.other_contacts) = (last.pairs, last.other_contacts);
        sum.impacts += last.impacts;
        *steps += 1;
        self.fx.consume(&self.events, &self.world);
        self.fx
            .update(self.world.config().solver.dt, self.world.fireball());
        stepped
    }

    /// Ends a run's last step: on the GPU engine, waits for the reports of
    /// the steps still on their way and hands their events on now, as this
    /// step's (to [`Simulation::last_events`] and the effects), so that a
    /// run that ends here loses none. Their pushes still reach the tumblers
    /// when due, so the physics of a run stepped on after it keeps its
    /// bits (its effects saw those events two steps early).
    pub fn hand_on_events_in_flight(&mut self) -> Result<(), GpuError> {
        let Some(mut gpu) = self.balls.gpu_balls() else {
            return Ok(());
        };
        gpu.take_events_in_flight()?;
        let first = self.events.len();
        gpu.take_events(&mut self.events);
        drop(gpu);
        self.fx.consume(&self.events[first..], &self.world);
        Ok(())
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
        view.gpu_balls = self.balls.instances();
        view
    }

    /// As [`Simulation::view`], with the debug views `debug` shows of the
    /// last step.
    pub fn view_showing(&self, light: &LightConfig, debug: &DebugViews) -> SceneView {
        self.view(light)
            .with_debug(&self.world, &self.events, debug)
    }
}
