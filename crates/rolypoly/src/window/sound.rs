//! The window's sound, live (J1): each step is heard as it is taken, from
//! the camera, and its samples go through a lock-free queue to the audio
//! output's own thread. Without an audio device the window says so once
//! and plays on silent; M mutes.

use rolypoly_render::Camera;
use rolypoly_sound::{Listener, SoundConfig, Soundtrack};

use crate::engine::Engine;
use crate::simulation::Simulation;
use crate::sound::{StandIns, listener_of};

/// The window's sound: the run's soundtrack and the device it plays on.
pub struct LiveSound {
    track: Soundtrack,
    listener: Listener,
    muted: bool,
    /// The device's stream and the queue to it; none without a device.
    output: Option<output::Output>,
    /// Samples heard and not yet queued, left and right.
    frames: Vec<[f32; 2]>,
    /// The GPU engine's balls as heard, where it steps them.
    stand_ins: StandIns,
}

impl LiveSound {
    /// The sound of `sim` as `config` says, on the system's default output
    /// device; without one (or built without live sound, or on a device
    /// that will not play), silent, having said so once on standard error.
    pub fn open(config: &SoundConfig, sim: &Simulation) -> LiveSound {
        let output = match output::Output::open() {
            Ok(output) => Some(output),
            Err(why) => {
                eprintln!("{why}");
                None
            }
        };
        LiveSound {
            track: Soundtrack::new(config, &sim.world),
            listener: Listener {
                position: glam::DVec3::ZERO,
                forward: -glam::DVec3::Z,
            },
            muted: false,
            output,
            frames: Vec::new(),
            stand_ins: StandIns::default(),
        }
    }

    /// Whether a device plays the sound.
    pub fn playing(&self) -> bool {
        self.output.is_some()
    }

    /// Mutes, or plays again; returns whether muted.
    pub fn toggle_mute(&mut self) -> bool {
        self.muted = !self.muted;
        self.muted
    }

    /// Hears from `camera`, with `config`'s settings, from the next step.
    pub fn follow(&mut self, camera: &Camera, config: &SoundConfig) {
        self.listener = listener_of(camera);
        if self.track.config() != config {
            self.track.set_config(config);
        }
    }

    /// Hears the step `sim` just took and queues its samples, when a device
    /// plays them and the sound is not muted.
    pub fn hear(&mut self, sim: &Simulation) {
        let Some(output) = &mut self.output else {
            return;
        };
        if self.muted {
            return;
        }
        match sim.engine() {
            Engine::Cpu => self
                .track
                .hear_step(&sim.world, sim.last_events(), &self.listener),
            Engine::Gpu => {
                // A GPU engine that cannot be read stops; the window says
                // why from the simulation.
                let Ok(balls) = self.stand_ins.after_step(sim) else {
                    return;
                };
                self.track
                    .hear_step_among(&sim.world, balls, sim.last_events(), &self.listener);
            }
        }
        self.frames.append(&mut self.track.take_frames());
        output.queue(&mut self.frames);
    }
}

#[cfg(feature = "live-sound")]
mod output {
    //! The system's default output device through cpal, fed by an rtrb
    //! queue: the audio thread takes what the steps made, and plays
    //! silence while the queue refills after running dry.

    use cpal::traits::{DeviceTrait, HostTrait, StreamTrait};
    use rolypoly_sound::SAMPLE_RATE;

    /// The queue holds half a second; playing starts, and starts again
    /// after running dry, once it holds 60 ms.
    const QUEUE_FRAMES: usize = SAMPLE_RATE as usize / 2;
    const PRIMED_FRAMES: usize = SAMPLE_RATE as usize * 60 / 1000;

    /// What the window says, once, on a machine without an audio device.
    const NO_DEVICE: &str = "no audio output device: sound off";

    pub struct Output {
        // Kept: dropping the stream stops it.
        _stream: cpal::Stream,
        queue: rtrb::Producer<f32>,
    }

    impl Output {
        /// The default device, playing; or the line that says why not.
        pub fn open() -> Result<Output, String> {
            // What ALSA says while the device opens goes to a buffer on
            // this thread, not to the terminal: the window says once, in
            // its own words, when there is no device.
            #[cfg(target_os = "linux")]
            let _quiet = alsa::Output::local_error_handler();
            let host = cpal::default_host();
            let device = host.default_output_device().ok_or(NO_DEVICE)?;
            // ALSA names a default device on a machine without a sound
            // card; it is found missing only when opened.
            let refused = |e: cpal::Error| match e.kind() {
                cpal::ErrorKind::DeviceNotAvailable => NO_DEVICE.to_owned(),
                _ => {
                    format!("the audio output device does not play 48 kHz stereo: sound off ({e})")
                }
            };
            let config = cpal::StreamConfig {
                channels: 2,
                sample_rate: SAMPLE_RATE,
                buffer_size: cpal::BufferSize::Default,
            };
            let (queue, mut from_steps) = rtrb::RingBuffer::new(2 * QUEUE_FRAMES);
            let mut primed = false;
            let stream = device
                .build_output_stream::<f32, _, _>(
                    config,
                    move |out, _| {
                        let ready = from_steps.slots();
                        primed = primed && ready > 0 || ready >= 2 * PRIMED_FRAMES;
                        for sample in out.iter_mut() {
                            *sample = if primed {
                                from_steps.pop().unwrap_or(0.0)
                            } else {
                                0.0
                            };
                        }
                    },
                    // A stream that fails mid-run falls silent; the run goes on.
                    |_| {},
                    None,
                )
                .map_err(refused)?;
            stream.play().map_err(refused)?;
            Ok(Output {
                _stream: stream,
                queue,
            })
        }

        /// Queues `frames`, as many as fit (a run ahead of the device
        /// drops the rest), and empties `frames`.
        pub fn queue(&mut self, frames: &mut Vec<[f32; 2]>) {
            let room = self.queue.slots() / 2;
            for frame in frames.drain(..).take(room) {
                let _ = self.queue.push(frame[0]);
                let _ = self.queue.push(frame[1]);
            }
        }
    }
}

#[cfg(not(feature = "live-sound"))]
mod output {
    //! Built without live sound: there is no device to play on.

    pub struct Output;

    impl Output {
        pub fn open() -> Result<Output, String> {
            Err("built without the live-sound feature: sound off".to_owned())
        }

        pub fn queue(&mut self, frames: &mut Vec<[f32; 2]>) {
            frames.clear();
        }
    }
}
