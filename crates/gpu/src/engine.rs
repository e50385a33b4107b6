//! The ball engine: the balls' state on the GPU and the step that advances
//! it, recorded pass by pass into one submission.

use crate::GpuError;
use crate::bindings::{Buffers, Sizes};
use crate::device::describe;
use crate::layout::{
    Body, Catch, EVENT_CAPACITY, FIREBALL, IMPACT_CAPACITY, IMPACT_ROUNDS, Impact, Params,
    grid_cells,
};
use crate::profile::StageTimer;
use crate::readback::read_buffer;
use crate::step::{PassLayout, Stages, SweepCounts};
use crate::wait::WaitBound;
use glam::{DVec3, Vec3};
use rolypoly_physics::{Balls, Event, Tint, World};

mod ball_state;
mod limits;
mod palette;
mod reports;
mod snapshot;

pub use ball_state::BallState;
use limits::check_limits;
use palette::PaletteLayout;
pub use reports::{REPORT_DELAY, StepReport};
use reports::{ReportRing, catches_at, impacts_at};
pub use snapshot::GpuSnapshot;

/// Thrown balls a run can add on top of its scene's.
pub const THROW_ROOM: u64 = 1024;
/// Balls nearer than this, in the largest ball's radii, are solved
/// together whether or not they close at the step's start: a ball struck
/// into its neighbour within the step must meet it.
const REACH_RADII: f64 = 0.25;
/// The solver's dispatches for each of the scene's solver iterations
/// (Gauss-Seidel sweeps, on the CPU engine), and the Jacobi sweeps each
/// runs among each block of neighbouring balls (see `ball_in_block` in
/// `step/common.wgsl`; a block stops early once settled). A Jacobi sweep
/// passes a push one contact on where a Gauss-Seidel sweep may pass it
/// down a column, and a contact between two blocks is worked out once a
/// dispatch. The bench's 10 000-ball pit at eight iterations sank, in its
/// first half second: 3.5 mm with 48 dispatches of one sweep; 6.7 with 8
/// of six; 4.1 with 16 of six; 3.5 with 16 of twelve, 3.7 stopping early
/// (3.9 with eight Gauss-Seidel sweeps). Frictionless, the same pit was
/// 96.1 % at rest at 10 s with 16 dispatches of twelve sweeps, 96–98 %
/// from 7.5 s on with sixteen and 98.2–99.8 % with 24: a pile's residual
/// pushes, left unsolved, keep it trembling.
const SOLVE_DISPATCHES_PER_ITERATION: u32 = 2;
const SOLVE_SWEEPS_PER_DISPATCH: u32 = 24;
/// How far past its own fix a sweep pushes a contact among several (see
/// `relaxation` in `solve.wgsl`): shares of a ball's mass make each push
/// small. Below 2, where a contact would ring; 1.8 held the bench's pits
/// shallower than 1.5 did (3.5 mm for 4.0 at 10 000 balls, 4.8 for 5.2 at
/// 100 000). Lone contacts are met exactly: over-relaxed, they left a trace
/// of a push on balls in flight, and a 200-ball elastic gas under gravity
/// lost 1.6 % of its energy in 10 s, not 0.5 %.
const SOLVE_RELAXATION: f32 = 1.8;
// Jacobi sweeps alternate between two copies and must end in the first
// (see `vel_in` in `common.wgsl`).
const _: () = assert!(SOLVE_DISPATCHES_PER_ITERATION.is_multiple_of(2));
/// Worlds of up to this many balls sweep in one workgroup (see
/// `SMALL_GROUP` in `step/common.wgsl`), where the dispatches would cost
/// more than their work.
const SMALL_WORLD_BALLS: u32 = 1024;
/// How far past its share of each overlap a solver sweep shifts a ball
/// (see `shift_share` in `step/solve.wgsl`): the shares, split as the
/// pushes' are, are cautious. The bench's 10 000-ball pit, read every
/// 0.05 s through its landing, sank at worst 3.8 and 4.2 mm with 1.0
/// (seeds 1 and 2), 2.8 and 2.2 with 1.5, 3.1 and 2.3 with 1.8.
const SHIFT_RELAXATION: f32 = 1.5;
/// The speculative margin, in the largest ball's radii: contacts this near
/// are solved even if they do not close.
const MARGIN_RADII: f64 = 0.01;
/// The grid's cell, in the largest ball's radii: a pair closing by up to a
/// radius in a step is found.
const CELL_RADII: f64 = 3.0;

/// The balls of a world, simulated on the GPU. The world keeps its
/// tumblers and fireball and steps them itself; each step the balls meet
/// them where the world has put them, and push them back (see
/// [`GpuBalls::step`]).
pub struct GpuBalls {
    device: wgpu::Device,
    queue: wgpu::Queue,
    /// How long any wait on the device may last, and its adapter's name.
    wait: WaitBound,
    buffers: Buffers,
    stages: Stages,
    params: Params,
    /// Balls the buffers hold room for.
    capacity: u64,
    tumblers: usize,
    palette: Vec<[f32; 4]>,
    palette_layout: PaletteLayout,
    /// Worlds of up to this many balls sweep in one workgroup.
    small_world_balls: u32,
    /// The steps' reports of pushes, catches and impacts on their way back.
    reports: ReportRing,
    /// The catches and impacts reported and not yet taken.
    events: Vec<Event>,
    /// Whether each step's impacts are read back.
    listening: bool,
    /// Impacts past a step's capacity, counted and not reported.
    impacts_dropped: u64,
    steps: u64,
    /// Dispatches the last step recorded, one after another: on a GPU
    /// each waits for the one before, so their count bounds a step's time
    /// from below whatever the balls.
    dispatches: u32,
}

impl GpuBalls {
    /// Takes the balls out of `world` and puts them on `device`. `adapter`
    /// names the device's adapter, for messages.
    pub fn new(
        device: wgpu::Device,
        queue: wgpu::Queue,
        adapter: &wgpu::Adapter,
        world: &mut World,
    ) -> Result<GpuBalls, GpuError> {
        crate::device::check_compute(adapter)?;
        GpuBalls::on(device, queue, describe(adapter), world)
    }

    /// As [`GpuBalls::new`], on a device opened by [`crate::Compute`].
    pub fn on_compute(compute: &crate::Compute, world: &mut World) -> Result<GpuBalls, GpuError> {
        GpuBalls::on(
            compute.device.clone(),
            compute.queue.clone(),
            compute.adapter.clone(),
            world,
        )
    }

    fn on(
        device: wgpu::Device,
        queue: wgpu::Queue,
        adapter: String,
        world: &mut World,
    ) -> Result<GpuBalls, GpuError> {
        let config = world.config().clone();
        if config.balls.pour.rate > 0.0 && config.balls.count > 0 {
            return Err(GpuError::Unsupported(
                "it does not pour balls from a spout (balls.pour.rate is above 0)".into(),
            ));
        }
        let balls = world.take_balls();
        let room = *world.room();
        let largest = (0..balls.len())
            .map(|i| balls.radii()[i])
            .fold(config.balls.largest_radius(), f64::max);
        let size = room.max - room.min;
        // Balls spread thin through a large room get cells about as wide as
        // the space between them, so that the grid has no more cells than
        // balls to walk (as the CPU engine's grid).
        let spacing = (size.element_product() / balls.len().max(1) as f64).cbrt();
        let cell = (CELL_RADII * largest).max(spacing);
        let dims = (size / cell).ceil().max(DVec3::ONE);
        let cells = grid_cells([dims.x as u32, dims.y as u32, dims.z as u32]);
        let capacity = balls.len() as u64 + THROW_ROOM;
        let tumblers = world.tumblers().len();
        let spheres = world.tumbler_shape().spheres.len();
        let sizes = Sizes {
            balls: capacity,
            cells,
            bodies: (tumblers * spheres + 1) as u64,
            tumblers: tumblers as u64,
            colors: (7 + tumblers + config.balls.placements.len()) as u64,
        };
        check_limits(&device.limits(), &sizes, &adapter)?;

        let buffers = Buffers::new(&device, &sizes);
        let sweeps = SweepCounts {
            dispatches: SOLVE_DISPATCHES_PER_ITERATION * config.solver.iterations.max(1) as u32,
            block_sweeps: SOLVE_SWEEPS_PER_DISPATCH,
        };
        let stages = Stages::new(&device, &buffers, cells, &sweeps);

        let palette_layout = PaletteLayout {
            tumblers: 7,
            placed: 7 + tumblers as u32,
        };
        let mut palette = vec![[0.0; 4]; sizes.colors as usize];
        let mut put = |tint: Tint| {
            let [r, g, b] = world.tint_color(tint);
            palette[palette_layout.index(tint) as usize] = [r, g, b, 1.0];
        };
        put(Tint::White);
        for s in rolypoly_physics::Surface::ALL {
            put(Tint::Surface(s));
        }
        for t in 0..tumblers {
            put(Tint::Tumbler(t));
        }
        for k in 0..config.balls.placements.len() {
            put(Tint::Placed(k));
        }
        queue.write_buffer(&buffers.palette, 0, bytemuck::cast_slice(&palette));

        let solver = &config.solver;
        let params = Params {
            count: 0,
            cells: cells as u32,
            bodies: 0,
            consumes: u32::from(config.fireball.consumes_balls),
            dims: [dims.x as u32, dims.y as u32, dims.z as u32, 0],
            room_min: [
                room.min.x as f32,
                room.min.y as f32,
                room.min.z as f32,
                solver.dt as f32,
            ],
            room_max: [
                room.max.x as f32,
                room.max.y as f32,
                room.max.z as f32,
                config.gravity as f32,
            ],
            grid: [
                cell as f32,
                (MARGIN_RADII * largest) as f32,
                solver.bounce_threshold as f32,
                solver.event_threshold as f32,
            ],
            material: [
                config.balls.restitution as f32,
                config.balls.friction as f32,
                config.room.restitution as f32,
                config.room.friction as f32,
            ],
            more: [
                config.room.rolling_resistance as f32,
                config.tumblers.restitution as f32,
                (REACH_RADII * largest) as f32,
                SHIFT_RELAXATION,
            ],
            tumblers: tumblers as u32,
            surface_colors: PaletteLayout::SURFACES,
            step: 0,
            solve_relaxation: SOLVE_RELAXATION,
        };
        let reports = ReportRing::new(&device, tumblers);
        let mut engine = GpuBalls {
            device,
            queue,
            wait: WaitBound::new(adapter),
            buffers,
            stages,
            params,
            capacity,
            tumblers,
            palette,
            palette_layout,
            small_world_balls: SMALL_WORLD_BALLS,
            reports,
            events: Vec::new(),
            listening: false,
            impacts_dropped: 0,
            steps: 0,
            dispatches: 0,
        };
        engine.upload(&balls, 0);
        engine.params.count = balls.len() as u32;
        // Drawn as they start, before any step.
        engine.write_instances();
        Ok(engine)
    }

    /// The adapter it runs on, "name (backend)".
    pub fn adapter(&self) -> &str {
        &self.wait.adapter
    }

    /// Gives up any wait on the GPU after `limit` from now on (30 s unless
    /// told: [`crate::DEFAULT_GPU_TIMEOUT`]), with an error naming the
    /// stage waited for.
    pub fn set_gpu_timeout(&mut self, limit: std::time::Duration) {
        self.wait.limit = limit;
    }

    /// Balls in play or caught, thrown ones included.
    pub fn len(&self) -> usize {
        self.params.count as usize
    }

    /// Whether there are no balls.
    pub fn is_empty(&self) -> bool {
        self.params.count == 0
    }

    /// Steps taken since it was built.
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// Dispatches the last step recorded (0 before the first): each waits
    /// for the one before it, so on a GPU they set a floor under a step's
    /// time, however few the balls.
    pub fn dispatches_per_step(&self) -> u32 {
        self.dispatches
    }

    /// How many balls had a contact to meet first in each impact round of
    /// the last step (see `step/impacts.wgsl`). For tests and the bench:
    /// it waits for the GPU.
    pub fn impact_counts(&self) -> Result<[u32; IMPACT_ROUNDS as usize], GpuError> {
        let bytes = self.copy_back(
            self.buffers.section("IMPACT_COUNT"),
            4 * u64::from(IMPACT_ROUNDS),
            || format!("the gpu engine's step {} (its impact counts)", self.steps),
        )?;
        let counts: Vec<u32> = bytemuck::pod_collect_to_vec(&bytes);
        Ok(std::array::from_fn(|round| counts[round]))
    }

    /// What the renderer draws: each ball's centre and radius, then colour
    /// and a pad (32 bytes a ball, radius 0 for a caught one), written on
    /// the GPU by every step; the first [`GpuBalls::len`] are in use.
    pub fn instances(&self) -> &wgpu::Buffer {
        &self.buffers.instances
    }

    /// Writes `balls` into the buffers from ball number `first` on.
    fn upload(&mut self, balls: &Balls, first: u64) {
        let n = balls.len();
        let mut pos = Vec::with_capacity(n);
        let mut vel = Vec::with_capacity(n);
        let mut spin = Vec::with_capacity(n);
        let mut state = Vec::with_capacity(n);
        for i in 0..n {
            let p = balls.positions()[i].as_vec3();
            let v = balls.velocities()[i].as_vec3();
            let w = balls.spins()[i].as_vec3();
            pos.push([p.x, p.y, p.z, balls.radii()[i] as f32]);
            vel.push([v.x, v.y, v.z, (1.0 / balls.masses()[i]) as f32]);
            spin.push([w.x, w.y, w.z, 0.0]);
            let color = self.palette_layout.index(balls.tints()[i]);
            state.push(u32::from(balls.alive()[i]) | (color << 16));
        }
        self.write_section("POS", 16 * first, bytemuck::cast_slice(&pos));
        self.write_section("VEL", 16 * first, bytemuck::cast_slice(&vel));
        self.write_section("SPIN", 16 * first, bytemuck::cast_slice(&spin));
        self.write_section("STATE", 4 * first, bytemuck::cast_slice(&state));
    }

    /// Moves ball `ball` to `position` at `velocity`, keeping its spin,
    /// size, colour and contacts (the caller checks it fits there).
    pub fn set_ball(
        &mut self,
        ball: usize,
        position: DVec3,
        velocity: DVec3,
    ) -> Result<(), GpuError> {
        if ball >= self.len() {
            return Err(GpuError::Unsupported(format!(
                "there is no ball {ball}: the world has {}",
                self.len()
            )));
        }
        let xyz = |v: DVec3| v.as_vec3().to_array();
        let at = 16 * ball as u64;
        self.write_section("POS", at, bytemuck::cast_slice(&xyz(position)));
        self.write_section("VEL", at, bytemuck::cast_slice(&xyz(velocity)));
        self.write_instances();
        Ok(())
    }

    /// Puts the balls back as the scene starts them (I): `world` draws them
    /// afresh (see [`World::fresh_balls`]).
    pub fn restart(&mut self, world: &mut World) -> Result<(), GpuError> {
        let balls = world
            .fresh_balls()
            .map_err(|e| GpuError::Build(e.to_string()))?;
        self.upload(&balls, 0);
        self.params.count = balls.len() as u32;
        self.write_instances();
        Ok(())
    }

    /// Throws a new ball from `position` at `velocity` (B), as
    /// [`World::throw_ball`] makes one; its number, or an error once the
    /// room for thrown balls is used up.
    pub fn throw_ball(
        &mut self,
        world: &mut World,
        position: DVec3,
        velocity: DVec3,
    ) -> Result<usize, GpuError> {
        let number = u64::from(self.params.count);
        if number >= self.capacity {
            return Err(GpuError::Unsupported(format!(
                "no room for more thrown balls: {THROW_ROOM} can be thrown before the balls are restarted (I)"
            )));
        }
        world.throw_ball(position, velocity);
        let thrown = world.take_balls();
        self.upload(&thrown, number);
        self.params.count += 1;
        Ok(number as usize)
    }

    /// The bodies the balls meet this step: each tumbler's spheres, then the
    /// fireball if it flies.
    fn bodies(&self, world: &World) -> Vec<Body> {
        let shape = world.tumbler_shape();
        let mut bodies = Vec::with_capacity(self.tumblers * shape.spheres.len() + 1);
        let f32x4 = |v: DVec3, w: f32| [v.x as f32, v.y as f32, v.z as f32, w];
        for (t, tumbler) in world.tumblers().iter().enumerate() {
            let origin = tumbler.bottom_center();
            let (pivot, inverse) = world.tumbler_pivot(t).unwrap_or_default();
            let row = |k: usize| f32x4(inverse.row(k), 0.0);
            for (s, sphere) in shape.spheres.iter().enumerate() {
                bodies.push(Body {
                    sphere: f32x4(tumbler.sphere_center(shape, s), sphere.radius as f32),
                    origin: f32x4(origin, 0.0),
                    velocity: f32x4(tumbler.point_velocity(origin), 0.0),
                    spin: f32x4(tumbler.angular_velocity(), 0.0),
                    info: [
                        t as u32,
                        s as u32,
                        self.palette_layout.index(Tint::Tumbler(t)),
                        0,
                    ],
                    turn_inverse: [row(0), row(1), row(2)],
                    pivot: f32x4(pivot, 0.0),
                });
            }
        }
        if let Some(f) = world.fireball() {
            bodies.push(Body {
                sphere: f32x4(f.position, f.radius as f32),
                origin: f32x4(f.position, 0.0),
                velocity: f32x4(f.velocity, 0.0),
                spin: [0.0; 4],
                info: [FIREBALL, 0, 0, 0],
                ..Body::default()
            });
        }
        bodies
    }

    /// One step of the balls, against the tumblers and fireball where
    /// `world` has them now. It is queued, not waited for: the step's
    /// report (the tumblers' pushes from the balls, the balls the fireball
    /// caught, the impacts where it listens) is taken [`REPORT_DELAY`]
    /// steps later, when its pushes are given to `world`'s tumblers and its
    /// events to [`GpuBalls::take_events`]. A report not back by then is
    /// waited for, and counted ([`GpuBalls::blocking_waits`]).
    pub fn step(&mut self, world: &mut World) -> Result<(), GpuError> {
        self.step_timed(world, None)
    }

    fn step_timed(
        &mut self,
        world: &mut World,
        timer: Option<&StageTimer>,
    ) -> Result<(), GpuError> {
        let bodies = self.bodies(world);
        self.params.bodies = bodies.len() as u32;
        self.params.step = self.steps as u32;
        let catching = world.fireball().is_some() && self.params.consumes != 0;
        let q = &self.queue;
        if !bodies.is_empty() {
            q.write_buffer(&self.buffers.bodies, 0, bytemuck::cast_slice(&bodies));
        }
        q.write_buffer(&self.buffers.params, 0, bytemuck::bytes_of(&self.params));
        // Cleared whether or not the fireball catches this step: a report
        // copies the count, and a count left from the last catching step
        // would report its catches again.
        self.write_section("EVENT_COUNT", 0, &[0; 4]);
        self.write_section("IMPACT_EVENTS", 0, &[0; 4]);
        self.write_section(
            "IMPACT_COUNT",
            0,
            bytemuck::cast_slice(&[0u32; IMPACT_ROUNDS as usize]),
        );
        let mut encoder = self.device.create_command_encoder(&Default::default());
        self.dispatches = self.stages.record(
            &mut encoder,
            timer,
            u64::from(self.params.count),
            self.tumblers as u32,
            self.params.count <= self.small_world_balls,
            catching,
        );
        if let Some(timer) = timer {
            timer.resolve(&mut encoder);
        }
        let report = self.tumblers > 0 || catching || self.listening;
        let mut sent = None;
        if report {
            let (slot, buffer) = self.reports.take_buffer(&self.device);
            let push = 32 * self.tumblers as u64;
            encoder.copy_buffer_to_buffer(&self.buffers.tumbler_push, 0, buffer, 0, push);
            let at = catches_at(self.tumblers);
            let (counters, event_count) = self.buffers.section("EVENT_COUNT");
            encoder.copy_buffer_to_buffer(counters, event_count, buffer, at, 16);
            encoder.copy_buffer_to_buffer(
                &self.buffers.events,
                0,
                buffer,
                at + 16,
                EVENT_CAPACITY * std::mem::size_of::<Catch>() as u64,
            );
            if self.listening {
                let at = impacts_at(self.tumblers);
                let (counters, count) = self.buffers.section("IMPACT_EVENTS");
                encoder.copy_buffer_to_buffer(counters, count, buffer, at, 4);
                let (pushes, impacts) = self.buffers.section("IMPACTS");
                encoder.copy_buffer_to_buffer(
                    pushes,
                    impacts,
                    buffer,
                    at + 16,
                    IMPACT_CAPACITY * std::mem::size_of::<Impact>() as u64,
                );
            }
            sent = Some(slot);
        }
        let submission = self.queue.submit([encoder.finish()]);
        if let Some(slot) = sent {
            self.reports
                .sent(self.steps, slot, self.listening, submission);
        }
        self.steps += 1;
        for report in self.reports.due(&self.device, &self.wait, self.steps)? {
            self.apply(world, report);
        }
        Ok(())
    }

    /// Gives each tumbler its push from a step's report and keeps the
    /// report's events to be taken.
    fn apply(&mut self, world: &mut World, mut report: StepReport) {
        for (t, &(impulse, moment, pushing_mass)) in report.pushes.iter().enumerate() {
            world.push_tumbler(t, impulse, moment, pushing_mass);
        }
        self.events.append(&mut report.events);
        self.impacts_dropped += report.impacts_dropped;
    }

    /// Times a step found the step report it was due to take not yet back from
    /// the GPU and waited for it: none a step where the GPU keeps up with
    /// the steps asked of it.
    pub fn blocking_waits(&self) -> u64 {
        self.reports.waits()
    }

    /// Waits for the reports of the last steps, still on their way, and
    /// hands their events to [`GpuBalls::take_events`] now, not when due:
    /// for a run that ends, or reads its balls back and wants every event
    /// so far. Their pushes still reach the tumblers when due.
    pub fn take_events_in_flight(&mut self) -> Result<(), GpuError> {
        self.reports.read_all(&self.device, &self.wait)?;
        self.reports.take_read_events(&mut self.events);
        Ok(())
    }

    /// Steps `steps` times with each stage timed on the GPU, and returns
    /// each stage's mean seconds a step; `None` where the device writes no
    /// timestamps. For the bench: it waits for every step.
    pub fn profile(
        &mut self,
        world: &mut World,
        steps: u32,
    ) -> Result<Option<[f64; crate::profile::STAGES]>, GpuError> {
        let Some(timer) = StageTimer::new(&self.device, &self.queue) else {
            return Ok(None);
        };
        let mut sum = [0.0; crate::profile::STAGES];
        for _ in 0..steps {
            self.step_timed(world, Some(&timer))?;
            let step = self.steps;
            let stamps = timer.read(&self.device, &self.wait, || {
                format!("the gpu engine's step {step} (its stage timestamps)")
            })?;
            for (total, s) in sum.iter_mut().zip(stamps) {
                *total += s;
            }
        }
        Ok(Some(sum.map(|s| s / f64::from(steps.max(1)))))
    }

    /// What each of the engine's pipelines binds, an entry point a row.
    pub fn pass_layouts(&self) -> &[PassLayout] {
        self.stages.layouts()
    }

    /// Sweeps worlds of up to `balls` balls in one workgroup from now on
    /// (normally up to 1024), so that tests and the bench can hold the two
    /// ways of sweeping against each other.
    pub fn sweep_in_one_group_up_to(&mut self, balls: u32) {
        self.small_world_balls = balls;
    }

    /// Reports the balls' impacts from the next step on, or stops: each
    /// ball's with a wall, another ball or a tumbler closing faster than
    /// the scene's event threshold, as the CPU engine reports them (see
    /// [`GpuBalls::take_events`]). A step's impacts come back with its
    /// report, [`REPORT_DELAY`] steps later.
    pub fn listen(&mut self, on: bool) {
        self.listening = on;
    }

    /// Impacts the steps found past what a step reports
    /// (`IMPACT_CAPACITY`, 8192), counted and left out.
    pub fn impacts_dropped(&self) -> u64 {
        self.impacts_dropped
    }

    /// Waits until the GPU has done every step submitted.
    pub fn finish(&self) -> Result<(), GpuError> {
        let steps = self.steps;
        self.wait.wait(&self.device, None, || {
            format!("the gpu engine's steps (finishing {steps} steps)")
        })?;
        Ok(())
    }

    /// Writes the instances from the state as it is, without a step.
    fn write_instances(&mut self) {
        self.queue
            .write_buffer(&self.buffers.params, 0, bytemuck::bytes_of(&self.params));
        let mut encoder = self.device.create_command_encoder(&Default::default());
        self.stages
            .write_instances(&mut encoder, u64::from(self.params.count));
        self.queue.submit([encoder.finish()]);
    }

    /// The first `size` bytes of `buffer` (COPY_SRC), copied back once the
    /// GPU is done with what was submitted before; `what` names the wait.
    fn copy_back(
        &self,
        (buffer, offset): (&wgpu::Buffer, u64),
        size: u64,
        what: impl FnOnce() -> String,
    ) -> Result<Vec<u8>, GpuError> {
        let room = buffer.size() - offset;
        let size = size.min(room);
        // Buffers are at least 16 bytes; so is what is copied.
        let copied = size.max(16).min(room);
        let staging = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("read back"),
            size: copied,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut encoder = self.device.create_command_encoder(&Default::default());
        encoder.copy_buffer_to_buffer(buffer, offset, &staging, 0, copied);
        self.queue.submit([encoder.finish()]);
        read_buffer(&self.device, &self.wait, &staging, size as usize, what)
    }

    /// Writes `bytes` into section `name` of the packed buffers, from its
    /// byte `at` on.
    fn write_section(&self, name: &str, at: u64, bytes: &[u8]) {
        let (buffer, first) = self.buffers.section(name);
        self.queue.write_buffer(buffer, first + at, bytes);
    }

    /// The balls the fireball caught since the last call, then the impacts
    /// (where the engine listens, see [`GpuBalls::listen`]), as events.
    pub fn take_events(&mut self, into: &mut Vec<Event>) {
        into.append(&mut self.events);
    }

    /// Reads every ball back from the GPU (for traces, tests and the bench;
    /// the window never needs to).
    pub fn read(&self) -> Result<BallState, GpuError> {
        let n = u64::from(self.params.count);
        let copy = |buffer: (&wgpu::Buffer, u64), size: u64| {
            self.copy_back(buffer, size, || {
                format!(
                    "reading the gpu engine's balls back after step {}",
                    self.steps
                )
            })
        };
        let pos = copy(self.buffers.section("POS"), 16 * n)?;
        let vel = copy(self.buffers.section("VEL"), 16 * n)?;
        let spin = copy(self.buffers.section("SPIN"), 16 * n)?;
        let state = copy(self.buffers.section("STATE"), 4 * n)?;
        let pos: Vec<[f32; 4]> = bytemuck::pod_collect_to_vec(&pos);
        let vel: Vec<[f32; 4]> = bytemuck::pod_collect_to_vec(&vel);
        let spin: Vec<[f32; 4]> = bytemuck::pod_collect_to_vec(&spin);
        let state: Vec<u32> = bytemuck::pod_collect_to_vec(&state);
        let xyz = |v: &[f32; 4]| Vec3::new(v[0], v[1], v[2]);
        Ok(BallState {
            positions: pos.iter().map(xyz).collect(),
            velocities: vel.iter().map(xyz).collect(),
            spins: spin.iter().map(xyz).collect(),
            radii: pos.iter().map(|p| p[3]).collect(),
            inverse_masses: vel.iter().map(|v| v[3]).collect(),
            alive: state.iter().map(|s| s & 1 != 0).collect(),
            colors: state
                .iter()
                .map(|s| {
                    let [r, g, b, _] = self.palette[(s >> 16) as usize];
                    [r, g, b]
                })
                .collect(),
            tints: state
                .iter()
                .map(|s| self.palette_layout.tint(s >> 16))
                .collect(),
        })
    }
}
