//! A signal's pitch, for the sound's tests (the sound crate's laws and the
//! program's, which include this file).

use rustfft::{FftPlanner, num_complex::Complex};

/// The frequency (Hz) of the loudest bin of `signal` between `low` and
/// `high`, refined by a parabola through its neighbours.
pub fn spectral_peak(signal: &[f32], low: f64, high: f64) -> f64 {
    let n = signal.len().next_power_of_two();
    let mut data: Vec<Complex<f32>> = signal.iter().map(|&x| Complex::new(x, 0.0)).collect();
    data.resize(n, Complex::new(0.0, 0.0));
    FftPlanner::new().plan_fft_forward(n).process(&mut data);
    let bin = f64::from(rolypoly_sound::SAMPLE_RATE) / n as f64;
    let (lo, hi) = ((low / bin) as usize, (high / bin) as usize);
    let magnitude = |k: usize| data[k].norm() as f64;
    let k = (lo..hi)
        .max_by(|&a, &b| magnitude(a).total_cmp(&magnitude(b)))
        .unwrap();
    let (a, b, c) = (
        magnitude(k - 1).ln(),
        magnitude(k).ln(),
        magnitude(k + 1).ln(),
    );
    (k as f64 + 0.5 * (a - c) / (a - 2.0 * b + c)) * bin
}
