//! The light the room's surfaces bounce, gathered ahead of the frame at a
//! grid of points (an irradiance volume of ambient cubes, the way Valve's
//! Source engine lit its models): at each point, the light arriving on a
//! small patch facing each of the six axis directions. A fragment blends
//! the three directions its normal leans towards, by the squares of the
//! normal's components, between the eight nearest points (`indirect_light`
//! in scene.wgsl): three filtered texture reads instead of six form factors
//! a pixel.
//!
//! What each surface sends back changes with the lights every frame; how
//! much of each surface a patch sees does not while the room keeps its
//! size. The form factors are worked out once per room, and each frame only
//! weighs them by the surfaces' light.

use crate::room;
use glam::{UVec3, Vec3};

/// Probes per axis at most. The volume's texture holds this many per axis
/// and direction whatever the room, so that it is made once.
pub const MAX_PROBES: u32 = 16;

/// About how far apart neighbouring probes stand, in metres.
const PROBE_SPACING: f32 = 0.5;

/// The directions each probe gathers from, in the texture's order: slab
/// `k` of the texture holds direction `k`.
pub const DIRECTIONS: [Vec3; 6] = [
    Vec3::X,
    Vec3::NEG_X,
    Vec3::Y,
    Vec3::NEG_Y,
    Vec3::Z,
    Vec3::NEG_Z,
];

/// The probes of one room and what each sees of the room's surfaces.
pub struct IrradianceVolume {
    room_size: Vec3,
    counts: UVec3,
    /// Per direction, per probe (x fastest, then y, then z): each surface's
    /// form factor.
    form_factors: Vec<[f32; 6]>,
}

impl IrradianceVolume {
    /// Probes about `PROBE_SPACING` apart, each at the centre of its cell
    /// of the room, so that none lies on a surface (where half of what it
    /// would gather faces the wall it lies on).
    pub fn new(room_size: Vec3) -> IrradianceVolume {
        let counts = (room_size / PROBE_SPACING)
            .round()
            .as_uvec3()
            .clamp(UVec3::splat(2), UVec3::splat(MAX_PROBES));
        let surfaces = room::surfaces(room_size);
        let mut volume = IrradianceVolume {
            room_size,
            counts,
            form_factors: Vec::with_capacity(DIRECTIONS.len() * counts.element_product() as usize),
        };
        for direction in DIRECTIONS {
            for z in 0..counts.z {
                for y in 0..counts.y {
                    for x in 0..counts.x {
                        let p = volume.probe(UVec3::new(x, y, z));
                        let seen = surfaces.map(|s| form_factor(p, direction, &s.corners()));
                        volume.form_factors.push(seen);
                    }
                }
            }
        }
        volume
    }

    pub fn room_size(&self) -> Vec3 {
        self.room_size
    }

    /// Probes along x, y and z.
    pub fn counts(&self) -> UVec3 {
        self.counts
    }

    /// Where the probe of `cell` stands.
    pub fn probe(&self, cell: UVec3) -> Vec3 {
        let corner = Vec3::new(-0.5 * self.room_size.x, 0.0, -0.5 * self.room_size.z);
        corner + (cell.as_vec3() + 0.5) / self.counts.as_vec3() * self.room_size
    }

    /// The light arriving at each probe from each direction when the
    /// surfaces send back `surface_light` (see `lighting::bounce`), in the
    /// order of the form factors: one slab of probes per direction.
    pub fn gather<'a>(&'a self, surface_light: &'a [Vec3; 6]) -> impl Iterator<Item = Vec3> + 'a {
        self.form_factors.iter().map(move |seen| {
            seen.iter()
                .zip(surface_light)
                .map(|(f, light)| *light * *f)
                .sum()
        })
    }
}

/// The form factor from a small patch at `p` facing `n` to the convex
/// polygon `corners`: the share of the patch's cosine-weighted hemisphere
/// the polygon covers. The polygon is first cut to what lies in front of
/// the patch; then Lambert's closed form sums, over its edges, the angle
/// each edge subtends, weighed by how the plane through the patch and the
/// edge faces the normal.
pub fn form_factor(p: Vec3, n: Vec3, corners: &[Vec3]) -> f32 {
    // Sutherland and Hodgman's clipping against the patch's plane: a convex
    // polygon of k corners keeps at most k + 1.
    let mut front = [Vec3::ZERO; 8];
    let mut kept = 0;
    let mut keep = |v: Vec3| {
        front[kept] = v;
        kept += 1;
    };
    for (i, &corner) in corners.iter().enumerate() {
        let a = corner - p;
        let b = corners[(i + 1) % corners.len()] - p;
        let (da, db) = (n.dot(a), n.dot(b));
        if da >= 0.0 {
            keep(a);
        }
        if (da >= 0.0) != (db >= 0.0) {
            keep(a + (b - a) * (da / (da - db)));
        }
    }
    let mut sum = 0.0;
    for i in 0..kept {
        let a = front[i].normalize_or_zero();
        let b = front[(i + 1) % kept].normalize_or_zero();
        let c = a.cross(b);
        let s = c.length();
        if s > 1e-7 {
            sum += s.atan2(a.dot(b)) * n.dot(c) / s;
        }
    }
    // Whole in front of the patch, the polygon's edges all turn one way
    // round: which way is only a matter of the order of its corners.
    sum.abs() / std::f32::consts::TAU
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small, fixed pseudo-random sequence in 0..1.
    fn uniforms(seed: u64) -> impl FnMut() -> f32 {
        let mut state = seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1;
        move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 40) as f32 / (1u64 << 24) as f32
        }
    }

    #[test]
    fn a_patch_inside_a_closed_room_sees_the_whole_room_once() {
        // Whatever way a patch faces, its hemisphere is covered by the
        // room's surfaces exactly once: the form factors sum to one.
        for (seed, size) in [
            (1, Vec3::new(8.0, 4.0, 8.0)),
            (2, Vec3::new(24.0, 5.0, 24.0)),
            (3, Vec3::new(2.0, 6.0, 3.0)),
        ] {
            let mut next = uniforms(seed);
            let surfaces = room::surfaces(size);
            for _ in 0..200 {
                let p = Vec3::new(next() - 0.5, next(), next() - 0.5) * size * 0.98
                    + Vec3::new(0.0, 0.01 * size.y, 0.0);
                let n = (Vec3::new(next(), next(), next()) * 2.0 - 1.0).normalize_or(Vec3::Y);
                let total: f32 = surfaces
                    .iter()
                    .map(|s| form_factor(p, n, &s.corners()))
                    .sum();
                assert!((total - 1.0).abs() < 1e-4, "{size} {p} {n}: {total}");
            }
        }
    }

    #[test]
    fn a_square_overhead_matches_the_closed_form() {
        // A patch under the centre of a square of side 2a at height h, each
        // quarter the textbook rectangle with a corner over the patch:
        // F = (1 / 2 pi) (2 A / sqrt(1 + A^2) atan(A / sqrt(1 + A^2))),
        // A = a / h.
        for (a, h) in [(1.0f32, 1.0f32), (0.5, 2.0), (3.0, 0.7)] {
            let corners = [
                Vec3::new(-a, h, -a),
                Vec3::new(a, h, -a),
                Vec3::new(a, h, a),
                Vec3::new(-a, h, a),
            ];
            let big_a = a / h;
            let root = (1.0 + big_a * big_a).sqrt();
            let quarter = (2.0 * big_a / root * (big_a / root).atan()) / std::f32::consts::TAU;
            let got = form_factor(Vec3::ZERO, Vec3::Y, &corners);
            assert!((got - 4.0 * quarter).abs() < 1e-5, "a {a} h {h}: {got}");
            // Facing away, the patch sees none of it; edge on, half of it
            // lies in front, and seen that glancingly it counts for little.
            assert_eq!(form_factor(Vec3::ZERO, Vec3::NEG_Y, &corners), 0.0);
            let edge_on = form_factor(Vec3::ZERO, Vec3::X, &corners);
            assert!(edge_on > 0.0 && edge_on < got, "{edge_on} {got}");
        }
    }

    #[test]
    fn each_probe_gathers_what_its_form_factors_say() {
        let size = Vec3::new(8.0, 4.0, 6.0);
        let volume = IrradianceVolume::new(size);
        let counts = volume.counts();
        assert_eq!(counts, UVec3::new(16, 8, 12));
        // Light from the left wall alone, in red.
        let mut light = [Vec3::ZERO; 6];
        light[2] = Vec3::new(1.0, 0.0, 0.0);
        let gathered: Vec<Vec3> = volume.gather(&light).collect();
        let per_slab = counts.element_product() as usize;
        assert_eq!(gathered.len(), 6 * per_slab);
        let at = |direction: usize, cell: UVec3| {
            gathered
                [direction * per_slab + (cell.x + counts.x * (cell.y + counts.y * cell.z)) as usize]
        };
        let surfaces = room::surfaces(size);
        for cell in [
            UVec3::new(0, 0, 0),
            UVec3::new(7, 3, 5),
            UVec3::new(15, 7, 11),
        ] {
            let p = volume.probe(cell);
            assert!(p.abs().cmplt(Vec3::new(4.0, 4.0, 3.0)).all() && p.y > 0.0);
            for (k, direction) in DIRECTIONS.iter().enumerate() {
                let expected = form_factor(p, *direction, &surfaces[2].corners());
                assert!((at(k, cell).x - expected).abs() < 1e-6);
                assert_eq!(at(k, cell).y, 0.0);
            }
            // Facing the left wall (-x), a patch sees more of it than
            // facing away, where it sees none.
            assert!(at(1, cell).x > 0.0 && at(0, cell).x == 0.0);
        }
        // Nearer the wall, more of it.
        assert!(at(1, UVec3::new(0, 3, 5)).x > at(1, UVec3::new(8, 3, 5)).x);
    }
}
