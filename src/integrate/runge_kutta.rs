//! The Runge–Kutta kernel shared by every integrator: the [`State`], the
//! slope of a stage ([`Rate`]: the coordinates' rates `q̇ = N(q) v` and the
//! accelerations), stages moved along slopes, each step's end put back on
//! the configuration manifold, evaluations counted, and the fixed-step march
//! that ends exactly at the final time; with it, the classical fourth-order
//! method.

use std::cell::Cell;

use super::arguments::{BAD_STEP, check_positive, fixed_steps_to_take};
use super::integration::{Method, sealed};
use super::{Dynamics, IntegrationError, Solution, Statistics};
use crate::DynamicsError;

/// A point of a trajectory: time, coordinates and speeds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct State<const NQ: usize, const NV: usize> {
    /// Time `t`.
    pub t: f64,
    /// Generalized coordinates `q`.
    pub q: [f64; NQ],
    /// Speeds `v` (the coordinates' rates `q̇` for every system generated
    /// today).
    pub v: [f64; NV],
}

/// The slope of one stage of a Runge–Kutta method: the coordinates' rates
/// `q̇ = N(q) v` and the accelerations `v̇`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Rate<const NQ: usize, const NV: usize> {
    /// The coordinates' rates `q̇`.
    pub(crate) dq: [f64; NQ],
    /// The accelerations `v̇`.
    pub(crate) dv: [f64; NV],
}

impl<const NQ: usize, const NV: usize> Rate<NQ, NV> {
    /// No motion: the placeholder of a stage not yet evaluated.
    pub(crate) const ZERO: Self = Self {
        dq: [0.0; NQ],
        dv: [0.0; NV],
    };

    /// `Σⱼ weights[j] · stages[j]` (a row of a Butcher tableau applied to
    /// the stage slopes).
    #[inline(always)]
    pub(crate) fn combination<const S: usize>(weights: &[f64; S], stages: &[Self; S]) -> Self {
        Self::combination_of_first(S, weights, stages)
    }

    /// `Σⱼ weights[j] · stages[j]` over `j < count`: the row of an explicit stage,
    /// which weighs only the stages before it. Branch-free: testing each
    /// weight for zero costs more, in mispredictions, than its flops.
    #[inline(always)]
    pub(crate) fn combination_of_first<const S: usize>(
        count: usize,
        weights: &[f64; S],
        stages: &[Self; S],
    ) -> Self {
        let mut sum = Self::ZERO;
        for (&w, k) in weights.iter().zip(stages).take(count) {
            sum.add_scaled(w, k);
        }
        sum
    }

    /// `self += w · other`.
    #[inline(always)]
    pub(crate) fn add_scaled(&mut self, w: f64, other: &Self) {
        for i in 0..NQ {
            self.dq[i] += w * other.dq[i];
        }
        for i in 0..NV {
            self.dv[i] += w * other.dv[i];
        }
    }

    /// `self *= s`.
    #[inline(always)]
    pub(crate) fn scale(&mut self, s: f64) {
        for x in self.dq.iter_mut().chain(&mut self.dv) {
            *x *= s;
        }
    }

    /// The largest magnitude of any entry of `self − other` (a NaN entry
    /// ignored), in four independent running maxima over plain index loops:
    /// one chain of `f64::max` over chained iterators costs, per entry, its
    /// latency and the iterators' bookkeeping.
    #[inline(always)]
    pub(crate) fn largest_difference(&self, other: &Self) -> f64 {
        let mut largest = [0.0f64; 4];
        let mut keep = |k: usize, difference: f64| {
            let magnitude = difference.abs();
            if magnitude > largest[k % 4] {
                largest[k % 4] = magnitude;
            }
        };
        for i in 0..NQ {
            keep(i, self.dq[i] - other.dq[i]);
        }
        for i in 0..NV {
            keep(NQ + i, self.dv[i] - other.dv[i]);
        }
        largest[0].max(largest[1]).max(largest[2].max(largest[3]))
    }

    /// `self − other`, entry by entry.
    pub(crate) fn minus(&self, other: &Self) -> Self {
        Self {
            dq: std::array::from_fn(|i| self.dq[i] - other.dq[i]),
            dv: std::array::from_fn(|i| self.dv[i] - other.dv[i]),
        }
    }
}

/// The dynamics as the Runge–Kutta stages use them: slopes evaluated and
/// counted (the work measure of [`Statistics`]), states moved along slopes,
/// and the correction after a step.
///
/// The small functions of the stages are `#[inline(always)]`: each is a few
/// flops per entry between two evaluations, and a call or a spilled
/// temporary there is measurable next to the generated equations
/// (`generated/benches/integrators.rs`).
pub(crate) struct Kernel<'a, D> {
    dynamics: &'a D,
    evaluations: Cell<u64>,
}

impl<'a, D> Kernel<'a, D> {
    /// `dynamics`, counting from zero.
    pub(crate) fn new(dynamics: &'a D) -> Self {
        Self {
            dynamics,
            evaluations: Cell::new(0),
        }
    }

    /// The dynamics.
    pub(crate) fn dynamics(&self) -> &'a D {
        self.dynamics
    }

    /// Evaluations of the accelerations so far.
    pub(crate) fn evaluations(&self) -> u64 {
        self.evaluations.get()
    }

    /// The accelerations at `(t, q, v)`, counted; a failure names `(t, q)`.
    #[inline(always)]
    pub(crate) fn accelerations<const NQ: usize, const NV: usize>(
        &self,
        t: f64,
        q: &[f64; NQ],
        v: &[f64; NV],
    ) -> Result<[f64; NV], IntegrationError<NQ>>
    where
        D: Dynamics<NQ, NV>,
    {
        self.evaluations.set(self.evaluations.get() + 1);
        self.dynamics
            .accelerations(t, q, v)
            .map_err(|cause| IntegrationError::dynamics(t, *q, cause))
    }

    /// The slope at `state`.
    #[inline(always)]
    pub(crate) fn rate<const NQ: usize, const NV: usize>(
        &self,
        state: &State<NQ, NV>,
    ) -> Result<Rate<NQ, NV>, IntegrationError<NQ>>
    where
        D: Dynamics<NQ, NV>,
    {
        let dv = self.accelerations(state.t, &state.q, &state.v)?;
        let dq = self.dynamics.coordinate_rates(&state.q, &state.v);
        Ok(Rate { dq, dv })
    }

    /// `state` moved on by `dt` along `rate` (an explicit Euler step of both
    /// the coordinates and the speeds).
    #[inline(always)]
    pub(crate) fn advance<const NQ: usize, const NV: usize>(
        &self,
        state: &State<NQ, NV>,
        rate: &Rate<NQ, NV>,
        dt: f64,
    ) -> State<NQ, NV> {
        State {
            t: state.t + dt,
            q: std::array::from_fn(|i| state.q[i] + dt * rate.dq[i]),
            v: std::array::from_fn(|i| state.v[i] + dt * rate.dv[i]),
        }
    }

    /// The end of a step of length `h` from `state` along the combined slope
    /// `rate`, its configuration put back on the system's manifold.
    #[inline(always)]
    pub(crate) fn step_end<const NQ: usize, const NV: usize>(
        &self,
        state: &State<NQ, NV>,
        rate: &Rate<NQ, NV>,
        h: f64,
    ) -> State<NQ, NV>
    where
        D: Dynamics<NQ, NV>,
    {
        let end = self.advance(state, rate, h);
        State {
            q: self.dynamics.renormalise(&end.q),
            ..end
        }
    }

    /// The stage state of a step of length `h` from `state`: moved by `h`
    /// times the combined slope `rate`, at the stage time `t + c h`.
    #[inline(always)]
    pub(crate) fn stage<const NQ: usize, const NV: usize>(
        &self,
        state: &State<NQ, NV>,
        rate: &Rate<NQ, NV>,
        h: f64,
        c: f64,
    ) -> State<NQ, NV> {
        State {
            t: state.t + c * h,
            ..self.advance(state, rate, h)
        }
    }

    /// The dynamics' correction after a step from `start` that ended at
    /// `state`, then their [`watch`](Dynamics::watch) of the result; a
    /// failing correction is reported at `state`, a failing watch or a
    /// step that overflowed (a NaN or infinite end, which no later
    /// evaluation would catch after the last step) at `start` (the last
    /// good state).
    pub(crate) fn settle<const NQ: usize, const NV: usize>(
        &self,
        start: &State<NQ, NV>,
        state: &State<NQ, NV>,
    ) -> Result<State<NQ, NV>, IntegrationError<NQ>>
    where
        D: Dynamics<NQ, NV>,
    {
        if !state.q.iter().chain(&state.v).all(|x| x.is_finite()) {
            let cause = DynamicsError::NonFiniteAccelerations;
            return Err(IntegrationError::dynamics(start.t, start.q, cause));
        }
        let settled = self
            .dynamics
            .settle(state)
            .map_err(|cause| IntegrationError::dynamics(state.t, state.q, cause))?;
        self.dynamics
            .watch(&settled)
            .map_err(|cause| IntegrationError::at(start, cause))?;
        Ok(settled)
    }

    /// Whether the dynamics may start from `initial`
    /// ([`check_start`](Dynamics::check_start)).
    pub(crate) fn check_start<const NQ: usize, const NV: usize>(
        &self,
        initial: &State<NQ, NV>,
    ) -> Result<(), IntegrationError<NQ>>
    where
        D: Dynamics<NQ, NV>,
    {
        self.dynamics
            .check_start(initial)
            .map_err(|cause| IntegrationError::at(initial, cause))
    }

    /// `steps` fixed steps from `initial` to `t_end`: `step(state, h)` takes a
    /// state to the next, which is then settled and given the step's end
    /// time exactly (`t₀ + k (t_end − t₀) / steps`, the last one `t_end`
    /// itself). `observer` sees the initial state and every settled one.
    /// Returns the final state with the work done; stops at the first step
    /// that fails. Refuses what it cannot start from (see `arguments.rs`),
    /// and takes no step when `t_end` is the initial time.
    pub(crate) fn fixed_steps<const NQ: usize, const NV: usize>(
        &self,
        initial: State<NQ, NV>,
        t_end: f64,
        steps: u64,
        mut step: impl FnMut(&State<NQ, NV>, f64) -> Result<State<NQ, NV>, IntegrationError<NQ>>,
        mut observer: impl FnMut(&State<NQ, NV>),
    ) -> Result<Solution<NQ, NV>, IntegrationError<NQ>>
    where
        D: Dynamics<NQ, NV>,
    {
        let steps = fixed_steps_to_take(&initial, t_end, steps)?;
        self.check_start(&initial)?;
        observer(&initial);
        let span = t_end - initial.t;
        let mut state = initial;
        for k in 1..=steps {
            let t = if k == steps {
                t_end
            } else {
                initial.t + span * (k as f64 / steps as f64)
            };
            let mut next = step(&state, t - state.t)?;
            next.t = t;
            state = self.settle(&state, &next)?;
            observer(&state);
        }
        Ok(Solution {
            end: state,
            statistics: Statistics {
                rhs_evaluations: self.evaluations(),
                accepted_steps: steps,
                rejected_steps: 0,
            },
        })
    }
}

/// The classical fourth-order Runge–Kutta method in `steps` equal steps to
/// the final time (settled after each step): real-time loops, reproducible
/// runs, a cheap default. The final state is exactly at the final time; a
/// failing step's error names the time and configuration of the failing
/// stage.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Rk4 {
    /// The number of equal steps to the final time.
    pub steps: u64,
}

impl Rk4 {
    /// One step of length `h` of the method from `state`, settled: the
    /// building block of a control loop that changes its inputs between
    /// steps.
    pub fn step<D, const NQ: usize, const NV: usize>(
        dynamics: &D,
        state: &State<NQ, NV>,
        h: f64,
    ) -> Result<State<NQ, NV>, IntegrationError<NQ>>
    where
        D: Dynamics<NQ, NV>,
    {
        check_positive(state, h, BAD_STEP)?;
        let kernel = Kernel::new(dynamics);
        kernel.settle(state, &rk4_stages(&kernel, state, h)?)
    }
}

impl sealed::Sealed for Rk4 {}

impl<D, const NQ: usize, const NV: usize> Method<D, NQ, NV> for Rk4
where
    D: Dynamics<NQ, NV>,
{
    fn integrate(
        self,
        dynamics: &D,
        initial: State<NQ, NV>,
        t_end: f64,
        observer: impl FnMut(&State<NQ, NV>),
    ) -> Result<Solution<NQ, NV>, IntegrationError<NQ>> {
        let kernel = Kernel::new(dynamics);
        let step = |state: &State<NQ, NV>, h| rk4_stages(&kernel, state, h);
        kernel.fixed_steps(initial, t_end, self.steps, step, observer)
    }
}

/// The fraction of the step at which each of the first three slopes of RK4
/// places the next stage.
const RK4_NODES: [f64; 3] = [0.5, 0.5, 1.0];

/// The weights of the classical RK4 stages.
const RK4_WEIGHTS: [f64; 4] = [1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0];

/// The four stages of a classical RK4 step of length `h` from `state`.
///
/// Each slope is added into the weighted sum as soon as it is known (the
/// same operations in the same order as summing the four at the end): kept
/// in an array, the slopes were stored piecewise and read back 256 bits at
/// a time in AVX builds, a failed store-to-load forwarding on every step
/// (BENCHMARKS.md, "The host CPU's slowdowns").
///
/// The stages are a loop around one evaluation: with a single call site the
/// compiler inlines the system's accelerations into it, as into a bare loop
/// of calls; four call sites kept them out of line, and each evaluation of
/// the planar chain of 12 then cost a fifth more (BENCHMARKS.md,
/// "Integrators: cost per evaluation").
fn rk4_stages<D, const NQ: usize, const NV: usize>(
    kernel: &Kernel<'_, D>,
    state: &State<NQ, NV>,
    h: f64,
) -> Result<State<NQ, NV>, IntegrationError<NQ>>
where
    D: Dynamics<NQ, NV>,
{
    let mut weighted = Rate::ZERO;
    let mut stage = *state;
    for (i, weight) in RK4_WEIGHTS.into_iter().enumerate() {
        let slope = kernel.rate(&stage)?;
        weighted.add_scaled(weight, &slope);
        if let Some(fraction) = RK4_NODES.get(i) {
            stage = kernel.advance(state, &slope, fraction * h);
        }
    }
    Ok(kernel.step_end(state, &weighted, h))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrate::{Failure, Integration};
    use crate::test_systems::{Pendulum, RotatingBar};
    use crate::{DynamicsError, Unconstrained, energy};
    use std::f64::consts::FRAC_PI_2;

    const PENDULUM: Pendulum = Pendulum {
        m: 1.0,
        l: 1.0,
        g: 9.81,
    };

    fn at_rest(angle: f64) -> State<1, 1> {
        State {
            t: 0.0,
            q: [angle],
            v: [0.0],
        }
    }

    /// A bar of unit transverse inertia (`m l² / 12 = 1`), one metre from
    /// its vertical axis.
    const UNIT_BAR: RotatingBar = RotatingBar {
        m: 12.0,
        l: 1.0,
        d: 1.0,
    };

    /// [`UNIT_BAR`] level and at rest.
    const UNIT_BAR_AT_REST: State<2, 2> = State {
        t: 0.0,
        q: [0.0; 2],
        v: [0.0; 2],
    };

    /// The pendulum angle after `duration` in steps of `h`.
    fn pendulum_angle(duration: f64, h: f64) -> f64 {
        let steps = (duration / h).round() as u64;
        let dynamics = Unconstrained::without_inputs(&PENDULUM);
        let end = Integration::new(&dynamics, at_rest(1.0), duration, Rk4 { steps })
            .run()
            .unwrap()
            .end;
        assert_eq!(end.t, duration);
        end.q[0]
    }

    #[test]
    fn rk4_conserves_pendulum_energy_over_ten_seconds() {
        let start = at_rest(1.0);
        let initial_energy = energy(&PENDULUM, &start.q, &start.v);
        let mut worst_drift: f64 = 0.0;
        let observe = |s: &State<1, 1>| {
            let drift = energy(&PENDULUM, &s.q, &s.v) - initial_energy;
            worst_drift = worst_drift.max(drift.abs());
        };
        let dynamics = Unconstrained::without_inputs(&PENDULUM);
        let end = Integration::new(&dynamics, start, 10.0, Rk4 { steps: 10_000 })
            .observe(observe)
            .run()
            .unwrap()
            .end;
        assert_eq!(end.t, 10.0);
        let energy_scale = PENDULUM.m * PENDULUM.g * PENDULUM.l;
        assert!(worst_drift < 1e-8 * energy_scale, "drift {worst_drift}");
        assert!(end.v[0] != 0.0, "the pendulum must have moved");
    }

    #[test]
    fn small_swings_have_the_small_angle_period() {
        // Downward zero crossings of the angle are one period apart.
        let mut crossings = [0.0; 2];
        let mut found = 0;
        let mut previous = at_rest(0.01);
        let observe = |s: &State<1, 1>| {
            if previous.q[0] > 0.0 && s.q[0] <= 0.0 && found < crossings.len() {
                let fraction = previous.q[0] / (previous.q[0] - s.q[0]);
                crossings[found] = previous.t + fraction * (s.t - previous.t);
                found += 1;
            }
            previous = *s;
        };
        let dynamics = Unconstrained::without_inputs(&PENDULUM);
        Integration::new(&dynamics, at_rest(0.01), 5.0, Rk4 { steps: 5_000 })
            .observe(observe)
            .run()
            .unwrap();
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
        let (bar, start) = (UNIT_BAR, UNIT_BAR_AT_REST);
        let torque = |t: f64, _: &[f64; 2], _: &[f64; 2]| [0.0, 2.0 * t];
        let end = Rk4::step(&Unconstrained::new(&bar, torque), &start, 0.5).unwrap();
        // θ̈ = 2t (I = 1), so θ = t³/3 and θ̇ = t², which RK4 integrates exactly.
        assert!((end.q[1] - 0.125 / 3.0).abs() < 1e-15, "{end:?}");
        assert!((end.v[1] - 0.25).abs() < 1e-15 && end.q[0] == 0.0);
    }

    #[test]
    fn rk4_stops_where_the_mass_matrix_turns_singular() {
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
            v: [0.0, 1.0],
        };
        let mut observed = 0;
        let dynamics = Unconstrained::without_inputs(&bar);
        let error = Integration::new(&dynamics, start, 1.0, Rk4 { steps: 8 })
            .observe(|_| observed += 1)
            .run()
            .unwrap_err();
        assert_eq!(error.t, 0.5);
        assert!((error.q[1] - FRAC_PI_2).abs() < 1e-12);
        assert!(matches!(
            error.cause,
            Failure::Dynamics(DynamicsError::SingularMassMatrix {
                coordinate: "phi",
                ..
            })
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
    fn a_fixed_step_run_ends_exactly_at_its_final_time() {
        let dynamics = Unconstrained::without_inputs(&PENDULUM);
        for (t_end, steps) in [(5.0, 3_000), (0.3, 7), (1e-3, 1)] {
            let mut last = 0.0;
            let solution = Integration::new(&dynamics, at_rest(1.0), t_end, Rk4 { steps })
                .observe(|s| last = s.t)
                .run()
                .unwrap();
            assert_eq!((solution.end.t, last), (t_end, t_end));
            assert_eq!(solution.statistics.accepted_steps, steps);
            assert_eq!(solution.statistics.rhs_evaluations, 4 * steps);
        }
    }

    #[test]
    fn a_closure_input_law_needs_no_annotations() {
        let (bar, start) = (UNIT_BAR, UNIT_BAR_AT_REST);
        let dynamics = Unconstrained::new(&bar, |_, _, _| [0.0, 1.0]);
        let end = Integration::new(&dynamics, start, 1.0, Rk4 { steps: 10 })
            .run()
            .unwrap()
            .end;
        // θ̈ = u / I = 1 while φ̇ = 0: θ = t²/2.
        assert!((end.q[1] - 0.5).abs() < 1e-14, "{end:?}");
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
            v: [0.0; 2],
        };
        let torque_fails_later = |t: f64, _: &[f64; 2], _: &[f64; 2]| {
            if t > 2.0 { [f64::NAN, 0.0] } else { [0.0; 2] }
        };
        let dynamics = Unconstrained::new(&bar, torque_fails_later);
        let error = Rk4::step(&dynamics, &start, 0.5).unwrap_err();
        assert_eq!(
            error.cause,
            Failure::Dynamics(DynamicsError::NonFiniteState)
        );
        assert_eq!((error.t, error.q), (2.25, [0.1, 0.2]), "the second stage");
    }

    #[test]
    fn non_finite_state_fails_the_first_stage() {
        let dynamics = Unconstrained::without_inputs(&PENDULUM);
        let error = Rk4::step(&dynamics, &at_rest(f64::INFINITY), 0.1).unwrap_err();
        assert_eq!(
            error.cause,
            Failure::Dynamics(DynamicsError::NonFiniteState)
        );
        assert_eq!((error.t, error.q), (0.0, [f64::INFINITY]));
    }
}
