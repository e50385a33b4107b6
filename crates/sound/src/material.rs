//! What the room's things are made of, as far as sound cares: stiffness,
//! density and how quickly vibration dies in them (J1).

/// A material's elastic constants and internal damping.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Properties {
    /// Young's modulus (Pa).
    pub young: f64,
    /// Poisson's ratio.
    pub poisson: f64,
    /// Density (kg/m³).
    pub density: f64,
    /// Loss factor: a mode of frequency f decays as exp(-π f η t).
    pub loss: f64,
}

impl Properties {
    /// The speed of shear waves, √(G/ρ) with G = E / (2 (1 + ν)) (m/s).
    pub fn shear_speed(&self) -> f64 {
        (self.young / (2.0 * (1.0 + self.poisson) * self.density)).sqrt()
    }

    /// The speed of bending-free waves in a thin plate or shell,
    /// √(E / (ρ (1 - ν²))) (m/s).
    pub fn plate_speed(&self) -> f64 {
        (self.young / (self.density * (1.0 - self.poisson * self.poisson))).sqrt()
    }

    /// The plate's bending stiffness per unit mass for thickness `h`,
    /// √(D / (ρ h)) with D = E h³ / (12 (1 - ν²)) (m²/s).
    pub fn bending(&self, h: f64) -> f64 {
        (self.young * h * h / (12.0 * self.density * (1.0 - self.poisson * self.poisson))).sqrt()
    }

    /// The term (1 - ν²) / E that each body adds to Hertz's contact
    /// modulus 1/E* (1/Pa).
    pub fn compliance(&self) -> f64 {
        (1.0 - self.poisson * self.poisson) / self.young
    }
}

/// The materials a scene may name.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Material {
    /// Hard plastic (ABS).
    Plastic,
    /// Rubber: soft, heavily damped; thuds.
    Rubber,
    /// Wood, along the grain, as a floor board bends.
    Wood,
    /// Gypsum plaster board.
    Plaster,
    /// Steel: rings long.
    Steel,
    /// Glass.
    Glass,
    /// Brass, as bells are cast.
    Brass,
    /// Fired clay, as the old tumblers were.
    Ceramic,
}

impl Material {
    /// Every material, in the order the panel lists them.
    pub const ALL: [Material; 8] = [
        Material::Plastic,
        Material::Rubber,
        Material::Wood,
        Material::Plaster,
        Material::Steel,
        Material::Glass,
        Material::Brass,
        Material::Ceramic,
    ];

    /// Their names, as scene files write them.
    pub const NAMES: [&'static str; 8] = [
        "plastic", "rubber", "wood", "plaster", "steel", "glass", "brass", "ceramic",
    ];

    /// Its name in a scene file.
    pub fn name(self) -> &'static str {
        Self::NAMES[self as usize]
    }

    /// The material named `name`, if there is one.
    pub fn from_name(name: &str) -> Option<Material> {
        Self::NAMES
            .iter()
            .position(|&n| n == name)
            .map(|i| Self::ALL[i])
    }

    /// Handbook values (room temperature); the loss factors are those of
    /// the material in a small part, not of a laboratory sample.
    pub fn properties(self) -> Properties {
        let (young, poisson, density, loss) = match self {
            Material::Plastic => (2.3e9, 0.35, 1050.0, 0.012),
            Material::Rubber => (0.05e9, 0.45, 1100.0, 0.15),
            Material::Wood => (10e9, 0.3, 600.0, 0.03),
            Material::Plaster => (3.0e9, 0.2, 800.0, 0.04),
            Material::Steel => (200e9, 0.29, 7850.0, 0.0005),
            Material::Glass => (70e9, 0.22, 2500.0, 0.001),
            Material::Brass => (100e9, 0.34, 8500.0, 0.0008),
            Material::Ceramic => (60e9, 0.25, 2300.0, 0.002),
        };
        Properties {
            young,
            poisson,
            density,
            loss,
        }
    }
}
