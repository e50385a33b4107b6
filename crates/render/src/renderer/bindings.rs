//! What the shaders read besides vertices: the layouts of their bind
//! groups, and the scene's group (the frame's globals, the light's shadow
//! faces, the tumblers' paint and the irradiance volume).

use crate::gpu::Gpu;
use crate::irradiance::{DIRECTIONS, MAX_PROBES};
use crate::shadow::ShadowCube;

/// The irradiance volume's texels: light, smoothly filtered.
pub(super) const IRRADIANCE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

/// The bind group layouts the pipelines are built on.
#[derive(Clone)]
pub(super) struct Layouts {
    /// The lit scene: globals, the shadow faces with their comparison
    /// sampler, the paint texture with its sampler, and the irradiance
    /// volume with its sampler.
    pub scene: wgpu::BindGroupLayout,
    /// One shadow face: its view-projection and the light.
    pub face: wgpu::BindGroupLayout,
    /// Tone mapping: the HDR frame, its parameters, the bloom's glow, the
    /// contact occlusion and a bilinear sampler for those two.
    pub tonemap: wgpu::BindGroupLayout,
    /// The frame tone-mapped at the lit resolution, and the bilinear filter.
    pub upscale: wgpu::BindGroupLayout,
}

impl Layouts {
    pub fn new(device: &wgpu::Device) -> Layouts {
        let scene = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("scene"),
            entries: &[
                uniform_entry(0, wgpu::ShaderStages::VERTEX_FRAGMENT),
                wgpu::BindGroupLayoutEntry {
                    binding: 1,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Depth,
                        view_dimension: wgpu::TextureViewDimension::D2Array,
                        multisampled: false,
                    },
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: 2,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Comparison),
                    count: None,
                },
                texture_entry(3, true),
                filtering_sampler_entry(4),
                wgpu::BindGroupLayoutEntry {
                    binding: 5,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Float { filterable: true },
                        view_dimension: wgpu::TextureViewDimension::D3,
                        multisampled: false,
                    },
                    count: None,
                },
                filtering_sampler_entry(6),
            ],
        });
        let face = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("shadow face"),
            entries: &[uniform_entry(0, wgpu::ShaderStages::VERTEX_FRAGMENT)],
        });
        let tonemap = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("tonemap"),
            entries: &[
                texture_entry(0, true),
                uniform_entry(1, wgpu::ShaderStages::FRAGMENT),
                texture_entry(2, true),
                texture_entry(3, true),
                filtering_sampler_entry(4),
            ],
        });
        let upscale = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("upscale"),
            entries: &[texture_entry(0, true), filtering_sampler_entry(1)],
        });
        Layouts {
            scene,
            face,
            tonemap,
            upscale,
        }
    }
}

/// The texture of the irradiance volume: `MAX_PROBES` texels along each
/// axis for each direction, the directions' slabs one after another along
/// z. A room with fewer probes fills the low corner of each slab.
pub(super) fn irradiance_texture(device: &wgpu::Device) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some("irradiance volume"),
        size: wgpu::Extent3d {
            width: MAX_PROBES,
            height: MAX_PROBES,
            depth_or_array_layers: MAX_PROBES * DIRECTIONS.len() as u32,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D3,
        format: IRRADIANCE_FORMAT,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    })
}

/// The lit scene's bind group (see [`Layouts::scene`]): `globals`, the
/// faces of `shadow_cube`, the tumblers' `paint` (uploaded here) and the
/// `irradiance` volume.
pub(super) fn scene_bind_group(
    gpu: &Gpu,
    layout: &wgpu::BindGroupLayout,
    globals: &wgpu::Buffer,
    shadow_cube: &ShadowCube,
    paint: &image::RgbaImage,
    irradiance: &wgpu::Texture,
) -> wgpu::BindGroup {
    let device = &gpu.device;
    let shadow_sampler = device.create_sampler(&wgpu::SamplerDescriptor {
        label: Some("shadow comparison"),
        mag_filter: wgpu::FilterMode::Linear,
        min_filter: wgpu::FilterMode::Linear,
        compare: Some(wgpu::CompareFunction::LessEqual),
        ..Default::default()
    });
    let paint_view = upload_texture(gpu, "tumbler paint", paint);
    let paint_sampler = device.create_sampler(&wgpu::SamplerDescriptor {
        label: Some("paint"),
        address_mode_u: wgpu::AddressMode::Repeat,
        mag_filter: wgpu::FilterMode::Linear,
        min_filter: wgpu::FilterMode::Linear,
        ..Default::default()
    });
    // Clamped to the probes in use by the shader, not by the sampler.
    let irradiance_view = irradiance.create_view(&Default::default());
    let irradiance_sampler = device.create_sampler(&wgpu::SamplerDescriptor {
        label: Some("irradiance"),
        mag_filter: wgpu::FilterMode::Linear,
        min_filter: wgpu::FilterMode::Linear,
        ..Default::default()
    });
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("scene"),
        layout,
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: globals.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: wgpu::BindingResource::TextureView(&shadow_cube.array_view),
            },
            wgpu::BindGroupEntry {
                binding: 2,
                resource: wgpu::BindingResource::Sampler(&shadow_sampler),
            },
            wgpu::BindGroupEntry {
                binding: 3,
                resource: wgpu::BindingResource::TextureView(&paint_view),
            },
            wgpu::BindGroupEntry {
                binding: 4,
                resource: wgpu::BindingResource::Sampler(&paint_sampler),
            },
            wgpu::BindGroupEntry {
                binding: 5,
                resource: wgpu::BindingResource::TextureView(&irradiance_view),
            },
            wgpu::BindGroupEntry {
                binding: 6,
                resource: wgpu::BindingResource::Sampler(&irradiance_sampler),
            },
        ],
    })
}

/// A 2D colour texture at `binding` for fragments, sampled smoothly if
/// `filterable`, else read texel by texel.
pub(super) fn texture_entry(binding: u32, filterable: bool) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Float { filterable },
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled: false,
        },
        count: None,
    }
}

/// A sampler at `binding` that filters smoothly, for fragments.
pub(super) fn filtering_sampler_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
        count: None,
    }
}

/// A uniform buffer at `binding`, seen by the `visibility` stages.
pub(super) fn uniform_entry(
    binding: u32,
    visibility: wgpu::ShaderStages,
) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

fn upload_texture(gpu: &Gpu, label: &str, image: &image::RgbaImage) -> wgpu::TextureView {
    let size = wgpu::Extent3d {
        width: image.width(),
        height: image.height(),
        depth_or_array_layers: 1,
    };
    let texture = gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size,
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Rgba8UnormSrgb,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    });
    gpu.queue.write_texture(
        wgpu::TexelCopyTextureInfo {
            texture: &texture,
            mip_level: 0,
            origin: wgpu::Origin3d::ZERO,
            aspect: wgpu::TextureAspect::All,
        },
        image.as_raw(),
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(4 * image.width()),
            rows_per_image: None,
        },
        size,
    );
    texture.create_view(&Default::default())
}
