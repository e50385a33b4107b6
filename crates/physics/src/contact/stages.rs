//! The solver's two stages per step, predict and project (see the
//! module above for what each does).

use super::warm::{Held, StageFriction, WarmStart};
use crate::balls::Balls;
use crate::impulses::BallImpulses;

use super::{
    Bodies, Contact, Contacts, Crowd, FrictionImpulse, Pair, PairMaterial, RowStart, TOUCHING,
};

/// One step as the solver stages see it (after Box2D's step context): the
/// step's settings, the bodies and contacts they work on, last step's
/// impulses to start from and where this step's are recorded.
pub(crate) struct StepContext<'a> {
    pub dt: f64,
    /// Gauss-Seidel sweeps per stage.
    pub iterations: usize,
    /// Below this approach speed (m/s) an impact rests instead of bouncing.
    pub bounce_threshold: f64,
    pub ball_restitution: f64,
    /// Friction and rolling resistance between two balls.
    pub ball_material: PairMaterial,
    pub bodies: Bodies<'a>,
    pub contacts: &'a mut Contacts,
    pub crowd: &'a mut Crowd,
    /// Per ball: bounced off a wall while moving this step.
    pub hit_wall: &'a [bool],
    /// Last step's impulses, and each slot's ball number, if warm started.
    pub warm: Option<(&'a WarmStart, &'a [u32])>,
    /// Where this step's impulses are recorded.
    pub record: &'a mut WarmStart,
    /// Each slot's ball number.
    pub ids: &'a [u32],
}

/// Stage 1: speculative, non-penetrating velocities for the coming step.
///
/// A lone impact on a tumbler due within the step bounces here already, at
/// its full approach speed: a tumbler's response to an impulse changes as it
/// turns, and splitting one impact over two configurations could create
/// energy.
///
/// With `warm` (last step's impulses and each slot's ball number) pairs and
/// ball-wall contacts start from the impulse that held them last step; the
/// impulses they end with are kept for [`solve_project`] to record.
///
/// `hand(pair, balls)` finishes each pair before anything reads it: the
/// impacts resolved before this stage hand it their outcome.
///
/// Returns what the walls and tumblers gave the balls over the stage.
pub(crate) fn solve_predict(
    step: &mut StepContext,
    hand: &(dyn Fn(&mut Pair, &Balls) + Sync),
) -> BallImpulses {
    let StepContext {
        dt,
        iterations,
        bounce_threshold,
        ball_material,
        ref mut bodies,
        ref mut contacts,
        ref mut crowd,
        warm,
        ..
    } = *step;
    // Every ball within reach counts against a bounce, touching or not: a
    // ball sent back by a tumbler may meet a neighbour it was leaving, and
    // pressing it would make the bounce pump energy. Other contacts count
    // once they touch within the step.
    let touching =
        |gap: f64, approach: f64, kick: f64| gap + (approach + kick).min(0.0) * dt <= TOUCHING;
    // Pairs never bounce here, so all start warm. One lookup finds the
    // project stage's start too. The rows are built before the crowd reads
    // the pairs, each pair handed its impacts' outcome first, and they
    // start once the other contacts are ready.
    // Friction between balls acts here, as the walls' does, in the last
    // half of the stage's sweeps (see [`PROJECT_FRICTION_SWEEPS`]).
    let balls = &*bodies.balls;
    let friction = ball_material.any();
    contacts.build_rows(balls, ball_material, |p| {
        hand(p, balls);
        let target = if p.gap > 0.0 { -p.gap / dt } else { 0.0 };
        let (held, kept_friction) = warm_pair(warm, p, friction);
        p.project_start = held[Stage::Project as usize];
        Some(RowStart {
            target,
            impulse: share(warm, held[Stage::Predict as usize]),
            friction: friction.then_some(kept_friction[Stage::Predict as usize]),
        })
    });
    // Only a tumbler's contacts may bounce here, so only they ask the crowd.
    let may_bounce = !contacts.tumbler_contacts.is_empty();
    crowd.forget_asked(bodies.balls.len());
    if may_bounce {
        crowd.gather(contacts, bodies.tumblers.len(), false, |_| true);
    }
    for c in contacts.walls.iter_mut() {
        c.impulse = 0.0;
        if may_bounce {
            // Gravity's half step, which the wall does not share.
            let kick = bodies.balls.velocity[c.ball as usize].dot(c.normal()) - c.approach;
            if touching(c.gap, c.approach, kick) {
                crowd.add_wall(c);
            }
        }
    }
    for c in contacts.tumbler_contacts.iter_mut() {
        bodies.prepare(c);
        c.impulse = 0.0;
        // Gravity's half step, which the contact's two sides may not share.
        c.kick = bodies.normal_velocity(c) - c.approach;
        if touching(c.gap, c.approach, c.kick) {
            crowd.add(c);
        }
    }
    for c in contacts.tumbler_contacts.iter_mut() {
        c.bounce =
            c.approach < -bounce_threshold && c.gap + c.approach * dt <= 0.0 && crowd.lone(c);
    }
    contacts.start_rows(bodies.balls);
    if let Some((warm, ids)) = warm {
        warm_start_walls(bodies.balls, contacts, warm, ids, Stage::Predict);
    }
    let closing = |gap: f64| if gap > 0.0 { -gap / dt } else { 0.0 };
    let target = |c: &Contact| {
        if c.bounce {
            c.kick - c.restitution * c.approach
        } else {
            closing(c.gap)
        }
    };
    let friction = bodies.wall_friction;
    contacts.start_wall_rows(bodies.balls, |c| Some((closing(c.gap), friction)));
    let friction_sweeps = iterations.div_ceil(2);
    for k in 0..iterations {
        contacts.sweep_wall_rows(bodies.balls);
        contacts.sweep_rows(bodies.balls, k + friction_sweeps >= iterations);
        contacts.sweep_tumblers(bodies, |c, bodies| {
            bodies.solve_normal(c, target(c));
            bodies.solve_friction(c);
        });
    }
    let given = BallImpulses {
        surfaces: contacts.keep_wall_impulses(|_| true),
        tumblers: contacts.tumbler_impulse_on_balls(|_| true),
        ..BallImpulses::default()
    };
    // The project stage asks about the balls of contacts that pushed
    // against a fast approach: only those may bounce.
    let fast = |pushed: f64, approach: f64| pushed > 0.0 && approach < -bounce_threshold;
    let crowd = &*crowd;
    contacts.keep_predicted_impulses(|p: &mut Pair, impulse: f64| {
        p.pushed = impulse > 0.0;
        if fast(impulse, p.approach) {
            crowd.will_ask(p.i);
            crowd.will_ask(p.j);
        }
    });
    for c in contacts.tumbler_contacts.iter_mut() {
        c.pushed = c.impulse;
    }
    for c in contacts.walls.iter_mut() {
        c.pushed = c.impulse;
        if fast(c.pushed, c.approach) {
            crowd.will_ask(c.ball);
        }
    }
    given
}

/// The two solver stages, each warm-started from its own impulses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Stage {
    Predict,
    Project,
}

impl Stage {
    /// Whether the stage solves contact `pushed`/`bounce`; bouncing contacts
    /// start cold, their impulse is of this impact alone.
    fn warm_starts(self, pushed: f64, bounce: bool) -> bool {
        !bounce && (self == Stage::Predict || pushed > 0.0)
    }
}

/// Last step's impulses of pair `p` as kept, if there is a warm start,
/// and with `friction` its friction impulses as a start.
fn warm_pair(
    warm: Option<(&WarmStart, &[u32])>,
    p: &Pair,
    friction: bool,
) -> (Held, StageFriction) {
    let Some((warm, ids)) = warm else {
        return (Held::default(), StageFriction::default());
    };
    let (a, b) = (ids[p.i as usize], ids[p.j as usize]);
    if friction {
        warm.pair_with_friction(a, b)
    } else {
        (warm.pair(a, b), StageFriction::default())
    }
}

/// The impulse to start from, given one kept (0 without a warm start).
fn share(warm: Option<(&WarmStart, &[u32])>, impulse: f32) -> f64 {
    warm.map_or(0.0, |(warm, _)| warm.share(impulse))
}

/// Starts ball-wall contacts from last step's impulses.
fn warm_start_walls(
    balls: &mut Balls,
    contacts: &mut Contacts,
    warm: &WarmStart,
    ids: &[u32],
    stage: Stage,
) {
    for c in contacts.walls.iter_mut() {
        if !stage.warm_starts(c.pushed, c.bounce) {
            continue;
        }
        let i = c.ball as usize;
        let impulse = warm.share(warm.wall(ids[i], c.surface)[stage as usize]);
        if impulse > 0.0 {
            c.impulse = impulse;
            balls.velocity[i] += c.normal() * (impulse * balls.inv_mass[i]);
        }
    }
}

/// How many of the project stage's last sweeps solve friction between
/// balls (the predict stage's last half do). Friction's limits are the
/// normal impulses, which the sweeps before find; the project stage only
/// ends contacts at rest or bouncing, and friction there keeps a heap's
/// weight, spread by the normal rows, from pressing its balls sideways, for
/// which two sweeps suffice. Heaps stand as steep as with friction in every
/// sweep, and a 10 000-ball pit with friction steps some 30 % faster (its
/// deepest overlap 4.9 mm instead of 3.6): docs/performance.md.
const PROJECT_FRICTION_SWEEPS: usize = 2;

/// Stage 2: contacts that pushed end bouncing or resting.
///
/// A lone impact between balls, or of a ball on a wall, bounces to the speed
/// its restitution gives the approach measured before the step (so a pair
/// obeys the 1-D formulas exactly); every other contact that pushed ends at
/// rest. A ball that bounced off a wall while moving has spent its approach
/// already: `hit_wall` marks those, and their contacts only stop.
///
/// Warm started from `warm` as the predict stage. The impulses of both
/// stages are recorded into `record` for the next step's warm start.
/// Returns what the walls and tumblers gave the balls over the stage.
pub(crate) fn solve_project(step: &mut StepContext) -> BallImpulses {
    let StepContext {
        iterations,
        bounce_threshold,
        ball_restitution,
        ball_material,
        ref mut bodies,
        ref mut contacts,
        ref mut crowd,
        hit_wall,
        warm,
        ref mut record,
        ids,
        ..
    } = *step;
    crowd.gather(contacts, bodies.tumblers.len(), true, |p| p.pushed);
    for c in contacts.tumbler_contacts.iter().filter(|c| c.pushed > 0.0) {
        crowd.add_if_asked(c);
    }
    for c in contacts.walls.iter().filter(|c| c.pushed > 0.0) {
        if crowd.asked(c.ball as usize) {
            crowd.add_wall(c);
        }
    }
    // A tumbler's contacts bounced in the predict stage already.
    for c in contacts.tumbler_contacts.iter_mut() {
        c.bounce = false;
        c.impulse = 0.0;
        if c.pushed > 0.0 {
            bodies.prepare(c);
        }
    }
    for c in contacts.walls.iter_mut() {
        c.bounce = c.pushed > 0.0
            && c.approach < -bounce_threshold
            && !hit_wall[c.ball as usize]
            && crowd.lone_wall(c);
        c.impulse = 0.0;
    }
    // Only the pairs that pushed take part.
    // A bouncing pair starts cold: its impulse is of this impact alone.
    let crowd = &*crowd;
    // Friction holds here too, warm started as the normal rows: a pile
    // that friction holds would otherwise end the step pressed sideways by
    // its normal rows alone.
    let friction = ball_material.any();
    contacts.build_rows(bodies.balls, ball_material, |p| {
        p.pushed.then(|| {
            let bounce = p.approach < -bounce_threshold
                && !hit_wall[p.i as usize]
                && !hit_wall[p.j as usize]
                && crowd.lone_pair(p);
            let (target, impulse) = if bounce {
                (-ball_restitution * p.approach, 0.0)
            } else {
                (0.0, share(warm, p.project_start))
            };
            let kept_friction = if friction && !bounce {
                warm_pair(warm, p, true).1[Stage::Project as usize]
            } else {
                FrictionImpulse::default()
            };
            RowStart {
                target,
                impulse,
                friction: friction.then_some(kept_friction),
            }
        })
    });
    contacts.start_rows(bodies.balls);
    if let Some((warm, ids)) = warm {
        warm_start_walls(bodies.balls, contacts, warm, ids, Stage::Project);
    }
    // Contacts end bouncing or at rest. Where balls hold one another by
    // friction, the floor's friction holds them here too: else a heap's
    // weight, spread by the normal rows, would slide its foot outwards.
    let restitution = bodies.wall_restitution;
    let wall_friction = if ball_material.friction > 0.0 {
        bodies.wall_friction
    } else {
        0.0
    };
    contacts.start_wall_rows(bodies.balls, |c| {
        let target = if c.bounce {
            -restitution * c.approach
        } else {
            0.0
        };
        (c.pushed > 0.0).then_some((target, wall_friction))
    });
    for k in 0..iterations {
        contacts.sweep_wall_rows(bodies.balls);
        let friction = k + PROJECT_FRICTION_SWEEPS >= iterations;
        contacts.sweep_rows(bodies.balls, friction);
        contacts.sweep_tumblers(bodies, |c, bodies| {
            if c.pushed > 0.0 {
                bodies.solve_normal(c, 0.0);
                bodies.solve_friction(c);
            }
        });
    }
    contacts.record_row_impulses((&mut **record, ids));
    let given = BallImpulses {
        surfaces: contacts.keep_wall_impulses(|c| c.pushed > 0.0),
        // Only the contacts that pushed were solved: the others keep the
        // predict stage's friction.
        tumblers: contacts.tumbler_impulse_on_balls(|c| c.pushed > 0.0),
        ..BallImpulses::default()
    };
    for c in &contacts.walls {
        record.record_wall(c.ball as usize, c.surface, [c.pushed, c.impulse]);
    }
    given
}
