//! Frames without a window: render into a texture and read it back (R6).

use crate::camera::Camera;
use crate::gpu::{Gpu, RenderError};
use crate::renderer::{FrameStats, Renderer};
use crate::view::SceneView;
use image::RgbaImage;

/// The format of off-screen frames: 8-bit sRGB, as a PNG stores it.
pub const OFFSCREEN_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;

/// Largest side of an off-screen frame, in pixels.
pub const MAX_SIDE: u32 = 8192;

/// An off-screen colour target and the buffer it is read back through.
pub struct OffscreenTarget {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    texture: wgpu::Texture,
    view: wgpu::TextureView,
    readback: wgpu::Buffer,
    padded_row: u32,
}

impl OffscreenTarget {
    /// A target of `width` x `height` pixels, each side 1 to [`MAX_SIDE`].
    pub fn new(gpu: &Gpu, width: u32, height: u32) -> Result<OffscreenTarget, RenderError> {
        if width == 0 || height == 0 || width > MAX_SIDE || height > MAX_SIDE {
            return Err(RenderError::Size {
                width,
                height,
                reason: format!("each side must be 1 ..= {MAX_SIDE}"),
            });
        }
        let texture = gpu.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("offscreen"),
            size: wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: OFFSCREEN_FORMAT,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        });
        let view = texture.create_view(&Default::default());
        // Rows of a texture copy must be 256-byte aligned.
        let padded_row = (4 * width).div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT)
            * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
        let readback = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("readback"),
            size: (padded_row * height) as u64,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        Ok(OffscreenTarget {
            width,
            height,
            texture,
            view,
            readback,
            padded_row,
        })
    }

    /// The texture frames are drawn into, for what is drawn over them.
    pub fn view(&self) -> &wgpu::TextureView {
        &self.view
    }

    /// Draws one frame into the target.
    pub fn render(
        &self,
        gpu: &Gpu,
        renderer: &mut Renderer,
        view: &SceneView,
        camera: &Camera,
    ) -> Result<FrameStats, RenderError> {
        renderer.render(gpu, view, camera, &self.view, self.width, self.height)
    }

    /// Waits for the GPU and returns the last frame drawn; `what` names it
    /// if the wait runs out ("the frame at t = 1.000 s").
    pub fn read(&self, gpu: &Gpu, what: &str) -> Result<RgbaImage, RenderError> {
        let mut encoder = gpu
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("readback"),
            });
        encoder.copy_texture_to_buffer(
            wgpu::TexelCopyTextureInfo {
                texture: &self.texture,
                mip_level: 0,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            wgpu::TexelCopyBufferInfo {
                buffer: &self.readback,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(self.padded_row),
                    rows_per_image: Some(self.height),
                },
            },
            wgpu::Extent3d {
                width: self.width,
                height: self.height,
                depth_or_array_layers: 1,
            },
        );
        gpu.queue.submit([encoder.finish()]);
        let slice = self.readback.slice(..);
        let (sender, receiver) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |result| {
            let _ = sender.send(result);
        });
        gpu.wait.wait(&gpu.device, None, || self.named(what))?;
        // The wait ran the map's callback.
        receiver
            .try_recv()
            .map_err(|_| {
                RenderError::Readback("the GPU finished but the frame was not mapped".into())
            })?
            .map_err(|e| RenderError::Readback(e.to_string()))?;
        let mut pixels = Vec::with_capacity((4 * self.width * self.height) as usize);
        {
            let data = slice
                .get_mapped_range()
                .map_err(|e| RenderError::Readback(e.to_string()))?;
            for row in data
                .chunks(self.padded_row as usize)
                .take(self.height as usize)
            {
                pixels.extend_from_slice(&row[..(4 * self.width) as usize]);
            }
        }
        self.readback.unmap();
        RgbaImage::from_raw(self.width, self.height, pixels)
            .ok_or_else(|| RenderError::Readback("frame size does not match its pixels".into()))
    }

    /// Waits until the GPU has finished everything submitted so far;
    /// `what` names it if the wait runs out.
    pub fn finish(&self, gpu: &Gpu, what: &str) -> Result<(), RenderError> {
        gpu.wait.wait(&gpu.device, None, || self.named(what))?;
        Ok(())
    }

    /// `what`, with the frame's size: "the frame at t = 1.000 s (1280x720)".
    fn named(&self, what: &str) -> String {
        format!("{what} ({}x{})", self.width, self.height)
    }
}
