//! The last stage (J1): a peak limiter that never lets a sample past its
//! ceiling. The gain drops at once to what the loudest sample needs and
//! recovers slowly, so loud crowds are pressed down rather than clipped.

/// The largest magnitude a sample leaves with: -1 dBFS.
pub const CEILING: f32 = 0.891;

/// A stereo peak limiter.
#[derive(Clone, Debug)]
pub struct Limiter {
    /// The peak it follows: jumps up to a louder sample, falls back by
    /// `release` a sample.
    envelope: f32,
    release: f32,
}

impl Limiter {
    /// A limiter whose gain recovers with time constant 80 ms.
    pub fn new(sample_rate: f64) -> Limiter {
        Limiter {
            envelope: 0.0,
            release: (-1.0 / (0.08 * sample_rate)).exp() as f32,
        }
    }

    /// Limits `frames` in place.
    pub fn run(&mut self, frames: &mut [[f32; 2]]) {
        for frame in frames {
            let peak = frame[0].abs().max(frame[1].abs());
            self.envelope = (self.envelope * self.release).max(peak);
            if self.envelope > CEILING {
                // The envelope is at least this sample's peak, so the
                // sample ends at the ceiling or below it, but for the
                // product's rounding, which the clamp takes off.
                let gain = CEILING / self.envelope;
                for x in frame.iter_mut() {
                    *x = (*x * gain).clamp(-CEILING, CEILING);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::noise::WhiteNoise;

    #[test]
    fn no_sample_passes_the_ceiling_and_quiet_ones_pass_untouched() {
        let mut noise = WhiteNoise::new(7);
        let mut limiter = Limiter::new(48_000.0);
        for loudness in [0.5f32, 2.0, 40.0, 0.1] {
            let mut frames: Vec<[f32; 2]> = (0..4800)
                .map(|_| [noise.next() * loudness, noise.next() * loudness])
                .collect();
            limiter.run(&mut frames);
            let peak = frames
                .iter()
                .fold(0.0f32, |m, f| m.max(f[0].abs()).max(f[1].abs()));
            assert!(peak <= CEILING, "{loudness}: {peak}");
        }
        let mut fresh = Limiter::new(48_000.0);
        let quiet = [[0.3, -0.5], [0.8, 0.1]];
        let mut frames = quiet;
        fresh.run(&mut frames);
        assert_eq!(frames, quiet);
    }
}
