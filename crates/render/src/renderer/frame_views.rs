//! The extra pass of the frame's views that no frame target holds as it is
//! shown (see [`crate::FrameView`] and frame_views.wgsl): the light's
//! shadow cube unfolded as a cross, the pixels whose multisamples
//! disagree, and the temporal path's weight of history. One full-output
//! pass, drawn over the finished frame.

use super::bindings::{texture_entry, uniform_entry};
use super::pipelines::{screen_pipeline, screen_shader};
use crate::frame_view::SHADOW_CROSS;
use crate::shaders::ShaderSet;
use crate::shadow;
use bytemuck::{Pod, Zeroable};

/// The most weight a pixel's history holds: taa.wgsl's `MAX_WEIGHT` kept,
/// and the newest sample's at most 1.
const MOST_HISTORY_WEIGHT: f32 = 7.0;

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct Params {
    size: [f32; 4],
    place: [f32; 4],
    planes: [f32; 4],
    cells: [[f32; 4]; 6],
}

/// What a view of this pass reads, beside its parameters.
pub(super) enum ViewSource<'a> {
    /// The shadow faces (a 2D array of depth).
    ShadowCube(&'a wgpu::TextureView),
    /// The surfaces' normals and distances, each sample of each pixel.
    Samples(&'a wgpu::TextureView),
    /// The temporal path's resolved history (alpha: its weight).
    History(&'a wgpu::TextureView),
}

/// Where the shadow cube's cross lies on an output of `size`: its top left
/// and a face's side, in pixels (the cross is four faces wide and three
/// high, centred).
pub fn shadow_cross_place(size: (u32, u32)) -> (glam::Vec2, f32) {
    let size = glam::Vec2::new(size.0 as f32, size.1 as f32);
    let side = (size.x / 4.0).min(size.y / 3.0).floor();
    let cross = glam::Vec2::new(4.0, 3.0) * side;
    (((size - cross) * 0.5).floor(), side)
}

/// The pass's pipelines, one a view, each on its own bind group layout.
pub(super) struct FrameViewsPass {
    params: wgpu::Buffer,
    shadow_cube: (wgpu::BindGroupLayout, wgpu::RenderPipeline),
    /// Only where the frame is multisampled.
    msaa_edges: Option<(wgpu::BindGroupLayout, wgpu::RenderPipeline)>,
    history: (wgpu::BindGroupLayout, wgpu::RenderPipeline),
}

impl FrameViewsPass {
    pub fn new(
        device: &wgpu::Device,
        shaders: &ShaderSet,
        output_format: wgpu::TextureFormat,
        samples: u32,
    ) -> FrameViewsPass {
        let shader = screen_shader(device, shaders, &crate::shaders::FRAME_VIEWS);
        let pipeline = |entry: &str, read: wgpu::BindGroupLayoutEntry| {
            let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some(entry),
                entries: &[uniform_entry(0, wgpu::ShaderStages::FRAGMENT), read],
            });
            let pipeline = screen_pipeline(
                device,
                entry,
                &layout,
                &shader,
                ("vs_screen", entry),
                output_format.into(),
            );
            (layout, pipeline)
        };
        let texture =
            |binding, sample_type, view_dimension, multisampled| wgpu::BindGroupLayoutEntry {
                binding,
                visibility: wgpu::ShaderStages::FRAGMENT,
                ty: wgpu::BindingType::Texture {
                    sample_type,
                    view_dimension,
                    multisampled,
                },
                count: None,
            };
        FrameViewsPass {
            params: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("frame views"),
                size: std::mem::size_of::<Params>() as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
            shadow_cube: pipeline(
                "fs_shadow_cube",
                texture(
                    1,
                    wgpu::TextureSampleType::Float { filterable: false },
                    wgpu::TextureViewDimension::D2Array,
                    false,
                ),
            ),
            msaa_edges: (samples > 1).then(|| {
                pipeline(
                    "fs_msaa_edges",
                    texture(
                        2,
                        wgpu::TextureSampleType::Float { filterable: false },
                        wgpu::TextureViewDimension::D2,
                        true,
                    ),
                )
            }),
            history: pipeline("fs_history", texture_entry(3, false)),
        }
    }

    /// Draws `view` from `source` over `output` (of `size`, its scene lit at
    /// `scene_size`) with the light at `light` in a room whose farthest
    /// point from it is `farthest` away; with no source (its pass is off),
    /// clears the output to black. Returns the draw calls.
    #[allow(clippy::too_many_arguments)]
    pub fn draw(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        output: &wgpu::TextureView,
        source: Option<ViewSource>,
        (size, scene_size): ((u32, u32), (u32, u32)),
        (face_side, farthest): (u32, f32),
    ) -> u32 {
        let (place, side) = shadow_cross_place(size);
        let mut cells = [[0.0; 4]; 6];
        for (cell, (column, row)) in cells.iter_mut().zip(SHADOW_CROSS) {
            *cell = [column as f32, row as f32, 0.0, 0.0];
        }
        let params = Params {
            size: [size.0 as f32, size.1 as f32, side, face_side as f32],
            place: [place.x, place.y, farthest, MOST_HISTORY_WEIGHT],
            planes: [
                shadow::NEAR,
                shadow::FAR,
                scene_size.0 as f32,
                scene_size.1 as f32,
            ],
            cells,
        };
        queue.write_buffer(&self.params, 0, bytemuck::bytes_of(&params));
        let chosen = source.and_then(|source| {
            let (layout_pipeline, binding, texture) = match source {
                ViewSource::ShadowCube(t) => (Some(&self.shadow_cube), 1, t),
                ViewSource::Samples(t) => (self.msaa_edges.as_ref(), 2, t),
                ViewSource::History(t) => (Some(&self.history), 3, t),
            };
            layout_pipeline.map(|(layout, pipeline)| {
                let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("frame view"),
                    layout,
                    entries: &[
                        wgpu::BindGroupEntry {
                            binding: 0,
                            resource: self.params.as_entire_binding(),
                        },
                        wgpu::BindGroupEntry {
                            binding,
                            resource: wgpu::BindingResource::TextureView(texture),
                        },
                    ],
                });
                (pipeline, group)
            })
        });
        let mut pass = super::screen_pass(encoder, output, None);
        match chosen {
            Some((pipeline, group)) => {
                pass.set_pipeline(pipeline);
                pass.set_bind_group(0, &group, &[]);
                pass.draw(0..3, 0..1);
                1
            }
            None => 0,
        }
    }
}
