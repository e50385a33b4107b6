//! A bank of modes as two-pole filters (J1): each mode's velocity answers a
//! unit impulse with e^(-αt) cos(ωt), sampled exactly (impulse invariance),
//! so a force given sample by sample rings each mode as the body would.

use std::f64::consts::TAU;

use crate::modes::Mode;

/// One mode's filter and its state.
#[derive(Clone, Copy, Debug)]
struct ModeFilter {
    /// Input weight of this sample and the one before.
    b0: f32,
    b1: f32,
    /// Feedback: y[n] = b0 x[n] + b1 x[n-1] + a1 y[n-1] + a2 y[n-2].
    a1: f32,
    a2: f32,
    y1: f32,
    y2: f32,
    x1: f32,
    /// cos θ and 1 / sin θ of its step θ, for its amplitude.
    cos: f32,
    inv_sin: f32,
}

/// A body's modes, struck by a force given sample by sample.
#[derive(Clone, Debug)]
pub struct ModalBank {
    filters: Vec<ModeFilter>,
}

impl ModalBank {
    /// The bank of `modes`, heard at `sample_rate`, each mode's output
    /// scaled by its weight times `scale`. Modes at or above the Nyquist
    /// frequency are left out: sampled, they would fold down.
    pub fn new(modes: &[Mode], scale: f64, sample_rate: f64) -> ModalBank {
        let filters = modes
            .iter()
            .filter(|m| m.frequency < 0.45 * sample_rate)
            .map(|m| {
                let r = (-m.decay / sample_rate).exp();
                let theta = TAU * m.frequency / sample_rate;
                let gain = m.weight * scale;
                ModeFilter {
                    b0: gain as f32,
                    b1: (-gain * r * theta.cos()) as f32,
                    a1: (2.0 * r * theta.cos()) as f32,
                    a2: (-r * r) as f32,
                    y1: 0.0,
                    y2: 0.0,
                    x1: 0.0,
                    cos: theta.cos() as f32,
                    inv_sin: (1.0 / theta.sin()) as f32,
                }
            })
            .collect();
        ModalBank { filters }
    }

    /// Runs the bank over `input` (impulse per sample, N s), adding its
    /// output (the modes' summed velocity, scaled) into `out`.
    pub fn run(&mut self, input: &[f32], out: &mut [f32]) {
        for f in &mut self.filters {
            let (b0, b1, a1, a2) = (f.b0, f.b1, f.a1, f.a2);
            let (mut y1, mut y2, mut x1) = (f.y1, f.y2, f.x1);
            for (x, o) in input.iter().zip(out.iter_mut()) {
                let y = b0 * x + b1 * x1 + a1 * y1 + a2 * y2;
                y2 = y1;
                y1 = y;
                x1 = *x;
                *o += y;
            }
            (f.y1, f.y2, f.x1) = (y1, y2, x1);
        }
    }

    /// Runs the bank with no input for `n` samples, adding into `out`:
    /// a ringing body between strikes.
    pub fn ring(&mut self, out: &mut [f32]) {
        for f in &mut self.filters {
            let (b1, a1, a2) = (f.b1, f.a1, f.a2);
            let (mut y1, mut y2) = (f.y1, f.y2);
            // The input of the sample before still counts once.
            let mut x1 = f.x1;
            for o in out.iter_mut() {
                let y = b1 * x1 + a1 * y1 + a2 * y2;
                x1 = 0.0;
                y2 = y1;
                y1 = y;
                *o += y;
            }
            (f.y1, f.y2, f.x1) = (y1, y2, x1);
        }
    }

    /// An upper bound of the bank's amplitude now: each mode's amplitude
    /// from its last two outputs (of a sinusoid A sin(θn + φ),
    /// A² = (y1² + y2² - 2 y1 y2 cos θ) / sin² θ), summed.
    pub fn amplitude(&self) -> f32 {
        self.filters
            .iter()
            .map(|f| {
                let a2 = f.y1 * f.y1 + f.y2 * f.y2 - 2.0 * f.y1 * f.y2 * f.cos;
                a2.max(0.0).sqrt() * f.inv_sin
            })
            .sum()
    }
}
