//! Each body as a bank of damped modes (J1): a ball as a solid elastic
//! sphere, the floor and walls as plates, a tumbler as a hollow shell with a
//! bell inside. Frequencies follow from the body's size and its material's
//! wave speeds; each mode decays as exp(-π f η t), never slower than
//! [`SLOWEST_DECAY`].

use std::f64::consts::PI;

use crate::material::Properties;

/// The slowest a mode may decay (1/s): a body in the room also loses its
/// vibration to what holds it and to the air, so even steel falls 60 dB
/// within 0.8 s.
pub const SLOWEST_DECAY: f64 = 8.7;

/// One mode: a damped oscillation excited by impulses.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mode {
    /// Its frequency (Hz).
    pub frequency: f64,
    /// Its decay rate (1/s): the amplitude falls as exp(-decay t).
    pub decay: f64,
    /// How much of a unit impulse's velocity it takes, in the body's mass
    /// units (its share of the motion at a typical point of impact).
    pub weight: f64,
}

impl Mode {
    fn of(frequency: f64, weight: f64, material: &Properties) -> Mode {
        Mode {
            frequency,
            decay: (PI * frequency * material.loss).max(SLOWEST_DECAY),
            weight,
        }
    }
}

/// A free solid sphere's lowest spheroidal modes (Lamb 1882), as ω r / c_s
/// for a Poisson's ratio near 0.3, with the share of an impact each takes:
/// the quadrupole (n = 2) lowest and strongest, then n = 3, the breathing
/// mode (n = 0) and n = 4.
const SPHERE_MODES: [(f64, f64); 4] = [(2.64, 1.0), (3.87, 0.5), (4.44, 0.3), (4.86, 0.25)];

/// A solid sphere of `radius` (m): frequencies ω = k c_s / r, so they scale
/// as 1/r.
pub fn sphere(radius: f64, material: &Properties) -> Vec<Mode> {
    let c = material.shear_speed();
    SPHERE_MODES
        .iter()
        .map(|&(k, weight)| Mode::of(k * c / (2.0 * PI * radius), weight, material))
        .collect()
}

/// A square panel of side `side` and thickness `thickness` (m), simply
/// supported: ω_mn = π² ((m² + n²) / side²) √(D / ρh). The floor is its
/// boards and a wall its boards between studs: a room's whole floor rings
/// far below hearing, a board in the kilohertz range.
pub fn plate(side: f64, thickness: f64, material: &Properties) -> Vec<Mode> {
    let bend = material.bending(thickness);
    let mut modes = Vec::with_capacity(PLATE_ORDERS.len());
    for &(m, n) in &PLATE_ORDERS {
        let omega = PI * PI * (m * m + n * n) as f64 / (side * side) * bend;
        // A struck point away from the nodal lines: the higher orders'
        // shares fall off with their frequency.
        let weight = 1.0 / (m * n) as f64;
        modes.push(Mode::of(omega / (2.0 * PI), weight, material));
    }
    modes
}

/// The plate's mode orders (m, n) that sound.
const PLATE_ORDERS: [(u32, u32); 6] = [(1, 1), (1, 2), (2, 2), (1, 3), (2, 3), (3, 3)];

/// A thin hollow sphere of `radius` (m): its lower, bending-dominated modes
/// crowd below the ring frequency c_p / (2π r), approaching it as the order
/// grows (Love 1888); given as fractions of it for n = 2 to 5.
pub fn shell(radius: f64, material: &Properties) -> Vec<Mode> {
    let ring = material.plate_speed() / (2.0 * PI * radius);
    [(0.71, 1.0), (0.82, 0.6), (0.87, 0.4), (0.90, 0.3)]
        .iter()
        .map(|&(f, weight)| Mode::of(f * ring, weight, material))
        .collect()
}

/// A small bell's partials, as ratios to its strike note (hum, prime,
/// tierce, quint, nominal of a church bell's tuning), and their shares.
const BELL_PARTIALS: [(f64, f64); 5] = [(0.5, 0.4), (1.0, 1.0), (1.2, 0.6), (1.5, 0.4), (2.0, 0.5)];

/// A bell whose strike note is `note` (Hz).
pub fn bell(note: f64, material: &Properties) -> Vec<Mode> {
    BELL_PARTIALS
        .iter()
        .map(|&(ratio, weight)| Mode::of(ratio * note, weight, material))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::Material;

    #[test]
    fn a_sphere_rings_as_its_shear_speed_over_its_radius() {
        for material in Material::ALL {
            let p = material.properties();
            for r in [0.02, 0.05, 0.12, 0.4] {
                let lowest = sphere(r, &p)[0].frequency;
                let expected = 2.64 * p.shear_speed() / (2.0 * PI * r);
                assert!((lowest / expected - 1.0).abs() < 1e-12);
                let half = sphere(r / 2.0, &p)[0].frequency;
                assert!((half / lowest - 2.0).abs() < 1e-12, "{material:?} {r}");
            }
        }
    }

    #[test]
    fn every_mode_dies_at_least_as_fast_as_the_slowest_decay() {
        for material in Material::ALL {
            let p = material.properties();
            let all = [
                sphere(0.1, &p),
                plate(1.0, 0.02, &p),
                shell(0.3, &p),
                bell(2000.0, &p),
            ];
            for mode in all.iter().flatten() {
                assert!(mode.decay >= SLOWEST_DECAY, "{material:?}: {mode:?}");
                let by_loss = PI * mode.frequency * p.loss;
                assert!(mode.decay == by_loss.max(SLOWEST_DECAY));
            }
        }
    }

    #[test]
    fn a_plate_rings_higher_as_it_is_smaller_and_thicker() {
        let wood = Material::Wood.properties();
        let base = plate(1.0, 0.02, &wood)[0].frequency;
        // ω ∝ h / a²: half the side, four times; twice as thick, twice.
        assert!((plate(0.5, 0.02, &wood)[0].frequency / base - 4.0).abs() < 1e-9);
        assert!((plate(1.0, 0.04, &wood)[0].frequency / base - 2.0).abs() < 1e-9);
    }
}
