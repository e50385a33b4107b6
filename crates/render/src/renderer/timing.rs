//! The frame's passes timed on the GPU, where the adapter has timestamp
//! queries and only while someone looks (the profiler is open): the shadow
//! faces, the scene, the effects between them and tone mapping (the
//! occlusion and the bloom), and tone mapping. Read back a frame or two
//! late, without waiting for the GPU: the profiler shows the latest that
//! has come back.
//!
//! Only the slots a frame wrote are resolved. Resolving a slot that no pass
//! wrote is allowed, but some drivers (NVIDIA's on Vulkan) then hold the
//! submission for about 20 s before it completes (wgpu issues 3612, 7238):
//! a frame drawn without shadows writes no shadow stamps, so resolving all
//! six stalled every such frame.

use std::cell::Cell;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

/// How long the GPU spent on each of a frame's passes.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PassTimes {
    /// The shadow faces drawn.
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

/// Which of a frame's timestamp slots were written, and which resolved: a
/// bit a slot.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct StampSlots {
    /// Slots a pass wrote.
    pub written: u32,
    /// Slots resolved into the buffer they are read back through.
    pub resolved: u32,
}

/// The runs of consecutive set bits of `mask`, as slot ranges: what one
/// resolve call each covers.
pub(super) fn runs(mask: u32) -> impl Iterator<Item = std::ops::Range<u32>> {
    let mut slot = 0;
    std::iter::from_fn(move || {
        while slot < 32 && mask & (1 << slot) == 0 {
            slot += 1;
        }
        if slot >= 32 {
            return None;
        }
        let start = slot;
        while slot < 32 && mask & (1 << slot) != 0 {
            slot += 1;
        }
        Some(start..slot)
    })
}
/// Where a resolve may start in its buffer: a multiple of this.
const RUN_ALIGN: u64 = wgpu::QUERY_RESOLVE_BUFFER_ALIGNMENT;

/// Where slot `slot` lies once the runs of `written` are resolved: each
/// run from the boundary of its first slot.
fn resolved_at(written: u32, slot: u32) -> usize {
    let start = runs(written)
        .find(|run| run.contains(&slot))
        .map_or(slot, |run| run.start);
    (RUN_ALIGN * u64::from(start)) as usize + 8 * (slot - start) as usize
}

/// Frames whose timestamps may be on their way back at once.
const IN_FLIGHT: usize = 3;

/// One buffer the timestamps come back in.
struct Readback {
    buffer: wgpu::Buffer,
    /// Set by the map's callback once the values can be read.
    ready: Arc<AtomicBool>,
    /// Whether it waits for its values (mapping asked, not yet read).
    pending: bool,
    /// The slots the frame it holds wrote.
    written: u32,
}

/// The query set and the buffers its values come back through.
pub(super) struct GpuTimer {
    queries: wgpu::QuerySet,
    resolved: wgpu::Buffer,
    readbacks: Vec<Readback>,
    next: usize,
    /// The slots this frame's passes have asked to write so far.
    written: Cell<u32>,
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
        // A run of slots is resolved at the 256-byte boundary of its first
        // slot (resolves must start at one).
        let size = u64::from(STAMPS) * RUN_ALIGN;
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
                written: 0,
            })
            .collect();
        Some(GpuTimer {
            queries,
            resolved,
            readbacks,
            next: 0,
            written: Cell::new(0),
            period: f64::from(queue.get_timestamp_period()),
            latest: None,
        })
    }

    /// The writes that time a pass: the slot where it starts (or none) and
    /// where it ends (or none). Kept, so that only these are resolved.
    pub fn writes(
        &self,
        start: Option<u32>,
        end: Option<u32>,
    ) -> wgpu::RenderPassTimestampWrites<'_> {
        let bit = |slot: Option<u32>| slot.map_or(0, |s| 1 << s);
        self.written.set(self.written.get() | bit(start) | bit(end));
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

    /// Copies the stamps the frame wrote out, to be read once the GPU is
    /// done, and returns which slots were written and resolved.
    pub fn resolve(&mut self, encoder: &mut wgpu::CommandEncoder) -> StampSlots {
        let written = self.written.replace(0);
        let readback = &mut self.readbacks[self.next];
        for run in runs(written) {
            encoder.resolve_query_set(
                &self.queries,
                run.clone(),
                &self.resolved,
                RUN_ALIGN * u64::from(run.start),
            );
        }
        encoder.copy_buffer_to_buffer(&self.resolved, 0, &readback.buffer, 0, self.resolved.size());
        readback.written = written;
        StampSlots {
            written,
            resolved: runs(written)
                .fold(0, |mask, run| run.fold(mask, |mask, slot| mask | 1 << slot)),
        }
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
            let written = readback.written;
            let stamps: Vec<u64> = match readback.buffer.slice(..).get_mapped_range() {
                Ok(view) => (0..STAMPS)
                    .map(|slot| {
                        let at = resolved_at(written, slot);
                        view.get(at..at + 8).map_or(0, bytemuck::pod_read_unaligned)
                    })
                    .collect(),
                Err(_) => vec![0; STAMPS as usize],
            };
            readback.buffer.unmap();
            readback.pending = false;
            // A pass whose stamps were not both written took no time.
            let span = |a: usize, b: usize| {
                if written & (1 << a) == 0 || written & (1 << b) == 0 {
                    return Duration::ZERO;
                }
                let ticks = stamps[b].saturating_sub(stamps[a]) as f64;
                Duration::from_nanos((ticks * self.period) as u64)
            };
            self.latest = Some(PassTimes {
                shadow: span(0, 1),
                scene: span(2, 3),
                effects: span(3, 4),
                tonemap: span(4, 5),
            });
        }
        self.latest
    }
}

#[cfg(test)]
mod tests {
    use super::runs;

    #[test]
    fn runs_cover_exactly_the_set_bits() {
        for mask in [
            0u32,
            0b1,
            0b11_1100,
            0b11_1111,
            0b10_1101,
            1 << 31,
            u32::MAX,
        ] {
            let ranges: Vec<_> = runs(mask).collect();
            let covered = ranges
                .iter()
                .flat_map(|r| r.clone())
                .fold(0u32, |m, slot| m | 1 << slot);
            assert_eq!(covered, mask, "{mask:#b}: {ranges:?}");
            // Maximal: no two runs touch.
            for pair in ranges.windows(2) {
                assert!(pair[0].end < pair[1].start, "{mask:#b}: {ranges:?}");
            }
        }
        assert_eq!(runs(0b11_1100).collect::<Vec<_>>(), vec![2..6]);
    }

    #[test]
    fn each_slot_is_read_where_its_run_was_resolved() {
        use super::{RUN_ALIGN, resolved_at};
        let align = RUN_ALIGN as usize;
        assert_eq!(resolved_at(0b11_1111, 5), 40);
        assert_eq!(resolved_at(0b11_1100, 2), 2 * align);
        assert_eq!(resolved_at(0b11_1100, 5), 2 * align + 24);
        assert_eq!(resolved_at(0b11_0011, 4), 4 * align);
        assert_eq!(resolved_at(0b11_0011, 1), 8);
    }
}
