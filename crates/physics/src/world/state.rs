//! A world's state apart from its scene: what a snapshot carries to another
//! process or machine, where a world made from the same scene takes it on
//! and steps on to the same bits.
//!
//! The scene's part (the configuration, the room, the tumblers' shape) is
//! not carried: the receiving world rebuilds it from the scene. What a step
//! builds afresh (the contacts, the broadphase's grid, working storage) is
//! not carried either, as [`World`]'s `Clone` does not copy it.

use super::World;
use super::hand::BallHold;
use super::pour::Pour;
use crate::balls::Balls;
use crate::contact::WarmStart;
use crate::events::Event;
use crate::fireball::Fireball;
use crate::rng::Rng;
use crate::tumbler::Tumbler;
use serde::{Deserialize, Serialize};

/// Everything a world steps on from that its scene does not give (see the
/// module's documentation).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct WorldState {
    balls: Balls,
    tumblers: Vec<Tumbler>,
    fireball: Option<Fireball>,
    rng: Rng,
    time: f64,
    steps: u64,
    events: Vec<Event>,
    warm: WarmStart,
    retakes: u64,
    pour: Pour,
    ball_hold: Option<BallHold>,
}

/// Why a world cannot take on a state.
#[derive(Clone, Debug, PartialEq)]
pub enum StateError {
    /// The state has another number of tumblers than the world's scene.
    Tumblers {
        /// In the state.
        state: usize,
        /// In the world.
        scene: usize,
    },
    /// The balls' columns are not all as long.
    Balls,
    /// The balls still to pour are not among the state's balls.
    Pour,
    /// The hand holds a ball the state does not have.
    Hold {
        /// The ball held.
        ball: usize,
        /// How many there are.
        balls: usize,
    },
}

impl std::fmt::Display for StateError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            StateError::Tumblers { state, scene } => write!(
                f,
                "the state has {state} tumblers and the world's scene {scene}: it is of another scene"
            ),
            StateError::Balls => {
                write!(
                    f,
                    "the state's balls are damaged: their columns have different lengths"
                )
            }
            StateError::Pour => {
                write!(f, "the state's balls still to pour are not among its balls")
            }
            StateError::Hold { ball, balls } => {
                write!(f, "the state's hand holds ball {ball}, of {balls} balls")
            }
        }
    }
}

impl std::error::Error for StateError {}

impl World {
    /// A copy of the state a world of the same scene steps on from (see
    /// [`World::set_state`]).
    pub fn state(&self) -> WorldState {
        WorldState {
            balls: self.balls.clone(),
            tumblers: self.tumblers.clone(),
            fireball: self.fireball.clone(),
            rng: self.rng.clone(),
            time: self.time,
            steps: self.steps,
            events: self.events.clone(),
            warm: self.warm.clone(),
            retakes: self.retakes,
            pour: self.pour.clone(),
            ball_hold: self.ball_hold,
        }
    }

    /// Takes on `state`, from [`World::state`] of a world made from the same
    /// scene: it then steps on to the same bits as that world. A state that
    /// cannot be of this world's scene is refused, the world unchanged.
    pub fn set_state(&mut self, state: WorldState) -> Result<(), StateError> {
        if state.tumblers.len() != self.tumblers.len() {
            return Err(StateError::Tumblers {
                state: state.tumblers.len(),
                scene: self.tumblers.len(),
            });
        }
        if !state.balls.columns_agree() {
            return Err(StateError::Balls);
        }
        if !state.pour.within(state.balls.len()) {
            return Err(StateError::Pour);
        }
        if let Some(hold) = state.ball_hold
            && hold.ball >= state.balls.len()
        {
            return Err(StateError::Hold {
                ball: hold.ball,
                balls: state.balls.len(),
            });
        }
        let WorldState {
            balls,
            tumblers,
            fireball,
            rng,
            time,
            steps,
            events,
            warm,
            retakes,
            pour,
            ball_hold,
        } = state;
        self.scratch.hit_wall = vec![false; balls.len()];
        self.balls = balls;
        self.tumblers = tumblers;
        self.fireball = fireball;
        self.rng = rng;
        self.time = time;
        self.steps = steps;
        self.events = events;
        self.warm = warm;
        self.retakes = retakes;
        self.pour = pour;
        self.ball_hold = ball_hold;
        Ok(())
    }
}
