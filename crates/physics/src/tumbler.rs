//! The roly-poly tumbler (P6): a heavy, axisymmetric compound of six spheres
//! whose round bottom rests on the floor and whose centre of mass lies below
//! the bottom sphere's centre, so that gravity always rights it.
//!
//! The bottom sphere never leaves the floor, so its centre `C` stays at height
//! `R`. That removes one degree of freedom exactly (no penetration, no drift)
//! and leaves the tumbler free to rock, spin and move over the floor. At the
//! contact point `P = C - R y` the floor pushes up with a normal force `N` and
//! holds it with friction `f`:
//!
//! * rolling: `P` does not move, `v_C = R w x y`, and `f` is whatever rolling
//!   needs, as long as `|f| <= mu N`;
//! * sliding: `P` slips, and friction is `-mu N` along the slip.
//!
//! Newton-Euler for the centre of mass `G`, with both forces acting at `P`,
//! gives six linear equations in six unknowns per mode ([`grounded_solve`]).
//! The same equations with impulses in place of forces resolve collisions:
//! an impulse `J` at a point `Q` turns the tumbler about its contact point,
//! `I_P dw = (Q - P) x J`, where `I_P` is the inertia about `P` (the report's
//! "torque about the contact point").
//!
//! The bottom never lifts off: where the floor would have to pull it down
//! (a violent spin, a hard knock from below), the floor holds it without
//! friction instead. Tumblers are heavy and low, so this is rare; it keeps
//! the motion energy-consistent.

use crate::config::{SphereSpec, TumblerPlacement};
use glam::{DMat3, DQuat, DVec3};

/// The shape and mass properties shared by all tumblers, derived from the six
/// spheres with the parallel-axis theorem.
#[derive(Clone, Debug, PartialEq)]
pub struct TumblerShape {
    pub spheres: Vec<SphereSpec>,
    pub mass: f64,
    /// Centre of mass in the body frame: `(0, -a, 0)`.
    pub center_of_mass: DVec3,
    /// Radius `R` of the round bottom (sphere 0).
    pub bottom_radius: f64,
    /// Distance `a` of the centre of mass below the bottom sphere's centre.
    pub com_offset: f64,
    /// Inertia tensor about the centre of mass, in the body frame.
    pub inertia: DMat3,
    /// A sphere around all six spheres (centre on the axis, body frame) for
    /// cheap rejection before the six sphere tests (P7).
    pub bound_height: f64,
    pub bound_radius: f64,
}

impl TumblerShape {
    pub fn new(spheres: &[SphereSpec]) -> TumblerShape {
        let mass: f64 = spheres.iter().map(|s| s.mass).sum();
        let com_y = spheres.iter().map(|s| s.mass * s.height).sum::<f64>() / mass;
        // Each sphere is a uniform solid sphere: 2/5 m r^2 about its own centre,
        // shifted to the common centre of mass. Offsets lie on the axis, so the
        // shift adds only to the two transverse moments.
        let axial: f64 = spheres
            .iter()
            .map(|s| 0.4 * s.mass * s.radius * s.radius)
            .sum();
        let transverse: f64 = axial
            + spheres
                .iter()
                .map(|s| s.mass * (s.height - com_y).powi(2))
                .sum::<f64>();
        let (lo, hi) = axis_extent(spheres);
        let bound_height = 0.5 * (lo + hi);
        let bound_radius = spheres
            .iter()
            .map(|s| (s.height - bound_height).abs() + s.radius)
            .fold(0.0, f64::max);
        TumblerShape {
            spheres: spheres.to_vec(),
            mass,
            center_of_mass: DVec3::new(0.0, com_y, 0.0),
            bottom_radius: spheres[0].radius,
            com_offset: -com_y,
            inertia: DMat3::from_diagonal(DVec3::new(transverse, axial, transverse)),
            bound_height,
            bound_radius,
        }
    }

    /// Radius of gyration about a transverse axis through the centre of mass.
    pub fn transverse_gyration_radius(&self) -> f64 {
        (self.inertia.x_axis.x / self.mass).sqrt()
    }

    /// Small-amplitude rocking frequency of a rolling pendulum (rad/s):
    /// `w0^2 = g a / (k^2 + (R - a)^2)`.
    pub fn rocking_frequency(&self, gravity: f64) -> f64 {
        let k = self.transverse_gyration_radius();
        let (r, a) = (self.bottom_radius, self.com_offset);
        (gravity * a / (k * k + (r - a) * (r - a))).sqrt()
    }
}

/// The lowest and highest points of a compound of spheres on its axis
/// (body frame heights).
pub fn axis_extent(spheres: &[SphereSpec]) -> (f64, f64) {
    let lo = spheres
        .iter()
        .map(|s| s.height - s.radius)
        .fold(f64::INFINITY, f64::min);
    let hi = spheres
        .iter()
        .map(|s| s.height + s.radius)
        .fold(f64::NEG_INFINITY, f64::max);
    (lo, hi)
}

/// How the round bottom meets the floor during a step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum FloorMode {
    Rolling,
    /// Slipping along this horizontal unit direction.
    Sliding(DVec3),
}

/// Velocity change of a tumbler per unit impulse.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Response {
    pub angular_velocity: DVec3,
    pub center_velocity: DVec3,
}

/// A spring-damper "hand" holding a tumbler at a point fixed in its body.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Grip {
    /// The grab point in the body frame (relative to the bottom sphere's centre).
    pub anchor: DVec3,
    /// Where the hand pulls the grab point to (world).
    pub target: DVec3,
}

/// One tumbler's state.
#[derive(Clone, Debug, PartialEq)]
pub struct Tumbler {
    /// Centre of the bottom sphere; its height is always the floor + R.
    pub(crate) center: DVec3,
    pub(crate) orientation: DQuat,
    /// Velocity of `center` (horizontal).
    pub(crate) center_velocity: DVec3,
    pub(crate) angular_velocity: DVec3,
    pub(crate) mode: FloorMode,
    pub(crate) grip: Option<Grip>,
    /// Copies of the shape's `R` and centre of mass, so that a tumbler can
    /// answer questions about itself.
    pub(crate) bottom_radius: f64,
    pub(crate) com_body: DVec3,
}

impl Tumbler {
    pub(crate) fn new(shape: &TumblerShape, placement: &TumblerPlacement, floor_y: f64) -> Tumbler {
        let axis = DVec3::new(placement.tilt_axis.x, 0.0, placement.tilt_axis.z);
        let orientation = if axis.length_squared() > 0.0 && placement.tilt_deg != 0.0 {
            DQuat::from_axis_angle(axis.normalize(), placement.tilt_deg.to_radians())
        } else {
            DQuat::IDENTITY
        };
        Tumbler {
            center: DVec3::new(placement.x, floor_y + shape.bottom_radius, placement.z),
            orientation,
            center_velocity: DVec3::ZERO,
            angular_velocity: DVec3::ZERO,
            mode: FloorMode::Rolling,
            grip: None,
            bottom_radius: shape.bottom_radius,
            com_body: shape.center_of_mass,
        }
    }

    /// Centre of the bottom sphere (world).
    pub fn bottom_center(&self) -> DVec3 {
        self.center
    }

    pub fn orientation(&self) -> DQuat {
        self.orientation
    }

    /// The axis of symmetry, pointing from the bottom to the head.
    pub fn axis(&self) -> DVec3 {
        self.orientation * DVec3::Y
    }

    /// Angle between the axis and the vertical, in radians.
    pub fn tilt(&self) -> f64 {
        self.axis().y.clamp(-1.0, 1.0).acos()
    }

    pub fn center_of_mass(&self) -> DVec3 {
        self.center + self.orientation * self.com_body
    }

    pub fn linear_velocity(&self) -> DVec3 {
        self.center_velocity
            + self
                .angular_velocity
                .cross(self.orientation * self.com_body)
    }

    pub fn angular_velocity(&self) -> DVec3 {
        self.angular_velocity
    }

    /// The point of the round bottom that touches the floor.
    pub fn contact_point(&self) -> DVec3 {
        self.center - self.bottom_radius * DVec3::Y
    }

    /// Velocity of the material point at the floor contact: zero while rolling.
    pub fn contact_velocity(&self) -> DVec3 {
        self.center_velocity - self.bottom_radius * self.angular_velocity.cross(DVec3::Y)
    }

    pub fn sliding(&self) -> bool {
        matches!(self.mode, FloorMode::Sliding(_))
    }

    pub fn grip(&self) -> Option<Grip> {
        self.grip
    }

    /// World centre of sphere `i` of `shape`.
    pub fn sphere_center(&self, shape: &TumblerShape, i: usize) -> DVec3 {
        self.center + self.orientation * DVec3::new(0.0, shape.spheres[i].height, 0.0)
    }

    /// Velocity of a world point rigidly attached to the tumbler.
    pub fn point_velocity(&self, point: DVec3) -> DVec3 {
        self.center_velocity + self.angular_velocity.cross(point - self.center)
    }

    /// Inertia about the centre of mass, in world axes.
    pub(crate) fn world_inertia(&self, shape: &TumblerShape) -> DMat3 {
        let r = DMat3::from_quat(self.orientation);
        r * shape.inertia * r.transpose()
    }

    /// Inverse of the inertia about the floor contact point, in world axes:
    /// how an impulse's moment about `P` turns a rolling tumbler.
    pub(crate) fn contact_inertia_inverse(&self, shape: &TumblerShape) -> DMat3 {
        let r = self.center_of_mass() - self.contact_point();
        let shift = DMat3::from_diagonal(DVec3::splat(r.length_squared())) - outer(r, r);
        (self.world_inertia(shape) + shape.mass * shift).inverse()
    }

    /// How the velocities change per unit impulse along `n` at `point`.
    ///
    /// Rolling, the floor's reaction is impulsive too and holds the contact
    /// point: the tumbler turns about it, `I_P dw = (point - P) x n`.
    /// Sliding, the floor pushes only up, with kinetic friction against the
    /// slip, as in [`grounded_solve`].
    pub(crate) fn impulse_response(
        &self,
        shape: &TumblerShape,
        contact_inv: &DMat3,
        friction: f64,
        point: DVec3,
        n: DVec3,
    ) -> Response {
        match self.mode {
            FloorMode::Rolling => {
                let dw = *contact_inv * (point - self.contact_point()).cross(n);
                Response {
                    angular_velocity: dw,
                    center_velocity: self.bottom_radius * dw.cross(DVec3::Y),
                }
            }
            FloorMode::Sliding(_) => {
                let g = self.center_of_mass();
                let sol = grounded_solve(
                    shape,
                    self.orientation,
                    self.mode,
                    friction,
                    n,
                    (point - g).cross(n),
                );
                Response {
                    angular_velocity: sol.dw,
                    center_velocity: sol.planar,
                }
            }
        }
    }

    pub(crate) fn apply_response(&mut self, r: &Response, impulse: f64) {
        self.angular_velocity += r.angular_velocity * impulse;
        self.center_velocity += r.center_velocity * impulse;
    }

    pub fn kinetic_energy(&self, shape: &TumblerShape) -> f64 {
        let v = self.linear_velocity();
        let w = self.angular_velocity;
        0.5 * shape.mass * v.length_squared() + 0.5 * w.dot(self.world_inertia(shape) * w)
    }
}

fn outer(a: DVec3, b: DVec3) -> DMat3 {
    DMat3::from_cols(a * b.x, a * b.y, a * b.z)
}

/// `skew(v) * w == v.cross(w)`.
fn skew(v: DVec3) -> DMat3 {
    DMat3::from_cols(
        DVec3::new(0.0, v.z, -v.y),
        DVec3::new(-v.z, 0.0, v.x),
        DVec3::new(v.y, -v.x, 0.0),
    )
}

/// Result of the grounded Newton-Euler equations.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct GroundedSolution {
    /// Angular acceleration (or angular velocity change, for impulses).
    pub dw: DVec3,
    /// Floor normal force (or impulse).
    pub normal: f64,
    /// Rolling: the friction the floor must supply (horizontal).
    /// Sliding: the acceleration (or velocity change) of the bottom's centre.
    pub planar: DVec3,
}

/// Solves the tumbler's equations with the bottom on the floor.
///
/// Unknowns: angular acceleration `dw`, normal force `N`, and either friction
/// `f` (rolling) or the centre's planar acceleration `a_C` (sliding).
///
/// ```text
/// linear:   M (a_C + dw x d) - N y - f = lin
/// angular:  I_G dw - rho x (N y + f)   = ang
/// ```
/// with `d = G - C`, `rho = P - G`, and `a_C = R dw x y` when rolling,
/// `f = -mu N s` when sliding along `s`. `lin` and `ang` carry gravity, the
/// hand, damping and the velocity-dependent terms (or impulses).
pub(crate) fn grounded_solve(
    shape: &TumblerShape,
    orientation: DQuat,
    mode: FloorMode,
    friction: f64,
    lin: DVec3,
    ang: DVec3,
) -> GroundedSolution {
    let m = shape.mass;
    let rot = DMat3::from_quat(orientation);
    let d = rot * shape.center_of_mass;
    let r = shape.bottom_radius * DVec3::Y + d; // G - P
    let rho = -r;
    let inertia = rot * shape.inertia * rot.transpose();

    let mut a = [[0.0f64; 6]; 6];
    let lin_w = match mode {
        // a_C + dw x d = dw x (R y + d) = -skew(r) dw
        FloorMode::Rolling => skew(r) * -m,
        FloorMode::Sliding(_) => skew(d) * -m,
    };
    let (c4, c5) = (DVec3::X, DVec3::Z);
    let normal_dir = match mode {
        FloorMode::Rolling => DVec3::Y,
        FloorMode::Sliding(s) => DVec3::Y - friction * s,
    };
    // Columns: dw (3), N, then friction or the centre's planar acceleration.
    let (c4_lin, c5_lin, c4_ang, c5_ang) = match mode {
        FloorMode::Rolling => (-c4, -c5, -rho.cross(c4), -rho.cross(c5)),
        FloorMode::Sliding(_) => (m * c4, m * c5, DVec3::ZERO, DVec3::ZERO),
    };
    let columns_lin = [
        lin_w.x_axis,
        lin_w.y_axis,
        lin_w.z_axis,
        -normal_dir,
        c4_lin,
        c5_lin,
    ];
    let columns_ang = [
        inertia.x_axis,
        inertia.y_axis,
        inertia.z_axis,
        -rho.cross(normal_dir),
        c4_ang,
        c5_ang,
    ];
    for (col, (l, g)) in columns_lin.iter().zip(&columns_ang).enumerate() {
        for row in 0..3 {
            a[row][col] = l[row];
            a[row + 3][col] = g[row];
        }
    }
    let x = solve6(a, [lin.x, lin.y, lin.z, ang.x, ang.y, ang.z]);
    if let FloorMode::Sliding(_) = mode {
        if x[3] < 0.0 && friction > 0.0 {
            // The floor would have to pull down: it cannot, so there is no
            // friction either (the bottom stays on the floor; see module doc).
            return grounded_solve(shape, orientation, mode, 0.0, lin, ang);
        }
    }
    GroundedSolution {
        dw: DVec3::new(x[0], x[1], x[2]),
        normal: x[3],
        planar: DVec3::new(x[4], 0.0, x[5]),
    }
}

/// Gaussian elimination with partial pivoting. The grounded system is always
/// well posed (positive mass and inertia), so no pivot is ever zero.
fn solve6(mut a: [[f64; 6]; 6], mut b: [f64; 6]) -> [f64; 6] {
    for col in 0..6 {
        let pivot = (col..6)
            .max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))
            .unwrap_or(col);
        a.swap(col, pivot);
        b.swap(col, pivot);
        let (top, rest) = a.split_at_mut(col + 1);
        let pivot_row = &top[col];
        for (offset, row) in rest.iter_mut().enumerate() {
            let f = row[col] / pivot_row[col];
            if f != 0.0 {
                for (x, p) in row[col..].iter_mut().zip(&pivot_row[col..]) {
                    *x -= f * p;
                }
                b[col + 1 + offset] -= f * b[col];
            }
        }
    }
    let mut x = [0.0; 6];
    for row in (0..6).rev() {
        let known: f64 = a[row][row + 1..]
            .iter()
            .zip(&x[row + 1..])
            .map(|(c, v)| c * v)
            .sum();
        x[row] = (b[row] - known) / a[row][row];
    }
    x
}

/// Parameters of the grounded motion that come from the world.
pub(crate) struct GroundedParams<'a> {
    pub shape: &'a TumblerShape,
    pub gravity: f64,
    pub friction: f64,
    pub damping: f64,
    pub grab: &'a crate::config::GrabConfig,
}

/// Time derivative of a tumbler's state, with the floor forces that go with it.
struct Derivative {
    center_velocity: DVec3,
    orientation_rate: DQuat,
    center_accel: DVec3,
    angular_accel: DVec3,
    solution: GroundedSolution,
}

impl Tumbler {
    /// Force of the hand on the grab point, if held.
    pub(crate) fn grip_force(&self, grab: &crate::config::GrabConfig) -> Option<(DVec3, DVec3)> {
        let grip = self.grip?;
        let point = self.center + self.orientation * grip.anchor;
        let velocity = self.point_velocity(point);
        let mut force = grab.stiffness * (grip.target - point) - grab.damping * velocity;
        let len = force.length();
        if len > grab.max_force {
            force *= grab.max_force / len;
        }
        Some((point, force))
    }

    fn derivative(&self, p: &GroundedParams, mode: FloorMode) -> Derivative {
        let shape = p.shape;
        let m = shape.mass;
        let w = self.angular_velocity;
        let d = self.orientation * shape.center_of_mass;
        let inertia = self.world_inertia(shape);
        let g = self.center + d;
        let mut lin = DVec3::new(0.0, -m * p.gravity, 0.0) - m * w.cross(w.cross(d));
        let mut ang = -w.cross(inertia * w);
        if p.damping > 0.0 {
            // Rolling resistance: a torque that brings rocking and spinning to rest.
            let r = g - self.contact_point();
            let contact_inertia = inertia
                + m * (DMat3::from_diagonal(DVec3::splat(r.length_squared())) - outer(r, r));
            ang -= p.damping * (contact_inertia * w);
        }
        if let Some((point, force)) = self.grip_force(p.grab) {
            lin += force;
            ang += (point - g).cross(force);
        }
        let solution = grounded_solve(shape, self.orientation, mode, p.friction, lin, ang);
        let (center_velocity, center_accel) = match mode {
            FloorMode::Rolling => (
                self.bottom_radius * w.cross(DVec3::Y),
                self.bottom_radius * solution.dw.cross(DVec3::Y),
            ),
            FloorMode::Sliding(_) => (self.center_velocity, solution.planar),
        };
        Derivative {
            center_velocity,
            orientation_rate: DQuat::from_xyzw(w.x, w.y, w.z, 0.0) * self.orientation * 0.5,
            center_accel,
            angular_accel: solution.dw,
            solution,
        }
    }

    fn advanced(&self, k: &Derivative, h: f64) -> Tumbler {
        let mut t = self.clone();
        t.center += k.center_velocity * h;
        t.orientation = (self.orientation + k.orientation_rate * h).normalize();
        t.center_velocity += k.center_accel * h;
        t.angular_velocity += k.angular_accel * h;
        t
    }

    /// Picks rolling or sliding for the coming step: rolling while the floor
    /// can supply the friction it needs, sliding otherwise.
    pub(crate) fn choose_mode(&mut self, p: &GroundedParams) {
        if let FloorMode::Sliding(_) = self.mode {
            let slip = self.contact_velocity();
            if slip.length() > 1e-9 {
                self.mode = FloorMode::Sliding(slip.normalize());
                return;
            }
            self.mode = FloorMode::Rolling;
        }
        self.center_velocity = self.bottom_radius * self.angular_velocity.cross(DVec3::Y);
        let need = self.derivative(p, FloorMode::Rolling).solution;
        let limit = p.friction * need.normal.max(0.0);
        let f = need.planar.length();
        if f > limit * (1.0 + 1e-9) && f > 1e-12 {
            self.mode = FloorMode::Sliding(-need.planar / f);
        }
    }

    /// Advances the grounded motion by `dt` (classical Runge-Kutta: the
    /// equations are smooth within a step and RK4 keeps rocking energy to
    /// about 1e-8 of itself per step).
    pub(crate) fn integrate(&mut self, p: &GroundedParams, dt: f64) {
        let mode = self.mode;
        let k1 = self.derivative(p, mode);
        let k2 = self.advanced(&k1, 0.5 * dt).derivative(p, mode);
        let k3 = self.advanced(&k2, 0.5 * dt).derivative(p, mode);
        let k4 = self.advanced(&k3, dt).derivative(p, mode);
        let sum = |f: fn(&Derivative) -> DVec3| {
            (f(&k1) + 2.0 * f(&k2) + 2.0 * f(&k3) + f(&k4)) * (dt / 6.0)
        };
        self.center += sum(|k| k.center_velocity);
        self.center_velocity += sum(|k| k.center_accel);
        self.angular_velocity += sum(|k| k.angular_accel);
        let q_rate = (k1.orientation_rate
            + k2.orientation_rate * 2.0
            + k3.orientation_rate * 2.0
            + k4.orientation_rate)
            * (dt / 6.0);
        self.orientation = (self.orientation + q_rate).normalize();
        match mode {
            FloorMode::Rolling => {
                self.center_velocity = self.bottom_radius * self.angular_velocity.cross(DVec3::Y);
            }
            FloorMode::Sliding(s) => {
                // Friction stops the slip within the step: stick with an
                // impulse at the contact that takes out the remaining slip.
                let slip = self.contact_velocity();
                if slip.dot(s) <= 0.0 {
                    self.stick(p);
                }
            }
        }
    }

    /// Removes the slip at the contact with a friction impulse (dissipative).
    pub(crate) fn stick(&mut self, p: &GroundedParams) {
        let slip = self.contact_velocity();
        let m = p.shape.mass;
        let sol = grounded_solve(
            p.shape,
            self.orientation,
            FloorMode::Rolling,
            p.friction,
            m * slip,
            DVec3::ZERO,
        );
        self.angular_velocity += sol.dw;
        self.center_velocity = self.bottom_radius * self.angular_velocity.cross(DVec3::Y);
        self.mode = FloorMode::Rolling;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::{GrabConfig, WorldConfig};

    fn params(shape: &TumblerShape, grab: &GrabConfig, damping: f64) -> GroundedParams<'static> {
        let shape: &'static TumblerShape = Box::leak(Box::new(shape.clone()));
        let grab: &'static GrabConfig = Box::leak(Box::new(grab.clone()));
        GroundedParams {
            shape,
            gravity: 9.81,
            friction: 0.6,
            damping,
            grab,
        }
    }

    #[test]
    fn default_shape_has_centre_of_mass_below_bottom_centre() {
        let cfg = WorldConfig::default();
        let shape = TumblerShape::new(&cfg.tumblers.spheres);
        assert!(shape.com_offset > 0.0);
        assert!(shape.com_offset < shape.bottom_radius);
        assert_eq!(shape.spheres.len(), 6);
    }

    #[test]
    fn parallel_axis_inertia_matches_hand_computation() {
        let spheres = [
            SphereSpec {
                height: 0.0,
                radius: 1.0,
                mass: 2.0,
            },
            SphereSpec {
                height: 2.0,
                radius: 0.5,
                mass: 2.0,
            },
        ];
        let shape = TumblerShape::new(&spheres);
        // centre of mass at 1.0; each sphere 1.0 away from it
        let axial = 0.4 * 2.0 * 1.0 + 0.4 * 2.0 * 0.25;
        assert!((shape.inertia.y_axis.y - axial).abs() < 1e-12);
        assert!((shape.inertia.x_axis.x - (axial + 2.0 + 2.0)).abs() < 1e-12);
        assert!((shape.com_offset + 1.0).abs() < 1e-12);
    }

    #[test]
    fn upright_tumbler_at_rest_needs_its_weight_and_no_friction() {
        let cfg = WorldConfig::default();
        let shape = TumblerShape::new(&cfg.tumblers.spheres);
        let t = Tumbler::new(&shape, &cfg.tumblers.placements[0], 0.0);
        let p = params(&shape, &cfg.grab, 0.0);
        let k = t.derivative(&p, FloorMode::Rolling);
        assert!((k.solution.normal - shape.mass * 9.81).abs() < 1e-9);
        assert!(k.solution.planar.length() < 1e-12);
        assert!(k.angular_accel.length() < 1e-12);
    }

    #[test]
    fn impulse_response_matches_pivot_inertia() {
        // The general grounded equations with an impulse must agree with the
        // closed form I_P dw = (Q - P) x J used by the contact solver.
        let cfg = WorldConfig::default();
        let shape = TumblerShape::new(&cfg.tumblers.spheres);
        let mut placement = cfg.tumblers.placements[0];
        placement.tilt_deg = 25.0;
        placement.tilt_axis = DVec3::new(1.0, 0.0, 0.4);
        let t = Tumbler::new(&shape, &placement, 0.0);
        let q = t.sphere_center(&shape, 3) + DVec3::new(0.1, 0.05, -0.02);
        let j = DVec3::new(0.7, -0.3, 1.1);
        let g = t.center_of_mass();
        let sol = grounded_solve(
            &shape,
            t.orientation,
            FloorMode::Rolling,
            0.6,
            j,
            (q - g).cross(j),
        );
        let closed = t.contact_inertia_inverse(&shape) * (q - t.contact_point()).cross(j);
        assert!(
            (sol.dw - closed).length() < 1e-10,
            "{:?} vs {:?}",
            sol.dw,
            closed
        );
    }

    #[test]
    fn a_sliding_tumbler_trips_forward_and_comes_to_roll() {
        // Friction acts at the floor, below the centre of mass: it slows the
        // bottom and pitches the top forward, until the slip is gone.
        let cfg = WorldConfig::default();
        let shape = TumblerShape::new(&cfg.tumblers.spheres);
        let mut t = Tumbler::new(&shape, &cfg.tumblers.placements[0], 0.0);
        t.center_velocity = DVec3::new(1.0, 0.0, 0.0);
        t.mode = FloorMode::Sliding(DVec3::X);
        let p = params(&shape, &cfg.grab, 0.0);
        let momentum0 = shape.mass * t.linear_velocity().x;
        for _ in 0..6 {
            t.choose_mode(&p);
            t.integrate(&p, 1.0 / 120.0);
        }
        assert!(t.axis().x > 0.0, "leaned back: {}", t.axis());
        assert!(t.contact_velocity().x < 1.0);
        assert!(shape.mass * t.linear_velocity().x < momentum0);
        for _ in 0..240 {
            t.choose_mode(&p);
            t.integrate(&p, 1.0 / 120.0);
        }
        assert!(!t.sliding());
        assert!(t.contact_velocity().length() < 1e-9);
    }
}
