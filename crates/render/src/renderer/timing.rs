//! The frame's passes timed on the GPU, where the adapter has timestamp
//! queries: the shadow faces, the scene, the effects between them and tone
//! mapping (the occlusion and the bloom), and tone mapping. Read back a
//! frame or two late, without waiting for the GPU: the profiler shows the
//! latest that has come back.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

/// How long the GPU spent on each of a frame's passes.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PassTimes {
    /// The six shadow faces.
    pub shadow: Duration,
    /// The lit scene, the debug lines and the see-through particles.
    pub scene: Duration,
    /// The contact occlusion and the bloom's chain.
    pub effects: Duration,
    /// Tone mapping and the cursor.
    pub tonemap: Duration,
}

impl PassTimes {
    /// The passes' names and times, in the frame's order.
    pub fn named(&self) -> [(&'static str, Duration); 4] {
        [
            ("shadow", self.shadow),
            ("scene", self.scene),
            ("effects", self.effects),
            ("tone map", self.tonemap),
        ]
    }
}

/// Timestamps a frame writes: the shadow faces' start and end, the
/// scene's, tone mapping's.
const STAMPS: u32 = 6;
/// Frames whose timestamps may be on their way back at once.
const IN_FLIGHT: usize = 3;

/// One buffer the timestamps come back in.
struct Readback {
    buffer: wgpu::Buffer,
    /// Set by the map's callback once the values can be read.
    ready: Arc<AtomicBool>,
    /// Whether it waits for its values (mapping asked, not yet read).
    pending: bool,
    /// Whether the frame it holds drew shadows.
    shadows: bool,
}

/// The query set and the buffers its values come back through.
pub(super) struct GpuTimer {
    queries: wgpu::QuerySet,
    resolved: wgpu::Buffer,
    readbacks: Vec<Readback>,
    next: usize,
    /// Nanoseconds per timestamp tick.
    period: f64,
    latest: Option<PassTimes>,
}

impl GpuTimer {
    /// A timer, if the device can write timestamps.
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue) -> Option<GpuTimer> {
        if !device.features().contains(wgpu::Features::TIMESTAMP_QUERY) {
            return None;
        }
        let size = u64::from(STAMPS) * 8;
        let queries = device.create_query_set(&wgpu::QuerySetDescriptor {
            label: Some("pass timestamps"),
            ty: wgpu::QueryType::Timestamp,
            count: STAMPS,
        });
        let resolved = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("timestamps resolved"),
            size,
            usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let readbacks = (0..IN_FLIGHT)
            .map(|_| Readback {
                buffer: device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("timestamps read back"),
                    size,
                    usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                }),
                ready: Arc::new(AtomicBool::new(false)),
                pending: false,
                shadows: false,
            })
            .collect();
        Some(GpuTimer {
            queries,
            resolved,
            readbacks,
            next: 0,
            period: f64::from(queue.get_timestamp_period()),
            latest: None,
        })
    }

    /// The writes that time a pass: `first` is where it starts (or none)
    /// and `first + 1` where it ends (or none).
    pub fn writes(
        &self,
        start: Option<u32>,
        end: Option<u32>,
    ) -> wgpu::RenderPassTimestampWrites<'_> {
        wgpu::RenderPassTimestampWrites {
            query_set: &self.queries,
            beginning_of_pass_write_index: start,
            end_of_pass_write_index: end,
        }
    }

    /// Whether this frame's stamps have a buffer to come back in.
    pub fn free(&self) -> bool {
        !self.readbacks[self.next].pending
    }

    /// Copies the frame's stamps out, to be read once the GPU is done.
    pub fn resolve(&mut self, encoder: &mut wgpu::CommandEncoder, shadows: bool) {
        let readback = &mut self.readbacks[self.next];
        encoder.resolve_query_set(&self.queries, 0..STAMPS, &self.resolved, 0);
        encoder.copy_buffer_to_buffer(&self.resolved, 0, &readback.buffer, 0, self.resolved.size());
        readback.shadows = shadows;
    }

    /// After the frame is submitted: asks for its stamps back.
    pub fn submitted(&mut self) {
        let readback = &mut self.readbacks[self.next];
        readback.pending = true;
        readback.ready.store(false, Ordering::Release);
        let ready = Arc::clone(&readback.ready);
        readback
            .buffer
            .slice(..)
            .map_async(wgpu::MapMode::Read, move |result| {
                if result.is_ok() {
                    ready.store(true, Ordering::Release);
                }
            });
        self.next = (self.next + 1) % IN_FLIGHT;
    }

    /// Reads whatever stamps have come back (without waiting), and returns
    /// the latest frame's pass times.
    pub fn collect(&mut self, device: &wgpu::Device) -> Option<PassTimes> {
        let _ = device.poll(wgpu::PollType::Poll);
        for readback in &mut self.readbacks {
            if !readback.pending || !readback.ready.load(Ordering::Acquire) {
                continue;
            }
            let stamps: Vec<u64> = match readback.buffer.slice(..).get_mapped_range() {
                Ok(view) => bytemuck::cast_slice(&view).to_vec(),
                Err(_) => vec![0; STAMPS as usize],
            };
            readback.buffer.unmap();
            readback.pending = false;
            let span = |a: usize, b: usize| {
                let ticks = stamps[b].saturating_sub(stamps[a]) as f64;
                Duration::from_nanos((ticks * self.period) as u64)
            };
            self.latest = Some(PassTimes {
                shadow: if readback.shadows {
                    span(0, 1)
                } else {
                    Duration::ZERO
                },
                scene: span(2, 3),
                effects: span(3, 4),
                tonemap: span(4, 5),
            });
        }
        self.latest
    }
}
