//! The point light's shadow: six depth faces around the light (a cube map
//! laid out as a 2D array), each drawn in its own pass (R2), and again only
//! when what it sees moved ([`DrawnFaces`]).

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

/// The faces (bit k for face k, as numbered in [`FACES`]) of the light at
/// `light` that a sphere at `centre` of `radius` can cast into: those whose
/// square pyramid, with its apex at the light, it reaches into. Exact where
/// it says no: a sphere wholly behind a face's apex plane, or wholly beyond
/// one of its side planes, covers none of its texels (a face draws only the
/// traced sphere's own points, and a mesh lies inside its bounding sphere).
/// Near the apex it may say yes for a sphere that only grazes the corner
/// between two planes: drawn, then, into texels it does not cover.
pub fn faces_reached(light: Vec3, centre: Vec3, radius: f32) -> u8 {
    let d = (centre - light).to_array();
    let across = d.map(f32::abs);
    // A side plane through the apex at 45 degrees to the axis: a point is
    // (|across| - ahead) / sqrt 2 beyond it.
    let reach = radius * std::f32::consts::SQRT_2;
    let mut faces = 0;
    for axis in 0..3 {
        let widest = across[(axis + 1) % 3].max(across[(axis + 2) % 3]) - reach;
        for (sign, ahead) in [(0, d[axis]), (1, -d[axis])] {
            if ahead > -radius && ahead > widest {
                faces |= 1 << (2 * axis + sign);
            }
        }
    }
    faces
}

/// Sorts `casters` into `out` face by face, each only into the faces it can
/// cast into with the bounding sphere (centre, radius) `sphere_of` gives
/// for its index; returns each face's range of `out`. The spheres are
/// tested once each, into `reached` (kept by the caller, so that a frame
/// allocates nothing), then listed face by face.
pub fn sort_into_faces<T: Copy>(
    casters: &[T],
    sphere_of: impl Fn(usize) -> (Vec3, f32),
    light: Vec3,
    reached: &mut Vec<u8>,
    out: &mut Vec<T>,
) -> [std::ops::Range<u32>; 6] {
    reached.clear();
    reached.extend((0..casters.len()).map(|k| {
        let (centre, radius) = sphere_of(k);
        faces_reached(light, centre, radius)
    }));
    out.clear();
    std::array::from_fn(|face| {
        let start = out.len() as u32;
        let bit = 1 << face;
        out.extend(
            casters
                .iter()
                .zip(reached.iter())
                .filter(|(_, faces)| *faces & bit != 0)
                .map(|(caster, _)| *caster),
        );
        start..out.len() as u32
    })
}

/// What each shadow face was last drawn from: the light and, face by face,
/// where its casters were. A face whose light and casters are as they were
/// holds the depths it would be drawn with, and is not drawn again: a room
/// at rest draws no shadow faces at all, a ball rolling across one face
/// redraws that face alone.
#[derive(Default)]
pub struct DrawnFaces {
    light: Option<Vec3>,
    /// Per face: the numbers that placed its casters (as bits), in the
    /// order they were drawn.
    casters: [Vec<u32>; 6],
}

impl DrawnFaces {
    /// Which faces must be drawn for the light at `light`, whose casters
    /// face by face are placed by the numbers `casters(face)` (a ball's
    /// centre and radius, a tumbler's model matrix, one after another);
    /// they are kept as drawn.
    pub fn stale<I: Iterator<Item = f32>>(
        &mut self,
        light: Vec3,
        mut casters: impl FnMut(usize) -> I,
    ) -> [bool; 6] {
        let moved_light = self.light != Some(light);
        self.light = Some(light);
        std::array::from_fn(|face| {
            let kept = &mut self.casters[face];
            let same = !moved_light && kept.iter().copied().eq(casters(face).map(f32::to_bits));
            if !same {
                kept.clear();
                kept.extend(casters(face).map(f32::to_bits));
            }
            !same
        })
    }

    /// Every face is to be drawn next time (their depths are not known).
    pub fn forget(&mut self) {
        self.light = None;
    }
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

    /// Whether a sphere can cast into face `face`.
    fn casts_into(face: usize, light: Vec3, centre: Vec3, radius: f32) -> bool {
        faces_reached(light, centre, radius) & (1 << face) != 0
    }

    /// Points spread over a sphere of directions, from a seed.
    fn directions(seed: u32, count: usize) -> Vec<Vec3> {
        let mut state = seed.wrapping_mul(2_654_435_761).max(1);
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 17;
            state ^= state << 5;
            state as f32 / u32::MAX as f32 * 2.0 - 1.0
        };
        (0..count)
            .map(|_| Vec3::new(next(), next(), next()))
            .filter(|d| d.length() > 1e-3)
            .collect()
    }

    #[test]
    fn a_ball_wholly_below_the_light_casts_into_no_upward_face() {
        let light = Vec3::new(0.3, 3.75, -0.2);
        for seed in 1..4 {
            for d in directions(seed, 500) {
                let radius = 0.02 + d.x.abs() * 0.3;
                // Somewhere below the light by more than its radius.
                let centre =
                    light + Vec3::new(d.x * 5.0, -radius - d.y.abs() * 3.0 - 1e-3, d.z * 5.0);
                assert!(!casts_into(2, light, centre, radius), "{centre} r {radius}");
                // It still casts into the downward face or a side one.
                assert!((0..6).any(|f| casts_into(f, light, centre, radius)));
            }
        }
    }

    #[test]
    fn a_sphere_casts_into_every_face_its_points_fall_in() {
        // Any point of the sphere lies in some face's pyramid (the one its
        // direction selects); that face must be among those it casts into.
        let light = Vec3::new(0.0, 3.75, 0.0);
        for seed in 1..5 {
            let centres = directions(seed, 200);
            let offsets = directions(seed + 100, 60);
            for c in &centres {
                let centre = light + *c * 3.0;
                let radius = 0.05 + c.y.abs() * 0.8;
                for o in &offsets {
                    let point = centre + o.normalize() * radius * o.length().min(1.0);
                    let face = pick_face(point - light);
                    assert!(
                        casts_into(face, light, centre, radius),
                        "{centre} r {radius}: point {point} in face {face}"
                    );
                }
            }
        }
    }

    #[test]
    fn each_face_lists_exactly_the_casters_that_reach_it_in_their_order() {
        let light = Vec3::new(0.0, 3.75, 0.0);
        for seed in [7, 8, 9] {
            let balls: Vec<(Vec3, f32)> = directions(seed, 300)
                .into_iter()
                .map(|d| (Vec3::new(d.x * 4.0, 0.1 + d.y.abs() * 3.0, d.z * 4.0), 0.1))
                .collect();
            let indices: Vec<usize> = (0..balls.len()).collect();
            let mut out = Vec::new();
            let faces = sort_into_faces(&indices, |k| balls[k], light, &mut Vec::new(), &mut out);
            assert!(faces[2].is_empty(), "nothing above the light: {faces:?}");
            let total: usize = faces.iter().map(|r| r.len()).sum();
            assert!(total >= balls.len() && total < 2 * balls.len(), "{total}");
            for (face, range) in faces.iter().enumerate() {
                let listed = &out[range.start as usize..range.end as usize];
                let expected: Vec<usize> = indices
                    .iter()
                    .copied()
                    .filter(|&k| casts_into(face, light, balls[k].0, balls[k].1))
                    .collect();
                assert_eq!(listed, expected, "face {face}");
            }
        }
    }

    fn pick_face(d: Vec3) -> usize {
        let a = d.abs();
        if a.x >= a.y && a.x >= a.z {
            if d.x > 0.0 { 0 } else { 1 }
        } else if a.y >= a.z {
            if d.y > 0.0 { 2 } else { 3 }
        } else if d.z > 0.0 {
            4
        } else {
            5
        }
    }

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
            let face = pick_face(d);
            let clip = faces[face] * (light + d * 2.0).extend(1.0);
            let ndc = clip.truncate() / clip.w;
            assert!(ndc.x.abs() <= 1.0 && ndc.y.abs() <= 1.0, "{d}: {ndc}");
            assert!((0.0..1.0).contains(&ndc.z));
        }
    }
}
