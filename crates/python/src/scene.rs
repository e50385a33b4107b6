//! `rolypoly.Scene`: a scene file read and checked by the program's own
//! reader, with overrides of any of its keys.

use std::path::PathBuf;

use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};
use rolypoly_core::scene::keys::{KEYS, Slot, key};
use rolypoly_core::scene::{
    self, BUILTIN_ORIGIN, Overrides, Scene as SceneData, load_scene, parse_scene, scene_file_text,
};
use rolypoly_physics::Rgb;

use crate::errors::{io_error, one_line, scene_error, value_error};
use crate::overrides::{self, Override};

/// A scene: the room, its balls, tumblers and fireball, the light and the
/// solver's settings, read and checked exactly as ``rolypoly --scene FILE``
/// reads them.
///
/// Make one with :meth:`Scene.default`, :meth:`Scene.load` or
/// :meth:`Scene.parse`. Each takes ``overrides``, a dict of the scene
/// file's dotted keys laid over the scene, such as
/// ``{"balls.count": 2000, "balls.friction": 0.5}``. A bad file, key or
/// value raises ``ValueError`` with the program's one-line message, which
/// names the file and line or the override.
///
/// Two scenes are equal when every key is, whatever their names.
#[pyclass(module = "rolypoly", name = "Scene", frozen, eq)]
#[derive(Clone)]
pub struct Scene {
    pub data: SceneData,
    /// How messages and reprs name the scene: "the built-in default scene"
    /// or "scene `FILE`".
    pub name: String,
}

impl PartialEq for Scene {
    fn eq(&self, other: &Scene) -> bool {
        self.data == other.data
    }
}

impl Scene {
    fn build(
        source: Option<&str>,
        origin: &str,
        name: String,
        overrides: &[Override],
    ) -> PyResult<Scene> {
        let data = if overrides.is_empty() {
            match source {
                Some(text) => parse_scene(text, origin),
                None => load_scene(None),
            }
        } else {
            overrides::scene_with(source, origin, overrides)
        };
        data.map(|data| Scene { data, name })
            .map_err(|e| scene_error(&e))
    }

    /// The default scene, as a world made with `scene=None` uses.
    pub fn builtin() -> Scene {
        Scene {
            data: SceneData::default(),
            name: format!("the {BUILTIN_ORIGIN}"),
        }
    }

    /// The scene as a scene file (what `to_toml` gives, and what a scene
    /// travels to other processes as).
    pub fn text(&self) -> String {
        scene_file_text(
            &self.data,
            &format!("Saved from {} by rolypoly (Python).", self.name),
        )
    }

    /// The scene `text` (from [`Scene::text`]), named `name` again.
    pub fn from_text(text: &str, name: String) -> Result<Scene, scene::SceneError> {
        let data = parse_scene(text, &name)?;
        Ok(Scene { data, name })
    }
}

#[pymethods]
impl Scene {
    /// The built-in default scene (``scenes/default.toml``), with
    /// ``overrides`` laid over it.
    #[staticmethod]
    #[pyo3(signature = (overrides=None))]
    fn default(overrides: Option<&Bound<'_, PyDict>>) -> PyResult<Scene> {
        let overrides = overrides::from_dict(overrides)?;
        Scene::build(
            None,
            BUILTIN_ORIGIN,
            format!("the {BUILTIN_ORIGIN}"),
            &overrides,
        )
    }

    /// The scene file at ``path`` over the default scene, with
    /// ``overrides`` laid over both. A file that cannot be read raises
    /// ``OSError`` (``FileNotFoundError`` where there is none).
    #[staticmethod]
    #[pyo3(signature = (path, overrides=None))]
    fn load(path: PathBuf, overrides: Option<&Bound<'_, PyDict>>) -> PyResult<Scene> {
        let overrides = overrides::from_dict(overrides)?;
        let origin = path.display().to_string();
        let name = format!("scene `{origin}`");
        if overrides.is_empty() {
            let data = scene::load_scene_with(Some(&path), &Overrides::default())
                .map_err(|e| scene_error(&e))?;
            return Ok(Scene { data, name });
        }
        let text = std::fs::read_to_string(&path).map_err(|source| {
            let kind = source.kind();
            let error = scene::SceneError::Read {
                path: origin.clone(),
                source,
            };
            io_error(kind, one_line(&error))
        })?;
        Scene::build(Some(&text), &origin, name, &overrides)
    }

    /// A scene file's text over the default scene, with ``overrides``
    /// laid over both; ``name`` is how messages name the text.
    #[staticmethod]
    #[pyo3(signature = (text, overrides=None, name="<string>"))]
    fn parse(text: &str, overrides: Option<&Bound<'_, PyDict>>, name: &str) -> PyResult<Scene> {
        let overrides = overrides::from_dict(overrides)?;
        Scene::build(Some(text), name, format!("scene `{name}`"), &overrides)
    }

    /// A scene from the text :meth:`to_toml` wrote and its name: how a
    /// pickled scene is made again.
    #[staticmethod]
    fn _restore(text: &str, name: String) -> PyResult<Scene> {
        Scene::from_text(text, name).map_err(|e| scene_error(&e))
    }

    /// Pickled as its whole text and its name: scenes travel to other
    /// processes and machines, every key with them.
    fn __reduce__<'py>(&self, py: Python<'py>) -> PyResult<(Bound<'py, PyAny>, (String, String))> {
        Ok((
            py.get_type::<Scene>().getattr("_restore")?,
            (self.to_toml(), self.name.clone()),
        ))
    }

    /// The value of a scene key, such as ``"balls.count"`` or
    /// ``"room.size"`` (a tuple). Keys that hold lists of entries are read
    /// from :meth:`to_toml`.
    fn get<'py>(&self, py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyAny>> {
        let Some(found) = key(name) else {
            return Err(value_error(format!(
                "unknown key `{name}`: Scene.keys() lists them all"
            )));
        };
        let scene = &self.data;
        let value = match &found.slot {
            Slot::Real(place) => (place.read)(scene).into_pyobject(py)?.into_any(),
            Slot::Single(place) => f64::from(*(place.read)(scene))
                .into_pyobject(py)?
                .into_any(),
            Slot::Count(place) => (place.read)(scene).into_pyobject(py)?.into_any(),
            Slot::Switch(place) => (*(place.read)(scene))
                .into_pyobject(py)?
                .to_owned()
                .into_any(),
            Slot::Vector(place) => PyTuple::new(py, (place.read)(scene).to_array())?.into_any(),
            Slot::Color(place) => PyTuple::new(py, rgb(*(place.read)(scene)))?.into_any(),
            Slot::Word(place) => (place.read)(scene).into_pyobject(py)?.into_any(),
            Slot::List(_) => {
                return Err(value_error(format!(
                    "`{name}` holds a list of entries: read it from Scene.to_toml()"
                )));
            }
        };
        Ok(value)
    }

    /// Every key a scene file may set, in the order of
    /// ``scenes/default.toml`` (``docs/scenes.md`` says what each is for).
    #[staticmethod]
    fn keys() -> Vec<&'static str> {
        KEYS.iter().map(|k| k.name).collect()
    }

    /// The scene as a scene file: the keys that differ from the default
    /// scene. ``Scene.parse(scene.to_toml())`` gives the same scene.
    fn to_toml(&self) -> String {
        self.text()
    }

    /// How the scene is named: "the built-in default scene" or
    /// "scene `FILE`".
    #[getter]
    fn name(&self) -> &str {
        &self.name
    }

    /// Balls the scene starts with: its random ones and its placed ones.
    #[getter]
    fn ball_count(&self) -> usize {
        self.data.world.balls.total()
    }

    /// Tumblers in the scene.
    #[getter]
    fn tumbler_count(&self) -> usize {
        self.data.world.tumblers.placements.len()
    }

    /// The fixed time step (s).
    #[getter]
    fn dt(&self) -> f64 {
        self.data.world.solver.dt
    }

    /// Gravitational acceleration (m/s²), along -y.
    #[getter]
    fn gravity(&self) -> f64 {
        self.data.world.gravity
    }

    /// The room's inner size (x, y, z) in metres; the floor is y = 0.
    #[getter]
    fn room_size(&self) -> (f64, f64, f64) {
        self.data.world.room.size.into()
    }

    /// The engine the scene asks for (``solver.engine``): "cpu" or "gpu".
    #[getter]
    fn engine(&self) -> &'static str {
        self.data.engine.name()
    }

    /// How finely frames are drawn (``render.quality``).
    #[getter]
    fn quality(&self) -> &'static str {
        self.data.quality.name()
    }

    /// The scene as a table in a notebook: what it holds, then each key
    /// it sets apart from the default scene with its value.
    fn _repr_html_(&self) -> String {
        let world = &self.data.world;
        let size = world.room.size;
        let rows = vec![
            ("scene".to_owned(), self.name.clone()),
            ("balls".to_owned(), world.balls.total().to_string()),
            (
                "tumblers".to_owned(),
                world.tumblers.placements.len().to_string(),
            ),
            (
                "room (m)".to_owned(),
                format!("{} x {} x {}", size.x, size.y, size.z),
            ),
            ("gravity (m/s²)".to_owned(), world.gravity.to_string()),
            ("dt (s)".to_owned(), world.solver.dt.to_string()),
            ("engine".to_owned(), self.data.engine.name().to_owned()),
        ];
        let mut set = Vec::new();
        if let Ok(table) = toml::from_str::<toml::Table>(&self.text()) {
            flatten("", &table, &mut set);
        }
        let escape = |text: &str| {
            text.replace('&', "&amp;")
                .replace('<', "&lt;")
                .replace('>', "&gt;")
        };
        let mut html = String::from("<table>");
        for (key, value) in &rows {
            html += &format!(
                "<tr><th>{}</th><td>{}</td></tr>",
                escape(key),
                escape(value)
            );
        }
        if !set.is_empty() {
            html += "<tr><th colspan=\"2\">keys set apart from the default scene</th></tr>";
            for (key, value) in set.drain(..) {
                html += &format!(
                    "<tr><td><code>{}</code></td><td><code>{}</code></td></tr>",
                    escape(&key),
                    escape(&value)
                );
            }
        }
        html + "</table>"
    }

    fn __repr__(&self) -> String {
        let world = &self.data.world;
        format!(
            "<rolypoly.Scene {}: {} balls, {} tumblers, room {}x{}x{} m, gravity {} m/s², \
             dt {} s, engine {}>",
            self.name,
            world.balls.total(),
            world.tumblers.placements.len(),
            world.room.size.x,
            world.room.size.y,
            world.room.size.z,
            world.gravity,
            world.solver.dt,
            self.data.engine.name()
        )
    }
}

/// Each key of `table` under `prefix` as a dotted name and its value's
/// text, tables opened, in order.
fn flatten(prefix: &str, table: &toml::Table, into: &mut Vec<(String, String)>) {
    for (key, value) in table {
        let name = if prefix.is_empty() {
            key.clone()
        } else {
            format!("{prefix}.{key}")
        };
        match value {
            toml::Value::Table(inner) => flatten(&name, inner, into),
            other => into.push((name, other.to_string())),
        }
    }
}

/// A colour as the decimals it was written with.
pub fn rgb(color: Rgb) -> [f64; 3] {
    color.map(|c| c.to_string().parse().unwrap_or(f64::from(c)))
}
