//! The point light's shadow: six depth faces around the light (a cube map
//! laid out as a 2D array), each drawn in its own pass every frame (R2).

use glam::{Mat4, Vec3};
use wgpu::util::DeviceExt;

pub const SHADOW_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
/// Layers of the shadow texture: the six faces and one never drawn. OpenGL
/// must fix a texture's kind when it is made, and wgpu makes a square
/// texture of six layers a cube map there, which then samples as nothing
/// through the 2D array view (all in shadow). A seventh layer keeps it an
/// array on every backend.
const LAYERS: u32 = 7;
/// Near and far planes of the faces, in metres: the room's scale.
pub const NEAR: f32 = 0.05;
pub const FAR: f32 = 40.0;

/// The six directions a face looks in, with the up vector of each.
const FACES: [(Vec3, Vec3); 6] = [
    (Vec3::X, Vec3::NEG_Y),
    (Vec3::NEG_X, Vec3::NEG_Y),
    (Vec3::Y, Vec3::Z),
    (Vec3::NEG_Y, Vec3::NEG_Z),
    (Vec3::Z, Vec3::NEG_Y),
    (Vec3::NEG_Z, Vec3::NEG_Y),
];

/// View-projections of the six 90-degree faces around `light`.
pub fn face_view_projections(light: Vec3) -> [Mat4; 6] {
    let projection =
        glam::camera::rh::proj::directx::perspective(std::f32::consts::FRAC_PI_2, 1.0, NEAR, FAR);
    FACES.map(|(dir, up)| projection * glam::camera::rh::view::look_at_mat4(light, light + dir, up))
}

/// What a face is drawn with: its view-projection, and the light it looks
/// out from (balls face it; see `vs_ball_shadow` in the shader).
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct FaceUniform {
    view_proj: [f32; 16],
    light_pos: [f32; 4],
}

impl FaceUniform {
    fn new(view_proj: Mat4, light: Vec3) -> FaceUniform {
        FaceUniform {
            view_proj: view_proj.to_cols_array(),
            light_pos: light.extend(1.0).to_array(),
        }
    }
}

pub struct ShadowCube {
    pub size: u32,
    /// Every layer, for sampling: the faces are the first six.
    pub array_view: wgpu::TextureView,
    /// One view per layer, to draw into.
    pub face_views: Vec<wgpu::TextureView>,
    face_buffers: Vec<wgpu::Buffer>,
    pub face_bind_groups: Vec<wgpu::BindGroup>,
}

impl ShadowCube {
    pub fn new(
        device: &wgpu::Device,
        size: u32,
        face_layout: &wgpu::BindGroupLayout,
    ) -> ShadowCube {
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("shadow cube"),
            size: wgpu::Extent3d {
                width: size,
                height: size,
                depth_or_array_layers: LAYERS,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: SHADOW_FORMAT,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        });
        let array_view = texture.create_view(&wgpu::TextureViewDescriptor {
            label: Some("shadow cube array"),
            dimension: Some(wgpu::TextureViewDimension::D2Array),
            ..Default::default()
        });
        let face_views = (0..6)
            .map(|layer| {
                texture.create_view(&wgpu::TextureViewDescriptor {
                    label: Some("shadow face"),
                    dimension: Some(wgpu::TextureViewDimension::D2),
                    base_array_layer: layer,
                    array_layer_count: Some(1),
                    ..Default::default()
                })
            })
            .collect();
        let face_buffers: Vec<wgpu::Buffer> = (0..6)
            .map(|_| {
                device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("shadow face"),
                    contents: bytemuck::bytes_of(&FaceUniform::new(Mat4::IDENTITY, Vec3::ZERO)),
                    usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                })
            })
            .collect();
        let face_bind_groups = face_buffers
            .iter()
            .map(|buffer| {
                device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("shadow face"),
                    layout: face_layout,
                    entries: &[wgpu::BindGroupEntry {
                        binding: 0,
                        resource: buffer.as_entire_binding(),
                    }],
                })
            })
            .collect();
        ShadowCube {
            size,
            array_view,
            face_views,
            face_buffers,
            face_bind_groups,
        }
    }

    /// Sets the faces' view-projections around the light at `light`.
    pub fn update(&self, queue: &wgpu::Queue, faces: &[Mat4; 6], light: Vec3) {
        for (buffer, m) in self.face_buffers.iter().zip(faces) {
            queue.write_buffer(buffer, 0, bytemuck::bytes_of(&FaceUniform::new(*m, light)));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_direction_lands_inside_the_face_it_selects() {
        // The shader picks a face by the major axis; the point must project
        // inside that face with depth in 0..1.
        let light = Vec3::new(0.0, 3.75, 0.0);
        let faces = face_view_projections(light);
        for d in [
            Vec3::new(1.0, 0.2, -0.3),
            Vec3::new(-1.0, 0.9, 0.1),
            Vec3::new(0.1, 1.0, -0.5),
            Vec3::new(0.3, -1.0, 0.99),
            Vec3::new(-0.2, 0.4, 1.0),
            Vec3::new(0.7, -0.6, -1.0),
        ] {
            let a = d.abs();
            let face = if a.x >= a.y && a.x >= a.z {
                if d.x > 0.0 { 0 } else { 1 }
            } else if a.y >= a.z {
                if d.y > 0.0 { 2 } else { 3 }
            } else if d.z > 0.0 {
                4
            } else {
                5
            };
            let clip = faces[face] * (light + d * 2.0).extend(1.0);
            let ndc = clip.truncate() / clip.w;
            assert!(ndc.x.abs() <= 1.0 && ndc.y.abs() <= 1.0, "{d}: {ndc}");
            assert!((0.0..1.0).contains(&ndc.z));
        }
    }
}
