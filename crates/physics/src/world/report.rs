//! Step 5's reports: events and colours from the contacts that pushed.

use crate::balls::Tint;
use crate::contact::{BodyRef, Pair};
use crate::events::{Event, EventKind};

use super::World;

impl World {
    /// Events and colours from the contacts that pushed this step.
    pub(super) fn report_contacts(&mut self) {
        let threshold = self.config.solver.event_threshold;
        let dt = self.config.solver.dt;
        let hits = &mut self.scratch.picked_pairs;
        let hit = |p: &Pair| p.pushed && -p.approach > threshold;
        self.contacts.copy_pairs_where(hit, hits);
        for p in hits.iter() {
            let (i, j) = (p.i as usize, p.j as usize);
            let gap = p.gap.max(0.0);
            self.events.push(Event {
                kind: EventKind::BallBall { a: i, b: j },
                point: self.balls.position[j] + p.normal * (self.balls.radius[j] + 0.5 * gap),
                normal: p.normal,
                speed: -p.approach,
                within_step: closing_time(p.gap, p.approach, dt),
            });
        }
        for c in &self.contacts.walls {
            if c.pushed <= 0.0 || -c.approach <= threshold {
                continue;
            }
            let (i, s) = (c.ball as usize, c.surface);
            self.balls.tint[i] = Tint::Surface(s);
            self.events.push(Event {
                kind: EventKind::BallSurface {
                    ball: i,
                    surface: s,
                },
                // Where the ball meets the wall.
                point: self.room.foot(s, self.balls.position[i]),
                normal: c.normal(),
                speed: -c.approach,
                within_step: closing_time(c.gap, c.approach, dt),
            });
        }
        for c in &self.contacts.tumbler_contacts {
            if c.pushed <= 0.0 || -c.approach <= threshold {
                continue;
            }
            let kind = match (c.a, c.b) {
                (BodyRef::Ball(i), BodyRef::Tumbler(t, s)) => {
                    self.balls.tint[i] = Tint::Tumbler(t);
                    EventKind::BallTumbler {
                        ball: i,
                        tumbler: t,
                        sphere: s,
                    }
                }
                _ => continue,
            };
            self.events.push(Event {
                kind,
                point: c.point,
                normal: c.normal,
                speed: -c.approach,
                within_step: closing_time(c.gap, c.approach, dt),
            });
        }
    }
}

/// When a contact the solver pushed met, seconds into a step of `dt`: its
/// gap closed at its approach speed (an overlap met at the start).
fn closing_time(gap: f64, approach: f64, dt: f64) -> f64 {
    (gap.max(0.0) / (-approach).max(f64::MIN_POSITIVE)).min(dt)
}
