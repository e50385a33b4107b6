//! The tumbler's mesh: made from the physics' six spheres, written as a
//! Wavefront OBJ, and read back from one (R5).
//!
//! The surface is the outline of the union of the spheres turned about the
//! axis, so what is drawn is exactly what collides. `u` runs around the axis
//! (0.25 faces +z, the tumbler's front), `v` from the bottom (1) to the top (0).

use crate::gpu::RenderError;
use crate::mesh::{MeshData, Vertex};
use glam::Vec3;
use rolypoly_physics::SphereSpec;
use std::fmt::Write as _;

/// Rings along the axis and segments around it.
const RINGS: u32 = 96;
const SEGMENTS: u32 = 64;
/// The coarse mesh's (see [`coarse_tumbler_mesh`]): a ninth of the
/// triangles.
const COARSE_RINGS: u32 = 32;
const COARSE_SEGMENTS: u32 = 24;

/// The widest sphere at height `y`: its index and radius of the cut there.
fn outline(spheres: &[SphereSpec], y: f64) -> (usize, f64) {
    spheres
        .iter()
        .enumerate()
        .map(|(i, s)| {
            (
                i,
                (s.radius * s.radius - (y - s.height).powi(2))
                    .max(0.0)
                    .sqrt(),
            )
        })
        .fold((0, -1.0), |best, c| if c.1 > best.1 { c } else { best })
}

/// Builds the surface of revolution of the spheres' union.
pub fn tumbler_mesh(spheres: &[SphereSpec]) -> MeshData {
    revolved(spheres, RINGS, SEGMENTS)
}

/// The same surface in far fewer triangles, for frames lit so small that a
/// ring of the full mesh spans less than a pixel (the low quality level):
/// its outline stays within a quarter of a pixel of the full mesh's there,
/// and a software renderer draws five tumblers and their shadows in a
/// fraction of the time.
pub fn coarse_tumbler_mesh(spheres: &[SphereSpec]) -> MeshData {
    revolved(spheres, COARSE_RINGS, COARSE_SEGMENTS)
}

/// The surface of revolution of the spheres' union, in `rings` along the
/// axis and `segments` around it.
fn revolved(spheres: &[SphereSpec], rings: u32, segments: u32) -> MeshData {
    let (lo, hi) = rolypoly_physics::axis_extent(spheres);
    let mut mesh = MeshData::default();
    for r in 0..=rings {
        // Top (v = 0) to bottom (v = 1); rings cluster near the poles.
        let v = r as f64 / rings as f64;
        let y = hi - (hi - lo) * (0.5 - 0.5 * (std::f64::consts::PI * v).cos());
        let (owner, radius) = outline(spheres, y);
        let centre = Vec3::new(0.0, spheres[owner].height as f32, 0.0);
        for s in 0..=segments {
            let u = s as f32 / segments as f32;
            let phi = u * std::f32::consts::TAU;
            let p = Vec3::new(
                radius as f32 * phi.cos(),
                y as f32,
                radius as f32 * phi.sin(),
            );
            // On the union's outline the normal is that of the sphere that owns it.
            let n =
                (p - centre).normalize_or(Vec3::new(0.0, if v < 0.5 { 1.0 } else { -1.0 }, 0.0));
            mesh.vertices.push(Vertex {
                position: p.to_array(),
                normal: n.to_array(),
                uv: [u, v as f32],
            });
        }
    }
    mesh.grid_indices(rings, segments);
    mesh
}

/// Writes a mesh as Wavefront OBJ text (positions, UVs, normals, faces).
pub fn to_obj(mesh: &MeshData, comment: &str) -> String {
    let mut out = String::new();
    for line in comment.lines() {
        let _ = writeln!(out, "# {line}");
    }
    let _ = writeln!(out, "o tumbler");
    for v in &mesh.vertices {
        let [x, y, z] = v.position;
        let _ = writeln!(out, "v {x:.6} {y:.6} {z:.6}");
    }
    for v in &mesh.vertices {
        let [u, t] = v.uv;
        // OBJ's v runs upwards.
        let _ = writeln!(out, "vt {u:.6} {:.6}", 1.0 - t);
    }
    for v in &mesh.vertices {
        let [x, y, z] = v.normal;
        let _ = writeln!(out, "vn {x:.6} {y:.6} {z:.6}");
    }
    for t in mesh.indices.chunks(3) {
        let [a, b, c] = [t[0] + 1, t[1] + 1, t[2] + 1];
        let _ = writeln!(out, "f {a}/{a}/{a} {b}/{b}/{b} {c}/{c}/{c}");
    }
    out
}

/// Reads an OBJ (all its objects as one mesh). `origin` names the source in
/// errors. Every vertex needs a normal and a texture coordinate.
pub fn from_obj(text: &str, origin: &str) -> Result<MeshData, RenderError> {
    let error = |message: String| RenderError::Mesh {
        origin: origin.to_owned(),
        message,
    };
    check_face_indices(text).map_err(error)?;
    let (models, _) = tobj::load_obj_buf(&mut text.as_bytes(), &tobj::GPU_LOAD_OPTIONS, |_| {
        Err(tobj::LoadError::OpenFileFailed)
    })
    .map_err(|e| error(format!("not a valid OBJ file: {e}")))?;
    let mut mesh = MeshData::default();
    for model in &models {
        let m = &model.mesh;
        let n = m.positions.len() / 3;
        if n == 0 {
            continue;
        }
        if m.normals.len() != 3 * n || m.texcoords.len() != 2 * n {
            return Err(error(format!(
                "object `{}` lacks normals or texture coordinates",
                shown(&model.name)
            )));
        }
        let base = mesh.vertices.len() as u32;
        for i in 0..n {
            let position = [
                m.positions[3 * i],
                m.positions[3 * i + 1],
                m.positions[3 * i + 2],
            ];
            let normal = [m.normals[3 * i], m.normals[3 * i + 1], m.normals[3 * i + 2]];
            let uv = [m.texcoords[2 * i], 1.0 - m.texcoords[2 * i + 1]];
            if position
                .iter()
                .chain(&normal)
                .chain(&uv)
                .any(|x| !x.is_finite())
            {
                return Err(error(format!(
                    "object `{}` has a non-finite number",
                    shown(&model.name)
                )));
            }
            // Shading divides by the normal's length: none would light the
            // surface with NaN.
            if normal.iter().map(|x| x * x).sum::<f32>() < 1e-12 {
                return Err(error(format!(
                    "object `{}` has a normal of zero length (vn 0 0 0)",
                    shown(&model.name)
                )));
            }
            mesh.vertices.push(Vertex {
                position,
                normal,
                uv,
            });
        }
        mesh.indices.extend(m.indices.iter().map(|i| base + i));
    }
    if mesh.indices.is_empty() {
        return Err(error("it holds no triangles".to_owned()));
    }
    Ok(mesh)
}

/// A name from the file for a message: its control characters (a `\r`
/// before the line's end, ESC) escaped, so the message stays one line.
fn shown(name: &str) -> String {
    name.chars()
        .map(|c| {
            if c.is_control() {
                c.escape_default().to_string()
            } else {
                c.to_string()
            }
        })
        .collect()
}

/// Checks that every face's indices name a position, texture coordinate
/// and normal of the file. tobj turns a relative (negative) index that
/// reaches back past the first into a huge number, and a huge index
/// overflows its arithmetic before its bounds check: a panic in debug
/// builds, a wrong normal or texture coordinate in release builds.
fn check_face_indices(text: &str) -> Result<(), String> {
    const KINDS: [(&str, &str); 3] = [
        ("v", "position"),
        ("vt", "texture coordinate"),
        ("vn", "normal"),
    ];
    let kind = |line: &str| {
        let first = line.split_whitespace().next();
        KINDS.iter().position(|(key, _)| Some(*key) == first)
    };
    let mut totals = [0usize; 3];
    for k in text.lines().filter_map(kind) {
        totals[k] += 1;
    }
    // Relative indices count back from the line they are on.
    let mut before = [0usize; 3];
    for (n, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        if words.next() != Some("f") {
            if let Some(k) = kind(line) {
                before[k] += 1;
            }
            continue;
        }
        for word in words {
            for (k, part) in word.split('/').take(3).enumerate() {
                // Not a number (nor empty): tobj refuses it itself.
                let Ok(index) = part.parse::<isize>() else {
                    continue;
                };
                let names = if index < 0 {
                    index.unsigned_abs() <= before[k]
                } else {
                    index >= 1 && index.unsigned_abs() <= totals[k]
                };
                if !names {
                    return Err(format!(
                        "not a valid OBJ file: line {}: face corner `{}` names no {} {index}",
                        n + 1,
                        shown(word),
                        KINDS[k].1
                    ));
                }
            }
        }
    }
    Ok(())
}

/// The shipped mesh of the default tumbler (made by `rolypoly make-tumbler-obj`).
pub const DEFAULT_TUMBLER_OBJ: &str = include_str!("../../../assets/tumbler.obj");

/// The mesh for tumblers made of `spheres`: the shipped OBJ when they are
/// the default spheres, else one made from the spheres now.
pub fn mesh_for(
    spheres: &[SphereSpec],
    default_spheres: &[SphereSpec],
) -> Result<MeshData, RenderError> {
    if spheres == default_spheres {
        from_obj(DEFAULT_TUMBLER_OBJ, "assets/tumbler.obj (built in)")
    } else {
        Ok(tumbler_mesh(spheres))
    }
}

/// The comment at the top of the shipped OBJ.
pub const OBJ_HEADER: &str = "The rolypoly tumbler: the outline of its six collision spheres turned about\n\
the axis. Made by `rolypoly make-tumbler-obj`; body frame: origin at the\n\
bottom sphere's centre, +y along the axis, front towards +z.";

#[cfg(test)]
mod tests {
    use super::*;
    use rolypoly_physics::WorldConfig;

    #[test]
    fn mesh_surface_lies_on_the_collision_spheres() {
        let spheres = WorldConfig::default().tumblers.spheres;
        let (full, coarse) = (tumbler_mesh(&spheres), coarse_tumbler_mesh(&spheres));
        // The coarse level is the same surface in a ninth of the triangles.
        assert!(coarse.indices.len() * 8 <= full.indices.len());
        for v in full.vertices.iter().chain(&coarse.vertices) {
            let p = Vec3::from_array(v.position).as_dvec3();
            // Inside or on every sphere's union, and on at least one surface.
            let nearest = spheres
                .iter()
                .map(|s| (p - glam::DVec3::new(0.0, s.height, 0.0)).length() - s.radius)
                .fold(f64::INFINITY, f64::min);
            assert!(
                nearest.abs() < 1e-4,
                "vertex {p} is {nearest} m off the spheres"
            );
        }
    }

    #[test]
    fn obj_round_trip_keeps_the_mesh() {
        let mesh = tumbler_mesh(&WorldConfig::default().tumblers.spheres);
        let back = from_obj(&to_obj(&mesh, "test"), "test").expect("valid");
        assert_eq!(back.indices.len(), mesh.indices.len());
        // The loader may order vertices its own way: compare triangle corners.
        for (a, b) in back.indices.iter().zip(&mesh.indices).step_by(97) {
            let (va, vb) = (back.vertices[*a as usize], mesh.vertices[*b as usize]);
            for k in 0..3 {
                assert!((va.position[k] - vb.position[k]).abs() < 1e-5);
                assert!((va.normal[k] - vb.normal[k]).abs() < 1e-5);
            }
            assert!((va.uv[1] - vb.uv[1]).abs() < 1e-5);
        }
    }

    #[test]
    fn shipped_obj_is_the_one_the_generator_makes() {
        let spheres = WorldConfig::default().tumblers.spheres;
        let fresh = to_obj(&tumbler_mesh(&spheres), OBJ_HEADER);
        assert!(
            fresh == DEFAULT_TUMBLER_OBJ,
            "assets/tumbler.obj is stale: run `cargo run --release -- make-tumbler-obj --out assets/tumbler.obj`"
        );
    }

    #[test]
    fn broken_obj_files_are_clear_errors() {
        for (text, expect) in [
            ("", "no triangles"),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "lacks normals"),
            ("v 0 0 0\nf 1 2 9\n", "not a valid OBJ"),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvt 0 0\nf 1/1/1 2/1/1 3/1/1\n\
                 vn 0 0 0\nf 1/1/2 2/1/2 3/1/2\n",
                "normal of zero length",
            ),
            (
                "v nan 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvt 0 0\nf 1/1/1 2/1/1 3/1/1\n",
                "non-finite number",
            ),
        ] {
            let err = from_obj(text, "bad.obj")
                .expect_err("must fail")
                .to_string();
            assert!(err.contains("bad.obj") && err.contains(expect), "{err}");
        }
    }
}
