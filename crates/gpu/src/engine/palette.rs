//! The palette the balls' colours index: the colours a ball can take, by
//! what it took its colour from.

use rolypoly_physics::Tint;

/// Where each kind of colour starts in the palette.
#[derive(Clone, Copy, Debug)]
pub struct PaletteLayout {
    pub tumblers: u32,
    pub placed: u32,
}

impl PaletteLayout {
    /// White first, then the six surfaces, the tumblers, the placed balls.
    pub const SURFACES: u32 = 1;

    pub fn index(self, tint: Tint) -> u32 {
        match tint {
            Tint::White => 0,
            Tint::Surface(s) => Self::SURFACES + s.index() as u32,
            Tint::Tumbler(t) => self.tumblers + t as u32,
            Tint::Placed(k) => self.placed + k as u32,
        }
    }

    pub fn tint(self, index: u32) -> Tint {
        let surfaces = Self::SURFACES..Self::SURFACES + 6;
        if surfaces.contains(&index) {
            Tint::Surface(rolypoly_physics::Surface::ALL[(index - Self::SURFACES) as usize])
        } else if (self.tumblers..self.placed).contains(&index) {
            Tint::Tumbler((index - self.tumblers) as usize)
        } else if index >= self.placed {
            Tint::Placed((index - self.placed) as usize)
        } else {
            Tint::White
        }
    }
}
