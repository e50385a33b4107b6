//! The checks a ball's new state passes before the world takes it: inside
//! the room, in no tumbler and no other ball (touching is fine), finite,
//! no faster than a scene may start anything. Only the balls whose values
//! change are judged, so that a pile read back and written back whole is
//! taken as it is, with the slight overlaps the solver leaves in it.

use std::collections::HashMap;

use glam::DVec3;
use rolypoly_core::scene::keys::MAX_SPEED;
use rolypoly_physics::World;

/// Two surfaces this close (metres) touch rather than overlap, as for the
/// balls a scene file places.
const TOUCH: f64 = 1e-9;

/// Up to this many moved balls are each checked against every ball;
/// more, against their neighbours on a grid.
const CHECK_EACH: usize = 32;

/// Why ball `i` may not be put at `p` (radius `r`) in `world`: out of the
/// room or in a tumbler. Balls are checked apart ([`check_positions`]).
pub fn place_problem(world: &World, what: &str, p: DVec3, r: f64) -> Option<String> {
    if !p.is_finite() {
        return Some(format!("{what}: position {p} is not finite"));
    }
    let room = world.room();
    if !room.contains_sphere(p, r, TOUCH) {
        let (lo, hi) = (room.min + DVec3::splat(r), room.max - DVec3::splat(r));
        return Some(format!(
            "{what} at {p} does not lie inside the room: with radius {r} its centre must lie \
             within {lo} ..= {hi}"
        ));
    }
    let shape = world.tumbler_shape();
    for (t, tumbler) in world.tumblers().iter().enumerate() {
        for (s, sphere) in shape.spheres.iter().enumerate() {
            let overlap = r + sphere.radius - p.distance(tumbler.sphere_center(shape, s));
            if overlap > TOUCH {
                return Some(format!(
                    "{what} at {p} overlaps tumbler {t} by {overlap:.4} m"
                ));
            }
        }
    }
    None
}

/// The balls whose value in `new` differs from `old`.
pub fn changed(old: &[DVec3], new: &[DVec3]) -> Vec<usize> {
    // Compared bit for bit, so that a NaN written is a change (and refused).
    let same =
        |a: DVec3, b: DVec3| a.to_array().map(f64::to_bits) == b.to_array().map(f64::to_bits);
    (0..old.len()).filter(|&i| !same(old[i], new[i])).collect()
}

/// Whether the balls in `moved` may be put at `new`: each in play, in the
/// room, in no tumbler and in no other ball in play.
pub fn check_positions(world: &World, new: &[DVec3], moved: &[usize]) -> Result<(), String> {
    let balls = world.balls();
    let (radius, alive) = (balls.radii(), balls.alive());
    for &i in moved {
        if !alive[i] {
            return Err(out_of_play(i));
        }
        if let Some(problem) = place_problem(world, &format!("ball {i}"), new[i], radius[i]) {
            return Err(problem);
        }
    }
    let overlap = |i: usize, j: usize| {
        let gap = new[i].distance(new[j]);
        let overlap = radius[i] + radius[j] - gap;
        (i != j && alive[j] && overlap > TOUCH).then(|| {
            format!(
                "ball {i} at {} overlaps ball {j} at {} by {overlap:.4} m",
                new[i], new[j]
            )
        })
    };
    if moved.len() <= CHECK_EACH {
        for &i in moved {
            if let Some(problem) = (0..new.len()).find_map(|j| overlap(i, j)) {
                return Err(problem);
            }
        }
        return Ok(());
    }
    // Cells as wide as the largest ball: a ball's neighbours lie in the
    // 27 cells around its own.
    let largest = (0..new.len())
        .filter(|&j| alive[j])
        .map(|j| radius[j])
        .fold(0.0, f64::max);
    let cell = (2.0 * largest).max(1e-6);
    let key = |p: DVec3| (p / cell).floor().as_i64vec3().to_array();
    let mut grid: HashMap<[i64; 3], Vec<u32>> = HashMap::new();
    for j in (0..new.len()).filter(|&j| alive[j]) {
        grid.entry(key(new[j])).or_default().push(j as u32);
    }
    for &i in moved {
        let [x, y, z] = key(new[i]);
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    let Some(near) = grid.get(&[x + dx, y + dy, z + dz]) else {
                        continue;
                    };
                    if let Some(problem) = near.iter().find_map(|&j| overlap(i, j as usize)) {
                        return Err(problem);
                    }
                }
            }
        }
    }
    Ok(())
}

/// Whether the balls in `moved` may be given the velocities `new`.
pub fn check_velocities(world: &World, new: &[DVec3], moved: &[usize]) -> Result<(), String> {
    let alive = world.balls().alive();
    for &i in moved {
        if !alive[i] {
            return Err(out_of_play(i));
        }
        if let Some(problem) = speed_problem(&format!("ball {i}"), new[i]) {
            return Err(problem);
        }
    }
    Ok(())
}

/// Why `v` is no velocity to give `what`, if it is not.
pub fn speed_problem(what: &str, v: DVec3) -> Option<String> {
    if !v.is_finite() {
        return Some(format!("{what}: velocity {v} is not finite"));
    }
    let speed = v.length();
    (speed > MAX_SPEED).then(|| {
        format!("{what}: speed {speed} m/s is out of range: allowed 0 ..= {MAX_SPEED} m/s")
    })
}

fn out_of_play(i: usize) -> String {
    format!("ball {i} is out of play (the fireball caught it): its state cannot change")
}
