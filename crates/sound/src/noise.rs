//! Noise and the filters that colour it: the crowd's bed, rolling and the
//! fireball's roar. The generator is written out so that a run's sound is
//! the same samples everywhere.

use std::f64::consts::{PI, TAU};

/// A small, fast generator of white noise (xorshift32), the same
/// everywhere.
#[derive(Clone, Debug)]
pub struct WhiteNoise(u32);

impl WhiteNoise {
    /// A generator started from `seed` (any value; zero is moved off).
    pub fn new(seed: u32) -> WhiteNoise {
        WhiteNoise(seed.max(1))
    }

    /// The next sample, uniform in [-1, 1); its RMS is 1/√3.
    pub fn next(&mut self) -> f32 {
        let mut x = self.0;
        x ^= x << 13;
        x ^= x >> 17;
        x ^= x << 5;
        self.0 = x;
        (x as f32 / 2_147_483_648.0) - 1.0
    }
}

/// A two-pole band-pass filter (a resonator that keeps white noise's RMS),
/// retuned as its centre moves.
#[derive(Clone, Debug, Default)]
pub struct BandPass {
    y1: f32,
    y2: f32,
}

/// A band-pass filter's coefficients: centre, width.
#[derive(Clone, Copy, Debug)]
pub struct Band {
    a1: f32,
    a2: f32,
    gain: f32,
}

impl Band {
    /// A band at `centre` (Hz) with quality factor `q`, at `sample_rate`.
    pub fn new(centre: f64, q: f64, sample_rate: f64) -> Band {
        let centre = centre.min(0.45 * sample_rate);
        let bandwidth = centre / q;
        let r = (-PI * bandwidth / sample_rate).exp();
        let theta = TAU * centre / sample_rate;
        let (a1, a2) = (2.0 * r * theta.cos(), -r * r);
        // White noise through y = x + a1 y1 + a2 y2 gains a variance
        // (1 - a2) / ((1 + a2) ((1 - a2)² - a1²)): divided out, the band
        // keeps its input's RMS.
        let variance = (1.0 - a2) / ((1.0 + a2) * ((1.0 - a2).powi(2) - a1 * a1));
        Band {
            a1: a1 as f32,
            a2: a2 as f32,
            gain: (1.0 / variance).sqrt() as f32,
        }
    }
}

impl BandPass {
    /// The next output for input `x` through `band`.
    pub fn next(&mut self, band: &Band, x: f32) -> f32 {
        let y = band.gain * x + band.a1 * self.y1 + band.a2 * self.y2;
        self.y2 = self.y1;
        self.y1 = y;
        y
    }
}
