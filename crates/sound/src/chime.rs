//! The bell inside each tumbler (J1): as many roly-poly toys do, it chimes
//! when the tumbler rocks past an angle, its clapper striking as hard as
//! the tumbler swings. It sounds again only after the tumbler has come
//! back near upright, so a tumbler at rest, or leaning still, is silent.

use rolypoly_physics::World;

/// The tilt (radians) past which the clapper strikes: 14 degrees.
pub const CHIME_TILT: f64 = 0.245;
/// Back within this tilt, the clapper is free to strike again.
const REARM_TILT: f64 = 0.5 * CHIME_TILT;
/// The clapper's mass (kg), its arm's length (m) and its bounce off the
/// bell's wall.
pub const CLAPPER_MASS: f64 = 0.01;
const CLAPPER_ARM: f64 = 0.08;
const CLAPPER_RESTITUTION: f64 = 0.5;

/// A strike of tumbler `tumbler`'s bell: its clapper's impulse and speed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Chime {
    /// Which tumbler's bell.
    pub tumbler: usize,
    /// The clapper's impulse on the bell (N s).
    pub impulse: f64,
    /// How fast the clapper meets it (m/s).
    pub speed: f64,
}

/// Which clappers are free to strike.
#[derive(Clone, Debug, Default)]
pub struct Chimes {
    armed: Vec<bool>,
    /// The strikes so far.
    pub count: u64,
}

impl Chimes {
    /// The bells' strikes as the world's tumblers stand now.
    pub fn strikes(&mut self, world: &World, out: &mut Vec<Chime>) {
        let tumblers = world.tumblers();
        // A tumbler that starts leaning is not yet swinging.
        self.armed.resize(tumblers.len(), false);
        for (i, t) in tumblers.iter().enumerate() {
            let tilt = t.tilt();
            if tilt < REARM_TILT {
                self.armed[i] = true;
            } else if tilt > CHIME_TILT && self.armed[i] {
                self.armed[i] = false;
                let speed = t.angular_velocity().length() * CLAPPER_ARM;
                self.count += 1;
                out.push(Chime {
                    tumbler: i,
                    impulse: CLAPPER_MASS * (1.0 + CLAPPER_RESTITUTION) * speed,
                    speed,
                });
            }
        }
    }
}
