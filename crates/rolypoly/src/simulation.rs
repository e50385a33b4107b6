//! What every run shows: the world and its particle effects, stepped
//! together at the world's fixed step, and the one view of both that the
//! renderer draws.

use rolypoly_fx::{Effects, EffectsConfig};
use rolypoly_physics::{Event, StepTimes, World};
use rolypoly_render::{DebugViews, LightConfig, SceneView};

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
        }
    }

    /// One fixed step: the physics, then the effects its events set off.
    pub fn tick(&mut self) {
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
        self.fx.consume(&self.events, &self.world);
        self.fx
            .update(self.world.config().solver.dt, self.world.fireball());
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
        SceneView::from_world(&self.world, self.world.grabbed())
            .with_effects(&self.fx, &self.world)
            .with_light(light)
    }

    /// As [`Simulation::view`], with the debug views `debug` shows of the
    /// last step.
    pub fn view_showing(&self, light: &LightConfig, debug: &DebugViews) -> SceneView {
        self.view(light)
            .with_debug(&self.world, &self.events, debug)
    }
}
