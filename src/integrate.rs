//! Time integration of `M(q) q̈ = f(t, q, q̇, u)` as a first-order system in
//! `(q, q̇)`, with the inputs given as a law `u(t, q, q̇)`.
//!
//! Steppers are plain functions from a [`State`] to the next one; they
//! allocate nothing, and report a failure with the time and configuration at
//! which the equations could not be solved.

use std::fmt;

use crate::equations::Counted;
use crate::{DynamicsError, Equations, MultibodySystem, Solution, SolverError, accelerations};

/// A point of a trajectory: time, coordinates and speeds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct State<const NQ: usize> {
    /// Time `t`.
    pub t: f64,
    /// Generalized coordinates `q`.
    pub q: [f64; NQ],
    /// Generalized speeds `q̇`.
    pub qd: [f64; NQ],
}

/// The equations could not be solved during a step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IntegrationError<const NQ: usize> {
    /// Time of the failing evaluation (a stage of the step, so it may lie
    /// between two steps).
    pub t: f64,
    /// Configuration of the failing evaluation.
    pub q: [f64; NQ],
    /// Why the accelerations could not be computed there.
    pub cause: DynamicsError,
}

impl<const NQ: usize> fmt::Display for IntegrationError<NQ> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} at t = {} s, q = {:?}", self.cause, self.t, self.q)
    }
}

/// The cause is part of the message, so it is not repeated as a `source`.
impl<const NQ: usize> std::error::Error for IntegrationError<NQ> {}

/// One step of length `h` of the classical fourth-order Runge–Kutta method.
///
/// `inputs` gives the inputs `u` at a time, configuration and speed (a
/// feedback law, or a function of time alone); it is called at every stage.
pub fn rk4_step<S, const NQ: usize, const NU: usize>(
    system: &S,
    state: &State<NQ>,
    inputs: impl Fn(f64, &[f64; NQ], &[f64; NQ]) -> [f64; NU],
    h: f64,
) -> Result<State<NQ>, IntegrationError<NQ>>
where
    S: MultibodySystem<NQ, NU>,
{
    rk4_step_with(state, h, |t, q, qd| {
        accelerations(system, t, q, qd, &inputs(t, q, qd))
    })
}

/// One classical RK4 step of length `h` of `q̇' = q̈(t, q, q̇)`, with the
/// accelerations given by `acceleration` (the stepper shared by
/// unconstrained and constrained integration).
pub(crate) fn rk4_step_with<const NQ: usize>(
    state: &State<NQ>,
    h: f64,
    acceleration: impl Fn(f64, &[f64; NQ], &[f64; NQ]) -> Result<[f64; NQ], DynamicsError>,
) -> Result<State<NQ>, IntegrationError<NQ>> {
    let rate = |stage: &State<NQ>| Rate::at(&acceleration, stage);
    let k1 = rate(state)?;
    let k2 = rate(&k1.advance(state, h / 2.0))?;
    let k3 = rate(&k2.advance(state, h / 2.0))?;
    let k4 = rate(&k3.advance(state, h))?;
    let weighted = Rate::weighted_sum([(1.0, &k1), (2.0, &k2), (2.0, &k3), (1.0, &k4)], 6.0);
    Ok(weighted.advance(state, h))
}

/// Integrates `steps` fixed steps of length `h` with [`rk4_step`], from
/// `initial`, and returns the final state.
///
/// `observer` sees the initial state and then the state after every step.
/// Stops at the first step that fails.
pub fn simulate<S, const NQ: usize, const NU: usize>(
    system: &S,
    initial: State<NQ>,
    inputs: impl Fn(f64, &[f64; NQ], &[f64; NQ]) -> [f64; NU],
    h: f64,
    steps: usize,
    observer: impl FnMut(&State<NQ>),
) -> Result<State<NQ>, IntegrationError<NQ>>
where
    S: MultibodySystem<NQ, NU>,
{
    march(
        initial,
        steps as u64,
        |state| rk4_step(system, state, &inputs, h),
        observer,
    )
}

/// Integrates `steps` fixed steps of length `h` of `equations` with the
/// classical RK4 method (settled after each step), and returns the final
/// state with the work done: [`simulate`] for any [`Equations`], with the
/// report of the other integrators.
///
/// `observer` sees the initial state and then the state after every step.
/// Stops at the first step that fails.
pub fn simulate_rk4<E, const NQ: usize>(
    equations: &E,
    initial: State<NQ>,
    h: f64,
    steps: u64,
    observer: impl FnMut(&State<NQ>),
) -> Result<Solution<NQ>, SolverError<NQ>>
where
    E: Equations<NQ>,
{
    let counted = Counted::new(equations);
    let acceleration = counted.acceleration();
    let step =
        |state: &State<NQ>| rk4_step_with(state, h, &acceleration).map_err(SolverError::from);
    counted.fixed_steps(initial, steps, step, observer)
}

/// Applies `step` `steps` times from `initial` and returns the final state;
/// `observer` sees the initial state and then every new one. Stops at the
/// first step that fails.
pub(crate) fn march<const NQ: usize, Error>(
    initial: State<NQ>,
    steps: u64,
    mut step: impl FnMut(&State<NQ>) -> Result<State<NQ>, Error>,
    mut observer: impl FnMut(&State<NQ>),
) -> Result<State<NQ>, Error> {
    observer(&initial);
    let mut state = initial;
    for _ in 0..steps {
        state = step(&state)?;
        observer(&state);
    }
    Ok(state)
}

/// The time derivative of a [`State`]: `(q̇, q̈)`, the slope of one stage
/// of a Runge–Kutta method.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Rate<const NQ: usize> {
    /// `q̇`.
    pub(crate) dq: [f64; NQ],
    /// `q̈`.
    pub(crate) dqd: [f64; NQ],
}

impl<const NQ: usize> Rate<NQ> {
    /// No motion: the placeholder of a stage not yet evaluated.
    pub(crate) const ZERO: Self = Self {
        dq: [0.0; NQ],
        dqd: [0.0; NQ],
    };

    /// Evaluates the equations of motion, given as `acceleration`, at
    /// `state`.
    pub(crate) fn at(
        acceleration: &impl Fn(f64, &[f64; NQ], &[f64; NQ]) -> Result<[f64; NQ], DynamicsError>,
        state: &State<NQ>,
    ) -> Result<Self, IntegrationError<NQ>> {
        let State { t, q, qd } = state;
        let qdd = acceleration(*t, q, qd).map_err(|cause| IntegrationError {
            t: *t,
            q: *q,
            cause,
        })?;
        Ok(Self { dq: *qd, dqd: qdd })
    }

    /// `state` moved on by `dt` along this rate (an explicit Euler step).
    pub(crate) fn advance(&self, state: &State<NQ>, dt: f64) -> State<NQ> {
        State {
            t: state.t + dt,
            q: axpy(&state.q, dt, &self.dq),
            qd: axpy(&state.qd, dt, &self.dqd),
        }
    }

    /// `Σ wᵢ kᵢ / denominator`.
    fn weighted_sum<const K: usize>(terms: [(f64, &Self); K], denominator: f64) -> Self {
        let sum = |part: fn(&Self) -> &[f64; NQ]| {
            std::array::from_fn(|i| {
                terms.iter().map(|(w, k)| w * part(k)[i]).sum::<f64>() / denominator
            })
        };
        Self {
            dq: sum(|k| &k.dq),
            dqd: sum(|k| &k.dqd),
        }
    }

    /// `Σⱼ weights[j] · stages[j]`, skipping zero weights (a row of a
    /// Butcher tableau applied to the stage slopes).
    pub(crate) fn combination<const S: usize>(weights: &[f64; S], stages: &[Self; S]) -> Self {
        let mut sum = Self::ZERO;
        for (&w, k) in weights.iter().zip(stages).filter(|(w, _)| **w != 0.0) {
            for i in 0..NQ {
                sum.dq[i] += w * k.dq[i];
                sum.dqd[i] += w * k.dqd[i];
            }
        }
        sum
    }

    /// The stage state of a Runge–Kutta step of length `h` from `state`:
    /// coordinates and speeds moved by `h` times this combined slope, at the
    /// stage time `t + c h`.
    pub(crate) fn stage(&self, state: &State<NQ>, h: f64, c: f64) -> State<NQ> {
        State {
            t: state.t + c * h,
            ..self.advance(state, h)
        }
    }

    /// The largest magnitude of any entry.
    pub(crate) fn largest_magnitude(&self) -> f64 {
        self.dq
            .iter()
            .chain(&self.dqd)
            .fold(0.0, |m, x| m.max(x.abs()))
    }

    /// `self − other`, entry by entry.
    pub(crate) fn minus(&self, other: &Self) -> Self {
        Self {
            dq: std::array::from_fn(|i| self.dq[i] - other.dq[i]),
            dqd: std::array::from_fn(|i| self.dqd[i] - other.dqd[i]),
        }
    }
}

/// `x + a y`.
pub(crate) fn axpy<const N: usize>(x: &[f64; N], a: f64, y: &[f64; N]) -> [f64; N] {
    std::array::from_fn(|i| x[i] + a * y[i])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::energy;
    use crate::test_systems::{Pendulum, RotatingBar};
    use std::f64::consts::FRAC_PI_2;

    const PENDULUM: Pendulum = Pendulum {
        m: 1.0,
        l: 1.0,
        g: 9.81,
    };

    fn no_inputs(_: f64, _: &[f64; 1], _: &[f64; 1]) -> [f64; 0] {
        []
    }

    fn at_rest(angle: f64) -> State<1> {
        State {
            t: 0.0,
            q: [angle],
            qd: [0.0],
        }
    }

    /// The pendulum angle after `duration` in steps of `h`.
    fn pendulum_angle(duration: f64, h: f64) -> f64 {
        let steps = (duration / h).round() as usize;
        let end = simulate(&PENDULUM, at_rest(1.0), no_inputs, h, steps, |_| {}).unwrap();
        assert!((end.t - duration).abs() < 1e-9);
        end.q[0]
    }

    #[test]
    fn rk4_conserves_pendulum_energy_over_ten_seconds() {
        let start = at_rest(1.0);
        let initial_energy = energy(&PENDULUM, &start.q, &start.qd);
        let mut worst_drift: f64 = 0.0;
        let observe = |s: &State<1>| {
            let drift = energy(&PENDULUM, &s.q, &s.qd) - initial_energy;
            worst_drift = worst_drift.max(drift.abs());
        };
        let end = simulate(&PENDULUM, start, no_inputs, 1e-3, 10_000, observe).unwrap();
        let energy_scale = PENDULUM.m * PENDULUM.g * PENDULUM.l;
        assert!(worst_drift < 1e-8 * energy_scale, "drift {worst_drift}");
        assert!(end.qd[0] != 0.0, "the pendulum must have moved");
    }

    #[test]
    fn small_swings_have_the_small_angle_period() {
        // Downward zero crossings of the angle are one period apart.
        let mut crossings = [0.0; 2];
        let mut found = 0;
        let mut previous = at_rest(0.01);
        let observe = |s: &State<1>| {
            if previous.q[0] > 0.0 && s.q[0] <= 0.0 && found < crossings.len() {
                let fraction = previous.q[0] / (previous.q[0] - s.q[0]);
                crossings[found] = previous.t + fraction * (s.t - previous.t);
                found += 1;
            }
            previous = *s;
        };
        simulate(&PENDULUM, at_rest(0.01), no_inputs, 1e-3, 5_000, observe).unwrap();
        assert_eq!(found, 2);
        let period = crossings[1] - crossings[0];
        let expected = PENDULUM.small_angle_period();
        assert!(
            (period / expected - 1.0).abs() < 1e-4,
            "{period} vs {expected}"
        );
    }

    #[test]
    fn rk4_error_falls_sixteenfold_when_the_step_halves() {
        let reference = pendulum_angle(1.0, 1e-4);
        let errors = [0.02, 0.01, 0.005].map(|h| (pendulum_angle(1.0, h) - reference).abs());
        for pair in errors.windows(2) {
            let ratio = pair[0] / pair[1];
            assert!((12.0..20.0).contains(&ratio), "errors {errors:?}");
        }
    }

    #[test]
    fn inputs_are_evaluated_at_each_stage_state() {
        // A constant torque on the bar's tilt: θ̈ = u / I exactly while φ̇ = 0.
        let bar = RotatingBar {
            m: 12.0,
            l: 1.0,
            d: 1.0,
        };
        let start = State {
            t: 0.0,
            q: [0.0; 2],
            qd: [0.0; 2],
        };
        let torque = |t: f64, _: &[f64; 2], _: &[f64; 2]| [0.0, 2.0 * t];
        let end = rk4_step(&bar, &start, torque, 0.5).unwrap();
        // θ̈ = 2t (I = 1), so θ = t³/3 and θ̇ = t², which RK4 integrates exactly.
        assert!((end.q[1] - 0.125 / 3.0).abs() < 1e-15, "{end:?}");
        assert!((end.qd[1] - 0.25).abs() < 1e-15 && end.q[0] == 0.0);
    }

    #[test]
    fn simulate_stops_where_the_mass_matrix_turns_singular() {
        // Without spin the bar tilts at a constant rate and reaches the
        // vertical axis, θ = π/2, at t = 0.5.
        let bar = RotatingBar {
            m: 1.0,
            l: 1.0,
            d: 0.0,
        };
        let start = State {
            t: 0.0,
            q: [0.0, FRAC_PI_2 - 0.5],
            qd: [0.0, 1.0],
        };
        let mut observed = 0;
        let error =
            simulate(&bar, start, |_, _, _| [0.0; 2], 0.125, 8, |_| observed += 1).unwrap_err();
        assert_eq!(error.t, 0.5);
        assert!((error.q[1] - FRAC_PI_2).abs() < 1e-12);
        assert!(matches!(
            error.cause,
            DynamicsError::SingularMassMatrix {
                coordinate: "phi",
                ..
            }
        ));
        assert_eq!(observed, 4, "the initial state and three good steps");
        let message = error.to_string();
        assert!(message.starts_with("singular mass matrix"), "{message}");
        assert!(
            message.contains("at t = 0.5 s, q = [0.0, 1.57"),
            "{message}"
        );
    }

    #[test]
    fn non_finite_inputs_fail_the_step_at_the_stage_that_used_them() {
        let bar = RotatingBar {
            m: 1.0,
            l: 1.0,
            d: 1.0,
        };
        let start = State {
            t: 2.0,
            q: [0.1, 0.2],
            qd: [0.0; 2],
        };
        let torque_fails_later = |t: f64, _: &[f64; 2], _: &[f64; 2]| {
            if t > 2.0 { [f64::NAN, 0.0] } else { [0.0; 2] }
        };
        let error = rk4_step(&bar, &start, torque_fails_later, 0.5).unwrap_err();
        assert_eq!(error.cause, DynamicsError::NonFiniteState);
        assert_eq!((error.t, error.q), (2.25, [0.1, 0.2]), "the second stage");
    }

    #[test]
    fn non_finite_state_fails_the_first_stage() {
        let error = rk4_step(&PENDULUM, &at_rest(f64::INFINITY), no_inputs, 0.1).unwrap_err();
        assert_eq!(error.cause, DynamicsError::NonFiniteState);
        assert_eq!((error.t, error.q), (0.0, [f64::INFINITY]));
    }
}
