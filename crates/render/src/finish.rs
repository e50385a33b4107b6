//! How each kind of surface reflects light: the strength and sharpness of
//! its highlight. One place for the real-time frame (Blinn-Phong) and the
//! path-traced reference (the same highlight as a lobe that conserves
//! energy).

/// A surface's highlight: Blinn-Phong's `specular * (n . h)^shininess`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Finish {
    /// The highlight's peak, as a share of the light falling on it.
    pub specular: f32,
    /// Its exponent: larger is sharper.
    pub shininess: f32,
}

/// The varnished wooden floor.
pub const FLOOR_FINISH: Finish = Finish {
    specular: 0.35,
    shininess: 40.0,
};
/// The plaster walls and ceiling: nearly matte.
pub const WALL_FINISH: Finish = Finish {
    specular: 0.04,
    shininess: 8.0,
};
/// The tumblers' lacquered paint.
pub const TUMBLER_FINISH: Finish = Finish {
    specular: 0.55,
    shininess: 60.0,
};
/// Every ball: glossy and sharp-highlighted.
pub const BALL_FINISH: Finish = Finish {
    specular: 0.9,
    shininess: 110.0,
};
