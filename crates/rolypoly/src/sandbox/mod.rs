//! The toy as a player drives it, whatever draws it: the running
//! simulation, the settings as the player has left them, pause, single
//! steps and the time scale, thrown balls, the scene chosen from a list,
//! and every input kept so that a run can be recorded and replayed to the
//! same bits. The window's keys and panel only call into this, so that all
//! of it is tested without a window.

use std::collections::VecDeque;

use glam::{DVec3, Vec3};
use rolypoly_physics::{BuildError, World};

use crate::engine::Engine;
use crate::scene::{self, Scene, SceneError};
use crate::simulation::Simulation;

mod fixed_steps;
mod input;
mod playback;
mod replay_log;
mod rewind;

pub use crate::scene::{SHIPPED_SCENES, ShippedScene};
pub use fixed_steps::{MAX_CATCH_UP, STEP_BUDGET_PER_FRAME};
pub use input::{CameraPose, Input, Journal, Refused, Timed};
use input::{array, vector};
pub use playback::{Playback, TIME_SCALES};
pub use replay_log::{REPLAY_FORMAT, ReplayLog};
pub use rewind::REWIND_SECONDS;
use rewind::{History, Snapshot};

/// Most balls a player may throw into one run of a scene; I (restart)
/// takes them away and the count starts again.
pub const MAX_THROWN: usize = 500;

// The GPU engine keeps room for every ball a player may throw.
const _: () = assert!(MAX_THROWN as u64 <= rolypoly_gpu::THROW_ROOM);

/// Speed a ball is thrown at unless the player sets another (m/s), and the
/// range they may set.
pub const THROW_SPEED: f64 = 8.0;
/// The throw speeds a player may set (m/s).
pub const THROW_SPEEDS: (f64, f64) = (0.5, 40.0);

/// Why a ball was not thrown.
#[derive(Debug, thiserror::Error, PartialEq, Eq)]
#[error("{MAX_THROWN} balls thrown already: press I to restart and throw again")]
pub struct ThrowRefused;

/// The running toy.
pub struct Sandbox {
    /// The world and its effects.
    pub sim: Simulation,
    /// The settings as the player left them. The world runs on them, but
    /// for those that wait for a restart ([`Sandbox::restart_pending`]).
    scene: Scene,
    /// What the scene is called: its file or shipped name.
    scene_name: String,
    seed: u64,
    /// Pause, steps and time scale.
    pub playback: Playback,
    /// Speed of a thrown ball (m/s).
    pub throw_speed: f64,
    thrown: usize,
    /// Ticks since the world's line began (see [`Journal`]).
    ticks: u64,
    journal: Journal,
    /// The tick a recording started at, while one runs.
    recording_from: Option<u64>,
    /// Inputs still to play, in replays, and the tick the replay ends at.
    script: Option<(VecDeque<Timed>, u64)>,
    /// The camera as the last recorded input put it (replays follow it).
    pub view_pose: Option<CameraPose>,
    /// The last 30 s, to go back to (see [`rewind`]); kept only while the
    /// CPU engine steps the balls.
    history: History,
    /// The device the GPU engine steps the balls on, once there is one
    /// (see [`Sandbox::use_device`]).
    device: Option<Device>,
    /// The engine the simulation was built for (a change of
    /// `solver.engine` waits for the restart).
    engine: Engine,
}

pub use crate::frames::Device;

impl Sandbox {
    /// The toy on `scene`, its random balls drawn from `seed`.
    pub fn new(scene: Scene, name: &str, seed: u64) -> Result<Sandbox, BuildError> {
        let world = World::new(scene.world.clone(), seed)?;
        Ok(Sandbox::with_world(world, scene, name, seed))
    }

    /// The toy on `world`, built from `scene` with `seed`.
    pub fn with_world(world: World, scene: Scene, name: &str, seed: u64) -> Sandbox {
        let mut sandbox = Sandbox {
            sim: Simulation::new(world, scene.effects.clone(), seed),
            journal: Journal {
                scene: scene.clone(),
                name: name.to_owned(),
                inputs: Vec::new(),
            },
            scene,
            scene_name: name.to_owned(),
            seed,
            playback: Playback::default(),
            throw_speed: THROW_SPEED,
            thrown: 0,
            ticks: 0,
            recording_from: None,
            script: None,
            view_pose: None,
            history: History::default(),
            device: None,
            engine: Engine::Cpu,
        };
        sandbox.engine = sandbox.scene.engine;
        sandbox.history.begin(sandbox.snapshot());
        sandbox
    }

    /// Gives the sandbox the device to draw with; from here on a scene
    /// whose `solver.engine` is gpu has its balls stepped there, this one
    /// at once.
    pub fn use_device(&mut self, device: Device) -> Result<(), Refused> {
        self.device = Some(device);
        if self.scene.engine == Engine::Gpu && self.sim.engine() == Engine::Cpu {
            self.move_balls_to_gpu()?;
        }
        Ok(())
    }

    /// A simulation of `world` for the scene now, its balls on the GPU
    /// where the scene says so and a device is known.
    fn simulation(&self, world: World) -> Result<Simulation, Refused> {
        let mut sim = Simulation::new(world, self.scene.effects.clone(), self.seed);
        if let (Engine::Gpu, Some(d)) = (self.scene.engine, &self.device) {
            sim.move_balls_to_gpu(&d.device, &d.queue, &d.adapter)?;
        }
        Ok(sim)
    }

    fn move_balls_to_gpu(&mut self) -> Result<(), Refused> {
        if let Some(d) = &self.device {
            self.sim
                .move_balls_to_gpu(&d.device, &d.queue, &d.adapter)?;
            // What came before the balls moved cannot be gone back to.
            self.history.begin(self.snapshot());
        }
        Ok(())
    }

    /// The toy as it stands now, to go back to.
    fn snapshot(&self) -> Snapshot {
        Snapshot {
            tick: self.ticks,
            sim: self.sim.clone(),
            scene: self.scene.clone(),
            thrown: self.thrown,
            inputs: self.journal.inputs.len(),
        }
    }

    /// Takes `input` from the player: what it does to the world or the
    /// settings, kept in the journal when it did something. After going
    /// back, anything but a camera's move forgets the future the first time
    /// had (see the `rewind` module).
    pub fn apply(&mut self, input: Input) -> Result<(), Refused> {
        if !matches!(input, Input::Camera { .. }) {
            self.history.branch(self.ticks);
        }
        self.take(input)
    }

    /// Takes `input`, the player's or one played again.
    fn take(&mut self, input: Input) -> Result<(), Refused> {
        match &input {
            Input::Fireball { from, direction } => {
                self.sim
                    .world
                    .launch_fireball(Some((vector(*from), vector(*direction))));
            }
            Input::FireballOff => self.sim.world.remove_fireball(),
            Input::Throw {
                from,
                direction,
                speed,
            } => {
                if self.thrown >= MAX_THROWN {
                    return Err(ThrowRefused.into());
                }
                let (slowest, fastest) = THROW_SPEEDS;
                if !(slowest..=fastest).contains(speed) {
                    return Err(Refused::Speed(*speed));
                }
                let velocity = vector(*direction).normalize_or(DVec3::NEG_Z) * *speed;
                self.sim.throw_ball(vector(*from), velocity)?;
                self.thrown += 1;
            }
            Input::Grab { tumbler, point } => self.sim.world.grab(*tumbler, vector(*point)),
            Input::GrabBall { ball } => self.sim.world.hold_ball(*ball),
            Input::Drag { to } => self.sim.world.drag_to(vector(*to)),
            Input::Release => self.sim.world.release(),
            Input::Restart => self.rebuild_or_reset()?,
            Input::Settings { scene } => {
                let scene = scene::parse_scene(scene, "the panel's settings")?;
                scene::validate(&scene)?;
                self.sim.world.tune(&scene.world);
                self.scene = scene;
            }
            Input::Load { name, scene } => {
                let scene = scene::parse_scene(scene, name)?;
                let world = World::new(scene.world.clone(), self.seed)?;
                let previous = std::mem::replace(&mut self.scene, scene.clone());
                self.sim = match self.simulation(world) {
                    Ok(sim) => sim,
                    Err(e) => {
                        self.scene = previous;
                        return Err(e);
                    }
                };
                self.engine = scene.engine;
                self.scene_name.clone_from(name);
                self.thrown = 0;
                // A new line begins: what came before no longer matters.
                self.ticks = 0;
                self.journal = Journal {
                    scene: scene.clone(),
                    name: name.clone(),
                    inputs: Vec::new(),
                };
                self.recording_from = self.recording_from.map(|_| 0);
                self.scene = scene;
                self.history.begin(self.snapshot());
                return Ok(());
            }
            Input::Camera {
                position,
                yaw,
                pitch,
            } => {
                self.view_pose = Some(CameraPose {
                    position: Vec3::from_array(*position),
                    yaw: *yaw,
                    pitch: *pitch,
                });
            }
        }
        self.journal.inputs.push(Timed {
            tick: self.ticks,
            input,
        });
        Ok(())
    }

    /// The settings as the player left them.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The scene's file or shipped name.
    pub fn scene_name(&self) -> &str {
        &self.scene_name
    }

    /// The seed of the random start.
    pub fn seed(&self) -> u64 {
        self.seed
    }

    /// The physics world.
    pub fn world(&self) -> &World {
        &self.sim.world
    }

    /// Takes settings the player changed: checked by the scene file's
    /// rules (and refused whole if one breaks them); those the running
    /// world can take hold from the next step, the rest from the next
    /// restart.
    pub fn set_scene(&mut self, scene: Scene) -> Result<(), SceneError> {
        // Checked before it becomes text, to name the key and not a line.
        scene::validate(&scene)?;
        let text = scene::scene_file_text(&scene, "settings");
        match self.apply(Input::Settings { scene: text }) {
            Err(Refused::Scene(e)) => Err(e),
            _ => Ok(()),
        }
    }

    /// Whether some changed settings wait for a restart (I).
    pub fn restart_pending(&self) -> bool {
        self.sim.world.needs_rebuild(&self.scene.world)
            || *self.sim.fx.config() != self.scene.effects
            || self.engine != self.scene.engine
    }

    /// I: the balls anew, thrown balls gone; the whole world built anew
    /// from the settings when some wait for it.
    pub fn restart(&mut self) -> Result<(), Refused> {
        self.apply(Input::Restart)
    }

    fn rebuild_or_reset(&mut self) -> Result<(), Refused> {
        if self.restart_pending() {
            let world = World::new(self.scene.world.clone(), self.seed)?;
            self.sim = self.simulation(world)?;
            self.engine = self.scene.engine;
        } else {
            self.sim.reset_balls()?;
        }
        self.thrown = 0;
        Ok(())
    }

    /// Another scene at once, from the start; the time scale and pause stay
    /// as they were. `text` is its file's.
    pub fn load(&mut self, text: &str, name: &str) -> Result<(), Refused> {
        self.apply(Input::Load {
            name: name.to_owned(),
            scene: text.to_owned(),
        })
    }

    /// Throws a ball from `from` along `direction` at the throw speed.
    /// Returns its number.
    pub fn throw(&mut self, from: DVec3, direction: DVec3) -> Result<usize, ThrowRefused> {
        let input = Input::Throw {
            from: array(from),
            direction: array(direction),
            speed: self.throw_speed,
        };
        match self.apply(input) {
            Err(Refused::Throw(refused)) => Err(refused),
            _ => Ok(self.sim.ball_count() - 1),
        }
    }

    /// Balls thrown since the scene started or restarted.
    pub fn thrown(&self) -> usize {
        self.thrown
    }

    /// Runs the steps a frame of `elapsed` real seconds asks for (see
    /// [`Playback::advance`]); `spent` is the time the frame has spent
    /// stepping. Returns how many ran.
    pub fn frame(&mut self, elapsed: f64, spent: impl FnMut() -> std::time::Duration) -> u32 {
        self.frame_heard(elapsed, spent, |_| {})
    }

    /// [`Sandbox::frame`], handing the simulation to `heard` after each
    /// step it takes (the window's sound hears them so).
    pub fn frame_heard(
        &mut self,
        elapsed: f64,
        spent: impl FnMut() -> std::time::Duration,
        mut heard: impl FnMut(&Simulation),
    ) -> u32 {
        let dt = self.sim.world.config().solver.dt;
        let mut playback = std::mem::take(&mut self.playback);
        let steps = playback.advance(elapsed, dt, spent, || {
            let before = self.ticks;
            self.tick();
            if self.ticks > before {
                heard(&self.sim);
            }
        });
        self.playback = playback;
        steps
    }

    /// One step, after the replayed inputs due before it; none once a
    /// replay has reached its end (see [`Sandbox::end_replay`]).
    pub fn tick(&mut self) {
        self.play_due();
        if self.replay_end().is_some_and(|end| self.ticks >= end) {
            return;
        }
        self.sim.tick();
        self.ticks += 1;
        self.history.furthest = self.history.furthest.max(self.ticks);
        let (every, keep) = rewind::spacing(self.sim.world.config().solver.dt);
        // The GPU engine's balls are not copied back to the CPU to keep.
        if self.ticks.is_multiple_of(every) && self.sim.engine() == Engine::Cpu {
            let snapshot = self.snapshot();
            self.history.keep(snapshot, keep);
        }
    }

    /// Goes back (or on, within what happened) to the start of `tick`,
    /// as far as the history reaches: the toy stands as it stood then, and
    /// playing on gives the same run as the first time until the player
    /// acts. Returns the tick reached.
    pub fn rewind_to(&mut self, tick: u64) -> u64 {
        let target = tick.clamp(self.history.oldest(), self.history.furthest);
        if target < self.ticks
            && let Some(snapshot) = self.history.before(target).cloned()
        {
            // The inputs from the copy on, played again as their ticks come.
            let mut future: VecDeque<Timed> =
                self.journal.inputs.drain(snapshot.inputs..).collect();
            future.extend(self.history.ahead.drain(..));
            self.history.ahead = future;
            self.sim = snapshot.sim;
            self.scene = snapshot.scene;
            self.thrown = snapshot.thrown;
            self.ticks = snapshot.tick;
            self.recording_from = self.recording_from.map(|from| from.min(self.ticks));
        }
        while self.ticks < target {
            self.tick();
        }
        self.ticks
    }

    /// The ticks that can be gone back or on to: the oldest kept, and the
    /// furthest this line of the world has reached.
    pub fn timeline(&self) -> (u64, u64) {
        (self.history.oldest(), self.history.furthest)
    }

    /// How many copies of the toy the history holds now.
    pub fn snapshots_kept(&self) -> usize {
        self.history.len()
    }

    /// Steps until the replay has played every input and reached its end
    /// tick, or until `tick` if that comes first.
    pub fn replay_until(&mut self, tick: u64) {
        while self.replaying() && self.ticks < tick {
            self.tick();
        }
        if self.ticks >= tick {
            self.play_due();
        }
    }

    /// Lets the world run on after a replay, as a live one.
    pub fn end_replay(&mut self) {
        self.script = None;
    }

    /// Ticks since the world's line began.
    pub fn ticks(&self) -> u64 {
        self.ticks
    }

    fn play_due(&mut self) {
        let ticks = self.ticks;
        while self.history.ahead.front().is_some_and(|t| t.tick <= ticks) {
            if let Some(timed) = self.history.ahead.pop_front() {
                // What was refused the first time is refused again.
                let _ = self.take(timed.input);
            }
        }
        while let Some(timed) = self
            .script
            .as_mut()
            .and_then(|(inputs, _)| {
                inputs
                    .front()
                    .is_some_and(|t| t.tick <= ticks)
                    .then(|| inputs.pop_front())
            })
            .flatten()
        {
            // What was refused when recorded is refused again.
            let _ = self.take(timed.input);
        }
    }

    /// Whether R is recording.
    pub fn recording(&self) -> bool {
        self.recording_from.is_some()
    }

    /// R: from now on, what is done is part of the recording.
    pub fn start_recording(&mut self) {
        self.recording_from = Some(self.ticks);
    }

    /// R again: the recording, from the start of the world's line (so that
    /// a replay can rebuild the state the recording started from) to now.
    pub fn stop_recording(&mut self) -> Option<ReplayLog> {
        let from = self.recording_from.take()?;
        Some(ReplayLog {
            format: REPLAY_FORMAT,
            seed: self.seed,
            name: self.journal.name.clone(),
            scene: scene::scene_file_text(&self.journal.scene, &self.journal.name),
            from_tick: from,
            to_tick: self.ticks,
            end_digest: self.digest(),
            inputs: self.journal.inputs.clone(),
        })
    }

    /// The sandbox at the start of `log`'s world line with its inputs to
    /// play, not yet stepped.
    pub fn for_replay(log: &ReplayLog) -> Result<Sandbox, Refused> {
        Sandbox::for_replay_on(log, None)
    }

    /// [`Sandbox::for_replay`], its balls stepped by `engine` where given
    /// instead of the recording's (the end digest then holds only if it is
    /// the engine the recording was made on).
    pub fn for_replay_on(log: &ReplayLog, engine: Option<Engine>) -> Result<Sandbox, Refused> {
        let mut scene = scene::parse_scene(&log.scene, &log.name)?;
        if let Some(engine) = engine {
            scene.engine = engine;
        }
        let mut sandbox = Sandbox::new(scene, &log.name, log.seed)?;
        sandbox.script = Some((log.inputs.iter().cloned().collect(), log.to_tick));
        Ok(sandbox)
    }

    /// Whether a replay has inputs or ticks still to play.
    pub fn replaying(&self) -> bool {
        self.script
            .as_ref()
            .is_some_and(|(inputs, end)| !inputs.is_empty() || self.ticks < *end)
    }

    /// The tick a replay ends at.
    pub fn replay_end(&self) -> Option<u64> {
        self.script.as_ref().map(|(_, end)| *end)
    }

    /// A fingerprint of the state: every body's every bit, the time, the
    /// fireball. Two runs with the same digest are, as far as can be seen,
    /// the same run.
    pub fn digest(&self) -> String {
        let w = &self.sim.world;
        // The GPU engine's balls, read back: a digest is taken once a run.
        let gpu_balls = self
            .sim
            .balls
            .gpu_balls()
            .map(|balls| balls.read().map(|s| s.to_balls()).ok());
        let state = format!(
            "{:?}{:?}{:?}{:?}{}{}",
            w.balls(),
            gpu_balls,
            w.tumblers(),
            w.fireball(),
            w.time().to_bits(),
            w.step_count()
        );
        // FNV-1a, 64 bits.
        let hash = state.bytes().fold(0xcbf2_9ce4_8422_2325_u64, |h, b| {
            (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
        });
        format!("{hash:016x}")
    }
}

#[cfg(test)]
mod tests;
