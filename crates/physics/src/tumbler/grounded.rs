//! The grounded motion: the Newton-Euler equations with the round bottom
//! on the floor, rolling or sliding, solved for forces or impulses, and
//! integrated over a step with the hand's pull and rolling resistance.

use super::{FloorMode, Tumbler, TumblerShape, outer, skew};
use glam::{DMat3, DQuat, DVec3};

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
    if let FloorMode::Sliding(_) = mode
        && x[3] < 0.0
        && friction > 0.0
    {
        // The floor would have to pull down: it cannot, so there is no
        // friction either (the bottom stays on the floor; see module doc).
        return grounded_solve(shape, orientation, mode, 0.0, lin, ang);
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
