//! The traits that every generated system implements, so that solvers and
//! integrators work on any of them.
//!
//! A system has `NQ` generalized coordinates `q`, `NV` speeds `v` and `NU`
//! inputs `u`. Its equations of motion are `M(q) v̇ = f(t, q, v, u)` with the
//! kinematic equation `q̇ = N(q) v`. Today every generated system has
//! `NV = NQ` and `v = q̇`; joints whose configuration lives on a group
//! (a quaternion's four numbers for three rotational speeds) make them
//! differ.
//!
//! A system whose mass matrix, energies or constraint Jacobian depend on
//! time `t` (a mass moved by a prescribed motion: a shaken pivot, a
//! platform turned at a set rate) is [`TIME_DEPENDENT`](MultibodySystem::TIME_DEPENDENT):
//! the runtime calls the `_at` forms (`mass_matrix_at(t, q)`, ...), which
//! the time-free ones answer for every other system.

use crate::dynamics::{DynamicsError, cholesky_accelerations};

/// A system of equations of motion `M(q) v̇ = f(t, q, v, u)`, `q̇ = N(q) v`.
///
/// `NQ` is the number of generalized coordinates, `NV` the number of speeds
/// and `NU` the number of inputs. The `dalembert!` macro implements this
/// trait for every system it generates by forwarding to the struct's
/// inherent functions of the same names.
pub trait MultibodySystem<const NQ: usize, const NV: usize, const NU: usize> {
    /// Names of the generalized coordinates, in index order.
    const COORDINATES: [&'static str; NQ];
    /// Names of the speeds, in index order (`"dt(theta)"` when the speed is
    /// the coordinate's rate).
    const SPEEDS: [&'static str; NV];
    /// Names of the inputs, in index order.
    const INPUTS: [&'static str; NU];

    /// Whether time `t` enters `M`, `T`, `V` (or `A`): then the `_at`
    /// functions give them, and the time-free ones of a generated system
    /// return NaN (they depend on a time the call does not give).
    ///
    /// Provided: `false`.
    const TIME_DEPENDENT: bool = false;

    /// The symmetric mass matrix `M(q)`.
    fn mass_matrix(&self, q: &[f64; NQ]) -> [[f64; NV]; NV];

    /// The mass matrix `M(t, q)` at time `t`; what the solvers and
    /// integrators call.
    ///
    /// Provided: [`mass_matrix`](MultibodySystem::mass_matrix), for a
    /// time-free system. A time-dependent generated system overrides it.
    #[inline]
    fn mass_matrix_at(&self, t: f64, q: &[f64; NQ]) -> [[f64; NV]; NV] {
        let _ = t;
        self.mass_matrix(q)
    }

    /// The forcing `f(t, q, v, u)`: every generalized force other than the
    /// inertial term `M(q) v̇`, so that `M(q) v̇ = f`.
    fn forcing(&self, t: f64, q: &[f64; NQ], v: &[f64; NV], u: &[f64; NU]) -> [f64; NV];

    /// The kinetic energy `T(q, v)`.
    fn kinetic_energy(&self, q: &[f64; NQ], v: &[f64; NV]) -> f64;

    /// The kinetic energy `T(t, q, v)` at time `t`.
    ///
    /// Provided: [`kinetic_energy`](MultibodySystem::kinetic_energy).
    #[inline]
    fn kinetic_energy_at(&self, t: f64, q: &[f64; NQ], v: &[f64; NV]) -> f64 {
        let _ = t;
        self.kinetic_energy(q, v)
    }

    /// The potential energy `V(q)`: gravity relative to the origin `O` plus
    /// every `potential` statement.
    fn potential_energy(&self, q: &[f64; NQ]) -> f64;

    /// The potential energy `V(t, q)` at time `t`.
    ///
    /// Provided: [`potential_energy`](MultibodySystem::potential_energy).
    #[inline]
    fn potential_energy_at(&self, t: f64, q: &[f64; NQ]) -> f64 {
        let _ = t;
        self.potential_energy(q)
    }

    /// The coordinate rates `q̇ = N(q) v`.
    fn coordinate_rates(&self, q: &[f64; NQ], v: &[f64; NV]) -> [f64; NQ];

    /// `q ⊕ h v`: the configuration reached from `q` moving at the constant
    /// speeds `v` for the time `h` (an exact group update; `q + h v` when the
    /// speeds are the coordinates' rates).
    fn integrate_configuration(&self, q: &[f64; NQ], v: &[f64; NV], h: f64) -> [f64; NQ];

    /// Whether the coordinate rates `q̇ = N(q) v` are defined at `q`: an
    /// error naming the coordinate whose rate divides by a quantity that is
    /// (nearly) zero there
    /// ([`DynamicsError::SingularCoordinateRates`], with the tolerance
    /// [`SINGULAR_RATES_TOLERANCE`](crate::dynamics::SINGULAR_RATES_TOLERANCE)).
    /// The integrators call it at every state where they evaluate the
    /// accelerations.
    ///
    /// Provided: `Ok(())`, for systems whose `N(q)` divides by nothing.
    /// Generated systems with a `speeds` statement whose rates divide by an
    /// expression of the coordinates (`1 / cos θ`, `tan θ`) override it
    /// with their emitted check.
    #[inline]
    fn check_coordinate_rates(&self, _q: &[f64; NQ]) -> Result<(), DynamicsError> {
        Ok(())
    }

    /// The accelerations `v̇` that solve `M(q) v̇ = f(t, q, v, u)`.
    ///
    /// Provided: nalgebra's Cholesky factorisation of `M` on the stack, with
    /// the checks and errors that [`accelerations`](crate::accelerations)
    /// documents. Generated systems override it with their emitted solver,
    /// unrolled for their size; generated systems with constraints, with
    /// the accelerations the constraints allow
    /// ([`constrained_accelerations`](crate::constrained::constrained_accelerations),
    /// the multipliers dropped).
    fn accelerations(
        &self,
        t: f64,
        q: &[f64; NQ],
        v: &[f64; NV],
        u: &[f64; NU],
    ) -> Result<[f64; NV], DynamicsError> {
        cholesky_accelerations(self, t, q, v, u)
    }

    /// The accelerations of four states at once, state `k` being
    /// `(t[k], q[k], v[k], u[k])`: entry `k` is what
    /// [`accelerations`](MultibodySystem::accelerations) gives for state `k`.
    ///
    /// Provided: the four calls one after the other. A generated system
    /// whose model asks for `outputs accelerations_x4;` overrides it with
    /// its emitted solve over SIMD lanes, one state a lane (its inherent
    /// `accelerations_x4`; `docs/speed.md`, "Four states at once").
    fn accelerations_x4(
        &self,
        t: [f64; 4],
        q: &[[f64; NQ]; 4],
        v: &[[f64; NV]; 4],
        u: &[[f64; NU]; 4],
    ) -> [Result<[f64; NV], DynamicsError>; 4] {
        std::array::from_fn(|k| self.accelerations(t[k], &q[k], &v[k], &u[k]))
    }
}

/// A system with `NC` constraints: `M v̇ = f + Aᵀ λ` and `A v̇ = b`.
pub trait ConstrainedSystem<const NQ: usize, const NV: usize, const NU: usize, const NC: usize>:
    MultibodySystem<NQ, NV, NU>
{
    /// Whether each row vanishes identically: its Jacobian, bias, residual
    /// and velocity form are zero in every state (a `rolling` row of a
    /// wheel that cannot leave its plane, kept so that every `rolling`
    /// statement has its three rows). The solvers treat such rows as
    /// absent, with a zero multiplier.
    ///
    /// Provided: none. Generated systems with such a row override it, as
    /// the engine knows it at compile time.
    const VANISHING_ROWS: [bool; NC] = [false; NC];

    /// The constraint Jacobian `A(q)`, one row per constraint in declaration
    /// order.
    fn constraint_jacobian(&self, q: &[f64; NQ]) -> [[f64; NV]; NC];

    /// The constraint Jacobian `A(t, q)` at time `t`; what the solvers and
    /// integrators call.
    ///
    /// Provided: [`constraint_jacobian`](ConstrainedSystem::constraint_jacobian).
    #[inline]
    fn constraint_jacobian_at(&self, t: f64, q: &[f64; NQ]) -> [[f64; NV]; NC] {
        let _ = t;
        self.constraint_jacobian(q)
    }

    /// The constraint bias `b(t, q, v)` of the acceleration-level
    /// constraints `A v̇ = b`.
    fn constraint_bias(&self, t: f64, q: &[f64; NQ], v: &[f64; NV]) -> [f64; NC];

    /// The residual `lhs − rhs` of each holonomic constraint at `(t, q)`; `0`
    /// for the rows of nonholonomic constraints.
    fn constraint_residual(&self, t: f64, q: &[f64; NQ]) -> [f64; NC];

    /// The velocity form of each constraint at `(t, q, v)`: `dφ/dt` of a
    /// holonomic row, the row itself for a nonholonomic one; zero on the
    /// constraint manifold (velocity-level drift).
    fn constraint_velocity(&self, t: f64, q: &[f64; NQ], v: &[f64; NV]) -> [f64; NC];
}

/// The Taylor coefficients of a motion: `q[i][k]` and `v[i][k]` are the
/// coefficients of `τᵏ` in `qᵢ(t₀ + τ)` and `vᵢ(t₀ + τ)`.
pub type Expansion<const K: usize, const NQ: usize, const NV: usize> =
    ([[f64; K]; NQ], [[f64; K]; NV]);

/// A system whose model asks for `outputs taylor;`: the Taylor coefficients
/// of its motion through a state, which [`integrate::Taylor`](crate::integrate::Taylor)
/// sums.
pub trait TaylorSystem<const NQ: usize, const NV: usize, const NU: usize>:
    MultibodySystem<NQ, NV, NU>
{
    /// The coefficients of orders `0..=order` (at most `K − 1`; the rest are
    /// zero) of the motion through `(t, q, v)` with the inputs `u` held
    /// constant (for a system with constraints, the motion of its index-1
    /// form `M v̇ = f + Aᵀ λ`, `A v̇ = b`), or why they cannot be computed:
    /// the errors of [`accelerations`](crate::accelerations) for the system
    /// (a non-finite state, a singular mass matrix; with constraints, those
    /// of [`constrained_accelerations`](crate::constrained::constrained_accelerations)).
    fn taylor_coefficients<const K: usize>(
        &self,
        t: f64,
        q: &[f64; NQ],
        v: &[f64; NV],
        u: &[f64; NU],
        order: usize,
    ) -> Result<Expansion<K, NQ, NV>, DynamicsError>;
}

/// The model a generated system was derived from: its text and its
/// parameters' values, so that tools reading the model (the animated
/// scenes of `dalembert-lab`: `Scene::of(&system)`) need nothing pasted.
///
/// `NP` is the number of parameters. The `dalembert!` macro and the build
/// script's generated code implement it for every system with `std`.
pub trait Model<const NP: usize> {
    /// The model's text: the `.dal` file (or an imported robot's model) as
    /// the build script read it, or the macro's input as its tokens read
    /// (the same tokens; comments other than docs are not kept).
    const SOURCE: &'static str;
    /// Names of the parameters, in field order.
    const PARAMETERS: [&'static str; NP];

    /// The parameters' values, in field order.
    fn parameter_values(&self) -> [f64; NP];
}
