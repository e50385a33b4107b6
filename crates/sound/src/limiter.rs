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
                // sample ends at or below the ceiling.
                let gain = CEILING / self.envelope;
                frame[0] *= gain;
                frame[1] *= gain;
            }
        }
    }
}
