//! What pushed the balls over a step, besides one another: the impulses of
//! the room's surfaces and of the tumblers, the energy guard's and
//! gravity's, and what poured balls bring in, summed over the balls as each part of the step gives them.
//! They are what changes the balls' momentum (Newton's second law in
//! integral form), which the series and the window's plots show beside it.

use glam::DVec3;

/// The impulses given to the balls over one step, by what gave them (N s).
///
/// Left out, as pushes from outside the room's laws: a hand's pull on the
/// ball it holds, and the fireball's pushes.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BallImpulses {
    /// The room's walls, floor and ceiling on the balls: their bounces,
    /// the solver's wall rows (normal and friction), and rolling
    /// resistance.
    pub surfaces: DVec3,
    /// The tumblers on the balls: their contacts' normal and friction
    /// impulses.
    pub tumblers: DVec3,
    /// The energy guard's: a step that would make energy slows the balls
    /// until it does not (see [`crate::World::step`]), and separating
    /// overlapping balls pays for their rise from their motion. Rounding's
    /// size in an elastic gas; a settling pile meets it now and then.
    pub guard: DVec3,
    /// Gravity's on the live balls: `M g dt`.
    pub gravity: DVec3,
    /// The momentum the spout's new balls brought in (a scene that pours,
    /// `balls.pour`).
    pub poured: DVec3,
}

impl std::ops::AddAssign for BallImpulses {
    fn add_assign(&mut self, other: BallImpulses) {
        self.surfaces += other.surfaces;
        self.tumblers += other.tumblers;
        self.guard += other.guard;
        self.gravity += other.gravity;
        self.poured += other.poured;
    }
}

impl BallImpulses {
    /// All of them: the change of the balls' momentum over the step, to
    /// rounding (N s).
    pub fn total(&self) -> DVec3 {
        self.surfaces + self.tumblers + self.guard + self.gravity + self.poured
    }
}
