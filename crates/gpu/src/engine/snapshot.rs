//! The engine's whole state copied back to the CPU and put back: every
//! buffer a step reads (the balls, their contacts and warm-start impulses,
//! the grid) and the counts the CPU keeps, so that an engine put back
//! steps on to the same bits.

use super::GpuBalls;
use crate::GpuError;
use crate::layout::Params;
use rolypoly_physics::Event;

/// A copy of a [`GpuBalls`]' state (see [`GpuBalls::snapshot`]).
#[derive(Clone)]
pub struct GpuSnapshot {
    params: Params,
    steps: u64,
    catches: Vec<Event>,
    /// Each stored buffer's bytes, in binding order.
    buffers: Vec<Vec<u8>>,
}

impl GpuSnapshot {
    /// Bytes it holds.
    pub fn bytes(&self) -> usize {
        self.buffers.iter().map(Vec::len).sum()
    }
}

impl GpuBalls {
    /// Copies the engine's state back: its buffers whole (for a million
    /// balls some 600 MB) and its step count.
    pub fn snapshot(&self) -> Result<GpuSnapshot, GpuError> {
        let steps = self.steps;
        let buffers = self
            .buffers
            .stored()
            .map(|buffer| {
                self.copy_back(buffer, buffer.size(), || {
                    format!("copying the gpu engine's state back after step {steps}")
                })
            })
            .collect::<Result<_, _>>()?;
        Ok(GpuSnapshot {
            params: self.params,
            steps,
            catches: self.catches.clone(),
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
        for (buffer, bytes) in self.buffers.stored().zip(&snapshot.buffers) {
            self.queue.write_buffer(buffer, 0, bytes);
        }
        self.params = snapshot.params;
        self.steps = snapshot.steps;
        self.catches.clone_from(&snapshot.catches);
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
