//! What every run shows: the world and its particle effects, stepped
//! together at the world's fixed step, and the one view of both that the
//! renderer draws.

use rolypoly_fx::{Effects, EffectsConfig};
use rolypoly_physics::{Event, World};
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
}

impl Simulation {
    /// `world` with fresh effects of `effects`, their random sequence drawn
    /// from `seed`.
    pub fn new(world: World, effects: EffectsConfig, seed: u64) -> Simulation {
        Simulation {
            world,
            fx: Effects::new(effects, seed),
            events: Vec::new(),
        }
    }

    /// One fixed step: the physics, then the effects its events set off.
    pub fn tick(&mut self) {
        self.world.step();
        self.world.take_events(&mut self.events);
        self.fx.consume(&self.events, &self.world);
        self.fx
            .update(self.world.config().solver.dt, self.world.fireball());
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
