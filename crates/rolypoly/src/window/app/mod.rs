//! The interactive window: one frame is input -> camera and modes -> the
//! sandbox's fixed steps -> render -> panel and HUD -> present (I1-I7).
//!
//! This file holds the window's state and runs the frames. Opening the
//! window is in [`open`]; what the keys and the mouse do, in [`input`];
//! what the panel asks for, in [`actions`]. The simulation, its settings
//! and its playback are the [`Sandbox`]'s.

use std::path::PathBuf;
use std::sync::Arc;
use std::time::{Duration, Instant};

use crate::engine::Engine;
use anyhow::Context as _;
use glam::{Vec2, Vec3};
use rolypoly_physics::SphereSpec;
use rolypoly_render::shaders::{ShaderError, ShaderSet};
use rolypoly_render::{
    AUTO_TARGET_FPS, Camera, FrameView, Gpu, MeshData, OFFSCREEN_FORMAT, OffscreenTarget, Quality,
    QualityChoice, RenderSettings, Renderer,
};
use serde_json::json;
use winit::application::ApplicationHandler;
use winit::event::WindowEvent;
use winit::event_loop::{ActiveEventLoop, EventLoop};
use winit::keyboard::{KeyCode, PhysicalKey};
use winit::window::{Window, WindowId};

use super::fly_camera::FlyCamera;
use super::frame_rate::{FrameParts, FrameRate};
use super::hud::{Hud, HudState};
use super::log::EventLog;
use super::orbit_camera::OrbitCamera;
use super::panel::Panel;
use super::plots::Plots;
use super::profiler::{FrameProfile, Profiler};
use super::quality::{QualityChange, WindowQuality};
use super::shader_watch::ShaderWatch;
use super::sound::LiveSound;
use crate::sandbox::{MAX_CATCH_UP, Sandbox};
use input::{Keys, MouseMode};

mod actions;
mod input;
mod open;

/// How the window is opened and driven.
#[derive(Clone, Debug)]
pub struct WindowOptions {
    /// Width and height in pixels.
    pub size: (u32, u32),
    /// Borderless over the whole screen.
    pub fullscreen: bool,
    /// Wait for the display's refresh.
    pub vsync: bool,
    /// Multisamples at every quality level (4 or 1), or the level's own.
    pub msaa: Option<u32>,
    /// Temporal anti-aliasing with upsampling (see
    /// [`rolypoly_render::jitter`]) in place of multisampling, or None: on
    /// with a GPU, off on a software renderer.
    pub temporal: Option<bool>,
    /// The quality level the flag asks for, over the scene's.
    pub quality: Option<QualityChoice>,
    /// Print every change of state as a JSON line.
    pub log_events: bool,
    /// The scene's seed, for the HUD.
    pub seed: u64,
    /// Where the F12 key writes screenshots.
    pub screenshot_dir: PathBuf,
    /// Walking speed (m/s).
    pub move_speed: f32,
    /// Mouse-look sensitivity (radians per pixel).
    pub look_speed: f32,
    /// The scene file given, offered in the panel's list beside the
    /// shipped scenes.
    pub scene_file: Option<PathBuf>,
    /// For a replay: the digest of the recording's end state, to check the
    /// replay's against.
    pub replay_digest: Option<String>,
    /// In replays, the tick to play up to as soon as the window's device
    /// is known: a recording on the GPU engine runs there from its start.
    pub replay_from: Option<u64>,
    /// The folder of shaders to draw with, watched while the window is
    /// open; None: the shipped ones.
    pub shaders: Option<PathBuf>,
    /// The view of the frame shown first (V and Shift+V change it).
    pub view: FrameView,
}

/// Opens the window on `sandbox` and runs until it is closed.
pub fn run(sandbox: Sandbox, options: WindowOptions) -> anyhow::Result<()> {
    // A shader folder the flags name is read before a display is looked
    // for: its error is the one to fix, wherever the window runs.
    let shaders = match &options.shaders {
        Some(dir) => ShaderSet::load(dir)?,
        None => ShaderSet::shipped(),
    };
    let event_loop = EventLoop::new().context(
        "cannot open a window: no display was found (set DISPLAY or WAYLAND_DISPLAY, \
         or use the `render` and `simulate` commands, which need none)",
    )?;
    let mut app = App::new(sandbox, options, shaders)?;
    event_loop
        .run_app(&mut app)
        .context("the window's event loop failed")?;
    match app.error.take() {
        Some(error) => Err(error),
        None => Ok(()),
    }
}

/// Everything that exists once the window does.
struct Running {
    window: Arc<Window>,
    gpu: Gpu,
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    renderer: Renderer,
    hud: Hud,
    /// The frames submitted and not yet waited for, oldest first, with
    /// their numbers: at most [`FRAMES_IN_FLIGHT`].
    in_flight: std::collections::VecDeque<(u64, wgpu::SubmissionIndex)>,
    /// Frames submitted since the window opened.
    frames_submitted: u64,
    /// The frames a second auto holds where the scene leaves it open: the
    /// display's rate with a GPU, [`AUTO_TARGET_FPS`] on a software
    /// renderer.
    default_fps: f64,
}

/// The scene's `render.target_fps`, unless it is 0 (left open).
fn chosen_fps(target_fps: f64) -> Option<f64> {
    (target_fps > 0.0).then_some(target_fps)
}

/// Frames the GPU may have queued before the next waits, within the
/// program's bound, for the oldest: so that a GPU that stalls ends the
/// window with an error naming the frame instead of a window that never
/// draws.
const FRAMES_IN_FLIGHT: usize = 2;

/// What the orbit camera circles.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Circled {
    Ball(usize),
    Tumbler(usize),
    /// The room's centre.
    Room,
}

/// The plane the cursor drags a held body over: through `point`, facing
/// `normal` (up for a tumbler, which is dragged over the floor; towards
/// the camera for a ball, which the hand lifts and swings).
#[derive(Clone, Copy, Debug)]
struct DragPlane {
    point: glam::DVec3,
    normal: glam::DVec3,
}

struct App {
    sandbox: Sandbox,
    options: WindowOptions,
    log: EventLog,
    /// The tumblers' shape the mesh was made for, the mesh, its coarse
    /// level and its paint.
    tumbler_spheres: Vec<SphereSpec>,
    tumbler_mesh: MeshData,
    coarse_tumbler: MeshData,
    paint: image::RgbaImage,
    /// The shaders drawn with: the shipped ones, or the last good set of
    /// the folder watched.
    shaders: ShaderSet,
    shader_watch: Option<ShaderWatch>,
    /// A reload's first frame, not yet presented: when the file was saved,
    /// how long after it the window read it, and how long the pipelines
    /// took to build.
    reload_shown: Option<(Instant, Duration, Duration)>,
    /// The view of the frame the log last named.
    view_told: FrameView,
    panel: Panel,
    quality: WindowQuality,
    /// The room's sound, played live.
    sound: LiveSound,
    /// The time the last frame spent simulating, which its drawing did not.
    last_simulation: Duration,
    /// The profiler (key F3), and when the window opened (its plots' zero).
    profiler: Profiler,
    /// The plots of the run's totals (key F4).
    plots: Plots,
    opened: Instant,
    /// The frames since the frame rate was last logged.
    frame_rate: FrameRate,
    running: Option<Running>,
    error: Option<anyhow::Error>,

    camera: FlyCamera,
    /// While O holds it: the orbit camera, which the fly camera follows,
    /// and what it circles.
    orbit: Option<(OrbitCamera, Circled)>,
    mode: MouseMode,
    keys: Keys,
    /// Our arrow cursor in grab mode (pixels), and the height of the plane a
    /// held tumbler is dragged over.
    cursor: Vec2,
    drag_plane: Option<DragPlane>,
    /// Mouse look measures moves from the window's centre, where it puts the
    /// pointer back after each; false until the pointer is known to be there.
    look_settled: bool,

    last_frame: Option<Instant>,
    hud_state: HudState,
    camera_logged: Instant,
    /// The camera as last written to the event log, and as last given to
    /// the sandbox's recording.
    camera_reported: FlyCamera,
    camera_recorded: FlyCamera,
    screenshots: u32,
}

impl App {
    /// The app on `sandbox`, drawing with `shaders` (the flags' folder's,
    /// read, or the shipped ones).
    fn new(sandbox: Sandbox, options: WindowOptions, shaders: ShaderSet) -> anyhow::Result<App> {
        let world = sandbox.world();
        let room = world.config().room.size.as_vec3();
        let tumbler_spheres = world.config().tumblers.spheres.clone();
        let (tumbler_mesh, coarse_tumbler, paint) = tumbler_look(&tumbler_spheres)?;
        let camera = FlyCamera::from_camera(&Camera::overview(room));
        let shader_watch = options
            .shaders
            .as_deref()
            .map(ShaderWatch::new)
            .transpose()?;
        let mut panel = Panel::new(options.scene_file.clone());
        panel.view = options.view;
        Ok(App {
            log: EventLog::new(options.log_events),
            camera,
            orbit: None,
            camera_reported: camera,
            camera_recorded: camera,
            hud_state: HudState::new(options.seed, world.balls().len()),
            panel,
            shaders,
            shader_watch,
            reload_shown: None,
            view_told: options.view,
            quality: WindowQuality::new(
                sandbox.scene().quality,
                chosen_fps(sandbox.scene().target_fps).unwrap_or(AUTO_TARGET_FPS),
                options.msaa,
                options.temporal.unwrap_or(false),
            ),
            sound: LiveSound::open(&sandbox.scene().sound, &sandbox.sim),
            last_simulation: Duration::ZERO,
            profiler: Profiler::default(),
            plots: Plots::default(),
            opened: Instant::now(),
            frame_rate: FrameRate::default(),
            sandbox,
            options,
            tumbler_spheres,
            tumbler_mesh,
            coarse_tumbler,
            paint,
            running: None,
            error: None,
            mode: MouseMode::Look,
            keys: Keys::default(),
            cursor: Vec2::ZERO,
            drag_plane: None,
            look_settled: false,
            last_frame: None,
            camera_logged: Instant::now(),
            screenshots: 0,
        })
    }

    /// Stops the program with `error`, which `run` returns.
    fn fail(&mut self, event_loop: &ActiveEventLoop, error: anyhow::Error) {
        self.error.get_or_insert(error);
        event_loop.exit();
    }
    /// Advances the simulation by the time since the last frame, in fixed
    /// steps, as the playback says.
    fn simulate(&mut self, elapsed: f64) {
        let started = Instant::now();
        let skipped_before = self.sandbox.playback.skipped();
        self.sound
            .follow(&self.camera.camera(), &self.sandbox.scene().sound);
        let (sound, plots) = (&mut self.sound, &mut self.plots);
        let steps = self.sandbox.frame_heard(
            elapsed,
            || started.elapsed(),
            |sim| {
                sound.hear(sim);
                // Every step, not every frame: a frame of a slow window
                // spans many steps, and a tumbler's swing would alias.
                if plots.wanted() {
                    plots.record(&sim.world, sim.last_events());
                }
            },
        );
        if !self.sandbox.playback.frozen() {
            let simulated = elapsed * self.sandbox.playback.scale();
            let skipped = self.sandbox.playback.skipped() - skipped_before;
            self.hud_state.pace(simulated, skipped);
        }
        if steps > 0 {
            self.hud_state.step_time = started.elapsed().as_secs_f64() / f64::from(steps);
            if self.sandbox.playback.frozen() {
                let world = self.sandbox.world();
                self.log.say(
                    "stepped",
                    json!({ "steps": steps, "step_count": world.step_count(), "sim_time": world.time() }),
                );
            }
        }
    }

    fn frame(&mut self, event_loop: &ActiveEventLoop) {
        let now = Instant::now();
        // The real time since the last frame, whole: the HUD reports it, and
        // the fixed steps decide how much of it the world catches up on.
        let elapsed = self.last_frame.map_or(0.0, |t| (now - t).as_secs_f64());
        self.last_frame = Some(now);
        self.follow_shaders();
        // After a stall the camera, like the world, does not leap ahead.
        self.walk(elapsed.min(MAX_CATCH_UP) as f32);
        self.follow_orbit(elapsed.min(MAX_CATCH_UP) as f32);
        let drawing = Duration::from_secs_f64(elapsed).saturating_sub(self.last_simulation);
        self.simulate(elapsed);
        self.last_simulation = now.elapsed();
        let (steps, step_count) = self.sandbox.sim.take_step_times();
        self.follow_quality(drawing);
        if self.options.replay_digest.is_some() {
            self.follow_replay();
        }
        // Report the camera when it has moved or turned, at most five times a second.
        if self.camera != self.camera_reported && self.camera_logged.elapsed().as_secs_f64() > 0.2 {
            self.camera_logged = now;
            self.camera_reported = self.camera;
            self.log_camera();
        }
        if self.camera != self.camera_recorded {
            self.camera_recorded = self.camera;
            self.record_camera();
        }

        if self.plots.wanted() {
            // Moves the cursor after going back, which takes no step.
            let sim = &self.sandbox.sim;
            self.plots.record(&sim.world, sim.last_events());
        }
        let sim = &self.sandbox.sim;
        let view = sim.view_showing(&self.sandbox.scene().light, &self.panel.debug);
        let camera = self.camera.camera();
        self.hud_state.frame(
            elapsed,
            &sim.world,
            &sim.fx,
            self.sandbox.playback.frozen(),
            self.mode == MouseMode::Grab,
        );
        if sim.engine() == Engine::Gpu {
            self.hud_state.balls_total = sim.ball_count();
        }
        self.hud_state.engine = sim.balls.describe();
        self.hud_state.time_scale = self.sandbox.playback.scale();
        self.hud_state.held = held_facts(&sim.world);
        let furthest = self.sandbox.timeline().1;
        self.hud_state.rewound =
            furthest.saturating_sub(self.sandbox.ticks()) as f64 * sim.world.config().solver.dt;
        let cursor = (self.mode == MouseMode::Grab).then_some(self.cursor);
        // The view the keys or the panel chose.
        self.tell_view();
        let Some(r) = self.running.as_mut() else {
            return;
        };
        r.renderer.set_view(self.panel.view);
        self.hud_state.view = r.renderer.caption(&view, &camera);
        if r.config.width == 0 || r.config.height == 0 {
            return;
        }
        // Acquiring the surface's texture and the frames in flight wait
        // for the GPU (the profiler says so, not the pass after them).
        let acquiring = Instant::now();
        let texture = match r.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(t)
            | wgpu::CurrentSurfaceTexture::Suboptimal(t) => t,
            wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Lost => {
                r.surface.configure(&r.gpu.device, &r.config);
                return;
            }
            wgpu::CurrentSurfaceTexture::Timeout | wgpu::CurrentSurfaceTexture::Occluded => return,
            wgpu::CurrentSurfaceTexture::Validation => {
                self.fail(
                    event_loop,
                    anyhow::anyhow!("the window's surface failed validation"),
                );
                return;
            }
        };
        if r.in_flight.len() >= FRAMES_IN_FLIGHT
            && let Some((number, oldest)) = r.in_flight.pop_front()
            && let Err(e) = r.gpu.wait.wait(&r.gpu.device, Some(oldest), || {
                format!("the window's frame {number}")
            })
        {
            self.fail(event_loop, e.into());
            return;
        }
        let acquire = acquiring.elapsed();
        let target = texture.texture.create_view(&Default::default());
        r.renderer.set_cursor(cursor);
        r.renderer.set_gpu_timing(&r.gpu, self.profiler.open);
        let (w, h) = (r.config.width, r.config.height);
        let stats = match r.renderer.render(&r.gpu, &view, &camera, &target, w, h) {
            Ok(stats) => stats,
            Err(e) => {
                self.fail(event_loop, e.into());
                return;
            }
        };
        self.hud_state.render_cpu = stats.cpu_time.as_secs_f64();
        let balls = view.balls.len();
        let debug = self.panel.debug;
        let (panel, sandbox, profiler) = (&mut self.panel, &mut self.sandbox, &self.profiler);
        let (plots, folder) = (&mut self.plots, &self.options.screenshot_dir);
        let mut export = None;
        let mut action = None;
        let hud_started = Instant::now();
        let painted = r
            .hud
            .draw(&r.window, &r.gpu, &target, [w, h], &self.hud_state, |ui| {
                action = panel.show(ui, sandbox, plots, folder);
                profiler.show(ui.ctx());
                export = plots.show(ui.ctx(), folder);
                crate::legend::show(ui.ctx(), &debug);
            });
        let ui = hud_started.elapsed().saturating_sub(painted.submit);
        r.frames_submitted += 1;
        r.in_flight
            .push_back((r.frames_submitted, painted.submitted));
        let presenting = Instant::now();
        r.gpu.queue.present(texture);
        if let Some((saved_at, seen, build)) = self.reload_shown.take() {
            // The first frame drawn with a saved shader is on screen.
            self.log.say(
                "shader_reloaded",
                json!({
                    "dir": self.shader_watch.as_ref().map(|w| w.dir().display().to_string()),
                    "save_to_picture_ms": 1e3 * saved_at.elapsed().as_secs_f64(),
                    "seen_ms": 1e3 * seen.as_secs_f64(),
                    "build_ms": 1e3 * build.as_secs_f64(),
                }),
            );
        }
        let gpu_wait = acquire + stats.submit + painted.submit + presenting.elapsed();
        let parts = FrameParts {
            simulation: self.last_simulation.as_secs_f64(),
            render_cpu: stats.cpu_time.as_secs_f64(),
            hud_cpu: ui.as_secs_f64(),
            gpu_wait: gpu_wait.as_secs_f64(),
        };
        self.profiler.push(FrameProfile {
            at: (now - self.opened).as_secs_f64(),
            frame: Duration::from_secs_f64(elapsed),
            steps,
            step_count,
            render_cpu: stats.cpu_time,
            ui,
            gpu_wait,
            gpu: stats.gpu,
            shadow_faces: stats.shadow_faces,
            balls,
        });
        self.count_frame(elapsed, parts);
        if let Some(path) = export {
            self.export_plots(&path);
        }
        if let Some(action) = action {
            self.act(action);
        }
    }

    /// O: the orbit camera takes over, circling the body in the middle of
    /// the view (or the room's centre), or hands back to the fly camera.
    pub(super) fn toggle_orbit(&mut self) {
        if self.orbit.take().is_some() {
            self.log.say("orbit", json!({ "on": false }));
            return;
        }
        let world = &self.sandbox.sim.world;
        let (origin, dir) = (
            self.camera.position.as_dvec3(),
            self.camera.forward().as_dvec3(),
        );
        let tumbler = world.pick(origin, dir);
        let ball = world.pick_ball(origin, dir);
        let circled = match (tumbler, ball) {
            (Some(t), b) if b.is_none_or(|b| t.distance <= b.distance) => {
                Circled::Tumbler(t.tumbler)
            }
            (_, Some(b)) => Circled::Ball(b.ball),
            _ => Circled::Room,
        };
        let target = self.circled_point(circled);
        self.orbit = Some((OrbitCamera::take_over(&self.camera, target), circled));
        let what = match circled {
            Circled::Ball(i) => json!({ "ball": i }),
            Circled::Tumbler(i) => json!({ "tumbler": i }),
            Circled::Room => json!("room"),
        };
        self.log.say("orbit", json!({ "on": true, "around": what }));
    }

    /// Where the orbit camera's body is now (a ball caught or gone: the
    /// room's centre).
    fn circled_point(&self, circled: Circled) -> Vec3 {
        let world = &self.sandbox.sim.world;
        let room = world.room();
        let centre = ((room.min + room.max) * 0.5).as_vec3();
        match circled {
            Circled::Ball(i) if world.balls().alive().get(i) == Some(&true) => {
                world.balls().positions()[i].as_vec3()
            }
            Circled::Tumbler(i) => world
                .tumblers()
                .get(i)
                .map_or(centre, |t| t.center_of_mass().as_vec3()),
            _ => centre,
        }
    }

    /// The orbit camera's point glides after its body, and the fly camera
    /// stands where the orbit camera does.
    fn follow_orbit(&mut self, elapsed: f32) {
        let Some((_, circled)) = self.orbit else {
            return;
        };
        let target = self.circled_point(circled);
        if let Some((orbit, _)) = &mut self.orbit {
            orbit.follow(target, elapsed);
            self.camera = orbit.fly(self.camera.fov_y_deg);
        }
    }

    /// Goes back (or on) to the start of tick `tick` (see
    /// [`Sandbox::rewind_to`]), paused there.
    pub(super) fn rewind_to(&mut self, tick: u64) {
        self.sandbox.playback.set_paused(true);
        let reached = self.sandbox.rewind_to(tick);
        let (oldest, furthest) = self.sandbox.timeline();
        self.log.say(
            "rewound",
            json!({ "tick": reached, "oldest": oldest, "furthest": furthest, "sim_time": self.sandbox.world().time() }),
        );
    }

    /// Logs the frames drawn a second, their 95th percentile time, and at
    /// what level, once a second; `elapsed`: this frame's time (s).
    fn count_frame(&mut self, elapsed: f64, parts: FrameParts) {
        if let Some(report) = self.frame_rate.push(elapsed, parts) {
            let m = report.mean_ms;
            self.log.say(
                "frame_rate",
                json!({
                    "fps": report.fps,
                    "p95_ms": report.p95_ms,
                    "mean_ms": {
                        "simulation": m.simulation,
                        "render_cpu": m.render_cpu,
                        "hud_cpu": m.hud_cpu,
                        "gpu_wait": m.gpu_wait,
                    },
                    "quality": self.quality.level().name(),
                    "scale": self.quality.scale(),
                    "at": self.opened.elapsed().as_secs_f64(),
                }),
            );
        }
    }

    /// A renderer of the tumblers as they look now, drawing with
    /// `settings` into `format`.
    fn renderer(
        &self,
        gpu: &rolypoly_render::Gpu,
        settings: RenderSettings,
        format: wgpu::TextureFormat,
    ) -> Renderer {
        let mut renderer = Renderer::with_shaders(
            gpu,
            settings,
            format,
            &self.tumbler_mesh,
            &self.paint,
            &self.shaders,
        );
        renderer.set_coarse_tumbler(gpu, &self.coarse_tumbler);
        renderer.set_view(self.panel.view);
        renderer
    }

    /// Names the view of the frame chosen in the log, once a change: each
    /// press of V is told, even where two come between frames.
    fn tell_view(&mut self) {
        let view = self.panel.view;
        if view != self.view_told {
            self.view_told = view;
            self.log.say(
                "frame_view",
                json!({ "view": view.name(), "about": view.about() }),
            );
        }
    }

    /// Draws with the watched folder's shaders from the next frame where a
    /// file was saved and the set is good; where it is not, keeps the last
    /// good ones and says why on screen and in the log.
    fn follow_shaders(&mut self) {
        let Some(reload) = self.shader_watch.as_mut().and_then(ShaderWatch::poll) else {
            return;
        };
        let shaders = match reload.shaders {
            Ok(shaders) => shaders,
            Err(error) => return self.shader_failed(&error),
        };
        let Some(r) = self.running.take() else {
            self.shaders = shaders;
            return;
        };
        let building = Instant::now();
        let last_good = std::mem::replace(&mut self.shaders, shaders);
        // What naga lets through and the pipelines' layouts refuse (a
        // binding removed, an entry point renamed) is caught here too.
        let scope = r.gpu.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let renderer = self.renderer(&r.gpu, r.renderer.settings(), r.renderer.output_format());
        let refused = pollster::block_on(scope.pop());
        match refused {
            None => {
                self.running = Some(Running { renderer, ..r });
                self.reload_shown = Some((
                    reload.saved_at,
                    building - reload.saved_at,
                    building.elapsed(),
                ));
                self.hud_state.shader_error = None;
            }
            Some(error) => {
                self.shaders = last_good;
                self.running = Some(r);
                let dir = self.shader_watch.as_ref().map(|w| w.dir().to_path_buf());
                self.shader_error_said(
                    format!(
                        "{}: the pipelines refuse the shaders: {error}",
                        dir.unwrap_or_default().display()
                    ),
                    json!({}),
                );
            }
        }
    }

    /// A watched folder's shaders that cannot be drawn with.
    fn shader_failed(&mut self, error: &ShaderError) {
        let place = match error {
            ShaderError::Invalid {
                path, line, column, ..
            } => json!({ "file": path.display().to_string(), "line": line, "column": column }),
            ShaderError::Unreadable { path, .. } => json!({ "file": path.display().to_string() }),
            ShaderError::NoFolder { dir } => json!({ "file": dir.display().to_string() }),
        };
        self.shader_error_said(error.to_string(), place);
    }

    fn shader_error_said(&mut self, message: String, place: serde_json::Value) {
        let mut fields = json!({ "error": message });
        if let (Some(fields), serde_json::Value::Object(place)) = (fields.as_object_mut(), place) {
            fields.extend(place);
        }
        self.log.say("shader_error", fields);
        self.hud_state.shader_error = Some(message);
    }

    /// The frames a second auto holds now: the scene's, or the default of
    /// the window's adapter and display.
    fn target_fps(&self) -> f64 {
        chosen_fps(self.sandbox.scene().target_fps).unwrap_or_else(|| {
            self.running
                .as_ref()
                .map_or(AUTO_TARGET_FPS, |r| r.default_fps)
        })
    }

    /// Takes the scene's quality level, the target frame rate and the last
    /// frame's drawing time; where the scale changes the renderer lights
    /// the next frame at it, where the level changes it is made anew.
    fn follow_quality(&mut self, drawing: Duration) {
        let target = self.target_fps();
        let change = self
            .quality
            .update(self.sandbox.scene().quality, target, drawing);
        self.hud_state.quality = self.quality.describe();
        let Some(r) = self.running.as_mut() else {
            return;
        };
        match change {
            QualityChange::None => {}
            QualityChange::Scale => r.renderer.set_resolution(self.quality.scale()),
            QualityChange::Level => {
                if let Some(r) = self.running.take() {
                    let format = r.renderer.output_format();
                    let renderer = self.renderer(&r.gpu, self.quality.settings(), format);
                    self.running = Some(Running { renderer, ..r });
                }
                self.log.say(
                    "quality",
                    json!({ "level": self.quality.level().name(), "scale": self.quality.scale(), "why": self.hud_state.quality }),
                );
            }
        }
    }

    fn log_camera(&self) {
        let p = self.camera.position;
        self.log.say(
            "camera",
            json!({ "position": [p.x, p.y, p.z], "yaw": self.camera.yaw, "pitch": self.camera.pitch, "sim_time": self.sandbox.world().time() }),
        );
    }

    /// The F12 key: the current view, drawn off-screen at the window's size, as a PNG.
    fn screenshot(&mut self) -> anyhow::Result<()> {
        let Some(r) = &self.running else {
            return Ok(());
        };
        let (w, h) = (r.config.width.max(1), r.config.height.max(1));
        // As `render` draws: a picture that does not depend on the machine.
        let high = Quality::High.settings();
        let settings = RenderSettings {
            msaa: self.options.msaa.unwrap_or(high.msaa),
            ..high
        };
        let mut renderer = Renderer::with_shaders(
            &r.gpu,
            settings,
            OFFSCREEN_FORMAT,
            &self.tumbler_mesh,
            &self.paint,
            &self.shaders,
        );
        renderer.set_view(self.panel.view);
        let target = OffscreenTarget::new(&r.gpu, w, h)?;
        let view = self.sandbox.sim.view(&self.sandbox.scene().light);
        target.render(&r.gpu, &mut renderer, &view, &self.camera.camera())?;
        let image = target.read(&r.gpu, "the screenshot")?;
        self.screenshots += 1;
        let stamp = seconds_since_1970();
        let path = self
            .options
            .screenshot_dir
            .join(format!("rolypoly-{stamp}-{}.png", self.screenshots));
        image
            .save_with_format(&path, image::ImageFormat::Png)
            .with_context(|| format!("cannot write screenshot `{}`", path.display()))?;
        if self.options.log_events {
            self.log.say(
                "screenshot",
                json!({ "path": path.display().to_string(), "width": w, "height": h }),
            );
        } else {
            println!("screenshot: {}", path.display());
        }
        Ok(())
    }
}

impl ApplicationHandler for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.running.is_some() {
            return;
        }
        match self.open(event_loop) {
            Ok(running) => {
                self.running = Some(running);
                self.set_mode(MouseMode::Look);
            }
            Err(e) => self.fail(event_loop, e),
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        // Tab is the panel's key alone, never a move between its widgets.
        let tab = matches!(&event, WindowEvent::KeyboardInput { event, .. }
            if event.physical_key == PhysicalKey::Code(KeyCode::Tab));
        if let Some(r) = self.running.as_mut().filter(|_| !tab) {
            r.hud.on_event(&r.window, &event);
        }
        // While the panel's file name is being typed, keys go there only.
        let typing = self.running.as_ref().is_some_and(|r| r.hud.typing());
        if typing && !tab && matches!(event, WindowEvent::KeyboardInput { .. }) {
            return;
        }
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::Resized(size) => {
                if let Some(r) = self.running.as_mut() {
                    // A minimised window has no size: keep the old surface and draw nothing.
                    r.config.width = size.width;
                    r.config.height = size.height;
                    if size.width > 0 && size.height > 0 {
                        r.surface.configure(&r.gpu.device, &r.config);
                    }
                    self.log.say(
                        "resized",
                        json!({ "width": size.width, "height": size.height }),
                    );
                }
            }
            WindowEvent::KeyboardInput { event, .. } => self.key(event_loop, &event),
            WindowEvent::CursorMoved { position, .. } => {
                self.mouse_moved(Vec2::new(position.x as f32, position.y as f32))
            }
            WindowEvent::MouseInput { button, state, .. } => self.button(button, state),
            WindowEvent::MouseWheel { delta, .. } => {
                let notches = match delta {
                    winit::event::MouseScrollDelta::LineDelta(_, y) => y,
                    winit::event::MouseScrollDelta::PixelDelta(p) => p.y as f32 / 40.0,
                };
                if let Some((orbit, _)) = &mut self.orbit {
                    orbit.zoom(notches);
                }
            }
            WindowEvent::Focused(false) => self.keys = Keys::default(),
            WindowEvent::RedrawRequested => self.frame(event_loop),
            _ => {}
        }
    }

    fn about_to_wait(&mut self, _event_loop: &ActiveEventLoop) {
        if let Some(r) = &self.running {
            r.window.request_redraw();
        }
    }
}

/// What the HUD says of the body the hand holds: its number, speed, spin,
/// kinetic energy and the contacts it pushed at in the last step.
fn held_facts(world: &rolypoly_physics::World) -> Option<String> {
    if let Some(i) = world.held_ball() {
        let balls = world.balls();
        let contacts = world
            .contact_probes()
            .iter()
            .filter(|p| p.balls.contains(&Some(i)))
            .count();
        return Some(format!(
            "holding ball {i}: {:.2} m/s, spin {:.1} rad/s, {:.3} J, {contacts} contacts",
            balls.velocities()[i].length(),
            balls.spins()[i].length(),
            balls.kinetic_energy(i)
        ));
    }
    let t = world.grabbed()?;
    let tumbler = &world.tumblers()[t];
    Some(format!(
        "holding tumbler {t}: {:.2} m/s, spin {:.1} rad/s, {:.3} J, tilted {:.0} degrees",
        tumbler.linear_velocity().length(),
        tumbler.angular_velocity().length(),
        tumbler.kinetic_energy(world.tumbler_shape()),
        tumbler.tilt().to_degrees()
    ))
}

/// The time now in whole seconds since 1970, which names the files the F12 key
/// and R write so that each run's files sort in order and do not collide.
fn seconds_since_1970() -> u64 {
    std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs())
}

/// The mesh a tumbler of `spheres` is drawn with, and its paint.
fn tumbler_look(spheres: &[SphereSpec]) -> anyhow::Result<(MeshData, MeshData, image::RgbaImage)> {
    let designed = &rolypoly_physics::WorldConfig::default().tumblers.spheres;
    let mesh = rolypoly_render::mesh_for(spheres, designed)?;
    let coarse = rolypoly_render::coarse_tumbler_mesh(spheres);
    Ok((mesh, coarse, rolypoly_render::tumbler_paint(spheres)))
}
