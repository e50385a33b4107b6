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

/// Whether a wait that runs out ends the program ([`end_program`]): set by
/// the program, not by a library's user, whose process is not ours to end.
static EXIT_WHEN_STUCK: AtomicBool = AtomicBool::new(false);

/// Sets the bound of every wait on the GPU from now on (`--gpu-timeout`),
/// for a program that ends on the error: once a wait runs out, the program
/// prints it and ends there.
pub fn set_program_gpu_timeout(limit: Duration) {
    let nanos = u64::try_from(limit.as_nanos()).unwrap_or(u64::MAX).max(1);
    PROGRAM_BOUND_NANOS.store(nanos, Ordering::Relaxed);
    EXIT_WHEN_STUCK.store(true, Ordering::Relaxed);
}

/// Ends a program whose wait ran out, with the error's one line and exit
/// status 1, without letting go of the GPU. The GPU is still at work on
/// what was given up on: dropping the device and queue waits for it to go
/// idle with no bound (a stalled GPU never does), and freeing what it
/// works on, or the driver's teardown at exit, while it runs can fault (a
/// software Vulkan's worker threads did, now and then). So the process
/// ends at once, skipping the exit handlers where the platform allows.
fn end_program(timeout: &GpuTimeout) {
    if !EXIT_WHEN_STUCK.load(Ordering::Relaxed) {
        return;
    }
    use std::io::Write;
    let mut stderr = std::io::stderr().lock();
    let _ = writeln!(stderr, "error: {timeout}");
    let _ = stderr.flush();
    let _ = std::io::stdout().flush();
    #[cfg(unix)]
    // SAFETY: `_exit` ends the process without running anything else;
    // what had to be written is flushed above.
    unsafe {
        libc::_exit(1)
    };
    #[cfg(not(unix))]
    std::process::exit(1);
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
                end_program(&timeout);
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
