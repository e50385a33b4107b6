//! The frame's own render targets, made for its size: the HDR colour it is
//! lit into (multisampled, then resolved), and its depth.

use super::{DEPTH_FORMAT, HDR_FORMAT};

/// Size-dependent render targets.
pub(super) struct Targets {
    pub width: u32,
    pub height: u32,
    /// Multisampled colour (absent at 1x, where `hdr` is drawn directly).
    pub msaa: Option<wgpu::TextureView>,
    pub hdr: wgpu::TextureView,
    pub depth: wgpu::TextureView,
    /// Reads `hdr` for tone mapping.
    pub tonemap_bind_group: wgpu::BindGroup,
}

impl Targets {
    /// Targets of `width` by `height` pixels with `samples` per pixel, and
    /// the tone mapping's bind group (`layout`) over them with `params`.
    pub fn new(
        device: &wgpu::Device,
        (width, height): (u32, u32),
        samples: u32,
        layout: &wgpu::BindGroupLayout,
        params: &wgpu::Buffer,
    ) -> Targets {
        let size = wgpu::Extent3d {
            width,
            height,
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
        let hdr = texture(
            "hdr",
            HDR_FORMAT,
            1,
            wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
        );
        let msaa = (samples > 1).then(|| {
            texture(
                "hdr msaa",
                HDR_FORMAT,
                samples,
                wgpu::TextureUsages::RENDER_ATTACHMENT,
            )
        });
        let depth = texture(
            "depth",
            DEPTH_FORMAT,
            samples,
            wgpu::TextureUsages::RENDER_ATTACHMENT,
        );
        let tonemap_bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("tonemap"),
            layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::TextureView(&hdr),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: params.as_entire_binding(),
                },
            ],
        });
        Targets {
            width,
            height,
            msaa,
            hdr,
            depth,
            tonemap_bind_group,
        }
    }
}
