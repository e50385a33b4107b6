//! `world.balls`: the balls' state as NumPy arrays, and the checked
//! setters of their positions and velocities.

use std::borrow::Cow;

use glam::DVec3;
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use rolypoly_core::trace::tint_name;
use rolypoly_physics::{Balls as PhysicsBalls, World as PhysicsWorld};

use crate::arrays::{column, read_vectors, rows3, vectors};
use crate::checks::{changed, check_positions, check_velocities};
use crate::errors::{gpu_error, value_error};
use crate::world::World;

/// The balls of a :class:`World`, one row per ball, thrown balls and balls
/// the fireball caught included (see :attr:`alive`).
///
/// Every attribute reads a fresh NumPy array, copied from the world (O(N);
/// changing it changes nothing in the world). Positions and velocities
/// are written back whole, ``world.balls.positions = p``; only the balls
/// whose rows change are checked, and a ball moved outside the room, into
/// a tumbler or into another ball (touching is fine) raises ``ValueError``
/// naming the ball, leaving the world as it was.
#[pyclass(module = "rolypoly", name = "Balls", frozen)]
pub struct Balls {
    world: Py<World>,
}

impl Balls {
    pub fn of(world: Py<World>) -> Balls {
        Balls { world }
    }

    /// `read` on the balls now (read back from the GPU on its engine).
    fn read<T>(
        &self,
        py: Python<'_>,
        read: impl FnOnce(&PhysicsBalls, &World) -> T,
    ) -> PyResult<T> {
        let world = self.world.try_borrow(py)?;
        let balls: Cow<'_, PhysicsBalls> = world.run.balls().map_err(|e| gpu_error(&e))?;
        Ok(read(&balls, &world))
    }
}

/// Which of the balls' vectors a setter writes.
#[derive(Clone, Copy)]
enum Written {
    Positions,
    Velocities,
}

impl Written {
    /// The attribute, as messages name it.
    fn name(self) -> &'static str {
        match self {
            Written::Positions => "balls.positions",
            Written::Velocities => "balls.velocities",
        }
    }

    /// The vectors it writes, as they are now.
    fn now(self, balls: &PhysicsBalls) -> &[DVec3] {
        match self {
            Written::Positions => balls.positions(),
            Written::Velocities => balls.velocities(),
        }
    }

    /// Whether `new` may be written to the balls in `moved`.
    fn check(self, world: &PhysicsWorld, new: &[DVec3], moved: &[usize]) -> Result<(), String> {
        match self {
            Written::Positions => check_positions(world, new, moved),
            Written::Velocities => check_velocities(world, new, moved),
        }
    }

    /// Ball `i`'s position and velocity once `new` is written.
    fn apply(self, balls: &PhysicsBalls, i: usize, new: DVec3) -> (DVec3, DVec3) {
        match self {
            Written::Positions => (new, balls.velocities()[i]),
            Written::Velocities => (balls.positions()[i], new),
        }
    }
}

impl Balls {
    /// Writes `value` as the balls' `written` vectors: the rows that change
    /// are checked, then written (on the GPU engine, put on the GPU), or
    /// none is.
    fn write(&self, py: Python<'_>, value: &Bound<'_, PyAny>, written: Written) -> PyResult<()> {
        let mut world = self.world.try_borrow_mut(py)?;
        let sim = &mut world.run.sim;
        // The GPU engine's balls are read back and put in the world while
        // they are checked, as `rolypoly simulate` puts them for its trace.
        let checked = sim
            .with_balls(|sim| {
                let balls = sim.world.balls();
                let new = read_vectors(value, written.name(), balls.len())?;
                let moved = changed(written.now(balls), &new);
                written
                    .check(&sim.world, &new, &moved)
                    .map_err(value_error)?;
                let set: Vec<_> = moved
                    .into_iter()
                    .map(|i| (i, written.apply(balls, i, new[i])))
                    .collect();
                Ok::<_, PyErr>(set)
            })
            .map_err(|e| gpu_error(&e))??;
        for (i, (position, velocity)) in checked {
            sim.balls
                .set_ball(&mut sim.world, i, position, velocity)
                .map_err(|e| gpu_error(&e))?;
        }
        Ok(())
    }
}

#[pymethods]
impl Balls {
    /// Centres, shape (N, 3), float64, metres; the floor is y = 0.
    #[getter]
    fn positions<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        self.read(py, |balls, _| vectors(py, balls.positions()))?
    }

    #[setter]
    fn set_positions(&self, py: Python<'_>, value: &Bound<'_, PyAny>) -> PyResult<()> {
        self.write(py, value, Written::Positions)
    }

    /// Velocities, shape (N, 3), float64, m/s.
    #[getter]
    fn velocities<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        self.read(py, |balls, _| vectors(py, balls.velocities()))?
    }

    #[setter]
    fn set_velocities(&self, py: Python<'_>, value: &Bound<'_, PyAny>) -> PyResult<()> {
        self.write(py, value, Written::Velocities)
    }

    /// Angular velocities, shape (N, 3), float64, rad/s.
    #[getter]
    fn spins<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        self.read(py, |balls, _| vectors(py, balls.spins()))?
    }

    /// Radii, shape (N,), float64, metres.
    #[getter]
    fn radii<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        self.read(py, |balls, _| column(py, balls.radii()))
    }

    /// Masses, shape (N,), float64, kg.
    #[getter]
    fn masses<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        self.read(py, |balls, _| column(py, balls.masses()))
    }

    /// The colour each ball shows (r, g, b in linear light, 0 to 1): the
    /// colour of what it hit last (P5). Shape (N, 3), float64.
    #[getter]
    fn colors<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        self.read(py, |balls, world| {
            let world = &world.run.sim.world;
            rows3(
                py,
                balls
                    .tints()
                    .iter()
                    .map(|&tint| world.tint_color(tint).map(f64::from)),
            )
        })?
    }

    /// What each ball took its colour from, as traces name it: "white", a
    /// surface ("floor", "left"...), "tumblerN" or "placedK". A list of N.
    #[getter]
    fn tints(&self, py: Python<'_>) -> PyResult<Vec<String>> {
        self.read(py, |balls, _| {
            balls
                .tints()
                .iter()
                .map(|&t| tint_name(t).into_owned())
                .collect()
        })
    }

    /// Whether each ball is in play (False once the fireball caught it).
    /// Shape (N,), bool.
    #[getter]
    fn alive<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<bool>>> {
        self.read(py, |balls, _| column(py, balls.alive()))
    }

    fn __len__(&self, py: Python<'_>) -> PyResult<usize> {
        self.read(py, |balls, _| balls.len())
    }

    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        self.read(py, |balls, _| {
            let alive = balls.alive().iter().filter(|&&a| a).count();
            format!("<rolypoly.Balls: {} balls, {alive} in play>", balls.len())
        })
    }
}
