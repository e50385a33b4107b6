//! Stage 3, the impacts (`impacts.wgsl`): rounds in which each ball
//! meets the contact it touches first, if that contact's other side meets
//! it first too, so that impacts come one after another in time order and
//! a blow passes from ball to ball within the step. One dispatch ends each
//! round and starts the next: each ball works out its neighbours' bounces
//! as they do, rather than waiting for another dispatch to write them.
//! The last also gives the solver its start (`warm_start.wgsl`).

use super::{Kernel, Recorder, Shaders};
use crate::layout::IMPACT_ROUNDS;
use crate::profile::Stage;

pub struct Impacts {
    /// The dispatch that starts each round, and last the one that ends
    /// the last round.
    meet: Vec<Kernel>,
    in_one_group: Kernel,
}

impl Impacts {
    pub fn new(shaders: &Shaders) -> Impacts {
        let module = shaders.module(
            "impacts",
            &[("IMPACT_ROUNDS", IMPACT_ROUNDS)],
            concat!(
                include_str!("impacts.wgsl"),
                include_str!("warm_start.wgsl")
            ),
        );
        Impacts {
            meet: (0..=IMPACT_ROUNDS)
                .map(|round| {
                    shaders.pipeline_with(
                        &module,
                        "meet_in_round",
                        &[("IMPACT_ROUND", f64::from(round))],
                    )
                })
                .collect(),
            in_one_group: shaders.pipeline(&module, "impacts_in_one_group"),
        }
    }

    pub fn record(&self, step: &mut Recorder) {
        let small = step.small;
        step.stage(Stage::Impacts, |pass| {
            if small {
                return pass.workgroups(&self.in_one_group, 1, 1);
            }
            for meet in &self.meet {
                pass.over_balls(meet);
            }
        });
    }
}
