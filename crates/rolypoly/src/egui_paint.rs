//! Painting what egui laid out over a frame already drawn: the window's HUD
//! and panel, and the debug views' legend on off-screen frames.

use rolypoly_render::Gpu;

/// What painting submitted, and how long submitting took: on a software
/// renderer the submission may wait for the frame's own passes to be
/// drawn, which is the GPU's time, not the painter's.
pub struct Painted {
    /// The submission, to wait for.
    pub submitted: wgpu::SubmissionIndex,
    /// Time spent in the queue's submit.
    pub submit: std::time::Duration,
}

/// egui's renderer for frames of one colour format.
pub struct EguiPainter {
    renderer: egui_wgpu::Renderer,
}

impl EguiPainter {
    /// A painter for frames in `format`.
    pub fn new(gpu: &Gpu, format: wgpu::TextureFormat) -> EguiPainter {
        EguiPainter {
            renderer: egui_wgpu::Renderer::new(
                &gpu.device,
                format,
                egui_wgpu::RendererOptions::default(),
            ),
        }
    }

    /// Paints `output`, laid out by `context`, over `target` of `size`
    /// pixels, and submits it.
    pub fn paint(
        &mut self,
        gpu: &Gpu,
        context: &egui::Context,
        mut output: egui::FullOutput,
        target: &wgpu::TextureView,
        size: [u32; 2],
    ) -> Painted {
        let pixels_per_point = output.pixels_per_point;
        let jobs = context.tessellate(std::mem::take(&mut output.shapes), pixels_per_point);
        let screen = egui_wgpu::ScreenDescriptor {
            size_in_pixels: size,
            pixels_per_point,
        };
        // Texture changes must be applied (and taken out) every frame.
        for (id, deltas) in output.textures_delta.set.drain() {
            for delta in &deltas {
                self.renderer
                    .update_texture(&gpu.device, &gpu.queue, id, delta);
            }
        }
        let mut encoder = gpu
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("egui"),
            });
        let extra =
            self.renderer
                .update_buffers(&gpu.device, &gpu.queue, &mut encoder, &jobs, &screen);
        {
            let pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("egui"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: target,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Load,
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: None,
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            let mut pass = pass.forget_lifetime();
            self.renderer.render(&mut pass, &jobs, &screen);
        }
        let commands: Vec<_> = extra.into_iter().chain([encoder.finish()]).collect();
        let submitting = std::time::Instant::now();
        let submitted = gpu.queue.submit(commands);
        let submit = submitting.elapsed();
        for id in output.textures_delta.free.drain() {
            self.renderer.free_texture(&id);
        }
        Painted { submitted, submit }
    }
}
