//! Stage 2, the contacts (`contacts.wgsl`): each ball keeps its nearest
//! balls within reach, the nearest tumbler sphere and the nearest walls,
//! kept contacts starting from last step's impulse; the fireball takes the
//! balls it reaches, if the scene says so.

use super::{Kernel, Recorder, Shaders};
use crate::profile::Stage;

pub struct Contacts {
    gauge_near_speed: Kernel,
    catch_in_fireball: Kernel,
    find_contacts: Kernel,
}

impl Contacts {
    pub fn new(shaders: &Shaders) -> Contacts {
        let module = shaders.module("contacts", &[], include_str!("contacts.wgsl"));
        Contacts {
            gauge_near_speed: shaders.pipeline(&module, "gauge_near_speed"),
            catch_in_fireball: shaders.pipeline(&module, "catch_in_fireball"),
            find_contacts: shaders.pipeline(&module, "find_contacts"),
        }
    }

    pub fn record(&self, step: &mut Recorder) {
        let catching = step.catching;
        step.stage(Stage::Contacts, |pass| {
            pass.over_balls(&self.gauge_near_speed);
            if catching {
                pass.over_balls(&self.catch_in_fireball);
            }
            pass.over_balls(&self.find_contacts);
        });
    }
}
