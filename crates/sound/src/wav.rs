//! Sound to a WAV file: 16-bit stereo PCM at [`SAMPLE_RATE`].

use std::path::Path;

use crate::config::SAMPLE_RATE;

/// A sample as 16-bit PCM: rounded, and held within full scale.
pub fn to_pcm(x: f32) -> i16 {
    (x * 32767.0).round().clamp(-32767.0, 32767.0) as i16
}

/// Writes `frames` (left, right) to `path`.
pub fn write_wav(path: &Path, frames: &[[f32; 2]]) -> Result<(), hound::Error> {
    let spec = hound::WavSpec {
        channels: 2,
        sample_rate: SAMPLE_RATE,
        bits_per_sample: 16,
        sample_format: hound::SampleFormat::Int,
    };
    let mut writer = hound::WavWriter::create(path, spec)?;
    for frame in frames {
        writer.write_sample(to_pcm(frame[0]))?;
        writer.write_sample(to_pcm(frame[1]))?;
    }
    writer.finalize()
}
