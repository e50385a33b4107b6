//! `world.tumblers` and `world.fireball`: their state as NumPy arrays and
//! tuples.

use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use rolypoly_physics::{Fireball as PhysicsFireball, Tumbler};

use crate::arrays::{column, rows3, rows4};
use crate::world::World;

/// The tumblers of a :class:`World`, one row per tumbler. Every attribute
/// reads a fresh NumPy array.
#[pyclass(module = "rolypoly", name = "Tumblers", frozen)]
pub struct Tumblers {
    world: Py<World>,
}

impl Tumblers {
    pub fn of(world: Py<World>) -> Tumblers {
        Tumblers { world }
    }

    fn read<T>(&self, py: Python<'_>, read: impl FnOnce(&[Tumbler]) -> T) -> PyResult<T> {
        let world = self.world.try_borrow(py)?;
        Ok(read(world.run.sim.world.tumblers()))
    }

    fn vectors<'py>(
        &self,
        py: Python<'py>,
        of: impl Fn(&Tumbler) -> glam::DVec3,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        self.read(py, |tumblers| {
            rows3(py, tumblers.iter().map(|t| of(t).to_array()))
        })?
    }
}

#[pymethods]
impl Tumblers {
    /// Centres of mass, shape (T, 3), float64, metres.
    #[getter]
    fn positions<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        self.vectors(py, Tumbler::center_of_mass)
    }

    /// Orientations as unit quaternions **(x, y, z, w)**, the order traces
    /// write, shape (T, 4), float64. Upright is (0, 0, 0, 1).
    #[getter]
    fn orientations<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        self.read(py, |tumblers| {
            rows4(py, tumblers.iter().map(|t| t.orientation().to_array()))
        })?
    }

    /// Velocities of the centres of mass, shape (T, 3), float64, m/s.
    #[getter]
    fn velocities<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        self.vectors(py, Tumbler::linear_velocity)
    }

    /// Angular velocities, shape (T, 3), float64, rad/s.
    #[getter]
    fn angular_velocities<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        self.vectors(py, Tumbler::angular_velocity)
    }

    /// Centres of the round bottoms (sphere 0), shape (T, 3), float64, metres.
    #[getter]
    fn bottom_centers<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        self.vectors(py, Tumbler::bottom_center)
    }

    /// Tilts of the axes from the vertical, shape (T,), float64, radians.
    #[getter]
    fn tilts<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        self.read(py, |tumblers| {
            let tilts: Vec<f64> = tumblers.iter().map(Tumbler::tilt).collect();
            column(py, &tilts)
        })
    }

    /// Whether each slides on the floor rather than rolls, shape (T,), bool.
    #[getter]
    fn sliding<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<bool>>> {
        self.read(py, |tumblers| {
            let sliding: Vec<bool> = tumblers.iter().map(Tumbler::sliding).collect();
            column(py, &sliding)
        })
    }

    fn __len__(&self, py: Python<'_>) -> PyResult<usize> {
        self.read(py, <[Tumbler]>::len)
    }

    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        self.read(py, |tumblers| {
            format!("<rolypoly.Tumblers: {} tumblers>", tumblers.len())
        })
    }
}

/// The fireball as it flies now: a copy, taken when read.
#[pyclass(module = "rolypoly", name = "Fireball", frozen, get_all)]
pub struct Fireball {
    /// Its centre (x, y, z), metres.
    position: (f64, f64, f64),
    /// Its velocity (x, y, z), m/s.
    velocity: (f64, f64, f64),
    /// Its radius (m).
    radius: f64,
    /// The constant speed it keeps (m/s).
    speed: f64,
    /// The mass it strikes with (kg): a ball's.
    mass: f64,
}

impl Fireball {
    pub fn of(fireball: &PhysicsFireball) -> Fireball {
        Fireball {
            position: fireball.position.into(),
            velocity: fireball.velocity.into(),
            radius: fireball.radius,
            speed: fireball.speed,
            mass: fireball.mass,
        }
    }
}

#[pymethods]
impl Fireball {
    fn __repr__(&self) -> String {
        let (x, y, z) = self.position;
        format!(
            "<rolypoly.Fireball at ({x:.3}, {y:.3}, {z:.3}) m, {} m/s, radius {} m>",
            self.speed, self.radius
        )
    }
}
