//! Where the balls start: the placed ones where their scene puts them,
//! the others at random free spots drawn from the world's random sequence.

use crate::balls::Tint;
use crate::config::WorldConfig;
use crate::room::Room;
use crate::tumbler::{Tumbler, TumblerShape};
use glam::DVec3;

use super::{BuildError, World};

/// Two surfaces this close (metres) touch rather than overlap: a row of
/// balls written in a scene file at twice their radius apart touches.
const PLACEMENT_TOLERANCE: f64 = 1e-9;

/// What is wrong with where placed ball `k` starts, if anything: out of
/// the room, or in an earlier placed ball or a tumbler. Touching is fine.
pub fn placement_problem(
    config: &WorldConfig,
    room: &Room,
    shape: &TumblerShape,
    k: usize,
) -> Option<String> {
    let balls = &config.balls;
    let p = balls.placements[k].position;
    let r = balls.placed_radius(k);
    if !p.is_finite() {
        return Some(format!("has no finite position: {p}"));
    }
    if !room.contains_sphere(p, r, PLACEMENT_TOLERANCE) {
        let (lo, hi) = (room.min + DVec3::splat(r), room.max - DVec3::splat(r));
        return Some(format!(
            "at {p} does not lie inside the room: with radius {r} its centre must lie within {lo} ..= {hi}"
        ));
    }
    for j in 0..k {
        let (q, rj) = (balls.placements[j].position, balls.placed_radius(j));
        let overlap = r + rj - p.distance(q);
        if overlap > PLACEMENT_TOLERANCE {
            return Some(format!(
                "at {p} overlaps ball {j} (balls.placement[{j}]) at {q} by {overlap:.4} m"
            ));
        }
    }
    for (t, placement) in config.tumblers.placements.iter().enumerate() {
        let tumbler = Tumbler::new(shape, placement, room.min.y);
        for (s, sphere) in shape.spheres.iter().enumerate() {
            let centre = tumbler.sphere_center(shape, s);
            let overlap = r + sphere.radius - p.distance(centre);
            if overlap > PLACEMENT_TOLERANCE {
                return Some(format!(
                    "at {p} overlaps tumbler {t} (tumblers.placement[{t}]) by {overlap:.4} m"
                ));
            }
        }
    }
    None
}

impl World {
    /// Places every ball: the placed ones where the scene puts them, the
    /// others at random free spots with random velocities.
    ///
    /// Random spots come from a jittered lattice whose spacing leaves each
    /// ball room to move: shuffled lattice sites give random, non-overlapping
    /// positions in time linear in the ball count.
    pub(super) fn spawn_balls(&mut self) -> Result<(), BuildError> {
        self.pour = super::pour::Pour::default();
        let placed = self.config.balls.placements.len();
        for (k, p) in self.config.balls.placements.iter().enumerate() {
            self.balls.set(k, p.position, p.velocity);
            self.balls.spin[k] = p.spin;
            self.balls.radius[k] = self.config.balls.placed_radius(k);
            self.balls
                .set_mass(k, p.mass.unwrap_or(self.config.balls.mass));
            self.balls.alive[k] = true;
            self.balls.tint[k] = if p.color.is_some() {
                Tint::Placed(k)
            } else {
                Tint::White
            };
        }
        let n = self.balls.len() - placed;
        if n == 0 {
            return Ok(());
        }
        if self.pours() {
            self.check_spout()?;
            self.park_for_pouring(placed);
            return Ok(());
        }
        let r = self.config.balls.radius;
        let fill = self.config.balls.start_fill;
        if !(fill > 0.0 && fill <= 1.0) {
            return Err(BuildError(format!(
                "balls.start_fill = {fill} is out of range: allowed > 0 and <= 1"
            )));
        }
        let lo = self.room.min + DVec3::splat(r);
        let mut top = self.room.max;
        top.y = self.room.min.y + fill * (self.room.max.y - self.room.min.y);
        let hi = top - DVec3::splat(r);
        let span = hi - lo;
        let within = if fill < 1.0 {
            format!("the lowest {fill} of the room's height (balls.start_fill)")
        } else {
            "the room".to_string()
        };
        if span.min_element() < 0.0 {
            return Err(BuildError(format!(
                "balls of radius {r} do not fit in {within}"
            )));
        }
        // Aim for about four sites per ball, never closer than 2.1 radii.
        let volume = span.x.max(0.0) * span.y.max(0.0) * span.z.max(0.0);
        let spacing = (volume / (4.0 * n as f64)).cbrt().max(2.1 * r);
        let dims = [
            (span.x / spacing).floor() as usize + 1,
            (span.y / spacing).floor() as usize + 1,
            (span.z / spacing).floor() as usize + 1,
        ];
        let jitter = 0.5 * (spacing - 2.05 * r).max(0.0);
        let clearance = self.shape.bound_radius + r + 0.5 * spacing;
        let mut sites = Vec::with_capacity(dims[0] * dims[1] * dims[2]);
        for z in 0..dims[2] {
            for y in 0..dims[1] {
                for x in 0..dims[0] {
                    let p = lo + DVec3::new(x as f64, y as f64, z as f64) * spacing;
                    let clear = self.tumblers.iter().all(|t| {
                        let c = t.center
                            + t.orientation * DVec3::new(0.0, self.shape.bound_height, 0.0);
                        p.distance(c) > clearance
                    }) && self.config.balls.placements.iter().enumerate().all(
                        |(k, q)| {
                            let apart =
                                r + self.config.balls.placed_radius(k) + jitter * 3f64.sqrt();
                            p.distance(q.position) > apart + PLACEMENT_TOLERANCE
                        },
                    );
                    if clear && p.cmple(hi + DVec3::splat(1e-9)).all() {
                        sites.push(p);
                    }
                }
            }
        }
        if sites.len() < n {
            return Err(BuildError(format!(
                "{n} balls of radius {r} do not fit in {within} beside the tumblers (room for {})",
                sites.len()
            )));
        }
        let (min_speed, max_speed) = (self.config.balls.speed_min, self.config.balls.speed_max);
        for i in 0..n {
            let ball = placed + i;
            // Partial Fisher-Yates: site i is a uniform pick among the rest.
            let k = i + (self.rng.next_u64() % (sites.len() - i) as u64) as usize;
            sites.swap(i, k);
            let offset = DVec3::new(
                self.rng.range(-jitter, jitter),
                self.rng.range(-jitter, jitter),
                self.rng.range(-jitter, jitter),
            );
            let p = (sites[i] + offset).clamp(lo, hi);
            let v = self.rng.direction() * self.rng.range(min_speed, max_speed);
            self.balls.set(ball, p, v);
            self.balls.alive[ball] = true;
            self.balls.tint[ball] = Tint::White;
        }
        Ok(())
    }
}
