//! The ringing bodies (J1): a voice a body, struck as often as it is
//! hit. At most [`MAX_VOICES`] ring at once; a crowd's quieter strikes
//! merge into a bed of noise of the same energy, so that ten thousand
//! landing balls cost what sixty-four do and sound as loud as they would.

use glam::DVec3;

use crate::listener::Listener;
use crate::noise::{Band, BandPass, WhiteNoise};
use crate::resonator::ModalBank;

/// The most bodies that ring at once.
pub const MAX_VOICES: usize = 64;

/// Below this amplitude (full scale), a voice has fallen silent: -100 dBFS.
const SILENT: f32 = 1e-5;

/// How much louder (amplitude) than the quietest voice a strike must be to
/// take its place: 6 dB, so that a crowd of like strikes merges into the
/// bed rather than cutting each other off.
const STEAL_MARGIN: f32 = 2.0;

/// What a voice is the sound of.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Body {
    /// Ball number n.
    Ball(usize),
    /// One board of a surface: the surface's index and the board's place
    /// along its two axes.
    Board(usize, i64, i64),
    /// Tumbler number n's shell.
    Shell(usize),
    /// The bell inside tumbler number n.
    Bell(usize),
}

/// A strike on a body: a force pulse that begins `at` seconds after the
/// current block's first sample.
#[derive(Clone, Copy, Debug)]
pub struct Strike {
    /// The body struck.
    pub body: Body,
    /// Where it is heard from.
    pub point: DVec3,
    /// When the pulse starts, from the block's start, travel included (s).
    pub at: f64,
    /// How long the force lasts (s).
    pub duration: f64,
    /// The impulse it carries (N s).
    pub impulse: f64,
    /// The body's output a unit impulse gives its strongest mode, at 1 m
    /// (full scale per N s): how loud the strike will be, before its voice
    /// exists.
    pub loudness: f64,
}

/// A body ringing.
struct Voice {
    body: Body,
    bank: ModalBank,
    /// Impulse per sample still to come, from the block's first sample.
    pending: Vec<f32>,
    position: DVec3,
    /// The channels' gains at the block's start and end.
    gains: [f32; 2],
    /// The modes' amplitude at the block's end (full scale, at 1 m).
    level: f32,
}

impl Voice {
    fn heard(&self) -> f32 {
        self.level * self.gains[0].max(self.gains[1])
    }
}

/// The voices ringing, and the bed the rest merge into.
pub struct Voices {
    voices: Vec<Voice>,
    sample_rate: f64,
    mono: Vec<f32>,
    /// The bed's energy per channel (full scale²), and its decay a sample.
    bed: [f32; 2],
    bed_decay: f32,
    bed_band: Band,
    bed_noise: [(WhiteNoise, BandPass); 2],
    /// Strikes sounded by a voice of their own, and merged into the bed.
    pub voiced: u64,
    /// Strikes merged into the bed.
    pub bedded: u64,
}

impl Voices {
    /// No voices yet; the bed sounds like a struck body ringing at
    /// `bed_frequency` (Hz) and decaying at `bed_decay` (1/s).
    pub fn new(sample_rate: f64, bed_frequency: f64, bed_decay: f64) -> Voices {
        Voices {
            voices: Vec::with_capacity(MAX_VOICES),
            sample_rate,
            mono: Vec::new(),
            bed: [0.0; 2],
            // Energy decays twice as fast as amplitude.
            bed_decay: (-2.0 * bed_decay / sample_rate).exp() as f32,
            bed_band: Band::new(bed_frequency, 2.0, sample_rate),
            bed_noise: [
                (WhiteNoise::new(0x9e37_79b9), BandPass::default()),
                (WhiteNoise::new(0x85eb_ca6b), BandPass::default()),
            ],
            voiced: 0,
            bedded: 0,
        }
    }

    /// How many voices ring now.
    pub fn ringing(&self) -> usize {
        self.voices.len()
    }

    /// Sounds `strike` on its body's voice, making one with `make` (the
    /// body's modes, scaled) when it has none; when all are taken, it takes
    /// the quietest's place if it is clearly louder, or else joins the bed.
    pub fn strike(
        &mut self,
        strike: &Strike,
        listener: &Listener,
        make: impl FnOnce() -> ModalBank,
    ) {
        let placement = listener.place(strike.point);
        let index = match self.voices.iter().position(|v| v.body == strike.body) {
            Some(i) => i,
            None => {
                let heard = (strike.loudness * strike.impulse) as f32
                    * placement.gains[0].max(placement.gains[1]);
                let slot = if self.voices.len() < MAX_VOICES {
                    None
                } else {
                    let (quietest, level) = self
                        .voices
                        .iter()
                        .enumerate()
                        .map(|(i, v)| (i, v.heard()))
                        .fold((0, f32::INFINITY), |a, b| if b.1 < a.1 { b } else { a });
                    if heard <= STEAL_MARGIN * level {
                        self.merge_into_bed(strike, placement.gains);
                        return;
                    }
                    Some(quietest)
                };
                let voice = Voice {
                    body: strike.body,
                    bank: make(),
                    pending: Vec::new(),
                    position: strike.point,
                    gains: placement.gains,
                    // Until it rings, the strike's own peak.
                    level: (strike.loudness * strike.impulse) as f32,
                };
                match slot {
                    Some(i) => {
                        self.voices[i] = voice;
                        i
                    }
                    None => {
                        self.voices.push(voice);
                        self.voices.len() - 1
                    }
                }
            }
        };
        self.voiced += 1;
        let voice = &mut self.voices[index];
        voice.position = strike.point;
        crate::hertz::add_pulse(
            &mut voice.pending,
            strike.at + placement.delay,
            strike.duration,
            strike.impulse,
            self.sample_rate,
        );
    }

    /// Adds `strike`'s energy to the bed, heard with `gains`: a ringing
    /// mode of peak A holds A²/(4α) of energy, noise of RMS a decaying
    /// alike a²/(2α), the same at a² = A²/2.
    fn merge_into_bed(&mut self, strike: &Strike, gains: [f32; 2]) {
        for (bed, gain) in self.bed.iter_mut().zip(gains) {
            let peak = (strike.loudness * strike.impulse) as f32 * gain;
            *bed += 0.5 * peak * peak;
        }
        self.bedded += 1;
    }

    /// Renders the next `frames.len()` samples of every voice and the bed,
    /// adding them into `frames`; `position` gives a moving body's place
    /// now (a ball's, a tumbler's), `None` where it stays put.
    pub fn render(
        &mut self,
        frames: &mut [[f32; 2]],
        listener: &Listener,
        position: impl Fn(Body) -> Option<DVec3>,
    ) {
        let n = frames.len();
        self.mono.resize(n, 0.0);
        for voice in &mut self.voices {
            if let Some(p) = position(voice.body) {
                voice.position = p;
            }
            let start = voice.gains;
            let end = listener.place(voice.position).gains;
            voice.gains = end;
            self.mono.fill(0.0);
            if voice.pending.is_empty() {
                voice.bank.ring(&mut self.mono);
            } else {
                if voice.pending.len() < n {
                    voice.pending.resize(n, 0.0);
                }
                voice.bank.run(&voice.pending[..n], &mut self.mono);
                voice.pending.drain(..n);
                if voice.pending.iter().all(|&x| x == 0.0) {
                    voice.pending.clear();
                }
            }
            let step = 1.0 / n as f32;
            for (k, (frame, &m)) in frames.iter_mut().zip(&self.mono).enumerate() {
                let f = k as f32 * step;
                frame[0] += m * (start[0] + (end[0] - start[0]) * f);
                frame[1] += m * (start[1] + (end[1] - start[1]) * f);
            }
            voice.level = voice.bank.amplitude();
        }
        self.voices
            .retain(|v| !v.pending.is_empty() || v.heard() >= SILENT);
        self.render_bed(frames);
    }

    /// The bed: band-limited noise carrying the merged strikes' energy.
    fn render_bed(&mut self, frames: &mut [[f32; 2]]) {
        if self.bed[0] < SILENT * SILENT && self.bed[1] < SILENT * SILENT {
            self.bed = [0.0; 2];
            return;
        }
        // Uniform noise has RMS 1/√3; the band keeps it.
        let norm = 3f32.sqrt();
        for frame in frames.iter_mut() {
            for (c, (noise, band)) in self.bed_noise.iter_mut().enumerate() {
                let x = band.next(&self.bed_band, noise.next() * norm);
                frame[c] += x * self.bed[c].sqrt();
                self.bed[c] *= self.bed_decay;
            }
        }
    }
}
