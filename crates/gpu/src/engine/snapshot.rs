//! The engine's whole state copied back to the CPU and put back: every
//! buffer a step reads (the balls, their contacts and warm-start impulses,
//! the grid) and the counts the CPU keeps, so that an engine put back
//! steps on to the same bits.

use super::{GpuBalls, StepReport};
use crate::GpuError;
use crate::layout::Params;
use rolypoly_physics::Event;
use serde::{Deserialize, Serialize};

/// A copy of a [`GpuBalls`]' state (see [`GpuBalls::snapshot`]). It
/// serializes (to carry it to another process or machine), the step's
/// constants as their bytes.
#[derive(Clone, Serialize, Deserialize)]
#[serde(into = "Carried", try_from = "Carried")]
pub struct GpuSnapshot {
    params: Params,
    steps: u64,
    catches: Vec<Event>,
    /// The reports of the last steps, not yet due (see
    /// [`crate::REPORT_DELAY`]): their pushes are still to be given.
    reports: Vec<StepReport>,
    /// Each stored buffer's bytes, in binding order.
    buffers: Vec<Vec<u8>>,
}

/// A [`GpuSnapshot`] as it travels: [`Params`] as its bytes, which must be
/// as many as a `Params` has when they come back.
#[derive(Serialize, Deserialize)]
struct Carried {
    params: Vec<u8>,
    steps: u64,
    catches: Vec<Event>,
    reports: Vec<StepReport>,
    buffers: Vec<Vec<u8>>,
}

impl From<GpuSnapshot> for Carried {
    fn from(snapshot: GpuSnapshot) -> Carried {
        Carried {
            params: bytemuck::bytes_of(&snapshot.params).to_vec(),
            steps: snapshot.steps,
            catches: snapshot.catches,
            reports: snapshot.reports,
            buffers: snapshot.buffers,
        }
    }
}

impl TryFrom<Carried> for GpuSnapshot {
    type Error = String;

    fn try_from(carried: Carried) -> Result<GpuSnapshot, String> {
        let params = bytemuck::try_pod_read_unaligned(&carried.params).map_err(|_| {
            format!(
                "the gpu engine's constants are {} bytes, not {}",
                carried.params.len(),
                std::mem::size_of::<Params>()
            )
        })?;
        Ok(GpuSnapshot {
            params,
            steps: carried.steps,
            catches: carried.catches,
            reports: carried.reports,
            buffers: carried.buffers,
        })
    }
}

impl GpuSnapshot {
    /// Bytes it holds.
    pub fn bytes(&self) -> usize {
        self.buffers.iter().map(Vec::len).sum()
    }
}

impl GpuBalls {
    /// Copies the engine's state back: its buffers whole (for a million
    /// balls some 600 MB), its step count, and the reports of the last
    /// steps (waited for, if still on their way).
    pub fn snapshot(&mut self) -> Result<GpuSnapshot, GpuError> {
        self.reports.read_all(&self.device, &self.wait)?;
        let steps = self.steps;
        let buffers = self
            .buffers
            .stored()
            .map(|buffer| {
                self.copy_back((buffer, 0), buffer.size(), || {
                    format!("copying the gpu engine's state back after step {steps}")
                })
            })
            .collect::<Result<_, _>>()?;
        Ok(GpuSnapshot {
            params: self.params,
            steps,
            catches: self.events.clone(),
            reports: self.reports.read_reports().cloned().collect(),
            buffers,
        })
    }

    /// Puts back the state `snapshot` copied, of this engine or one built
    /// for the same scene; an engine of other sizes is refused, unchanged.
    pub fn restore(&mut self, snapshot: &GpuSnapshot) -> Result<(), GpuError> {
        let fits = scene_constants(&self.params) == scene_constants(&snapshot.params)
            && self.buffers.stored().count() == snapshot.buffers.len()
            && self
                .buffers
                .stored()
                .zip(&snapshot.buffers)
                .all(|(buffer, bytes)| buffer.size() == bytes.len() as u64);
        if !fits {
            return Err(GpuError::Unsupported(
                "a snapshot of a world of another scene (its sizes, room or materials) cannot be \
                 put back into this one"
                    .into(),
            ));
        }
        self.reports
            .replace(&self.device, &self.wait, &snapshot.reports)?;
        for (buffer, bytes) in self.buffers.stored().zip(&snapshot.buffers) {
            self.queue.write_buffer(buffer, 0, bytes);
        }
        self.params = snapshot.params;
        self.steps = snapshot.steps;
        self.events.clone_from(&snapshot.catches);
        self.queue
            .write_buffer(&self.buffers.params, 0, bytemuck::bytes_of(&self.params));
        self.queue.submit([]);
        Ok(())
    }
}

/// What the scene fixes of a step's constants: all but the counts that
/// change as it runs.
fn scene_constants(params: &Params) -> Params {
    Params {
        count: 0,
        bodies: 0,
        step: 0,
        ..*params
    }
}
