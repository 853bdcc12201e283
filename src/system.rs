//! The traits that every generated system implements, so that solvers and
//! integrators work on any of them.

/// A system of equations of motion `M(q) q̈ = f(t, q, q̇, u)`.
///
/// `NQ` is the number of generalized coordinates and `NU` the number of
/// inputs. The `dalembert!` macro implements this trait for every system it
/// generates by forwarding to the struct's inherent functions of the same
/// names.
pub trait MultibodySystem<const NQ: usize, const NU: usize> {
    /// Names of the generalized coordinates, in index order.
    const COORDINATES: [&'static str; NQ];
    /// Names of the inputs, in index order.
    const INPUTS: [&'static str; NU];

    /// The symmetric mass matrix `M(q)`.
    fn mass_matrix(&self, q: &[f64; NQ]) -> [[f64; NQ]; NQ];

    /// The forcing `f(t, q, q̇, u)`: every generalized force other than the
    /// inertial term `M(q) q̈`, so that `M(q) q̈ = f`.
    fn forcing(&self, t: f64, q: &[f64; NQ], qd: &[f64; NQ], u: &[f64; NU]) -> [f64; NQ];

    /// The kinetic energy `T(q, q̇)`.
    fn kinetic_energy(&self, q: &[f64; NQ], qd: &[f64; NQ]) -> f64;

    /// The potential energy `V(q)`: gravity relative to the origin `O` plus
    /// every `potential` statement.
    fn potential_energy(&self, q: &[f64; NQ]) -> f64;
}

/// A system with `NC` constraints: `M q̈ = f + Aᵀ λ` and `A q̈ = b`.
pub trait ConstrainedSystem<const NQ: usize, const NU: usize, const NC: usize>:
    MultibodySystem<NQ, NU>
{
    /// The constraint Jacobian `A(q)`, one row per constraint in declaration
    /// order.
    fn constraint_jacobian(&self, q: &[f64; NQ]) -> [[f64; NQ]; NC];

    /// The constraint bias `b(t, q, q̇)` of the acceleration-level
    /// constraints `A q̈ = b`.
    fn constraint_bias(&self, t: f64, q: &[f64; NQ], qd: &[f64; NQ]) -> [f64; NC];

    /// The residual `lhs − rhs` of each holonomic constraint at `(t, q)`; `0`
    /// for the rows of nonholonomic constraints.
    fn constraint_residual(&self, t: f64, q: &[f64; NQ]) -> [f64; NC];

    /// The velocity form of each constraint at `(t, q, q̇)`: `dφ/dt` of a
    /// holonomic row, the row itself for a nonholonomic one; zero on the
    /// constraint manifold (velocity-level drift).
    fn constraint_velocity(&self, t: f64, q: &[f64; NQ], qd: &[f64; NQ]) -> [f64; NC];
}
