//! The white arrow cursor, drawn over the finished frame where the window
//! asks for it (while the mouse holds a tumbler, the system's cursor is
//! hidden and this one drawn): part of the frame, so screenshots show it.

use super::bindings::uniform_entry;
use super::pipelines::screen_pipeline;
use crate::shaders::ShaderSet;

pub(super) struct Cursor {
    pipeline: wgpu::RenderPipeline,
    /// Where the tip is and the frame's size, in pixels.
    place: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
    /// Where to draw the tip (pixels from the frame's top left), if anywhere.
    pub at: Option<glam::Vec2>,
}

impl Cursor {
    /// A cursor, hidden, for frames in `output_format`.
    pub fn new(
        device: &wgpu::Device,
        shaders: &ShaderSet,
        output_format: wgpu::TextureFormat,
    ) -> Cursor {
        let shader = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(crate::shaders::CURSOR.name),
            source: wgpu::ShaderSource::Wgsl(shaders.source(&crate::shaders::CURSOR).into()),
        });
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("cursor"),
            entries: &[uniform_entry(0, wgpu::ShaderStages::VERTEX)],
        });
        let place = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("cursor"),
            size: 16,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("cursor"),
            layout: &layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: place.as_entire_binding(),
            }],
        });
        let pipeline = screen_pipeline(
            device,
            "cursor",
            &layout,
            &shader,
            ("vs_cursor", "fs_cursor"),
            output_format.into(),
        );
        Cursor {
            pipeline,
            place,
            bind_group,
            at: None,
        }
    }

    /// Draws the cursor into `pass`, over a frame of `width` by `height`
    /// pixels, if it is shown. Returns the draw calls made.
    pub fn draw(
        &self,
        queue: &wgpu::Queue,
        pass: &mut wgpu::RenderPass,
        width: u32,
        height: u32,
    ) -> u32 {
        let Some(at) = self.at else {
            return 0;
        };
        let place = [at.x, at.y, width as f32, height as f32];
        queue.write_buffer(&self.place, 0, bytemuck::cast_slice(&place));
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &self.bind_group, &[]);
        // Outline, then arrow.
        pass.draw(0..15, 0..2);
        1
    }
}
