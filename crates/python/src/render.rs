//! `rolypoly.render`: a world's frame drawn off-screen by the program's own
//! renderer (`rolypoly render`'s frames), returned as an (H, W, 4) array.

use std::sync::{Mutex, PoisonError};

use glam::Vec3;
use numpy::{PyArray1, PyArray3, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyList, PyString, PyTuple};
use rolypoly_core::frames::FrameOptions as Drawing;
use rolypoly_core::frames::Frames;
use rolypoly_core::simulation::Simulation;
use rolypoly_physics::WorldConfig;
use rolypoly_render::{Camera, DebugViews, FrameView, LightConfig, QualityChoice};

use crate::errors::{device_error, gpu_error, value_error};
use crate::run::Run;
use crate::world::World;

/// The largest frame side, as `--size` allows.
const MAX_SIDE: u32 = 8192;

/// What a renderer was made for: a new one is made when any of it changes.
#[derive(PartialEq)]
struct Made {
    config: WorldConfig,
    scene_quality: QualityChoice,
    quality: Option<QualityChoice>,
    size: (u32, u32),
    show: DebugViews,
    view: FrameView,
}

/// The last renderer made: opening the adapter and building the pipelines
/// takes longer than a frame, so it is kept for the next call.
static FRAMES: Mutex<Option<(Made, Frames)>> = Mutex::new(None);

/// Draws ``world`` as it is now into an (H, W, 4) uint8 RGBA array, with
/// the renderer and settings of ``rolypoly render``: for the same scene,
/// seed, time and camera, the same pixels as its PNG on the same adapter.
///
/// ``size`` is (width, height) in pixels, each 1 to 8192. ``camera`` is
/// ``(eye, target)``, two points (x, y, z) in metres, or None for the
/// program's overview of the room (see :func:`overview_camera`).
/// ``quality`` is "high", "medium", "low" or "auto" (drawn as high), None
/// for the scene's ``render.quality``. ``show`` names debug views drawn
/// over the frame: some of "contacts", "impulses", "velocities", "grid",
/// "rest", "com" (a list, or one comma-separated string). ``view`` names
/// the view of the frame's passes drawn instead of the finished frame, as
/// ``rolypoly render --view``: "final" (None), "albedo", "normals",
/// "depth", "shadow-cube", "shadow", "ambient", "diffuse", "specular",
/// "bounce", "occlusion", "bloom", "motion", "history" or "msaa-edges"
/// (:func:`frame_views` lists them with what each shows).
///
/// Without a usable graphics adapter it raises ``rolypoly.DeviceError``;
/// Mesa's lavapipe draws on machines without a GPU.
#[pyfunction]
#[pyo3(signature = (world, size=(640, 360), camera=None, quality=None, show=None, view=None))]
pub fn render<'py>(
    py: Python<'py>,
    world: &Bound<'py, World>,
    size: (i64, i64),
    camera: Option<&Bound<'py, PyAny>>,
    quality: Option<&str>,
    show: Option<&Bound<'py, PyAny>>,
    view: Option<&str>,
) -> PyResult<Bound<'py, PyArray3<u8>>> {
    let options = FrameOptions::read(size, camera, quality, show, view)?;
    let world = world.try_borrow()?;
    let run = &world.run;
    let held = held_balls(run)?;
    let sim = held.as_ref().unwrap_or(&run.sim);
    let image = py
        .detach(|| {
            with_frames(run, &options, |frames, light, camera| {
                frames.draw_from(sim, light, camera)
            })
        })
        .map_err(|e| device_error(&e))?;
    let (width, height) = (image.width() as usize, image.height() as usize);
    PyArray1::from_vec(py, image.into_raw()).reshape([height, width, 4])
}

/// `world` drawn as :func:`render` draws it by default (640x360, the
/// overview), as PNG bytes: what a notebook shows for a world. None where
/// there is no graphics adapter to draw with, so that the notebook shows
/// the world's text instead.
pub fn png(py: Python<'_>, world: &Bound<'_, World>) -> PyResult<Option<Vec<u8>>> {
    let options = FrameOptions::read((640, 360), None, None, None, None)?;
    let world = world.try_borrow()?;
    let run = &world.run;
    let held = held_balls(run)?;
    let sim = held.as_ref().unwrap_or(&run.sim);
    let Ok(image) = py.detach(|| {
        with_frames(run, &options, |frames, light, camera| {
            frames.draw_from(sim, light, camera)
        })
    }) else {
        return Ok(None);
    };
    let mut bytes = Vec::new();
    image
        .write_to(
            &mut std::io::Cursor::new(&mut bytes),
            image::ImageFormat::Png,
        )
        .map_err(|e| value_error(format!("cannot encode the frame as PNG: {e}")))?;
    Ok(Some(bytes))
}

/// How frames are drawn, as ``render`` and ``record`` take it.
pub struct FrameOptions {
    pub size: (u32, u32),
    quality: Option<QualityChoice>,
    show: DebugViews,
    view: FrameView,
    eye_target: Option<(Vec3, Vec3)>,
}

impl FrameOptions {
    /// The options as Python gave them, checked.
    pub fn read(
        size: (i64, i64),
        camera: Option<&Bound<'_, PyAny>>,
        quality: Option<&str>,
        show: Option<&Bound<'_, PyAny>>,
        view: Option<&str>,
    ) -> PyResult<FrameOptions> {
        let view = view
            .map(|name| {
                name.parse::<FrameView>()
                    .map_err(|e| value_error(format!("view: {e}")))
            })
            .transpose()?
            .unwrap_or_default();
        let quality = quality
            .map(|name| {
                QualityChoice::from_name(name).ok_or_else(|| {
                    value_error(format!(
                        "quality = \"{name}\" is not a quality level: use one of {}",
                        QualityChoice::NAMES.join(", ")
                    ))
                })
            })
            .transpose()?;
        Ok(FrameOptions {
            size: frame_size(size)?,
            quality,
            show: debug_views(show)?,
            view,
            eye_target: camera.map(read_camera).transpose()?,
        })
    }
}

/// The GPU engine's balls are drawn from a copy of the world that holds
/// them, read back; None on the CPU engine.
pub fn held_balls(run: &Run) -> PyResult<Option<Simulation>> {
    let Some(gpu) = run.sim.balls.gpu_balls() else {
        return Ok(None);
    };
    let balls = gpu.read().map_err(|e| gpu_error(&e))?.to_balls();
    drop(gpu);
    let mut sim = run.sim.clone();
    // A copy that draws its balls from the world, not from the GPU.
    sim.balls = Default::default();
    sim.world.put_balls(balls);
    Ok(Some(sim))
}

/// `draw` with the renderer for `run`'s scene and `options` (the one kept,
/// or a new one), its light and camera. Call without the GIL: other
/// threads may be drawing.
pub fn with_frames<T>(
    run: &Run,
    options: &FrameOptions,
    draw: impl FnOnce(&mut Frames, &LightConfig, &Camera) -> anyhow::Result<T>,
) -> anyhow::Result<T> {
    let made = Made {
        config: run.sim.world.config().clone(),
        scene_quality: run.scene.data.quality,
        quality: options.quality,
        size: options.size,
        show: options.show,
        view: options.view,
    };
    let mut cache = FRAMES.lock().unwrap_or_else(PoisonError::into_inner);
    if cache.as_ref().is_none_or(|(was, _)| *was != made) {
        // The old renderer goes first: two may not fit the adapter.
        *cache = None;
        let args = frame_args(options.quality, options.show, options.view);
        let frames = Frames::new(&made.config, made.scene_quality, &args, options.size)?;
        *cache = Some((made, frames));
    }
    let Some((made, frames)) = cache.as_mut() else {
        unreachable!("a renderer was just made");
    };
    let overview = Camera::overview(made.config.room.size.as_vec3());
    let camera = match options.eye_target {
        Some((eye, target)) => Camera {
            eye,
            target,
            ..overview
        },
        None => overview,
    };
    draw(frames, &run.scene.data.light, &camera)
}

/// Every view of the frame's passes ``render``'s ``view`` takes, as
/// ``(name, what it shows)`` pairs in the order the window's V steps
/// through them.
#[pyfunction]
pub fn frame_views() -> Vec<(&'static str, &'static str)> {
    FrameView::ALL
        .iter()
        .map(|v| (v.name(), v.about()))
        .collect()
}

/// The camera ``render`` uses when given none: the program's overview of
/// ``world``'s room, from outside its front wall. Returns ``(eye, target)``.
#[pyfunction]
pub fn overview_camera(world: &Bound<'_, World>) -> PyResult<(Point, Point)> {
    let world = world.try_borrow()?;
    let camera = Camera::overview(world.run.sim.world.config().room.size.as_vec3());
    let point = |v: Vec3| (f64::from(v.x), f64::from(v.y), f64::from(v.z));
    Ok((point(camera.eye), point(camera.target)))
}

/// A point (x, y, z) in metres, as Python sees it.
type Point = (f64, f64, f64);

/// The options of `rolypoly render` that these frames differ by.
fn frame_args(quality: Option<QualityChoice>, show: DebugViews, view: FrameView) -> Drawing {
    Drawing {
        quality,
        show: Some(show),
        view: Some(view),
        ..Drawing::default()
    }
}

fn frame_size((width, height): (i64, i64)) -> PyResult<(u32, u32)> {
    let side = |n: i64| u32::try_from(n).ok().filter(|n| (1..=MAX_SIDE).contains(n));
    match (side(width), side(height)) {
        (Some(w), Some(h)) => Ok((w, h)),
        _ => Err(value_error(format!(
            "size = ({width}, {height}) is out of range: each side 1 ..= {MAX_SIDE} pixels"
        ))),
    }
}

fn debug_views(show: Option<&Bound<'_, PyAny>>) -> PyResult<DebugViews> {
    let Some(show) = show else {
        return Ok(DebugViews::default());
    };
    let names: Vec<String> = if show.is_instance_of::<PyString>() {
        vec![show.extract()?]
    } else if show.is_instance_of::<PyList>() || show.is_instance_of::<PyTuple>() {
        show.extract()
            .map_err(|_| value_error("show: give the debug views' names as strings"))?
    } else {
        return Err(value_error("show: give a list of debug views' names"));
    };
    DebugViews::parse(&names.join(",")).map_err(|why| value_error(format!("show: {why}")))
}

/// `(eye, target)`: two points of three numbers, apart.
pub fn read_camera(camera: &Bound<'_, PyAny>) -> PyResult<(Vec3, Vec3)> {
    let bad = || {
        value_error(
            "camera: give (eye, target), two points (x, y, z) in metres, such as \
             ((0, 2, 9), (0, 1, 0))",
        )
    };
    let (eye, target): ([f64; 3], [f64; 3]) = camera.extract().map_err(|_| bad())?;
    let (eye, target) = (glam::DVec3::from(eye), glam::DVec3::from(target));
    if !(eye.is_finite() && target.is_finite()) {
        return Err(value_error(format!(
            "camera: eye {eye} and target {target} must be finite"
        )));
    }
    if eye.distance(target) < 1e-6 {
        return Err(value_error(format!(
            "camera: eye and target are the same point {eye}; the camera must look somewhere"
        )));
    }
    Ok((eye.as_vec3(), target.as_vec3()))
}
