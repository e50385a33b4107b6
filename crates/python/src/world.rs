//! `rolypoly.World`: a scene's world, stepped as the program steps it,
//! its state read as NumPy arrays and changed through checked setters.

use std::path::PathBuf;
use std::time::{Duration, Instant};

use glam::DVec3;
use pyo3::exceptions::PyRuntimeWarning;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyTuple};
use rolypoly_core::engine::Engine;
use rolypoly_core::steps_for;

use crate::arrays::read_vector;
use crate::balls::Balls;
use crate::checks::{place_problem, speed_problem};
use crate::errors::{gpu_error, value_error};
use crate::events::Event;
use crate::progress::Progress;
use crate::run::{MakeError, Run, Saved};
use crate::scene::Scene;
use crate::series;
use crate::trace::write_trace;
use crate::tumblers::{Fireball, Tumblers};

/// A point (x, y, z) in metres, as Python sees it.
type Point = (f64, f64, f64);

/// How long a call to `step` runs between looks at Ctrl-C.
const SIGNAL_EVERY: Duration = Duration::from_millis(50);

/// A world: the room, its balls, tumblers and fireball, and the particle
/// effects its impacts set off, made from a scene and a seed.
///
/// ``World(scene=None, seed=1, engine=None)``: ``scene`` is a
/// :class:`Scene` (``None``: the built-in default scene); the same scene
/// and seed give the same world, step for step, bit for bit, as
/// ``rolypoly --scene FILE --seed N``. ``engine`` is ``"cpu"`` or
/// ``"gpu"`` (``None``: the scene's ``solver.engine``).
///
/// State is read as NumPy arrays through :attr:`balls`, :attr:`tumblers`
/// and :attr:`fireball`; each read is a fresh copy. A world steps in one
/// thread at a time: reading it from another thread while :meth:`step`
/// runs raises ``RuntimeError`` ("already borrowed").
#[pyclass(module = "rolypoly", name = "World")]
pub struct World {
    pub run: Run,
}

impl World {
    /// `total` steps, in runs of at most [`SIGNAL_EVERY`] without the GIL,
    /// signals checked and `bar` moved on between them.
    fn step_with(&mut self, py: Python<'_>, total: u64, bar: &Progress<'_>) -> PyResult<()> {
        let run = &mut self.run;
        let mut left = total;
        while left > 0 {
            let done = py.detach(|| {
                let started = Instant::now();
                let mut done = 0;
                while done < left && started.elapsed() < SIGNAL_EVERY {
                    run.tick()?;
                    done += 1;
                }
                Ok::<u64, rolypoly_gpu::GpuError>(done)
            });
            let done = done.map_err(|e| gpu_error(&e))?;
            left -= done;
            bar.advance(done)?;
            py.check_signals()?;
        }
        Ok(())
    }
}

#[pymethods]
impl World {
    #[new]
    #[pyo3(signature = (scene=None, seed=1, engine=None))]
    fn new(
        py: Python<'_>,
        scene: Option<&Bound<'_, Scene>>,
        seed: i128,
        engine: Option<&str>,
    ) -> PyResult<World> {
        let seed = u64::try_from(seed).map_err(|_| {
            value_error(format!(
                "seed = {seed} is out of range: allowed 0 ..= {}",
                u64::MAX
            ))
        })?;
        let scene = scene.map_or_else(Scene::builtin, |s| s.get().clone());
        let engine = match engine {
            None => scene.data.engine,
            Some(name) => Engine::from_name(name).ok_or_else(|| {
                value_error(format!(
                    "engine = \"{name}\" is not an engine: use one of {}",
                    Engine::NAMES.join(", ")
                ))
            })?,
        };
        // Placing a million balls takes a while: other threads run meanwhile.
        let run = py.detach(|| Run::new(scene, seed, engine));
        match run {
            Ok(run) => Ok(World { run }),
            Err(MakeError::Build(why)) => Err(value_error(why)),
            Err(MakeError::Gpu(error)) => Err(gpu_error(&error)),
        }
    }

    /// Advances the world by ``n`` fixed steps (``n * dt`` seconds). Other
    /// Python threads run while it steps; Ctrl-C stops it between steps.
    ///
    /// ``progress``: None (the default) shows a tqdm bar where tqdm is
    /// installed, once stepping has lasted a second; True shows it at once
    /// (tqdm required); False never.
    #[pyo3(signature = (n=1, progress=None))]
    fn step(&mut self, py: Python<'_>, n: i64, progress: Option<bool>) -> PyResult<()> {
        let total = u64::try_from(n)
            .map_err(|_| value_error(format!("n = {n}: the number of steps cannot be negative")))?;
        let bar = Progress::new(py, total, progress)?;
        let stepped = self.step_with(py, total, &bar);
        bar.close()?;
        stepped
    }
    /// The steps that ``seconds`` of simulated time take, rounded as
    /// ``rolypoly render --time`` rounds them.
    fn steps_for(&self, seconds: f64) -> PyResult<u64> {
        if !(seconds.is_finite() && seconds >= 0.0) {
            return Err(value_error(format!(
                "seconds = {seconds}: give a time of 0 or more"
            )));
        }
        Ok(steps_for(seconds, self.run.sim.world.config().solver.dt))
    }

    /// Simulated time (s): ``steps * dt``.
    #[getter]
    fn time(&self) -> f64 {
        self.run.sim.world.time()
    }

    /// Steps taken since the world was made.
    #[getter]
    fn steps(&self) -> u64 {
        self.run.sim.world.step_count()
    }

    /// The fixed time step (s).
    #[getter]
    fn dt(&self) -> f64 {
        self.run.sim.world.config().solver.dt
    }

    /// The seed the world was made with.
    #[getter]
    fn seed(&self) -> u64 {
        self.run.seed
    }

    /// The engine that steps the balls: "cpu" or "gpu".
    #[getter]
    fn engine(&self) -> &'static str {
        self.run.engine().name()
    }

    /// The scene the world was made from.
    #[getter]
    fn scene(&self) -> Scene {
        self.run.scene.clone()
    }

    /// The room's inner corners ((x, y, z) least, (x, y, z) greatest), in
    /// metres; the floor is y = 0.
    #[getter]
    fn room(&self) -> (Point, Point) {
        let room = self.run.sim.world.room();
        (room.min.into(), room.max.into())
    }

    /// The balls: positions, velocities, spins, radii, masses, colours,
    /// whether each is in play. See :class:`Balls`.
    #[getter]
    fn balls(slf: Py<World>) -> Balls {
        Balls::of(slf)
    }

    /// The tumblers: positions, orientations, velocities. See
    /// :class:`Tumblers`.
    #[getter]
    fn tumblers(slf: Py<World>) -> Tumblers {
        Tumblers::of(slf)
    }

    /// The fireball while it flies, else None.
    #[getter]
    fn fireball(&self) -> Option<Fireball> {
        self.run.sim.world.fireball().map(Fireball::of)
    }

    /// Kinetic, potential (from the floor) and total energy of every body,
    /// in joules, as the physics adds them up (the fireball's flight
    /// included). Unpacks as ``kinetic, potential, total``.
    fn energy(&mut self) -> PyResult<Energy> {
        let energy = self
            .run
            .sim
            .with_balls(|sim| sim.world.energy())
            .map_err(|e| gpu_error(&e))?;
        Ok(Energy {
            kinetic: energy.kinetic,
            potential: energy.potential,
            total: energy.total(),
        })
    }

    /// The impacts since the last call (or since the world was made), in
    /// the order they happened: collisions, and with each ball that hit a
    /// surface or a tumbler the colour it took on. See :class:`Event`.
    ///
    /// At most a million are kept between calls; if more happened, a
    /// ``RuntimeWarning`` says how many were not kept.
    fn events(&mut self, py: Python<'_>) -> PyResult<Vec<Event>> {
        let run = &mut self.run;
        if run.dropped > 0 {
            let message = format!(
                "{} events were not kept: World.events() keeps at most {} between calls",
                run.dropped,
                crate::run::MAX_PENDING_EVENTS
            );
            run.dropped = 0;
            let category = py.get_type::<PyRuntimeWarning>();
            PyErr::warn(py, &category, &std::ffi::CString::new(message)?, 1)?;
        }
        let world = &run.sim.world;
        Ok(run
            .pending
            .drain(..)
            .map(|(step, event)| Event::new(world, step, &event))
            .collect())
    }

    /// Adds a ball of the scene's radius and mass at ``position`` moving
    /// at ``velocity`` (m/s) and returns its number, as the sandbox's B
    /// throws one. A position outside the room (with the ball's radius),
    /// a velocity that is not finite or faster than a scene allows raise
    /// ``ValueError``. Like a thrown ball, it may land touching or in
    /// another body; the next step pushes them apart.
    fn throw_ball(
        &mut self,
        position: &Bound<'_, PyAny>,
        velocity: &Bound<'_, PyAny>,
    ) -> PyResult<usize> {
        let position = read_vector(position, "throw_ball position")?;
        let velocity = read_vector(velocity, "throw_ball velocity")?;
        let run = &mut self.run;
        let world = &run.sim.world;
        let radius = world.config().balls.radius;
        let room = world.room();
        if !room.contains_sphere(position, radius, 1e-9) {
            let (lo, hi) = (
                room.min + DVec3::splat(radius),
                room.max - DVec3::splat(radius),
            );
            return Err(value_error(format!(
                "the thrown ball at {position} does not lie inside the room: with radius \
                 {radius} its centre must lie within {lo} ..= {hi}"
            )));
        }
        if let Some(problem) = speed_problem("the thrown ball", velocity) {
            return Err(value_error(problem));
        }
        run.sim
            .throw_ball(position, velocity)
            .map_err(|e| gpu_error(&e))
    }

    /// Launches the fireball from ``position`` towards ``direction``, or
    /// from the scene's spawn point along its direction where both are
    /// None (as ``--fireball`` does). It flies at the scene's
    /// ``fireball.speed``. A start outside the room or in a tumbler, or a
    /// direction that is zero or not finite, raises ``ValueError``.
    #[pyo3(signature = (position=None, direction=None))]
    fn launch_fireball(
        &mut self,
        position: Option<&Bound<'_, PyAny>>,
        direction: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<()> {
        let world = &mut self.run.sim.world;
        if position.is_none() && direction.is_none() {
            // The scene's own start, which its checks passed, as --fireball.
            world.launch_fireball(None);
            return Ok(());
        }
        let config = world.config().fireball.clone();
        let position = match position {
            Some(p) => read_vector(p, "launch_fireball position")?,
            None => config.spawn,
        };
        let direction = match direction {
            Some(d) => read_vector(d, "launch_fireball direction")?,
            None => config.direction,
        };
        if let Some(problem) = place_problem(world, "the fireball", position, config.radius) {
            return Err(value_error(problem));
        }
        if direction.length_squared() == 0.0 {
            return Err(value_error(
                "launch_fireball direction: [0, 0, 0] points nowhere; give a direction that is not zero",
            ));
        }
        world.launch_fireball(Some((position, direction)));
        Ok(())
    }

    /// Takes the fireball away: it no longer flies nor collides.
    fn remove_fireball(&mut self) {
        self.run.sim.world.remove_fireball();
    }

    /// A copy of the world's whole state (bodies, random sequence, solver
    /// warm start, effects, events not yet taken) to go back to with
    /// :meth:`restore`: a world restored steps on to the same bits. On
    /// the GPU engine its buffers are copied back whole (about 600 bytes
    /// a ball).
    fn snapshot(&mut self) -> PyResult<Snapshot> {
        let saved = self.run.save().map_err(|e| gpu_error(&e))?;
        Ok(Snapshot { saved })
    }

    /// Puts the world back as it was when ``snapshot`` was taken: of this
    /// world, or of another on the same engine (on the GPU engine, of the
    /// same scene). Another engine's snapshot raises ``ValueError`` and
    /// changes nothing.
    fn restore(&mut self, snapshot: &Snapshot) -> PyResult<()> {
        self.run.restore(&snapshot.saved).map_err(|e| gpu_error(&e))
    }

    /// The world made again from ``scene``, ``seed`` and ``engine`` and put
    /// back to ``snapshot``: how a pickled world is unpickled.
    #[staticmethod]
    fn _restore(
        py: Python<'_>,
        scene: &Bound<'_, Scene>,
        seed: i128,
        engine: &str,
        snapshot: &Snapshot,
    ) -> PyResult<World> {
        let mut world = World::new(py, Some(scene), seed, Some(engine))?;
        world.restore(snapshot)?;
        Ok(world)
    }

    /// Pickled as its scene, seed, engine and a snapshot of its state, so
    /// that a world sent to another process or machine steps on there to
    /// the same bits. On the GPU engine, unpickling needs a graphics
    /// adapter there too.
    #[allow(clippy::type_complexity)]
    fn __reduce__<'py>(
        &mut self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyAny>, (Scene, u64, &'static str, Snapshot))> {
        let snapshot = self.snapshot()?;
        Ok((
            py.get_type::<World>().getattr("_restore")?,
            (
                self.run.scene.clone(),
                self.run.seed,
                self.run.engine().name(),
                snapshot,
            ),
        ))
    }

    /// Steps the world ``steps`` times and gives its totals as ``rolypoly
    /// simulate --series FILE --steps STEPS --series-every EVERY`` writes
    /// them: the state now, then every ``every`` steps and at the last. A
    /// dict of column name to a float64 array, one value a sample, in the
    /// order ``step``, ``time``, ``kinetic_translational``,
    /// ``kinetic_rotational``, ``potential``, ``total``, ``momentum_x``,
    /// ``momentum_y``, ``momentum_z``, the step's impulses on the balls
    /// ``surface_impulse_x`` (``_y``, ``_z``), ``tumbler_impulse_x``,
    /// ``guard_impulse_x`` (each with ``_y`` and ``_z``) and
    /// ``gravity_impulse_y``, ``poured_momentum_y``, ``contacts``, ``impacts``,
    /// ``surface_impacts``, then
    /// ``tumbler_K_tilt`` a tumbler; with ``frame=True``, a pandas
    /// DataFrame of the same columns.
    #[pyo3(signature = (steps, every=1, frame=false))]
    fn series<'py>(
        &mut self,
        py: Python<'py>,
        steps: i64,
        every: i64,
        frame: bool,
    ) -> PyResult<Bound<'py, PyAny>> {
        let (steps, every) = steps_and_every(steps, every)?;
        let run = &mut self.run;
        let samples = py.detach(|| series::samples(run, steps, every))?;
        let tumblers = self.run.sim.world.tumblers().len();
        series::to_python(py, &samples, tumblers, frame)
    }

    /// Steps the world ``steps`` times, writing a JSON Lines trace to
    /// ``path`` as ``rolypoly simulate --trace PATH --steps STEPS --every
    /// EVERY`` writes it: the scene line, the state now, then a state line
    /// every ``every`` steps and at the last, each with the events since
    /// the one before. From a new world the file is byte for byte the
    /// program's. The events also stay for :meth:`events`.
    #[pyo3(signature = (path, steps, every=1))]
    fn write_trace(
        &mut self,
        py: Python<'_>,
        path: PathBuf,
        steps: i64,
        every: i64,
    ) -> PyResult<()> {
        let (steps, every) = steps_and_every(steps, every)?;
        let run = &mut self.run;
        py.detach(|| write_trace(run, &path, steps, every))
    }

    /// The world's frame in a notebook (Jupyter's rich display): what
    /// :func:`render` draws by default, as PNG; nothing without a graphics
    /// adapter, where the notebook shows the text instead.
    fn _repr_png_<'py>(
        slf: &Bound<'py, Self>,
        py: Python<'py>,
    ) -> PyResult<Option<Bound<'py, PyBytes>>> {
        Ok(crate::render::png(py, slf)?.map(|bytes| PyBytes::new(py, &bytes)))
    }

    fn __repr__(&self) -> String {
        let run = &self.run;
        let world = &run.sim.world;
        let (balls, alive) = match run.balls() {
            Ok(balls) => (balls.len(), balls.alive().iter().filter(|&&a| a).count()),
            Err(_) => (0, 0),
        };
        format!(
            "<rolypoly.World of {}, seed {}, engine {}: t = {:.4} s (step {}), {balls} balls \
             ({alive} in play), {} tumblers, fireball {}>",
            run.scene.name,
            run.seed,
            run.engine().name(),
            world.time(),
            world.step_count(),
            world.tumblers().len(),
            if world.fireball().is_some() {
                "flying"
            } else {
                "absent"
            }
        )
    }
}

/// Kinetic, potential and total energy (J). Unpacks as a tuple:
/// ``kinetic, potential, total = world.energy()``.
#[pyclass(module = "rolypoly", name = "Energy", frozen, get_all)]
pub struct Energy {
    /// Energy of motion, moving and turning (J).
    kinetic: f64,
    /// Energy of height above the floor (J).
    potential: f64,
    /// Their sum (J).
    total: f64,
}

#[pymethods]
impl Energy {
    fn __iter__<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let parts = PyTuple::new(py, [self.kinetic, self.potential, self.total])?;
        Ok(parts.try_iter()?.into_any())
    }

    fn __repr__(&self) -> String {
        format!(
            "<rolypoly.Energy kinetic {} J, potential {} J, total {} J>",
            self.kinetic, self.potential, self.total
        )
    }
}

/// A world's whole state, from :meth:`World.snapshot`, for
/// :meth:`World.restore`.
#[pyclass(module = "rolypoly", name = "Snapshot", frozen)]
pub struct Snapshot {
    saved: Saved,
}

#[pymethods]
impl Snapshot {
    /// Simulated time when it was taken (s).
    #[getter]
    fn time(&self) -> f64 {
        self.saved.sim.world.time()
    }

    /// Steps taken when it was taken.
    #[getter]
    fn steps(&self) -> u64 {
        self.saved.sim.world.step_count()
    }

    /// The snapshot as bytes, to store or send to another process or
    /// machine: :meth:`from_bytes` there gives it back. The bytes name the
    /// version of rolypoly that wrote them; another version refuses them.
    fn to_bytes<'py>(&self, py: Python<'py>) -> Bound<'py, PyBytes> {
        PyBytes::new(py, &self.saved.to_bytes())
    }

    /// The snapshot :meth:`to_bytes` wrote. Bytes that are not one, are
    /// cut short, or come from another version raise ``ValueError``. A GPU
    /// engine's snapshot reads without a graphics adapter; putting it
    /// back into a world needs one.
    #[staticmethod]
    fn from_bytes(data: &[u8]) -> PyResult<Snapshot> {
        let saved = Saved::from_bytes(data).map_err(value_error)?;
        Ok(Snapshot { saved })
    }

    /// Pickled as its bytes.
    fn __reduce__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyAny>, (Bound<'py, PyBytes>,))> {
        Ok((
            py.get_type::<Snapshot>().getattr("from_bytes")?,
            (self.to_bytes(py),),
        ))
    }

    /// The seed of the world it was taken of.
    #[getter]
    fn seed(&self) -> u64 {
        self.saved.seed
    }

    /// The engine of the world it was taken of: ``"cpu"`` or ``"gpu"``.
    #[getter]
    fn engine(&self) -> &'static str {
        self.saved.engine().name()
    }

    fn __repr__(&self) -> String {
        format!(
            "<rolypoly.Snapshot of {}, seed {}: t = {:.4} s (step {})>",
            self.saved.scene.name,
            self.saved.seed,
            self.time(),
            self.steps()
        )
    }
}

/// A run's length and spacing as Python gave them, checked: `steps` not
/// negative, `every` at least 1.
fn steps_and_every(steps: i64, every: i64) -> PyResult<(u64, u64)> {
    let steps = u64::try_from(steps)
        .map_err(|_| value_error(format!("steps = {steps}: cannot be negative")))?;
    let every = u64::try_from(every)
        .ok()
        .filter(|&e| e >= 1)
        .ok_or_else(|| value_error(format!("every = {every}: give 1 or more")))?;
    Ok((steps, every))
}
