//! Triangle meshes: what the CPU builds and what the GPU draws.

use bytemuck::{Pod, Zeroable};
use wgpu::util::DeviceExt;

/// One corner of a triangle, as the shaders read it.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct Vertex {
    /// Where it is (m).
    pub position: [f32; 3],
    /// The surface's normal there.
    pub normal: [f32; 3],
    /// Where it lies on the paint.
    pub uv: [f32; 2],
}

impl Vertex {
    /// The shaders' vertex inputs: position, normal, uv.
    pub const ATTRIBUTES: [wgpu::VertexAttribute; 3] =
        wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32x2];

    /// How a vertex buffer of these is laid out.
    pub fn layout() -> wgpu::VertexBufferLayout<'static> {
        wgpu::VertexBufferLayout {
            array_stride: std::mem::size_of::<Vertex>() as u64,
            step_mode: wgpu::VertexStepMode::Vertex,
            attributes: &Self::ATTRIBUTES,
        }
    }
}

/// A mesh on the CPU side.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MeshData {
    /// The corners.
    pub vertices: Vec<Vertex>,
    /// Three corners a triangle, by number.
    pub indices: Vec<u32>,
}

impl MeshData {
    /// A sphere that holds every corner (so every triangle): the centre of
    /// their box and the farthest corner's distance from it.
    pub fn bounding_sphere(&self) -> (glam::Vec3, f32) {
        let points = self.vertices.iter().map(|v| glam::Vec3::from(v.position));
        let (lo, hi) = points.clone().fold(
            (glam::Vec3::splat(f32::MAX), glam::Vec3::splat(f32::MIN)),
            |(lo, hi), p| (lo.min(p), hi.max(p)),
        );
        if self.vertices.is_empty() {
            return (glam::Vec3::ZERO, 0.0);
        }
        let centre = (lo + hi) * 0.5;
        let radius = points.map(|p| p.distance(centre)).fold(0.0, f32::max);
        (centre, radius)
    }

    /// A unit sphere (radius 1) of `rings` x `segments` quads.
    pub fn sphere(rings: u32, segments: u32) -> MeshData {
        let mut mesh = MeshData::default();
        for r in 0..=rings {
            let v = r as f32 / rings as f32;
            let theta = v * std::f32::consts::PI;
            for s in 0..=segments {
                let u = s as f32 / segments as f32;
                let phi = u * std::f32::consts::TAU;
                let n = [
                    theta.sin() * phi.cos(),
                    theta.cos(),
                    theta.sin() * phi.sin(),
                ];
                mesh.vertices.push(Vertex {
                    position: n,
                    normal: n,
                    uv: [u, v],
                });
            }
        }
        mesh.grid_indices(rings, segments);
        mesh
    }

    /// A cube of edge 1 centred on the origin, each face with its own
    /// normal and full 0..1 UVs.
    pub fn cube() -> MeshData {
        let mut mesh = MeshData::default();
        for axis in 0..3 {
            for sign in [1.0f32, -1.0] {
                let mut n = [0.0; 3];
                n[axis] = sign;
                let normal = glam::Vec3::from_array(n);
                // Two edge directions whose cross product is the normal.
                let u = glam::Vec3::from_array(
                    [[0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]][axis],
                ) * sign;
                let v = normal.cross(u);
                let base = mesh.vertices.len() as u32;
                for (a, b) in [(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)] {
                    let p = normal * 0.5 + u * a + v * b;
                    mesh.vertices.push(Vertex {
                        position: p.to_array(),
                        normal: n,
                        uv: [a + 0.5, b + 0.5],
                    });
                }
                mesh.indices.extend_from_slice(&[
                    base,
                    base + 1,
                    base + 2,
                    base,
                    base + 2,
                    base + 3,
                ]);
            }
        }
        mesh
    }

    /// The unit square in the xy plane (0..1), facing +z.
    pub fn quad() -> MeshData {
        let corners = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        MeshData {
            vertices: corners
                .iter()
                .map(|&[x, y]| Vertex {
                    position: [x, y, 0.0],
                    normal: [0.0, 0.0, 1.0],
                    uv: [x, 1.0 - y],
                })
                .collect(),
            indices: vec![0, 1, 2, 0, 2, 3],
        }
    }

    /// Indices for a (rows + 1) x (columns + 1) vertex grid, counter-clockwise
    /// seen from outside when rows run top to bottom and columns turn east.
    pub(crate) fn grid_indices(&mut self, rows: u32, columns: u32) {
        let stride = columns + 1;
        for r in 0..rows {
            for c in 0..columns {
                let a = r * stride + c;
                let b = a + stride;
                self.indices
                    .extend_from_slice(&[a, a + 1, b, a + 1, b + 1, b]);
            }
        }
    }
}

/// A mesh uploaded to the GPU.
pub struct GpuMesh {
    pub vertices: wgpu::Buffer,
    pub indices: wgpu::Buffer,
    pub index_count: u32,
}

impl GpuMesh {
    pub fn upload(device: &wgpu::Device, label: &str, mesh: &MeshData) -> GpuMesh {
        GpuMesh {
            vertices: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents: bytemuck::cast_slice(&mesh.vertices),
                usage: wgpu::BufferUsages::VERTEX,
            }),
            indices: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents: bytemuck::cast_slice(&mesh.indices),
                usage: wgpu::BufferUsages::INDEX,
            }),
            index_count: mesh.indices.len() as u32,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cube_faces_point_outwards() {
        let m = MeshData::cube();
        assert_eq!(m.vertices.len(), 24);
        for t in m.indices.chunks(3) {
            let [a, b, c] =
                [t[0], t[1], t[2]].map(|i| glam::Vec3::from_array(m.vertices[i as usize].position));
            let n = (b - a).cross(c - a);
            assert!(n.dot(a + b + c) > 0.0, "a cube face winds inwards");
            assert!(
                n.normalize()
                    .dot(glam::Vec3::from_array(m.vertices[t[0] as usize].normal))
                    > 0.99
            );
        }
    }

    #[test]
    fn sphere_vertices_lie_on_the_unit_sphere_and_triangles_face_out() {
        let m = MeshData::sphere(8, 12);
        for v in &m.vertices {
            let p = glam::Vec3::from_array(v.position);
            assert!((p.length() - 1.0).abs() < 1e-6);
        }
        for t in m.indices.chunks(3) {
            let [a, b, c] =
                [t[0], t[1], t[2]].map(|i| glam::Vec3::from_array(m.vertices[i as usize].position));
            let n = (b - a).cross(c - a);
            if n.length() > 1e-6 {
                assert!(n.dot(a + b + c) > 0.0, "a triangle faces inwards");
            }
        }
    }
}
