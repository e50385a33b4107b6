//! The frame's own render targets, made for its size: the HDR colour it is
//! lit into and the surfaces' normals and distances (multisampled, then
//! resolved), its depth, the bloom's chain and the contact occlusion, tone
//! mapping's bind group over them, the surfaces' motion on the temporal
//! path, and where the scene is lit at a lower resolution or the temporal
//! path resolves it, the frame tone-mapped at the lit resolution.

use super::bloom::{BloomChain, BloomPipelines};
use super::debug_marks::DebugMarksPass;
use super::occlusion::{OcclusionPipeline, OcclusionTarget};
use super::taa::{MOTION_FORMAT, NEIGHBOURHOOD_FORMAT};
use super::{DEPTH_FORMAT, GEOMETRY_FORMAT, HDR_FORMAT};

/// Size-dependent render targets.
pub(super) struct Targets {
    /// The output's size, which tone mapping draws.
    pub width: u32,
    pub height: u32,
    /// The size the scene is lit at, which every other target has.
    pub scene_size: (u32, u32),
    /// Multisampled colour (absent at 1x, where `hdr` is drawn directly).
    pub msaa: Option<wgpu::TextureView>,
    pub hdr: wgpu::TextureView,
    pub depth: wgpu::TextureView,
    /// The surfaces' normals and distances, resolved; the occlusion reads it.
    pub geometry: wgpu::TextureView,
    pub geometry_texture: wgpu::Texture,
    /// The last frame's surfaces (the temporal path only), copied from
    /// `geometry` at the end of each frame: where the distance seen at a
    /// pixel's place then differs from now's, the history there shows
    /// something else (what moved away) and is not used.
    pub geometry_before: Option<(wgpu::Texture, wgpu::TextureView)>,
    pub geometry_msaa: Option<wgpu::TextureView>,
    /// The surfaces' motion since the last frame (the temporal path only,
    /// which draws without multisampling).
    pub motion: Option<wgpu::TextureView>,
    /// Each lit texel's neighbourhood (the temporal path only).
    pub neighbourhood: Option<[wgpu::TextureView; 2]>,
    pub bloom: BloomChain,
    pub occlusion: OcclusionTarget,
    /// Reads `hdr`, the glow and the occlusion for tone mapping.
    pub tonemap_bind_group: wgpu::BindGroup,
    /// Reads `geometry` for the debug marks' depth.
    pub marks_bind_group: wgpu::BindGroup,
    /// Where the scene is lit at a lower resolution than the output, or the
    /// temporal path resolves it: the frame tone-mapped at the lit
    /// resolution, and the upscale's bind group over it.
    pub composed: Option<(wgpu::TextureView, wgpu::BindGroup)>,
}

/// What the targets are made with besides their size.
pub(super) struct TargetKit<'a> {
    pub samples: u32,
    /// Whether the multisampled surfaces are read sample by sample (see
    /// [`crate::Gpu::reads_multisampled_targets`]).
    pub read_samples: bool,
    /// Whether the frame takes the temporal path.
    pub temporal: bool,
    pub tonemap_layout: &'a wgpu::BindGroupLayout,
    pub tonemap_params: &'a wgpu::Buffer,
    pub smooth_sampler: &'a wgpu::Sampler,
    pub bloom: &'a BloomPipelines,
    pub occlusion: &'a OcclusionPipeline,
    pub marks: &'a DebugMarksPass,
    pub upscale_layout: &'a wgpu::BindGroupLayout,
    /// The output's colour format, which the frame is tone-mapped into.
    pub output_format: wgpu::TextureFormat,
}

impl Targets {
    /// Targets for an output of `width` by `height` pixels whose scene is
    /// lit at `scene_size`.
    /// Keeps this frame's surfaces for the next frame's resolve (the
    /// temporal path only).
    pub fn keep_geometry(&self, encoder: &mut wgpu::CommandEncoder) {
        if let Some((before, _)) = &self.geometry_before {
            encoder.copy_texture_to_texture(
                self.geometry_texture.as_image_copy(),
                before.as_image_copy(),
                self.geometry_texture.size(),
            );
        }
    }

    pub fn new(
        device: &wgpu::Device,
        (width, height): (u32, u32),
        scene_size: (u32, u32),
        kit: &TargetKit,
    ) -> Targets {
        let size = wgpu::Extent3d {
            width: scene_size.0,
            height: scene_size.1,
            depth_or_array_layers: 1,
        };
        let texture = |label, format, samples, usage| {
            device
                .create_texture(&wgpu::TextureDescriptor {
                    label: Some(label),
                    size,
                    mip_level_count: 1,
                    sample_count: samples,
                    dimension: wgpu::TextureDimension::D2,
                    format,
                    usage,
                    view_formats: &[],
                })
                .create_view(&Default::default())
        };
        let drawn_and_read =
            wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING;
        let hdr = texture("hdr", HDR_FORMAT, 1, drawn_and_read);
        let multisampled = |label, format| {
            (kit.samples > 1).then(|| {
                texture(
                    label,
                    format,
                    kit.samples,
                    wgpu::TextureUsages::RENDER_ATTACHMENT,
                )
            })
        };
        let msaa = multisampled("hdr msaa", HDR_FORMAT);
        let geometry_texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("geometry"),
            size,
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: GEOMETRY_FORMAT,
            usage: drawn_and_read | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        });
        let geometry = geometry_texture.create_view(&Default::default());
        let geometry_before = kit.temporal.then(|| {
            let texture = device.create_texture(&wgpu::TextureDescriptor {
                label: Some("geometry before"),
                size,
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: GEOMETRY_FORMAT,
                usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
                view_formats: &[],
            });
            let view = texture.create_view(&Default::default());
            (texture, view)
        });
        // Read sample by sample by the msaa-edges view.
        let geometry_msaa = if kit.read_samples {
            (kit.samples > 1).then(|| {
                texture(
                    "geometry msaa",
                    GEOMETRY_FORMAT,
                    kit.samples,
                    drawn_and_read,
                )
            })
        } else {
            multisampled("geometry msaa", GEOMETRY_FORMAT)
        };
        let depth = texture(
            "depth",
            DEPTH_FORMAT,
            kit.samples,
            wgpu::TextureUsages::RENDER_ATTACHMENT,
        );
        let motion = kit
            .temporal
            .then(|| texture("motion", MOTION_FORMAT, 1, drawn_and_read));
        let neighbourhood = kit.temporal.then(|| {
            ["neighbourhood mean", "neighbourhood spread"]
                .map(|label| texture(label, NEIGHBOURHOOD_FORMAT, 1, drawn_and_read))
        });
        let bloom = BloomChain::new(device, kit.bloom, &hdr, scene_size);
        let occlusion = kit.occlusion.target(device, &geometry, scene_size);
        let tonemap_bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("tonemap"),
            layout: kit.tonemap_layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::TextureView(&hdr),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: kit.tonemap_params.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: wgpu::BindingResource::TextureView(&bloom.glow),
                },
                wgpu::BindGroupEntry {
                    binding: 3,
                    resource: wgpu::BindingResource::TextureView(&occlusion.view),
                },
                wgpu::BindGroupEntry {
                    binding: 4,
                    resource: wgpu::BindingResource::Sampler(kit.smooth_sampler),
                },
            ],
        });
        let marks_bind_group = kit.marks.bind_group(device, &geometry);
        let composed = (kit.temporal || scene_size != (width, height)).then(|| {
            let view = texture("composed", kit.output_format, 1, drawn_and_read);
            let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("upscale"),
                layout: kit.upscale_layout,
                entries: &[
                    wgpu::BindGroupEntry {
                        binding: 0,
                        resource: wgpu::BindingResource::TextureView(&view),
                    },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: wgpu::BindingResource::Sampler(kit.smooth_sampler),
                    },
                ],
            });
            (view, bind_group)
        });
        Targets {
            width,
            height,
            scene_size,
            msaa,
            hdr,
            depth,
            geometry,
            geometry_texture,
            geometry_before,
            geometry_msaa,
            motion,
            neighbourhood,
            bloom,
            occlusion,
            tonemap_bind_group,
            marks_bind_group,
            composed,
        }
    }
}
