//! The 27 colours of grid cells that let the contact solver sweep by
//! Gauss-Seidel on many threads at once (see `shaders/solve.wgsl`): a pass
//! takes the cells whose coordinates are one colour's offsets modulo 3
//! (`colour_offset` there).

/// Colours of cells: three offsets along each axis.
pub const COLOURS: u32 = 27;

/// Bytes between two colours' uniforms: the most any adapter may ask a
/// dynamic offset to be aligned to.
const STRIDE: u64 = 256;

/// Each colour's number, in one uniform buffer read at a dynamic offset.
pub struct CellColours {
    pub layout: wgpu::BindGroupLayout,
    group: wgpu::BindGroup,
    /// Cells of the most numerous colour: the threads of one pass.
    pub cells_per_colour: u64,
}

impl CellColours {
    /// The colours of a grid of `dims` cells.
    pub fn new(device: &wgpu::Device, dims: [u32; 3]) -> CellColours {
        use wgpu::util::DeviceExt;
        let mut bytes = vec![0u8; (STRIDE * u64::from(COLOURS)) as usize];
        for q in 0..COLOURS {
            let at = (STRIDE * u64::from(q)) as usize;
            bytes[at..at + 4].copy_from_slice(bytemuck::bytes_of(&q));
        }
        let buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("cell colours"),
            contents: &bytes,
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("cell colour"),
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::COMPUTE,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: true,
                    min_binding_size: wgpu::BufferSize::new(16),
                },
                count: None,
            }],
        });
        let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("cell colour"),
            layout: &layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                    buffer: &buffer,
                    offset: 0,
                    size: wgpu::BufferSize::new(16),
                }),
            }],
        });
        let cells_per_colour = dims.iter().map(|&d| u64::from(d.div_ceil(3))).product();
        CellColours {
            layout,
            group,
            cells_per_colour,
        }
    }

    /// Binds colour `q` as group 1 of `pass`.
    pub fn bind(&self, pass: &mut wgpu::ComputePass, q: u32) {
        pass.set_bind_group(1, &self.group, &[(STRIDE * u64::from(q)) as u32]);
    }
}
