//! The interactive window: one frame is input -> camera and modes -> fixed
//! physics steps (with the effects) -> render -> HUD -> present (I1-I7).

use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

use anyhow::Context as _;
use glam::{DVec3, Vec2, Vec3};
use rolypoly_fx::{Effects, EffectsConfig};
use rolypoly_physics::{Event, World};
use rolypoly_render::{
    Camera, Gpu, LightConfig, MeshData, OFFSCREEN_FORMAT, OffscreenTarget, RenderSettings,
    Renderer, SceneView,
};
use serde_json::json;
use winit::application::ApplicationHandler;
use winit::dpi::{PhysicalPosition, PhysicalSize};
use winit::event::{ElementState, KeyEvent, MouseButton, WindowEvent};
use winit::event_loop::{ActiveEventLoop, EventLoop};
use winit::keyboard::{KeyCode, PhysicalKey};
use winit::window::{CursorGrabMode, Fullscreen, Window, WindowId};

use super::fixed_steps::{FixedSteps, MAX_CATCH_UP};
use super::fly_camera::FlyCamera;
use super::hud::{Hud, HudState};
use super::log::EventLog;

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

/// What the mouse does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum MouseMode {
    /// Captured and hidden; moving it turns the view.
    Look,
    /// The view is locked; our own white arrow is the cursor; the left
    /// button grabs tumblers.
    Grab,
    /// Released by Escape: the mouse is the desktop's again.
    Free,
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

#[derive(Clone, Copy, Debug, Default)]
struct Keys {
    forward: bool,
    back: bool,
    left: bool,
    right: bool,
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

    fn open(&mut self, event_loop: &ActiveEventLoop) -> anyhow::Result<Running> {
        let (w, h) = self.options.size;
        let mut attributes = Window::default_attributes()
            .with_title("rolypoly")
            .with_inner_size(PhysicalSize::new(w, h));
        if self.options.fullscreen {
            attributes = attributes.with_fullscreen(Some(Fullscreen::Borderless(None)));
        }
        let window = Arc::new(
            event_loop
                .create_window(attributes)
                .context("cannot create the window")?,
        );
        let desc = wgpu::InstanceDescriptor::new_with_display_handle_from_env(Box::new(
            event_loop.owned_display_handle(),
        ));
        let instance = wgpu::Instance::new(desc);
        let surface = instance
            .create_surface(window.clone())
            .context("cannot draw into the window (no surface for this graphics backend)")?;
        let adapter =
            pollster::block_on(
                instance.request_adapter(&wgpu::RequestAdapterOptions {
                    power_preference: wgpu::PowerPreference::from_env()
                        .unwrap_or(wgpu::PowerPreference::HighPerformance),
                    force_fallback_adapter: false,
                    compatible_surface: Some(&surface),
                    apply_limit_buckets: false,
                }),
            )
            .map_err(|_| rolypoly_render::RenderError::NoAdapter {
                backends: "those that can draw into this window".into(),
            })?;
        let gpu = Gpu::open(adapter)?;
        let caps = surface.get_capabilities(&gpu.adapter);
        // The renderer writes linear colour and lets an sRGB format encode it.
        let format = caps
            .formats
            .iter()
            .copied()
            .find(|f| f.is_srgb())
            .or_else(|| caps.formats.first().copied())
            .context("the window's surface offers no colour format")?;
        let size = window.inner_size();
        let config = wgpu::SurfaceConfiguration {
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
            format,
            color_space: wgpu::SurfaceColorSpace::default(),
            width: size.width.max(1),
            height: size.height.max(1),
            present_mode: if self.options.vsync {
                wgpu::PresentMode::AutoVsync
            } else {
                wgpu::PresentMode::AutoNoVsync
            },
            desired_maximum_frame_latency: 2,
            alpha_mode: caps
                .alpha_modes
                .first()
                .copied()
                .unwrap_or(wgpu::CompositeAlphaMode::Auto),
            view_formats: vec![],
        };
        surface.configure(&gpu.device, &config);
        let settings = RenderSettings {
            msaa: self.options.msaa,
            ..RenderSettings::default()
        };
        let renderer = Renderer::new(&gpu, settings, format, &self.tumbler_mesh, &self.paint);
        let hud = Hud::new(&window, &gpu, format);
        self.cursor = Vec2::new(config.width as f32, config.height as f32) * 0.5;
        self.log.say(
            "ready",
            json!({ "width": config.width, "height": config.height, "adapter": gpu.describe(), "seed": self.options.seed }),
        );
        Ok(Running {
            window,
            gpu,
            surface,
            config,
            renderer,
            hud,
        })
    }

    fn set_mode(&mut self, mode: MouseMode) {
        let Some(r) = &self.running else { return };
        let window = &r.window;
        match mode {
            MouseMode::Look => {
                // Confining is a courtesy: without it (no window manager) the
                // pointer is re-centred every move anyway.
                let _ = window.set_cursor_grab(CursorGrabMode::Confined);
                window.set_cursor_visible(false);
                self.look_settled = false;
                self.recentre();
            }
            MouseMode::Grab => {
                let _ = window.set_cursor_grab(CursorGrabMode::None);
                window.set_cursor_visible(false);
            }
            MouseMode::Free => {
                let _ = window.set_cursor_grab(CursorGrabMode::None);
                window.set_cursor_visible(true);
            }
        }
        if self.mode == MouseMode::Grab && mode != MouseMode::Grab {
            self.release_tumbler();
        }
        self.mode = mode;
    }

    fn centre(&self) -> Vec2 {
        self.running.as_ref().map_or(Vec2::ZERO, |r| {
            Vec2::new(r.config.width as f32, r.config.height as f32) * 0.5
        })
    }

    fn recentre(&self) {
        if let Some(r) = &self.running {
            let c = self.centre();
            let _ = r
                .window
                .set_cursor_position(PhysicalPosition::new(c.x as f64, c.y as f64));
        }
    }

    fn viewport(&self) -> Vec2 {
        self.running.as_ref().map_or(Vec2::ONE, |r| {
            Vec2::new(r.config.width as f32, r.config.height as f32)
        })
    }

    fn key(&mut self, event_loop: &ActiveEventLoop, event: &KeyEvent) {
        let PhysicalKey::Code(code) = event.physical_key else {
            return;
        };
        let down = event.state == ElementState::Pressed;
        match code {
            KeyCode::KeyW => self.keys.forward = down,
            KeyCode::KeyS => self.keys.back = down,
            KeyCode::KeyA => self.keys.left = down,
            KeyCode::KeyD => self.keys.right = down,
            KeyCode::ShiftLeft if self.paused != down => {
                self.paused = down;
                self.log.say(
                    "pause",
                    json!({ "paused": down, "sim_time": self.world.time() }),
                );
            }
            KeyCode::ShiftLeft => {}
            _ if !down || event.repeat => {}
            KeyCode::KeyF => {
                if self.world.fireball().is_some() {
                    self.world.remove_fireball();
                } else {
                    let from = self.camera.position + self.camera.forward() * 0.6;
                    self.world
                        .launch_fireball(Some((from.as_dvec3(), self.camera.forward().as_dvec3())));
                }
                self.log
                    .say("fireball", json!({ "on": self.world.fireball().is_some() }));
            }
            KeyCode::KeyG => {
                let next = if self.mode == MouseMode::Grab {
                    MouseMode::Look
                } else {
                    MouseMode::Grab
                };
                self.set_mode(next);
                self.log.say("grab_mode", json!({ "on": next == MouseMode::Grab, "tumblers_on_screen": self.tumblers_on_screen() }));
            }
            KeyCode::KeyI => match self.world.reset_balls() {
                Ok(()) => self.log.say(
                    "reset",
                    json!({ "balls": self.world.balls().len(), "sim_time": self.world.time() }),
                ),
                Err(e) => self.fail(
                    event_loop,
                    anyhow::Error::new(e).context("cannot re-initialise the balls"),
                ),
            },
            KeyCode::KeyH | KeyCode::F1 => self.help = !self.help,
            KeyCode::F12 => {
                if let Err(e) = self.screenshot() {
                    // A screenshot that cannot be written is reported, and the program goes on.
                    eprintln!("error: {e:#}");
                    self.log
                        .say("screenshot_failed", json!({ "error": format!("{e:#}") }));
                }
            }
            KeyCode::Escape => {
                if self.mode == MouseMode::Free {
                    event_loop.exit();
                } else {
                    self.set_mode(MouseMode::Free);
                    self.log.say("mouse", json!({ "captured": false }));
                }
            }
            _ => {}
        }
    }

    fn mouse_moved(&mut self, at: Vec2) {
        match self.mode {
            MouseMode::Look => {
                let delta = at - self.centre();
                // The first position after capturing says where the pointer
                // was, not how far it moved; so does a jump across a good part
                // of the window (the pointer left and came back).
                let jump = 0.25 * self.viewport().min_element();
                if !self.look_settled {
                    self.look_settled = true;
                } else if delta.length_squared() > 0.0 && delta.length() < jump {
                    self.camera.turn(delta, self.options.look_speed);
                }
                if delta.length_squared() > 0.0 {
                    self.recentre();
                }
            }
            MouseMode::Grab => {
                self.cursor = at;
                if let Some(height) = self.drag_height {
                    if let Some(target) = self.cursor_on_plane(height) {
                        self.world.drag_to(target);
                    }
                }
            }
            MouseMode::Free => {}
        }
    }

    /// Where the ray under our cursor meets the horizontal plane at `height`.
    fn cursor_on_plane(&self, height: f64) -> Option<DVec3> {
        let (origin, dir) = self.camera.camera().ray(self.cursor, self.viewport());
        if dir.y.abs() < 1e-4 {
            return None;
        }
        let t = (height as f32 - origin.y) / dir.y;
        (t > 0.0).then(|| (origin + dir * t).as_dvec3())
    }

    fn button(&mut self, button: MouseButton, state: ElementState) {
        if button != MouseButton::Left {
            return;
        }
        match (self.mode, state) {
            (MouseMode::Free, ElementState::Pressed) => {
                self.set_mode(MouseMode::Look);
                self.log.say("mouse", json!({ "captured": true }));
            }
            (MouseMode::Grab, ElementState::Pressed) => {
                let (origin, dir) = self.camera.camera().ray(self.cursor, self.viewport());
                if let Some(pick) = self.world.pick(origin.as_dvec3(), dir.as_dvec3()) {
                    self.world.grab(pick.tumbler, pick.point);
                    self.drag_height = Some(pick.point.y);
                    let at = self.world.tumblers()[pick.tumbler].bottom_center();
                    self.log.say("grabbed", json!({ "tumbler": pick.tumbler, "at": [at.x, at.z], "point": pick.point.to_array() }));
                }
            }
            (MouseMode::Grab, ElementState::Released) => self.release_tumbler(),
            _ => {}
        }
    }

    /// Where each tumbler's belly appears in the window (pixels), for the log.
    fn tumblers_on_screen(&self) -> Vec<[f32; 2]> {
        let size = self.viewport();
        let view_proj = self.camera.camera().view_projection(size.x / size.y);
        let shape = self.world.tumbler_shape();
        self.world
            .tumblers()
            .iter()
            .map(|t| {
                let belly = t
                    .sphere_center(shape, 2.min(shape.spheres.len() - 1))
                    .as_vec3();
                let clip = view_proj * belly.extend(1.0);
                if clip.w <= 0.0 {
                    // Behind the camera: nowhere on screen.
                    return [-1.0, -1.0];
                }
                let ndc = clip.truncate() / clip.w;
                [(ndc.x * 0.5 + 0.5) * size.x, (0.5 - ndc.y * 0.5) * size.y]
            })
            .collect()
    }

    fn release_tumbler(&mut self) {
        if let Some(index) = self.world.grabbed() {
            self.world.release();
            let at = self.world.tumblers()[index].bottom_center();
            self.log
                .say("released", json!({ "tumbler": index, "at": [at.x, at.z] }));
        }
        self.drag_height = None;
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

    fn walk(&mut self, elapsed: f32) {
        let forward = self.keys.forward as i32 - self.keys.back as i32;
        let right = self.keys.right as i32 - self.keys.left as i32;
        if forward == 0 && right == 0 {
            return;
        }
        let room = *self.world.room();
        let margin = Vec3::splat(0.15);
        self.camera.walk(
            forward as f32,
            right as f32,
            self.options.move_speed,
            elapsed,
            room.min.as_vec3() + margin,
            room.max.as_vec3() - margin,
        );
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
