//! Opening the window: the window itself, a graphics adapter that can draw
//! into it, its surface, and the renderer and HUD for that surface.

use std::sync::Arc;

use anyhow::Context as _;
use glam::Vec2;
use rolypoly_render::{AUTO_TARGET_FPS, Gpu};
use serde_json::json;
use winit::dpi::PhysicalSize;
use winit::event_loop::ActiveEventLoop;
use winit::window::{Fullscreen, Window};

use super::{App, Running};
use crate::window::hud::Hud;

impl App {
    pub(super) fn open(&mut self, event_loop: &ActiveEventLoop) -> anyhow::Result<Running> {
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
        // A software renderer cannot keep up with a display; a GPU aims at
        // the display's rate (60 where the display does not say), and
        // draws on the temporal path unless told otherwise.
        let software = gpu.adapter.get_info().device_type == wgpu::DeviceType::Cpu;
        self.quality
            .set_temporal(self.options.temporal.unwrap_or(!software));
        let renderer = self.renderer(&gpu, self.quality.settings(), format);
        let hud = Hud::new(&window, &gpu, format);
        self.sandbox.use_device(crate::sandbox::Device {
            device: gpu.device.clone(),
            queue: gpu.queue.clone(),
            adapter: gpu.adapter.clone(),
        })?;
        if let Some(tick) = self.options.replay_from.take() {
            self.sandbox.replay_until(tick);
        }
        self.cursor = Vec2::new(config.width as f32, config.height as f32) * 0.5;
        self.log.say(
            "ready",
            json!({
                "width": config.width,
                "height": config.height,
                "adapter": gpu.describe(),
                "seed": self.options.seed,
                "engine": self.sandbox.scene().engine.name(),
                "balls": self.sandbox.sim.ball_count(),
                "temporal": renderer.settings().temporal,
            }),
        );
        let display_fps = window
            .current_monitor()
            .and_then(|monitor| monitor.refresh_rate_millihertz())
            .map_or(60.0, |mhz| f64::from(mhz) / 1e3);
        Ok(Running {
            window,
            gpu,
            surface,
            config,
            renderer,
            hud,
            in_flight: Default::default(),
            frames_submitted: 0,
            default_fps: if software {
                AUTO_TARGET_FPS
            } else {
                display_fps
            },
        })
    }
}
