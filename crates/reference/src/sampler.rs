//! Random numbers for one pixel's one sample: a PCG32 stream whose start
//! is hashed from the seed, the pixel and the sample's number, so that no
//! two samples share numbers and none depends on which thread drew it.

/// A PCG32 generator (O'Neill 2014).
#[derive(Clone, Debug)]
pub struct Sampler {
    state: u64,
    increment: u64,
}

/// SplitMix64's finaliser: a 64-bit hash that spreads every input bit.
fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

impl Sampler {
    /// The stream of sample `sample` of pixel `pixel` under `seed`.
    pub fn new(seed: u64, pixel: u64, sample: u64) -> Sampler {
        let key = mix(seed ^ mix(pixel ^ mix(sample)));
        let mut s = Sampler {
            state: 0,
            increment: (mix(key ^ 0x9e37_79b9_7f4a_7c15) << 1) | 1,
        };
        s.next_u32();
        s.state = s.state.wrapping_add(key);
        s.next_u32();
        s
    }

    fn next_u32(&mut self) -> u32 {
        let old = self.state;
        self.state = old
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(self.increment);
        let xorshifted = (((old >> 18) ^ old) >> 27) as u32;
        xorshifted.rotate_right((old >> 59) as u32)
    }

    /// Uniform in [0, 1).
    pub fn uniform(&mut self) -> f32 {
        // The top 24 bits: every value a float can hold exactly below 1.
        (self.next_u32() >> 8) as f32 * (1.0 / 16_777_216.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn streams_are_uniform_and_distinct() {
        let mut sum = 0.0f64;
        let n = 100_000;
        let mut s = Sampler::new(7, 3, 0);
        for _ in 0..n {
            let u = s.uniform();
            assert!((0.0..1.0).contains(&u));
            sum += f64::from(u);
        }
        assert!(
            (sum / f64::from(n) - 0.5).abs() < 0.005,
            "{}",
            sum / f64::from(n)
        );
        let first = |seed, pixel, sample| Sampler::new(seed, pixel, sample).uniform();
        assert_ne!(first(7, 3, 0), first(7, 3, 1));
        assert_ne!(first(7, 3, 0), first(7, 4, 0));
        assert_ne!(first(7, 3, 0), first(8, 3, 0));
        assert_eq!(first(7, 3, 0), first(7, 3, 0));
    }
}
