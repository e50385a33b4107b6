//! The interactive window: one frame is input -> camera and modes -> fixed
//! physics steps (with the effects) -> render -> HUD -> present (I1-I7).
//!
//! This file holds the program's state and runs the frames. Opening the
//! window is in [`open`]; what the keys and the mouse do, in [`input`].

use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

use anyhow::Context as _;
use glam::Vec2;
use rolypoly_fx::{Effects, EffectsConfig};
use rolypoly_physics::{Event, World};
use rolypoly_render::{
    Camera, Gpu, LightConfig, MeshData, OFFSCREEN_FORMAT, OffscreenTarget, RenderSettings,
    Renderer, SceneView,
};
use serde_json::json;
use winit::application::ApplicationHandler;
use winit::event::WindowEvent;
use winit::event_loop::{ActiveEventLoop, EventLoop};
use winit::window::{Window, WindowId};

use super::fixed_steps::{FixedSteps, MAX_CATCH_UP};
use super::fly_camera::FlyCamera;
use super::hud::{Hud, HudState};
use super::log::EventLog;
use input::{Keys, MouseMode};

mod input;
mod open;

/// How the window is opened and driven.
#[derive(Clone, Debug)]
pub struct WindowOptions {
    pub size: (u32, u32),
    pub fullscreen: bool,
    pub vsync: bool,
    pub msaa: u32,
    pub log_events: bool,
    pub seed: u64,
    /// Where F12 writes screenshots.
    pub screenshot_dir: PathBuf,
    /// Walking speed (m/s) and mouse-look sensitivity (radians per pixel).
    pub move_speed: f32,
    pub look_speed: f32,
    pub light: LightConfig,
}

/// Opens the window on `world` and runs until it is closed.
pub fn run(
    world: World,
    effects: EffectsConfig,
    tumbler_mesh: MeshData,
    options: WindowOptions,
) -> anyhow::Result<()> {
    let event_loop = EventLoop::new().context(
        "cannot open a window: no display was found (set DISPLAY or WAYLAND_DISPLAY, \
         or use the `render` and `simulate` commands, which need none)",
    )?;
    let mut app = App::new(world, effects, tumbler_mesh, options);
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
}

struct App {
    world: World,
    fx: Effects,
    options: WindowOptions,
    log: EventLog,
    tumbler_mesh: MeshData,
    paint: image::RgbaImage,
    running: Option<Running>,
    error: Option<anyhow::Error>,

    camera: FlyCamera,
    mode: MouseMode,
    keys: Keys,
    paused: bool,
    /// Our arrow cursor in grab mode (pixels), and the height of the plane a
    /// held tumbler is dragged over.
    cursor: Vec2,
    drag_height: Option<f64>,
    /// Mouse look measures moves from the window's centre, where it puts the
    /// pointer back after each; false until the pointer is known to be there.
    look_settled: bool,
    help: bool,

    fixed_steps: FixedSteps,
    last_frame: Option<Instant>,
    events: Vec<Event>,
    hud_state: HudState,
    camera_logged: Instant,
    /// The camera as last written to the event log.
    camera_reported: FlyCamera,
    screenshots: u32,
}

impl App {
    fn new(
        world: World,
        effects: EffectsConfig,
        tumbler_mesh: MeshData,
        options: WindowOptions,
    ) -> App {
        let room = world.config().room.size.as_vec3();
        let paint = rolypoly_render::tumbler_paint(&world.config().tumblers.spheres);
        let camera = FlyCamera::from_camera(&Camera::overview(room));
        App {
            fx: Effects::new(effects, options.seed),
            log: EventLog::new(options.log_events),
            camera,
            camera_reported: camera,
            hud_state: HudState::new(options.seed, world.balls().len()),
            world,
            options,
            tumbler_mesh,
            paint,
            running: None,
            error: None,
            mode: MouseMode::Look,
            keys: Keys::default(),
            paused: false,
            cursor: Vec2::ZERO,
            drag_height: None,
            look_settled: false,
            help: false,
            fixed_steps: FixedSteps::default(),
            last_frame: None,
            events: Vec::new(),
            camera_logged: Instant::now(),
            screenshots: 0,
        }
    }

    /// Stops the program with `error`, which `run` returns.
    fn fail(&mut self, event_loop: &ActiveEventLoop, error: anyhow::Error) {
        self.error.get_or_insert(error);
        event_loop.exit();
    }
    /// Advances the simulation by the time since the last frame, in fixed steps.
    fn simulate(&mut self, elapsed: f64) {
        if self.paused {
            return;
        }
        let dt = self.world.config().solver.dt;
        let started = Instant::now();
        let skipped_before = self.fixed_steps.skipped();
        let (fx, world, events) = (&mut self.fx, &mut self.world, &mut self.events);
        let steps = self.fixed_steps.advance(
            elapsed,
            dt,
            || started.elapsed(),
            || fx.step_with(world, events),
        );
        self.hud_state
            .pace(elapsed, self.fixed_steps.skipped() - skipped_before);
        if steps > 0 {
            self.hud_state.step_time = started.elapsed().as_secs_f64() / steps as f64;
        }
    }

    fn frame(&mut self, event_loop: &ActiveEventLoop) {
        let now = Instant::now();
        // The real time since the last frame, whole: the HUD reports it, and
        // the fixed steps decide how much of it the world catches up on.
        let elapsed = self.last_frame.map_or(0.0, |t| (now - t).as_secs_f64());
        self.last_frame = Some(now);
        // After a stall the camera, like the world, does not leap ahead.
        self.walk(elapsed.min(MAX_CATCH_UP) as f32);
        self.simulate(elapsed);
        // Report the camera when it has moved or turned, at most five times a second.
        if self.camera != self.camera_reported && self.camera_logged.elapsed().as_secs_f64() > 0.2 {
            self.camera_logged = now;
            self.camera_reported = self.camera;
            self.log_camera();
        }

        let view = SceneView::from_world(&self.world, self.world.grabbed())
            .with_effects(&self.fx, &self.world)
            .with_light(&self.options.light);
        let camera = self.camera.camera();
        self.hud_state.frame(
            elapsed,
            &self.world,
            &self.fx,
            self.paused,
            self.mode == MouseMode::Grab,
        );
        let cursor = (self.mode == MouseMode::Grab).then_some(self.cursor);
        let help = self.help;
        let Some(r) = self.running.as_mut() else {
            return;
        };
        if r.config.width == 0 || r.config.height == 0 {
            return;
        }
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
        let target = texture.texture.create_view(&Default::default());
        r.renderer.set_cursor(cursor);
        let (w, h) = (r.config.width, r.config.height);
        match r.renderer.render(&r.gpu, &view, &camera, &target, w, h) {
            Ok(stats) => self.hud_state.render_cpu = stats.cpu_time.as_secs_f64(),
            Err(e) => {
                self.fail(event_loop, e.into());
                return;
            }
        }
        r.hud
            .draw(&r.window, &r.gpu, &target, [w, h], &self.hud_state, help);
        r.gpu.queue.present(texture);
    }

    fn log_camera(&self) {
        let p = self.camera.position;
        self.log.say(
            "camera",
            json!({ "position": [p.x, p.y, p.z], "yaw": self.camera.yaw, "pitch": self.camera.pitch, "sim_time": self.world.time() }),
        );
    }

    /// F12: the current view, drawn off-screen at the window's size, as a PNG.
    fn screenshot(&mut self) -> anyhow::Result<()> {
        let Some(r) = &self.running else {
            return Ok(());
        };
        let (w, h) = (r.config.width.max(1), r.config.height.max(1));
        let settings = RenderSettings {
            msaa: self.options.msaa,
            ..RenderSettings::default()
        };
        let mut renderer = Renderer::new(
            &r.gpu,
            settings,
            OFFSCREEN_FORMAT,
            &self.tumbler_mesh,
            &self.paint,
        );
        let target = OffscreenTarget::new(&r.gpu, w, h)?;
        let view = SceneView::from_world(&self.world, self.world.grabbed())
            .with_effects(&self.fx, &self.world)
            .with_light(&self.options.light);
        target.render(&r.gpu, &mut renderer, &view, &self.camera.camera())?;
        let image = target.read(&r.gpu)?;
        self.screenshots += 1;
        let stamp = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.as_secs());
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
        if let Some(r) = self.running.as_mut() {
            r.hud.on_event(&r.window, &event);
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
