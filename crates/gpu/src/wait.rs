//! Every wait on the GPU, bounded: a driver that stalls (an unwritten
//! timestamp resolved on some drivers, a lost device that never says so)
//! gives one error naming what was waited for, instead of a program that
//! hangs.

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::time::Duration;

use thiserror::Error;

/// How long a wait on the GPU lasts before it is given up, unless
/// `--gpu-timeout` says otherwise.
pub const DEFAULT_GPU_TIMEOUT: Duration = Duration::from_secs(30);

/// The bound new [`WaitBound`]s start with, in nanoseconds: one setting for
/// the whole program, as `--gpu-timeout` is, so that every device opened
/// anywhere in it (a renderer's, the engine's, a clip's) has it.
static PROGRAM_BOUND_NANOS: AtomicU64 = AtomicU64::new(DEFAULT_GPU_TIMEOUT.as_nanos() as u64);

/// Whether a wait that runs out also arms [`exit_if_stuck`]: set by the
/// program, not by a library's user, whose process is not ours to end.
static EXIT_WHEN_STUCK: AtomicBool = AtomicBool::new(false);

/// How long the program has to end after a wait ran out, before it is
/// ended anyway.
const GRACE: Duration = Duration::from_secs(5);

/// Sets the bound of every wait on the GPU from now on (`--gpu-timeout`),
/// for a program that ends on the error: once a wait runs out, the program
/// is ended within a few seconds even if letting go of the GPU hangs.
pub fn set_program_gpu_timeout(limit: Duration) {
    let nanos = u64::try_from(limit.as_nanos()).unwrap_or(u64::MAX).max(1);
    PROGRAM_BOUND_NANOS.store(nanos, Ordering::Relaxed);
    EXIT_WHEN_STUCK.store(true, Ordering::Relaxed);
}

/// After a wait ran out the program unwinds to print `timeout`, and on the
/// way drops its device and queue; wgpu waits for the GPU to go idle when
/// a queue is dropped, with no bound. A GPU that stalled may never be idle,
/// so a watchdog prints the error and ends the program if it is still
/// running after [`GRACE`].
fn exit_if_stuck(timeout: &GpuTimeout) {
    if !EXIT_WHEN_STUCK.load(Ordering::Relaxed) {
        return;
    }
    let message = timeout.to_string();
    std::thread::spawn(move || {
        std::thread::sleep(GRACE);
        eprintln!("error: {message}");
        std::process::exit(1);
    });
}

/// The bound new waits start with: [`DEFAULT_GPU_TIMEOUT`] unless
/// [`set_program_gpu_timeout`] said otherwise.
pub fn program_gpu_timeout() -> Duration {
    Duration::from_nanos(PROGRAM_BOUND_NANOS.load(Ordering::Relaxed))
}

/// A wait on the GPU that ran out of time.
#[derive(Clone, Debug, Error, PartialEq)]
#[error(
    "gave up waiting {bound} for the GPU to finish {what} on the graphics adapter {adapter}; \
     try --quality low or WGPU_BACKEND=gl, or allow it longer with --gpu-timeout SECONDS",
    bound = seconds(*.bound)
)]
pub struct GpuTimeout {
    /// What was waited for, in words: "the frame at t = 1.000 s".
    pub what: String,
    /// The adapter, "name (backend)".
    pub adapter: String,
    /// How long it was waited for.
    pub bound: Duration,
}

/// Why a wait on the GPU ended without the work done.
#[derive(Debug, Error)]
pub enum WaitError {
    /// The bound ran out.
    #[error(transparent)]
    Timeout(#[from] GpuTimeout),
    /// The device said it could not wait (lost, or a submission unknown).
    #[error("waiting for the GPU to finish {what} failed: {message}")]
    Failed {
        /// What was waited for.
        what: String,
        /// What the device said.
        message: String,
    },
}

/// How long the GPU may be waited for, and the adapter to name when it
/// runs out.
#[derive(Clone, Debug, PartialEq)]
pub struct WaitBound {
    /// The longest wait.
    pub limit: Duration,
    /// The adapter, "name (backend)".
    pub adapter: String,
}

impl WaitBound {
    /// The program's bound ([`program_gpu_timeout`]) on `adapter`.
    pub fn new(adapter: impl Into<String>) -> WaitBound {
        WaitBound {
            limit: program_gpu_timeout(),
            adapter: adapter.into(),
        }
    }

    /// Waits until `submission` (or everything submitted, if none) is done
    /// and its callbacks have run, at most [`WaitBound::limit`]. `what`
    /// names it in the error.
    pub fn wait(
        &self,
        device: &wgpu::Device,
        submission: Option<wgpu::SubmissionIndex>,
        what: impl FnOnce() -> String,
    ) -> Result<(), WaitError> {
        match device.poll(wgpu::PollType::Wait {
            submission_index: submission,
            timeout: Some(self.limit),
        }) {
            Ok(_) => Ok(()),
            Err(wgpu::PollError::Timeout) => {
                let timeout = GpuTimeout {
                    what: what(),
                    adapter: self.adapter.clone(),
                    bound: self.limit,
                };
                exit_if_stuck(&timeout);
                Err(WaitError::Timeout(timeout))
            }
            Err(e) => Err(WaitError::Failed {
                what: what(),
                message: e.to_string(),
            }),
        }
    }
}

/// A bound in words: "30 s", "0.001 s".
fn seconds(bound: Duration) -> String {
    format!("{} s", bound.as_secs_f64())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_timeout_names_what_the_adapter_the_bound_and_the_ways_out() {
        let message = GpuTimeout {
            what: "the frame at t = 1.000 s".into(),
            adapter: "NVIDIA H100 (Vulkan)".into(),
            bound: Duration::from_millis(1),
        }
        .to_string();
        for part in [
            "the frame at t = 1.000 s",
            "NVIDIA H100 (Vulkan)",
            "0.001 s",
            "--quality low",
            "WGPU_BACKEND=gl",
            "--gpu-timeout",
        ] {
            assert!(message.contains(part), "{part:?} missing from {message:?}");
        }
        assert!(!message.contains('\n'), "one line: {message:?}");
    }

    #[test]
    fn the_default_bound_is_thirty_seconds() {
        assert_eq!(DEFAULT_GPU_TIMEOUT, Duration::from_secs(30));
        assert_eq!(
            PROGRAM_BOUND_NANOS.load(Ordering::Relaxed),
            DEFAULT_GPU_TIMEOUT.as_nanos() as u64
        );
    }
}
