//! The fireball's roar (J1): noise in a low band that swells as the
//! fireball nears the listener, its pitch shifted by its speed towards or
//! away (Doppler: f' = f c / (c - v), v its speed towards the listener).

use rolypoly_physics::Fireball;

use crate::listener::{Listener, SPEED_OF_SOUND};
use crate::noise::{Band, BandPass, WhiteNoise};

/// The roar's centre when still (Hz), and its width.
const ROAR_HZ: f64 = 160.0;
const ROAR_Q: f64 = 1.2;
/// Its crackle's centre and width: the flame's upper band.
const CRACKLE_HZ: f64 = 1200.0;
const CRACKLE_Q: f64 = 2.0;
/// Its loudness at 1 m (RMS, full scale), and the crackle's share.
const LOUDNESS: f64 = 0.12;
const CRACKLE_SHARE: f32 = 0.3;

/// The fireball's roar.
pub struct Roar {
    sample_rate: f64,
    noise: [WhiteNoise; 2],
    low: [BandPass; 2],
    high: [BandPass; 2],
    amplitude: [f32; 2],
    shift: f64,
}

impl Roar {
    /// Silence, at `sample_rate`.
    pub fn new(sample_rate: f64) -> Roar {
        Roar {
            sample_rate,
            noise: [WhiteNoise::new(0x1b87_3593), WhiteNoise::new(0xcc9e_2d51)],
            low: Default::default(),
            high: Default::default(),
            amplitude: [0.0; 2],
            shift: 1.0,
        }
    }

    /// The Doppler factor of `fireball` heard by `listener`.
    pub fn doppler(fireball: &Fireball, listener: &Listener) -> f64 {
        let to = listener.position - fireball.position;
        let towards = to.try_normalize().map_or(0.0, |d| fireball.velocity.dot(d));
        // Never at or past the speed of sound here, but kept finite.
        SPEED_OF_SOUND / (SPEED_OF_SOUND - towards).max(0.1 * SPEED_OF_SOUND)
    }

    /// Adds the roar of the block that ends with `fireball` where it is now.
    pub fn render(
        &mut self,
        frames: &mut [[f32; 2]],
        fireball: Option<&Fireball>,
        listener: &Listener,
    ) {
        let start = self.amplitude;
        let end = match fireball {
            Some(f) => {
                self.shift = Self::doppler(f, listener);
                let gains = listener.place(f.position).gains;
                gains.map(|g| g * LOUDNESS as f32)
            }
            None => [0.0; 2],
        };
        self.amplitude = end;
        if start == [0.0; 2] && end == [0.0; 2] {
            return;
        }
        let low = Band::new(ROAR_HZ * self.shift, ROAR_Q, self.sample_rate);
        let high = Band::new(CRACKLE_HZ * self.shift, CRACKLE_Q, self.sample_rate);
        let norm = 3f32.sqrt();
        let step = 1.0 / frames.len() as f32;
        for (k, frame) in frames.iter_mut().enumerate() {
            let f = k as f32 * step;
            for c in 0..2 {
                let x = self.noise[c].next() * norm;
                let y = self.low[c].next(&low, x) + CRACKLE_SHARE * self.high[c].next(&high, x);
                frame[c] += y * (start[c] + (end[c] - start[c]) * f);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn the_roar_rises_as_the_fireball_comes_and_falls_as_it_goes() {
        let ear = Listener {
            position: DVec3::ZERO,
            forward: -DVec3::Z,
        };
        let at = |velocity: DVec3| Fireball {
            position: DVec3::new(0.0, 0.0, -5.0),
            velocity,
            radius: 0.2,
            mass: 0.25,
            speed: velocity.length(),
        };
        for v in [2.0, 6.0, 20.0] {
            let coming = Roar::doppler(&at(DVec3::new(0.0, 0.0, v)), &ear);
            let going = Roar::doppler(&at(DVec3::new(0.0, 0.0, -v)), &ear);
            let across = Roar::doppler(&at(DVec3::new(v, 0.0, 0.0)), &ear);
            assert!((coming - SPEED_OF_SOUND / (SPEED_OF_SOUND - v)).abs() < 1e-12);
            assert!((going - SPEED_OF_SOUND / (SPEED_OF_SOUND + v)).abs() < 1e-12);
            assert_eq!(across, 1.0);
        }
    }
}
