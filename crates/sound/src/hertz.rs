//! The force of an impact over time (J1): Hertz's contact between two
//! elastic bodies lasts τ = 2.87 (m*² / (R* E*² v))^(1/5), shorter for a
//! faster hit, so that a harder hit excites higher modes and sounds
//! brighter (Chadwick, Zheng and James 2012). The force is taken as a half
//! sine over τ carrying the impact's whole impulse.

use std::f64::consts::PI;

/// The two bodies of a contact, as Hertz's law sees them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Contact {
    /// Reduced mass m1 m2 / (m1 + m2) (kg).
    pub mass: f64,
    /// Reduced radius of curvature r1 r2 / (r1 + r2); a flat body's is
    /// infinite, leaving the other's (m).
    pub radius: f64,
    /// Contact modulus E* = 1 / ((1 - ν1²)/E1 + (1 - ν2²)/E2) (Pa).
    pub modulus: f64,
}

impl Contact {
    /// How long the bodies touch when they meet at `speed` (s).
    pub fn duration(&self, speed: f64) -> f64 {
        let speed = speed.max(1e-6);
        2.87 * (self.mass * self.mass / (self.radius * self.modulus * self.modulus * speed))
            .powf(0.2)
    }
}

/// The impulse a force pulse delivers in each sample, added into `input`
/// from sample `start` (seconds from `input`'s first sample, at
/// `sample_rate`): a half sine of length `duration` carrying `impulse`
/// (N s) in all. Each sample gets the pulse's integral over its interval,
/// so the pulse starts between samples where it should and its samples sum
/// to the impulse exactly.
pub fn add_pulse(input: &mut Vec<f32>, start: f64, duration: f64, impulse: f64, sample_rate: f64) {
    let begin = start * sample_rate;
    let end = (start + duration) * sample_rate;
    let first = begin.floor().max(0.0) as usize;
    let last = end.ceil() as usize;
    if input.len() < last + 1 {
        input.resize(last + 1, 0.0);
    }
    // ∫ sin(π t / τ) dt over [a, b], over its whole: 2τ/π.
    let share = |t: f64| (1.0 - (PI * (t.clamp(begin, end) - begin) / (end - begin)).cos()) / 2.0;
    if end - begin < 1e-9 {
        input[first] += impulse as f32;
        return;
    }
    for (n, slot) in input.iter_mut().enumerate().take(last + 1).skip(first) {
        let part = share((n + 1) as f64) - share(n as f64);
        *slot += (impulse * part) as f32;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 0.25 kg plastic ball of radius 0.12 m on a wooden floor.
    const BALL_ON_WOOD: Contact = Contact {
        mass: 0.25,
        radius: 0.12,
        modulus: 2.1e9,
    };

    #[test]
    fn a_faster_hit_is_shorter_as_the_fifth_root() {
        let t1 = BALL_ON_WOOD.duration(1.0);
        for v in [0.5, 2.0, 8.0, 32.0] {
            let ratio = BALL_ON_WOOD.duration(v) / t1;
            assert!((ratio - v.powf(-0.2)).abs() < 1e-12, "{v} m/s: {ratio}");
        }
        // Hertz's time for this pair at 1 m/s is about half a millisecond.
        assert!((3e-4..8e-4).contains(&t1), "{t1}");
    }

    #[test]
    fn a_pulse_carries_its_impulse_from_its_moment() {
        let rate = 48_000.0;
        for (start, duration) in [
            (0.0, 5e-4),
            (0.010_01, 2e-4),
            (0.003_333, 1e-5),
            (0.0005, 3e-3),
        ] {
            let mut input = Vec::new();
            add_pulse(&mut input, start, duration, 1.25, rate);
            let sum: f64 = input.iter().map(|&x| f64::from(x)).sum();
            assert!((sum - 1.25).abs() < 1e-5, "{start} {duration}: {sum}");
            let first = input.iter().position(|&x| x > 0.0).unwrap();
            assert_eq!(
                first,
                (start * rate).floor() as usize,
                "{start}: begins in its sample"
            );
            let last = input.iter().rposition(|&x| x > 0.0).unwrap();
            assert!(last as f64 <= ((start + duration) * rate).ceil());
        }
    }
}
