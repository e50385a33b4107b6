//! What the paths travel through: the room's six rectangles, spheres (the
//! balls and the lights), and meshes placed in the room (the tumblers),
//! each with its material; built from the real-time frame's `SceneView`.

use glam::{Affine3A, Vec2, Vec3};
use image::RgbaImage;
use rolypoly_render::{
    BALL_FINISH, FLOOR_FINISH, Finish, MeshData, PointLight, SceneView, TUMBLER_FINISH,
    WALL_FINISH, power_of, room_surfaces,
};

use crate::albedo::{Paint, plaster, wood};
use crate::bvh::Bvh;
use crate::geometry::{Aabb, Ray, hit_rectangle, hit_sphere, hit_triangle};
use crate::light::SphereLight;
use crate::material::{Albedo, Material};

/// Why a scene cannot be traced.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// The balls are on the GPU engine, out of the CPU's reach.
    #[error(
        "the reference traces balls stepped on the CPU; the GPU engine's balls stay on the GPU (drop --gpu)"
    )]
    BallsOnGpu,
    /// The tumbler mesh has nothing to trace.
    #[error("the tumbler mesh has no triangles")]
    EmptyMesh,
}

/// A flat rectangle, lit and seen from its front only.
#[derive(Clone, Copy, Debug)]
pub struct Rectangle {
    corner: Vec3,
    u: Vec3,
    v: Vec3,
    material: u32,
}

#[derive(Clone, Copy, Debug)]
struct Sphere {
    centre: Vec3,
    radius: f32,
    material: u32,
    /// Its number among the lights, where it is one.
    light: Option<u32>,
}

/// Triangles in their own space, with their normals and paint coordinates.
#[derive(Clone, Debug)]
pub struct Mesh {
    positions: Vec<Vec3>,
    normals: Vec<Vec3>,
    uvs: Vec<Vec2>,
    triangles: Vec<[u32; 3]>,
    bvh: Bvh,
    bounds: Aabb,
}

impl Mesh {
    /// The triangles of a mesh the real-time frame draws.
    pub fn new(data: &MeshData) -> Result<Mesh, SceneError> {
        let triangles: Vec<[u32; 3]> = data
            .indices
            .chunks_exact(3)
            .map(|t| [t[0], t[1], t[2]])
            .collect();
        if triangles.is_empty() {
            return Err(SceneError::EmptyMesh);
        }
        let positions: Vec<Vec3> = data
            .vertices
            .iter()
            .map(|v| Vec3::from(v.position))
            .collect();
        let bounds: Vec<Aabb> = triangles
            .iter()
            .map(|t| {
                t.iter()
                    .fold(Aabb::EMPTY, |b, &i| b.with(positions[i as usize]))
            })
            .collect();
        Ok(Mesh {
            normals: data.vertices.iter().map(|v| Vec3::from(v.normal)).collect(),
            uvs: data.vertices.iter().map(|v| Vec2::from(v.uv)).collect(),
            bvh: Bvh::new(&bounds),
            bounds: bounds.iter().fold(Aabb::EMPTY, |a, &b| a.union(b)),
            triangles,
            positions,
        })
    }
}

/// A mesh placed in the room.
#[derive(Clone, Copy, Debug)]
struct Placed {
    to_world: Affine3A,
    to_mesh: Affine3A,
    material: u32,
}

/// Where a ray meets the scene, and what it found there.
#[derive(Clone, Copy, Debug)]
pub struct Hit {
    /// How far along the ray.
    pub distance: f32,
    /// The point.
    pub point: Vec3,
    /// The surface's normal there, facing the ray.
    pub normal: Vec3,
    /// Its material's number.
    pub material: u32,
    /// The paint's coordinates, for a mesh.
    pub uv: Vec2,
    /// The light met, where it is one.
    pub light: Option<u32>,
}

/// Things in the scene that the object hierarchy holds.
#[derive(Clone, Copy, Debug)]
enum Object {
    Sphere(u32),
    Placed(u32),
}

/// Everything a path may meet.
#[derive(Clone, Debug)]
pub struct Scene {
    rectangles: Vec<Rectangle>,
    spheres: Vec<Sphere>,
    mesh: Option<Mesh>,
    placed: Vec<Placed>,
    objects: Vec<Object>,
    bvh: Bvh,
    materials: Vec<Material>,
    lights: Vec<SphereLight>,
    paint: Option<Paint>,
}

impl Default for Scene {
    fn default() -> Scene {
        Scene::new()
    }
}

impl Scene {
    /// Nothing at all.
    pub fn new() -> Scene {
        Scene {
            rectangles: Vec::new(),
            spheres: Vec::new(),
            mesh: None,
            placed: Vec::new(),
            objects: Vec::new(),
            bvh: Bvh::new(&[]),
            materials: Vec::new(),
            lights: Vec::new(),
            paint: None,
        }
    }

    fn material(&mut self, material: Material) -> u32 {
        self.materials.push(material);
        self.materials.len() as u32 - 1
    }

    /// Adds the rectangle `corner + s u + t v`, seen from the side `u x v`
    /// points to.
    pub fn add_rectangle(&mut self, corner: Vec3, u: Vec3, v: Vec3, material: Material) {
        let material = self.material(material);
        self.rectangles.push(Rectangle {
            corner,
            u,
            v,
            material,
        });
    }

    /// Adds a sphere.
    pub fn add_sphere(&mut self, centre: Vec3, radius: f32, material: Material) {
        let material = self.material(material);
        self.spheres.push(Sphere {
            centre,
            radius,
            material,
            light: None,
        });
    }

    /// Adds a glowing sphere, which paths are also sent towards.
    pub fn add_light(&mut self, light: SphereLight) {
        let material = self.material(Material {
            emission: light.radiance,
            ..Material::matte(Vec3::ZERO)
        });
        self.spheres.push(Sphere {
            centre: light.centre,
            radius: light.radius,
            material,
            light: Some(self.lights.len() as u32),
        });
        self.lights.push(light);
    }

    /// Sets the mesh that [`Scene::place_mesh`] places, and its paint.
    pub fn set_mesh(&mut self, mesh: Mesh, paint: &RgbaImage) {
        self.mesh = Some(mesh);
        self.paint = Some(Paint::new(paint));
    }

    /// Places the mesh, turned, scaled and moved by `to_world`.
    pub fn place_mesh(&mut self, to_world: Affine3A, material: Material) {
        let material = self.material(material);
        self.placed.push(Placed {
            to_world,
            to_mesh: to_world.inverse(),
            material,
        });
    }

    /// Builds the hierarchy over what was added; call once all is in.
    pub fn finish(&mut self) {
        self.objects = (0..self.spheres.len() as u32)
            .map(Object::Sphere)
            .chain((0..self.placed.len() as u32).map(Object::Placed))
            .collect();
        let bounds: Vec<Aabb> = self
            .objects
            .iter()
            .map(|o| match *o {
                Object::Sphere(i) => {
                    let s = &self.spheres[i as usize];
                    Aabb::of_sphere(s.centre, s.radius)
                }
                Object::Placed(i) => {
                    let b = self.mesh.as_ref().map_or(Aabb::EMPTY, |m| m.bounds);
                    let to_world = self.placed[i as usize].to_world;
                    (0..8).fold(Aabb::EMPTY, |acc, k| {
                        let corner = Vec3::new(
                            if k & 1 == 0 { b.min.x } else { b.max.x },
                            if k & 2 == 0 { b.min.y } else { b.max.y },
                            if k & 4 == 0 { b.min.z } else { b.max.z },
                        );
                        acc.with(to_world.transform_point3(corner))
                    })
                }
            })
            .collect();
        self.bvh = Bvh::new(&bounds);
    }

    /// The frame `view` shows, its tumblers shaped as `mesh` and painted
    /// with `paint`: the room in its colours (wood below, plaster around),
    /// the balls, the tumblers, the bulb as a sphere light of its radius
    /// and power, and the fireball's light, while it shines, as a sphere
    /// light of the fireball's heart.
    pub fn from_view(
        view: &SceneView,
        mesh: &MeshData,
        paint: &RgbaImage,
    ) -> Result<Scene, SceneError> {
        if view.gpu_balls.is_some() {
            return Err(SceneError::BallsOnGpu);
        }
        let mut scene = Scene::new();
        for (i, surface) in room_surfaces(view.room_size).iter().enumerate() {
            let color = view.room_colors[i];
            let (albedo, finish) = if i == 0 {
                (Albedo::Wood(color), FLOOR_FINISH)
            } else {
                (Albedo::Plaster(color), WALL_FINISH)
            };
            scene.add_rectangle(
                surface.corner,
                surface.u,
                surface.v,
                surface_material(albedo, finish),
            );
        }
        for ball in &view.balls {
            scene.add_sphere(
                ball.position,
                ball.radius,
                surface_material(Albedo::Flat(ball.color), BALL_FINISH),
            );
        }
        scene.set_mesh(Mesh::new(mesh)?, paint);
        for t in &view.tumblers {
            let to_world = Affine3A::from_scale_rotation_translation(
                Vec3::splat(t.scale),
                t.orientation,
                t.position,
            );
            scene.place_mesh(
                to_world,
                surface_material(Albedo::Painted(t.color), TUMBLER_FINISH),
            );
        }
        let light = view.light;
        let bulb = light.point();
        scene.add_light(SphereLight::of_intensity(
            bulb.position,
            light.bulb_radius,
            power_of(&bulb, view.room_size),
        ));
        if let (true, Some(glow)) = (light.fireball_light, view.fireball_light) {
            scene.add_light(fireball_light(&glow, view));
        }
        scene.finish();
        Ok(scene)
    }

    /// The lights.
    pub fn lights(&self) -> &[SphereLight] {
        &self.lights
    }

    /// The material numbered `index`.
    pub fn material_of(&self, index: u32) -> &Material {
        &self.materials[index as usize]
    }

    /// The colour of the surface at `hit`.
    pub fn albedo(&self, hit: &Hit) -> Vec3 {
        match self.materials[hit.material as usize].albedo {
            Albedo::Flat(c) => c,
            Albedo::Wood(c) => wood(c, Vec2::new(hit.point.x, hit.point.z)),
            Albedo::Plaster(c) => plaster(c, hit.point),
            Albedo::Painted(c) => self.paint.as_ref().map_or(c, |p| p.at(hit.uv, c)),
        }
    }

    /// The nearest thing `ray` meets before `t_max`.
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<Hit> {
        let mut best: Option<Hit> = None;
        let mut t_max = t_max;
        for r in &self.rectangles {
            if let Some((t, _, _)) = hit_rectangle(ray, r.corner, r.u, r.v, t_max) {
                t_max = t;
                best = Some(Hit {
                    distance: t,
                    point: ray.origin + ray.dir * t,
                    normal: r.u.cross(r.v).normalize(),
                    material: r.material,
                    uv: Vec2::ZERO,
                    light: None,
                });
            }
        }
        self.bvh.nearest(ray, t_max, |object, t_max| {
            match self.objects[object as usize] {
                Object::Sphere(i) => {
                    let s = &self.spheres[i as usize];
                    let t = hit_sphere(ray, s.centre, s.radius, t_max)?;
                    let point = ray.origin + ray.dir * t;
                    let outward = (point - s.centre) / s.radius;
                    best = Some(Hit {
                        distance: t,
                        point,
                        normal: if outward.dot(ray.dir) > 0.0 {
                            -outward
                        } else {
                            outward
                        },
                        material: s.material,
                        uv: Vec2::ZERO,
                        light: s.light,
                    });
                    Some(t)
                }
                Object::Placed(i) => {
                    let hit = self.hit_placed(&self.placed[i as usize], ray, t_max)?;
                    let t = hit.distance;
                    best = Some(hit);
                    Some(t)
                }
            }
        });
        best
    }

    /// Where `ray` meets a placed mesh: traced in the mesh's own space,
    /// where the transform's uniform scale keeps distances in proportion.
    fn hit_placed(&self, placed: &Placed, ray: &Ray, t_max: f32) -> Option<Hit> {
        let mesh = self.mesh.as_ref()?;
        let origin = placed.to_mesh.transform_point3(ray.origin);
        let along = placed.to_mesh.transform_vector3(ray.dir);
        let scale = along.length();
        let local = Ray {
            origin,
            dir: along / scale,
        };
        let mut found = None;
        mesh.bvh.nearest(&local, t_max * scale, |tri, t_max| {
            let [a, b, c] = mesh.triangles[tri as usize];
            let p = |i: u32| mesh.positions[i as usize];
            let (t, u, v) = hit_triangle(&local, p(a), p(b), p(c), t_max)?;
            found = Some((tri, t, u, v));
            Some(t)
        });
        let (tri, t, u, v) = found?;
        let [a, b, c] = mesh.triangles[tri as usize];
        let w = 1.0 - u - v;
        let n = |i: u32| mesh.normals[i as usize];
        let uv = |i: u32| mesh.uvs[i as usize];
        let normal = placed
            .to_world
            .transform_vector3(n(a) * w + n(b) * u + n(c) * v)
            .normalize();
        let distance = t / scale;
        Some(Hit {
            distance,
            point: ray.origin + ray.dir * distance,
            normal: if normal.dot(ray.dir) > 0.0 {
                -normal
            } else {
                normal
            },
            material: placed.material,
            uv: uv(a) * w + uv(b) * u + uv(c) * v,
            light: None,
        })
    }

    /// Whether nothing lies between `ray`'s origin and `distance` along it.
    pub fn clear(&self, ray: &Ray, distance: f32) -> bool {
        self.intersect(ray, distance).is_none()
    }
}

fn surface_material(albedo: Albedo, finish: Finish) -> Material {
    Material {
        albedo,
        finish,
        emission: Vec3::ZERO,
    }
}

/// The fireball's heart, or a flash's point where the fireball is gone,
/// as a sphere light with the power of the real-time fireball light.
fn fireball_light(glow: &PointLight, view: &SceneView) -> SphereLight {
    /// A flash's light, once the fireball is gone, comes from a small
    /// sphere where it hit.
    const FLASH_RADIUS: f32 = 0.05;
    let radius = view
        .fireball
        .as_ref()
        .map_or(FLASH_RADIUS, |f| f.heart_radius);
    SphereLight::of_intensity(glow.position, radius, power_of(glow, view.room_size))
}
