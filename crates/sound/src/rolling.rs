//! Rolling and sliding (J1): a body moving over a surface it touches
//! rumbles, quietly, as loud as its speed; the rumble ends when it rests.

use glam::DVec3;
use rolypoly_physics::{Balls, World};

use crate::listener::Listener;
use crate::noise::{Band, BandPass, WhiteNoise};

/// A body touches a surface within this gap (m).
const TOUCHING: f64 = 2e-3;
/// Slower than this (m/s), a body is at rest and silent.
const RESTING: f64 = 0.01;
/// The rumble's loudness at 1 m per metre per second of a body's speed
/// over a surface and metre of its radius (full scale).
const LOUDNESS: f64 = 0.004;
/// Where the rumble's energy lies (Hz), and how wide.
const RUMBLE_HZ: f64 = 220.0;
const RUMBLE_Q: f64 = 0.8;

/// The rumble of everything rolling or sliding.
pub struct Rolling {
    band: Band,
    noise: [(WhiteNoise, BandPass); 2],
    /// The channels' amplitudes at the block's start (RMS, full scale).
    amplitude: [f32; 2],
}

impl Rolling {
    /// Silence, at `sample_rate`.
    pub fn new(sample_rate: f64) -> Rolling {
        Rolling {
            band: Band::new(RUMBLE_HZ, RUMBLE_Q, sample_rate),
            noise: [
                (WhiteNoise::new(0x2545_f491), BandPass::default()),
                (WhiteNoise::new(0x6c07_8965), BandPass::default()),
            ],
            amplitude: [0.0; 2],
        }
    }

    /// Each channel's amplitude now: the bodies' rumbles, summed by energy.
    fn target(world: &World, balls: &Balls, listener: &Listener) -> [f32; 2] {
        let mut energy = [0.0f64; 2];
        let mut add = |point: DVec3, speed: f64, radius: f64| {
            if speed > RESTING {
                let gains = listener.place(point).gains;
                let a = LOUDNESS * speed * radius;
                for (e, g) in energy.iter_mut().zip(gains) {
                    *e += (a * g as f64).powi(2);
                }
            }
        };
        let room = world.room();
        for i in 0..balls.len() {
            let (p, r) = (balls.positions()[i], balls.radii()[i]);
            if balls.alive()[i] && room.nearest_distance(p) - r < TOUCHING {
                add(p, balls.velocities()[i].length(), r);
            }
        }
        let shape = world.tumbler_shape();
        for t in world.tumblers() {
            // Rolling carries the body; sliding rubs its foot as well.
            let speed = t.linear_velocity().length() + t.contact_velocity().length();
            add(t.contact_point(), speed, shape.bottom_radius);
        }
        energy.map(|e| e.sqrt() as f32)
    }

    /// Adds the rumble of the block that ends with `world` as it is now.
    pub fn render(
        &mut self,
        frames: &mut [[f32; 2]],
        world: &World,
        balls: &Balls,
        listener: &Listener,
    ) {
        let start = self.amplitude;
        let end = Self::target(world, balls, listener);
        self.amplitude = end;
        if start == [0.0; 2] && end == [0.0; 2] {
            return;
        }
        let norm = 3f32.sqrt();
        let step = 1.0 / frames.len() as f32;
        for (k, frame) in frames.iter_mut().enumerate() {
            let f = k as f32 * step;
            for (c, (noise, band)) in self.noise.iter_mut().enumerate() {
                let x = band.next(&self.band, noise.next() * norm);
                frame[c] += x * (start[c] + (end[c] - start[c]) * f);
            }
        }
    }
}
