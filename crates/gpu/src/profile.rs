//! Where a step's GPU time goes: each stage of the step is its own compute
//! pass, and where the device writes timestamps, each pass's start and end
//! are stamped.

use crate::GpuError;
use crate::readback::read_buffer;

/// The stages of a step, in the order they run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    /// Each ball's cell counted, the counts scanned, the balls placed and
    /// each cell sorted.
    Grid,
    /// The contacts found, kept ones started from their last impulse.
    Contacts,
    /// The impact rounds, the last ending in gravity and the warm start.
    Impacts,
    /// The contact solver's Jacobi sweeps, which also shift the balls out
    /// of their overlaps.
    Solve,
    /// The tumblers' pushes summed.
    Push,
    /// The balls moved, lone ones along their parabolas, and the
    /// renderer's instances written.
    Flight,
}

impl Stage {
    /// Every stage, in order.
    pub const ALL: [Stage; 6] = [
        Stage::Grid,
        Stage::Contacts,
        Stage::Impacts,
        Stage::Solve,
        Stage::Push,
        Stage::Flight,
    ];

    /// Its name, as tables print it.
    pub fn name(self) -> &'static str {
        match self {
            Stage::Grid => "grid",
            Stage::Contacts => "contacts",
            Stage::Impacts => "impacts",
            Stage::Solve => "solve",
            Stage::Push => "tumbler pushes",
            Stage::Flight => "flight",
        }
    }
}

/// How many stages a step has.
pub const STAGES: usize = Stage::ALL.len();

/// Two timestamps for each stage: where it starts and ends.
const STAMPS: u32 = 2 * Stage::ALL.len() as u32;

/// The query set the stages are stamped into, and where they come back.
pub struct StageTimer {
    queries: wgpu::QuerySet,
    resolved: wgpu::Buffer,
    readback: wgpu::Buffer,
    /// Nanoseconds per tick.
    period: f64,
}

impl StageTimer {
    /// A timer, if the device writes timestamps.
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue) -> Option<StageTimer> {
        if !device.features().contains(wgpu::Features::TIMESTAMP_QUERY) {
            return None;
        }
        let size = u64::from(STAMPS) * 8;
        Some(StageTimer {
            queries: device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("stage timestamps"),
                ty: wgpu::QueryType::Timestamp,
                count: STAMPS,
            }),
            resolved: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("stage timestamps resolved"),
                size,
                usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            }),
            readback: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("stage timestamps read back"),
                size,
                usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
            period: f64::from(queue.get_timestamp_period()),
        })
    }

    /// The writes that stamp `stage`'s pass.
    pub fn writes(&self, stage: Stage) -> wgpu::ComputePassTimestampWrites<'_> {
        let at = Stage::ALL.iter().position(|&s| s == stage).unwrap_or(0) as u32;
        wgpu::ComputePassTimestampWrites {
            query_set: &self.queries,
            beginning_of_pass_write_index: Some(2 * at),
            end_of_pass_write_index: Some(2 * at + 1),
        }
    }

    /// Copies the stamps out, after the step's passes.
    pub fn resolve(&self, encoder: &mut wgpu::CommandEncoder) {
        encoder.resolve_query_set(&self.queries, 0..STAMPS, &self.resolved, 0);
        encoder.copy_buffer_to_buffer(&self.resolved, 0, &self.readback, 0, self.resolved.size());
    }

    /// Each stage's seconds in the step just submitted, waiting for it.
    pub fn read(
        &self,
        device: &wgpu::Device,
        bound: &crate::WaitBound,
        what: impl FnOnce() -> String,
    ) -> Result<[f64; STAGES], GpuError> {
        let bytes = read_buffer(device, bound, &self.readback, 8 * STAMPS as usize, what)?;
        let stamps: Vec<u64> = bytemuck::pod_collect_to_vec(&bytes);
        let mut seconds = [0.0; STAGES];
        for (k, s) in seconds.iter_mut().enumerate() {
            let ticks = stamps[2 * k + 1].saturating_sub(stamps[2 * k]);
            *s = ticks as f64 * self.period * 1e-9;
        }
        Ok(seconds)
    }
}
