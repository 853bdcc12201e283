//! A hand-derived constrained system for the unit tests, in the shape the
//! macro emits.

use crate::test_systems::euler_update;
use crate::{ConstrainedSystem, MultibodySystem};

/// A point mass `m` in the vertical plane, coordinates `(x, y)`, held on the
/// circle `x² + y² = l²` about the origin by each of its `NC` identical
/// constraint rows (`NC = 1` is a pendulum; `NC > 1` is redundant).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointOnCircle<const NC: usize> {
    pub m: f64,
    pub l: f64,
    pub g: f64,
}

impl<const NC: usize> MultibodySystem<2, 2, 0> for PointOnCircle<NC> {
    const COORDINATES: [&'static str; 2] = ["x", "y"];
    const SPEEDS: [&'static str; 2] = ["dt(x)", "dt(y)"];
    const INPUTS: [&'static str; 0] = [];

    fn mass_matrix(&self, _q: &[f64; 2]) -> [[f64; 2]; 2] {
        [[self.m, 0.0], [0.0, self.m]]
    }

    fn forcing(&self, _t: f64, _q: &[f64; 2], _qd: &[f64; 2], _u: &[f64; 0]) -> [f64; 2] {
        [0.0, -self.m * self.g]
    }

    fn kinetic_energy(&self, _q: &[f64; 2], qd: &[f64; 2]) -> f64 {
        0.5 * self.m * (qd[0] * qd[0] + qd[1] * qd[1])
    }

    fn potential_energy(&self, q: &[f64; 2]) -> f64 {
        self.m * self.g * q[1]
    }

    fn coordinate_rates(&self, _q: &[f64; 2], v: &[f64; 2]) -> [f64; 2] {
        *v
    }

    fn integrate_configuration(&self, q: &[f64; 2], v: &[f64; 2], h: f64) -> [f64; 2] {
        euler_update(q, v, h)
    }
}

impl<const NC: usize> ConstrainedSystem<2, 2, 0, NC> for PointOnCircle<NC> {
    fn constraint_jacobian(&self, q: &[f64; 2]) -> [[f64; 2]; NC] {
        [[2.0 * q[0], 2.0 * q[1]]; NC]
    }

    fn constraint_bias(&self, _t: f64, _q: &[f64; 2], qd: &[f64; 2]) -> [f64; NC] {
        [-2.0 * (qd[0] * qd[0] + qd[1] * qd[1]); NC]
    }

    fn constraint_residual(&self, _t: f64, q: &[f64; 2]) -> [f64; NC] {
        [q[0] * q[0] + q[1] * q[1] - self.l * self.l; NC]
    }

    fn constraint_velocity(&self, _t: f64, q: &[f64; 2], qd: &[f64; 2]) -> [f64; NC] {
        [2.0 * (q[0] * qd[0] + q[1] * qd[1]); NC]
    }
}

/// A mass `m` on a vertical line at height `y`, and a coordinate `s` with no
/// inertia of its own, pushed by a force `push` and tied to the mass by the
/// constraint `s − y = 0`: `M = diag(m, 0)` is singular, the KKT matrix is
/// not. Closed form: `ÿ = s̈ = push/m − g`, `λ = −push`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TiedMassless {
    pub m: f64,
    pub g: f64,
    pub push: f64,
}

impl MultibodySystem<2, 2, 0> for TiedMassless {
    const COORDINATES: [&'static str; 2] = ["y", "s"];
    const SPEEDS: [&'static str; 2] = ["dt(y)", "dt(s)"];
    const INPUTS: [&'static str; 0] = [];

    fn mass_matrix(&self, _q: &[f64; 2]) -> [[f64; 2]; 2] {
        [[self.m, 0.0], [0.0, 0.0]]
    }

    fn forcing(&self, _t: f64, _q: &[f64; 2], _v: &[f64; 2], _u: &[f64; 0]) -> [f64; 2] {
        [-self.m * self.g, self.push]
    }

    fn kinetic_energy(&self, _q: &[f64; 2], v: &[f64; 2]) -> f64 {
        0.5 * self.m * v[0] * v[0]
    }

    fn potential_energy(&self, q: &[f64; 2]) -> f64 {
        self.m * self.g * q[0] - self.push * q[1]
    }

    fn coordinate_rates(&self, _q: &[f64; 2], v: &[f64; 2]) -> [f64; 2] {
        *v
    }

    fn integrate_configuration(&self, q: &[f64; 2], v: &[f64; 2], h: f64) -> [f64; 2] {
        euler_update(q, v, h)
    }
}

impl ConstrainedSystem<2, 2, 0, 1> for TiedMassless {
    fn constraint_jacobian(&self, _q: &[f64; 2]) -> [[f64; 2]; 1] {
        [[-1.0, 1.0]]
    }

    fn constraint_bias(&self, _t: f64, _q: &[f64; 2], _v: &[f64; 2]) -> [f64; 1] {
        [0.0]
    }

    fn constraint_residual(&self, _t: f64, q: &[f64; 2]) -> [f64; 1] {
        [q[1] - q[0]]
    }

    fn constraint_velocity(&self, _t: f64, _q: &[f64; 2], v: &[f64; 2]) -> [f64; 1] {
        [v[1] - v[0]]
    }
}
