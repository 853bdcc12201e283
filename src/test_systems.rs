//! Hand-derived systems for the tests, written in the shape the macro emits:
//! inherent functions, and trait impls that forward to them.

use crate::MultibodySystem;

/// `q + h v`: the configuration update of systems whose speeds are their
/// coordinates' rates.
pub fn euler_update<const N: usize>(q: &[f64; N], v: &[f64; N], h: f64) -> [f64; N] {
    std::array::from_fn(|i| q[i] + h * v[i])
}

/// A point mass `m` on a massless rod of length `l`; `q` is the angle from the
/// downward vertical.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pendulum {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

impl Pendulum {
    pub const COORDINATES: [&'static str; 1] = ["theta"];
    pub const INPUTS: [&'static str; 0] = [];

    pub fn mass_matrix(&self, _q: &[f64; 1]) -> [[f64; 1]; 1] {
        [[self.m * self.l * self.l]]
    }

    pub fn forcing(&self, _t: f64, q: &[f64; 1], _qd: &[f64; 1], _u: &[f64; 0]) -> [f64; 1] {
        [-self.m * self.g * self.l * q[0].sin()]
    }

    pub fn kinetic_energy(&self, _q: &[f64; 1], qd: &[f64; 1]) -> f64 {
        0.5 * self.m * self.l * self.l * qd[0] * qd[0]
    }

    pub fn potential_energy(&self, q: &[f64; 1]) -> f64 {
        -self.m * self.g * self.l * q[0].cos()
    }

    /// The small-angle period `2π √(l/g)`.
    pub fn small_angle_period(&self) -> f64 {
        std::f64::consts::TAU * (self.l / self.g).sqrt()
    }
}

impl MultibodySystem<1, 1, 0> for Pendulum {
    const COORDINATES: [&'static str; 1] = Self::COORDINATES;
    const SPEEDS: [&'static str; 1] = ["dt(theta)"];
    const INPUTS: [&'static str; 0] = Self::INPUTS;

    fn mass_matrix(&self, q: &[f64; 1]) -> [[f64; 1]; 1] {
        Self::mass_matrix(self, q)
    }

    fn forcing(&self, t: f64, q: &[f64; 1], qd: &[f64; 1], u: &[f64; 0]) -> [f64; 1] {
        Self::forcing(self, t, q, qd, u)
    }

    fn kinetic_energy(&self, q: &[f64; 1], qd: &[f64; 1]) -> f64 {
        Self::kinetic_energy(self, q, qd)
    }

    fn potential_energy(&self, q: &[f64; 1]) -> f64 {
        Self::potential_energy(self, q)
    }

    fn coordinate_rates(&self, _q: &[f64; 1], v: &[f64; 1]) -> [f64; 1] {
        *v
    }

    fn integrate_configuration(&self, q: &[f64; 1], v: &[f64; 1], h: f64) -> [f64; 1] {
        euler_update(q, v, h)
    }
}

/// Seed example 2 without gravity: a slender bar (mass `m`, length `l`, axis
/// `B.x`) at distance `d` from the vertical axis, turning about it by `phi`
/// and tilting about the arm by `theta`, driven by two torques. With `d = 0`
/// its mass matrix `diag(m d² + I cos²θ, I)`, `I = m l²/12`, is singular at
/// `theta = ±π/2`, where the bar lies along the vertical axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RotatingBar {
    pub m: f64,
    pub l: f64,
    pub d: f64,
}

impl RotatingBar {
    fn transverse_inertia(&self) -> f64 {
        self.m * self.l * self.l / 12.0
    }
}

impl MultibodySystem<2, 2, 2> for RotatingBar {
    const COORDINATES: [&'static str; 2] = ["phi", "theta"];
    const SPEEDS: [&'static str; 2] = ["dt(phi)", "dt(theta)"];
    const INPUTS: [&'static str; 2] = ["M_phi", "M_theta"];

    fn mass_matrix(&self, q: &[f64; 2]) -> [[f64; 2]; 2] {
        let i = self.transverse_inertia();
        let c = q[1].cos();
        [[self.m * self.d * self.d + i * c * c, 0.0], [0.0, i]]
    }

    fn forcing(&self, _t: f64, q: &[f64; 2], qd: &[f64; 2], u: &[f64; 2]) -> [f64; 2] {
        let i = self.transverse_inertia();
        let (s, c) = q[1].sin_cos();
        [
            2.0 * i * s * c * qd[0] * qd[1] + u[0],
            -i * s * c * qd[0] * qd[0] + u[1],
        ]
    }

    fn kinetic_energy(&self, q: &[f64; 2], qd: &[f64; 2]) -> f64 {
        let m = self.mass_matrix(q);
        0.5 * (m[0][0] * qd[0] * qd[0] + m[1][1] * qd[1] * qd[1])
    }

    fn potential_energy(&self, _q: &[f64; 2]) -> f64 {
        0.0
    }

    fn coordinate_rates(&self, _q: &[f64; 2], v: &[f64; 2]) -> [f64; 2] {
        *v
    }

    fn integrate_configuration(&self, q: &[f64; 2], v: &[f64; 2], h: f64) -> [f64; 2] {
        euler_update(q, v, h)
    }
}

/// Equations with a given constant mass matrix and forcing, to probe the
/// solver.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FixedEquations {
    pub mass: [[f64; 2]; 2],
    pub forcing: [f64; 2],
}

impl MultibodySystem<2, 2, 0> for FixedEquations {
    const COORDINATES: [&'static str; 2] = ["a", "b"];
    const SPEEDS: [&'static str; 2] = ["dt(a)", "dt(b)"];
    const INPUTS: [&'static str; 0] = [];

    fn mass_matrix(&self, _q: &[f64; 2]) -> [[f64; 2]; 2] {
        self.mass
    }

    fn forcing(&self, _t: f64, _q: &[f64; 2], _qd: &[f64; 2], _u: &[f64; 0]) -> [f64; 2] {
        self.forcing
    }

    fn kinetic_energy(&self, _q: &[f64; 2], qd: &[f64; 2]) -> f64 {
        let m = self.mass;
        0.5 * (m[0][0] * qd[0] * qd[0] + 2.0 * m[1][0] * qd[0] * qd[1] + m[1][1] * qd[1] * qd[1])
    }

    fn potential_energy(&self, _q: &[f64; 2]) -> f64 {
        0.0
    }

    fn coordinate_rates(&self, _q: &[f64; 2], v: &[f64; 2]) -> [f64; 2] {
        *v
    }

    fn integrate_configuration(&self, q: &[f64; 2], v: &[f64; 2], h: f64) -> [f64; 2] {
        euler_update(q, v, h)
    }
}
