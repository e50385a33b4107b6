//! `rolypoly.Event`: one impact the physics reported (P9), with the
//! colour a ball took on from it (P5).

use pyo3::prelude::*;
use pyo3::types::PyDict;
use rolypoly_core::trace::{EVENT_KINDS, event_kind_name};
use rolypoly_physics::{Event as PhysicsEvent, EventKind, Surface, Tint, World};

use crate::errors::value_error;

/// One impact: which bodies met, where, along which normal, how hard, in
/// which step; and for a ball that hit a surface or a tumbler, the colour
/// it took on.
///
/// ``kind`` is one of ``"ball_surface"``, ``"ball_ball"``,
/// ``"ball_tumbler"``, ``"fireball_surface"``, ``"fireball_ball"`` (the
/// fireball caught the ball), ``"fireball_tumbler"``, as in traces. The
/// fields a kind has not are ``None``.
#[pyclass(module = "rolypoly", name = "Event", frozen, get_all)]
pub struct Event {
    /// What met: see the class's doc.
    kind: &'static str,
    /// The step the impact happened in (1 for the first step).
    step: u64,
    /// The simulated time at the end of that step (s).
    time: f64,
    /// The ball (ball_surface, ball_tumbler, fireball_ball).
    ball: Option<usize>,
    /// One ball of a ball_ball impact.
    a: Option<usize>,
    /// The other ball of a ball_ball impact.
    b: Option<usize>,
    /// The tumbler hit.
    tumbler: Option<usize>,
    /// Which of the tumbler's six spheres.
    sphere: Option<usize>,
    /// The surface hit: floor, ceiling, left, right, back or front.
    surface: Option<&'static str>,
    /// The contact point (m).
    point: (f64, f64, f64),
    /// The contact normal, from the second body (or the surface) to the first.
    normal: (f64, f64, f64),
    /// Approach speed along the normal just before the impact (m/s).
    speed: f64,
    /// The colour (r, g, b) the ball took on, for ball_surface and
    /// ball_tumbler; else None.
    color: Option<(f64, f64, f64)>,
}

impl Event {
    /// `event` of step `step`, its colours read in `world`.
    pub fn new(world: &World, step: u64, event: &PhysicsEvent) -> Event {
        let color = |tint| {
            let [r, g, b] = world.tint_color(tint).map(f64::from);
            Some((r, g, b))
        };
        let mut out = Event {
            kind: event_kind_name(&event.kind),
            step,
            time: step as f64 * world.config().solver.dt,
            ball: None,
            a: None,
            b: None,
            tumbler: None,
            sphere: None,
            surface: None,
            point: event.point.into(),
            normal: event.normal.into(),
            speed: event.speed,
            color: None,
        };
        match event.kind {
            EventKind::BallSurface { ball, surface } => {
                out.ball = Some(ball);
                out.surface = Some(surface.name());
                out.color = color(Tint::Surface(surface));
            }
            EventKind::BallBall { a, b } => (out.a, out.b) = (Some(a), Some(b)),
            EventKind::BallTumbler {
                ball,
                tumbler,
                sphere,
            } => {
                (out.ball, out.tumbler, out.sphere) = (Some(ball), Some(tumbler), Some(sphere));
                out.color = color(Tint::Tumbler(tumbler));
            }
            EventKind::FireballSurface { surface } => out.surface = Some(surface.name()),
            EventKind::FireballBall { ball } => out.ball = Some(ball),
            EventKind::FireballTumbler { tumbler, sphere } => {
                (out.tumbler, out.sphere) = (Some(tumbler), Some(sphere));
            }
        }
        out
    }
}

/// The field a pickled event holds, read back from its dict.
fn field<'py, T: for<'a> FromPyObject<'a, 'py, Error = PyErr>>(
    dict: &Bound<'py, PyDict>,
    name: &str,
) -> PyResult<Option<T>> {
    dict.get_item(name)?.map(|v| v.extract()).transpose()
}

#[pymethods]
impl Event {
    /// An event from the dict :meth:`to_dict` gave: how a pickled event is
    /// made again.
    #[staticmethod]
    fn _from_dict(dict: &Bound<'_, PyDict>) -> PyResult<Event> {
        let missing = |name: &str| value_error(format!("an event's dict has no `{name}`"));
        let kind: String = field(dict, "kind")?.ok_or_else(|| missing("kind"))?;
        let kind = EVENT_KINDS
            .into_iter()
            .find(|k| *k == kind)
            .ok_or_else(|| value_error(format!("`{kind}` is no kind of event")))?;
        let surface = field::<String>(dict, "surface")?
            .map(|name| {
                Surface::ALL
                    .into_iter()
                    .map(Surface::name)
                    .find(|s| *s == name)
                    .ok_or_else(|| value_error(format!("`{name}` is no surface of the room")))
            })
            .transpose()?;
        Ok(Event {
            kind,
            step: field(dict, "step")?.ok_or_else(|| missing("step"))?,
            time: field(dict, "time")?.ok_or_else(|| missing("time"))?,
            ball: field(dict, "ball")?,
            a: field(dict, "a")?,
            b: field(dict, "b")?,
            tumbler: field(dict, "tumbler")?,
            sphere: field(dict, "sphere")?,
            surface,
            point: field(dict, "point")?.ok_or_else(|| missing("point"))?,
            normal: field(dict, "normal")?.ok_or_else(|| missing("normal"))?,
            speed: field(dict, "speed")?.ok_or_else(|| missing("speed"))?,
            color: field(dict, "color")?,
        })
    }

    /// Pickled as its dict: events travel to other processes.
    fn __reduce__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyAny>, (Bound<'py, PyDict>,))> {
        Ok((
            py.get_type::<Event>().getattr("_from_dict")?,
            (self.to_dict(py)?,),
        ))
    }

    /// Two events are equal when every field is.
    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        other.extract::<PyRef<'_, Event>>().is_ok_and(|o| {
            (
                o.kind, o.step, o.time, o.ball, o.a, o.b, o.tumbler, o.sphere, o.surface,
            ) == (
                self.kind,
                self.step,
                self.time,
                self.ball,
                self.a,
                self.b,
                self.tumbler,
                self.sphere,
                self.surface,
            ) && (o.point, o.normal, o.speed, o.color)
                == (self.point, self.normal, self.speed, self.color)
        })
    }

    /// The event as a dict of its fields (those of its kind only).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let dict = PyDict::new(py);
        dict.set_item("kind", self.kind)?;
        dict.set_item("step", self.step)?;
        dict.set_item("time", self.time)?;
        for (name, value) in [
            ("ball", self.ball),
            ("a", self.a),
            ("b", self.b),
            ("tumbler", self.tumbler),
            ("sphere", self.sphere),
        ] {
            if let Some(value) = value {
                dict.set_item(name, value)?;
            }
        }
        if let Some(surface) = self.surface {
            dict.set_item("surface", surface)?;
        }
        dict.set_item("point", self.point)?;
        dict.set_item("normal", self.normal)?;
        dict.set_item("speed", self.speed)?;
        if let Some(color) = self.color {
            dict.set_item("color", color)?;
        }
        Ok(dict)
    }

    fn __repr__(&self) -> String {
        let who = match self.kind {
            "ball_ball" => format!("balls {} and {}", show(self.a), show(self.b)),
            "ball_surface" => format!(
                "ball {} on the {}",
                show(self.ball),
                self.surface.unwrap_or("?")
            ),
            "ball_tumbler" => format!("ball {} on tumbler {}", show(self.ball), show(self.tumbler)),
            "fireball_surface" => format!("fireball on the {}", self.surface.unwrap_or("?")),
            "fireball_ball" => format!("fireball caught ball {}", show(self.ball)),
            _ => format!("fireball on tumbler {}", show(self.tumbler)),
        };
        format!(
            "<rolypoly.Event {} step {} (t = {:.4} s): {who} at {:.3} m/s>",
            self.kind, self.step, self.time, self.speed
        )
    }
}

fn show(n: Option<usize>) -> String {
    n.map_or_else(|| "?".into(), |n| n.to_string())
}
