//! What a player changes while the world runs: settings the next step reads
//! as they are, and balls thrown in.

use glam::DVec3;

use super::World;
use crate::balls::Tint;
use crate::config::WorldConfig;

impl World {
    /// Takes the settings of `config` that a running world can take as they
    /// are (see [`WorldConfig::take_live_settings`]): they hold from the next
    /// step. The rest wait for a world built anew; [`World::needs_rebuild`]
    /// says whether any do.
    pub fn tune(&mut self, config: &WorldConfig) {
        self.config.take_live_settings(config);
    }

    /// Whether `config` differs from this world's in a setting that only a
    /// world built anew from it can take (the room's size, the balls' count
    /// or size, the tumblers' shape or places...).
    pub fn needs_rebuild(&self, config: &WorldConfig) -> bool {
        let mut tuned = self.config.clone();
        tuned.take_live_settings(config);
        tuned != *config
    }

    /// Adds a ball of the scene's radius and mass at `position` (pulled
    /// inside the room if need be), moving at `velocity`, and returns its
    /// number. It overlaps what it is thrown into only until the next step
    /// pushes them apart. Re-initialising the balls takes thrown balls away.
    pub fn throw_ball(&mut self, position: DVec3, velocity: DVec3) -> usize {
        let radius = self.config.balls.radius;
        let position = self.room.clamp_sphere(position, radius);
        let b = &mut self.balls;
        b.position.push(position);
        b.velocity.push(velocity);
        b.spin.push(DVec3::ZERO);
        b.radius.push(radius);
        b.mass.push(self.config.balls.mass);
        b.inv_mass.push(1.0 / self.config.balls.mass);
        b.tint.push(Tint::White);
        b.alive.push(true);
        self.scratch.hit_wall.push(false);
        b.len() - 1
    }
}

impl WorldConfig {
    /// Copies from `from` every setting a running world reads afresh when
    /// it needs it: gravity, restitutions, friction and rolling
    /// resistance, colours, the tumblers' damping, the fireball's flight
    /// (from its next launch), the hand's spring, the solver's iterations
    /// and thresholds, and how new random balls start (from the next
    /// re-initialisation). What sizes the world's bodies and storage (the
    /// room, the balls' count, radius and mass, placed balls, the tumblers'
    /// shape and places, the time step) is left as it is.
    pub fn take_live_settings(&mut self, from: &WorldConfig) {
        let WorldConfig {
            gravity,
            room,
            balls,
            tumblers,
            fireball,
            grab,
            solver,
        } = from;
        self.gravity = *gravity;
        self.room.restitution = room.restitution;
        self.room.friction = room.friction;
        self.room.rolling_resistance = room.rolling_resistance;
        self.room.colors = room.colors;
        self.balls.restitution = balls.restitution;
        self.balls.friction = balls.friction;
        self.balls.rolling_resistance = balls.rolling_resistance;
        self.balls.speed_min = balls.speed_min;
        self.balls.speed_max = balls.speed_max;
        self.balls.start_fill = balls.start_fill;
        self.balls.pour = balls.pour.clone();
        self.balls.color = balls.color;
        self.tumblers.restitution = tumblers.restitution;
        self.tumblers.floor_friction = tumblers.floor_friction;
        self.tumblers.damping = tumblers.damping;
        self.tumblers.colors.clone_from(&tumblers.colors);
        let starts_active = self.fireball.starts_active;
        self.fireball = fireball.clone();
        self.fireball.starts_active = starts_active;
        self.grab = grab.clone();
        self.solver.iterations = solver.iterations;
        self.solver.bounce_threshold = solver.bounce_threshold;
        self.solver.event_threshold = solver.event_threshold;
    }
}
