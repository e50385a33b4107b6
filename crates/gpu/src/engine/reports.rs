//! The step reports on their way back. What the CPU needs from a step
//! (the tumblers' pushes, the fireball's catches, the balls' impacts) is
//! copied into a buffer of a small ring and mapped without blocking; the
//! CPU takes it [`REPORT_DELAY`] steps later, by when a GPU that keeps up
//! has long written it. So steps are queued ahead and neither side waits
//! for the other: the CPU records the next step while the GPU runs the
//! last.
//!
//! The delay is counted in steps, never in time: a report is taken at the
//! same step whether the GPU was early or late (late, the CPU waits for
//! it, and the wait is counted), so reruns give the same bits.

use std::collections::VecDeque;
use std::sync::{Arc, OnceLock};

use glam::DVec3;
use rolypoly_physics::{Event, EventKind, Surface};
use serde::{Deserialize, Serialize};

use crate::GpuError;
use crate::layout::{
    Catch, EVENT_CAPACITY, FIREBALL, HIT_BALL, HIT_BODY, HIT_WALL, IMPACT_CAPACITY, Impact,
};
use crate::wait::{WaitBound, WaitError};

/// Steps between a step and the taking of its report. Two: at the
/// scene's 120 steps a second, a 60 Hz display queues two steps a frame,
/// and a report two steps old is the frame before's, done while that frame
/// was shown. The tumblers feel the balls' pushes two steps later than on
/// a report read at once (16.7 ms at 120 steps a second); the effects and
/// the sound hear the impacts as late.
pub const REPORT_DELAY: u64 = 2;

/// A step's report, read back: what the CPU applies and hands on.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct StepReport {
    /// The step it reports (counted from 0).
    pub step: u64,
    /// Each tumbler's push: the impulse (N s), its moment about the
    /// tumbler's bottom centre (N m s), the mass of the balls that pushed
    /// (kg).
    pub pushes: Vec<(DVec3, DVec3, f64)>,
    /// The catches, by ball, then the impacts (where the engine listened)
    /// in time order.
    pub events: Vec<Event>,
    /// Impacts past the step's capacity, counted and not reported.
    pub impacts_dropped: u64,
}

/// A report still on the GPU: its buffer of the ring, and the mapping
/// asked for.
struct InFlight {
    buffer: usize,
    /// Set by the mapping's callback, run in a poll of the device.
    mapped: Arc<OnceLock<Result<(), wgpu::BufferAsyncError>>>,
    submission: wgpu::SubmissionIndex,
    /// Whether the step copied its impacts.
    listened: bool,
}

/// A step's report, on its way back or read.
enum Pending {
    InFlight(u64, InFlight),
    Read(StepReport),
}

impl Pending {
    fn step(&self) -> u64 {
        match self {
            Pending::InFlight(step, _) => *step,
            Pending::Read(report) => report.step,
        }
    }
}

/// The ring of report buffers and the reports not yet taken, oldest first.
pub struct ReportRing {
    buffers: Vec<wgpu::Buffer>,
    free: Vec<usize>,
    pending: VecDeque<Pending>,
    tumblers: usize,
    /// Times a report was not back when due and the CPU waited for it.
    waits: u64,
}

impl ReportRing {
    /// A ring for reports of `tumblers` tumblers: one buffer a step on its
    /// way and one being written.
    pub fn new(device: &wgpu::Device, tumblers: usize) -> ReportRing {
        let mut ring = ReportRing {
            buffers: Vec::new(),
            free: Vec::new(),
            pending: VecDeque::new(),
            tumblers,
            waits: 0,
        };
        for _ in 0..=REPORT_DELAY {
            ring.grow(device);
        }
        ring
    }

    fn grow(&mut self, device: &wgpu::Device) {
        self.free.push(self.buffers.len());
        self.buffers
            .push(device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("step report"),
                size: report_size(self.tumblers),
                usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }));
    }

    /// Times a report was not back when due and the CPU waited for it.
    pub fn waits(&self) -> u64 {
        self.waits
    }

    /// A free buffer of the ring (a new one if every one is on its way,
    /// which a ring of `REPORT_DELAY + 1` never is), for the step being
    /// recorded to copy its report into.
    pub fn take_buffer(&mut self, device: &wgpu::Device) -> (usize, &wgpu::Buffer) {
        if self.free.is_empty() {
            self.grow(device);
        }
        let buffer = self.free.pop().expect("a free buffer, grown if none");
        (buffer, &self.buffers[buffer])
    }

    /// Records that step `step`, submitted as `submission`, copies its
    /// report into `buffer` (impacts too where `listened`), and asks for
    /// the buffer mapped once the GPU has written it.
    pub fn sent(
        &mut self,
        step: u64,
        buffer: usize,
        listened: bool,
        submission: wgpu::SubmissionIndex,
    ) {
        let mapped = Arc::new(OnceLock::new());
        let set = Arc::clone(&mapped);
        self.buffers[buffer]
            .slice(..)
            .map_async(wgpu::MapMode::Read, move |result| {
                let _ = set.set(result);
            });
        self.pending.push_back(Pending::InFlight(
            step,
            InFlight {
                buffer,
                mapped,
                submission,
                listened,
            },
        ));
    }

    /// The reports due once `steps` steps have been submitted: those of
    /// steps up to `steps - 1 - REPORT_DELAY`, oldest first. One not back
    /// yet is waited for, and the wait counted.
    pub fn due(
        &mut self,
        device: &wgpu::Device,
        bound: &WaitBound,
        steps: u64,
    ) -> Result<Vec<StepReport>, GpuError> {
        let mut due = Vec::new();
        while let Some(front) = self.pending.front() {
            if front.step() + REPORT_DELAY >= steps {
                break;
            }
            let report = match self.pending.pop_front() {
                Some(Pending::InFlight(step, flight)) => self.read(device, bound, step, flight)?,
                Some(Pending::Read(report)) => report,
                None => break,
            };
            due.push(report);
        }
        Ok(due)
    }

    /// Waits for every report on its way and reads it, keeping it to be
    /// taken when due (a snapshot's, or a run's last steps').
    pub fn read_all(&mut self, device: &wgpu::Device, bound: &WaitBound) -> Result<(), GpuError> {
        // Waiting here is the caller's asking, not a step's: not counted.
        let waits = self.waits;
        for pending in std::mem::take(&mut self.pending) {
            let read = match pending {
                Pending::InFlight(step, flight) => {
                    Pending::Read(self.read(device, bound, step, flight)?)
                }
                read => read,
            };
            self.pending.push_back(read);
        }
        self.waits = waits;
        Ok(())
    }

    /// Every report not yet taken, read (see [`ReportRing::read_all`]).
    pub fn read_reports(&self) -> impl Iterator<Item = &StepReport> {
        self.pending.iter().filter_map(|p| match p {
            Pending::Read(report) => Some(report),
            Pending::InFlight(..) => None,
        })
    }

    /// The events of every report read and not yet taken, moved out (their
    /// pushes are still given when due).
    pub fn take_read_events(&mut self, into: &mut Vec<Event>) {
        for pending in &mut self.pending {
            if let Pending::Read(report) = pending {
                into.append(&mut report.events);
            }
        }
    }

    /// Puts `reports` in place of the reports not yet taken (a snapshot's,
    /// put back), once those on their way are back.
    pub fn replace(
        &mut self,
        device: &wgpu::Device,
        bound: &WaitBound,
        reports: &[StepReport],
    ) -> Result<(), GpuError> {
        self.read_all(device, bound)?;
        self.pending = reports.iter().cloned().map(Pending::Read).collect();
        Ok(())
    }

    fn read(
        &mut self,
        device: &wgpu::Device,
        bound: &WaitBound,
        step: u64,
        flight: InFlight,
    ) -> Result<StepReport, GpuError> {
        if flight.mapped.get().is_none() {
            // The callback runs in a poll: one that does not block first.
            let _ = device.poll(wgpu::PollType::Poll);
        }
        if flight.mapped.get().is_none() {
            self.waits += 1;
            bound.wait(device, Some(flight.submission), || {
                format!(
                    "the gpu engine's step {} (its report of tumbler pushes, catches and impacts)",
                    step + 1
                )
            })?;
        }
        let buffer = &self.buffers[flight.buffer];
        flight
            .mapped
            .get()
            .ok_or_else(|| WaitError::Failed {
                what: "a step report's mapping".into(),
                message: "the GPU finished but the buffer was not mapped".into(),
            })?
            .clone()
            .map_err(|e| GpuError::Readback(e.to_string()))?;
        let report = {
            let bytes = buffer
                .slice(..)
                .get_mapped_range()
                .map_err(|e| GpuError::Readback(e.to_string()))?;
            parse(&bytes, step, self.tumblers, flight.listened)
        };
        buffer.unmap();
        self.free.push(flight.buffer);
        Ok(report)
    }
}

/// A report's bytes, as a [`StepReport`].
fn parse(bytes: &[u8], step: u64, tumblers: usize, listened: bool) -> StepReport {
    let word =
        |at: usize| u32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]]);
    let push: Vec<[f32; 4]> = bytemuck::pod_collect_to_vec(&bytes[..32 * tumblers]);
    let xyz = |[x, y, z, _]: [f32; 4]| DVec3::new(x.into(), y.into(), z.into());
    let pushes = (0..tumblers)
        .map(|t| {
            (
                xyz(push[2 * t]),
                xyz(push[2 * t + 1]),
                push[2 * t][3].into(),
            )
        })
        .collect();

    let at = 32 * tumblers;
    let count = (word(at) as usize).min(EVENT_CAPACITY as usize);
    let end = at + 16 + count * std::mem::size_of::<Catch>();
    let caught: Vec<Catch> = bytemuck::pod_collect_to_vec(&bytes[at + 16..end]);
    let mut events: Vec<Event> = caught
        .iter()
        .map(|c| {
            let [px, py, pz, ball] = c.point;
            let [nx, ny, nz, speed] = c.normal;
            Event {
                kind: EventKind::FireballBall {
                    ball: ball.to_bits() as usize,
                },
                point: DVec3::new(px.into(), py.into(), pz.into()),
                normal: DVec3::new(nx.into(), ny.into(), nz.into()),
                speed: speed.into(),
                // The GPU engine does not say when within the step.
                within_step: 0.0,
            }
        })
        .collect();
    // The atomics set the order they were written in; the ball's number
    // sets the order they are reported in.
    events.sort_by_key(|e| match e.kind {
        EventKind::FireballBall { ball } => ball,
        _ => usize::MAX,
    });

    let mut impacts_dropped = 0;
    if listened {
        let at = impacts_at(tumblers) as usize;
        let count = word(at);
        let taken = (count as usize).min(IMPACT_CAPACITY as usize);
        let end = at + 16 + taken * std::mem::size_of::<Impact>();
        let impacts: Vec<Impact> = bytemuck::pod_collect_to_vec(&bytes[at + 16..end]);
        let first = events.len();
        events.extend(impacts.iter().filter_map(impact_event));
        // In the atomics' order as written: put in the order of when within
        // the step, then the ball's and the other's numbers, then (a ball
        // may report one contact twice at one moment: its bounce in the
        // impacts, and the solver's push) every other number.
        events[first..].sort_by(|a, b| {
            let numbers = |e: &Event| {
                [e.speed, e.point.x, e.point.y, e.point.z]
                    .into_iter()
                    .chain([e.normal.x, e.normal.y, e.normal.z])
            };
            a.within_step
                .total_cmp(&b.within_step)
                .then_with(|| impact_key(a).cmp(&impact_key(b)))
                .then_with(|| {
                    numbers(a)
                        .zip(numbers(b))
                        .map(|(x, y)| x.total_cmp(&y))
                        .find(|o| o.is_ne())
                        .unwrap_or(std::cmp::Ordering::Equal)
                })
        });
        impacts_dropped = u64::from(count).saturating_sub(IMPACT_CAPACITY);
    }
    StepReport {
        step,
        pushes,
        events,
        impacts_dropped,
    }
}

/// Bytes of a step report: two vectors a tumbler, the catch count (padded
/// to 16), the catches, the impact count (padded to 16), the impacts.
pub fn report_size(tumblers: usize) -> u64 {
    impacts_at(tumblers) + 16 + IMPACT_CAPACITY * std::mem::size_of::<Impact>() as u64
}

/// Where the catch count starts in a step report.
pub fn catches_at(tumblers: usize) -> u64 {
    32 * tumblers as u64
}

/// Where the impact count starts in a step report.
pub fn impacts_at(tumblers: usize) -> u64 {
    catches_at(tumblers) + 16 + EVENT_CAPACITY * std::mem::size_of::<Catch>() as u64
}

/// What orders a step's impacts reported at the same moment: the ball,
/// then what it met.
fn impact_key(e: &Event) -> (usize, u8, usize) {
    match e.kind {
        EventKind::BallSurface { ball, surface } => (ball, 0, surface.index()),
        EventKind::BallBall { a, b } => (a, 1, b),
        EventKind::BallTumbler {
            ball,
            tumbler,
            sphere,
        } => (ball, 2, tumbler * 64 + sphere),
        _ => (usize::MAX, 3, 0),
    }
}

/// An impact as the step reported it, as an event; `None` for a ball's
/// bounce off the fireball, which the CPU engine does not report either.
fn impact_event(impact: &Impact) -> Option<Event> {
    let [px, py, pz, ball] = impact.point;
    let [nx, ny, nz, speed] = impact.normal;
    let [hit, other, within, _] = impact.info;
    let ball = ball.to_bits() as usize;
    let kind = match hit {
        HIT_WALL => EventKind::BallSurface {
            ball,
            surface: *Surface::ALL.get(other as usize)?,
        },
        HIT_BALL => EventKind::BallBall {
            a: ball,
            b: other as usize,
        },
        HIT_BODY if other & 0xffff != FIREBALL => EventKind::BallTumbler {
            ball,
            tumbler: (other & 0xffff) as usize,
            sphere: (other >> 16) as usize,
        },
        _ => return None,
    };
    Some(Event {
        kind,
        point: DVec3::new(px.into(), py.into(), pz.into()),
        normal: DVec3::new(nx.into(), ny.into(), nz.into()),
        speed: speed.into(),
        within_step: f32::from_bits(within).into(),
    })
}
