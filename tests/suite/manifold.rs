//! Integrators on a configuration manifold: a torque-free rigid body whose
//! orientation is a unit quaternion and whose speeds are its body angular
//! velocity (`NQ = 4`, `NV = 3`, `q̇ = N(q) v ≠ v`), written here by hand
//! from Euler's equations, independently of the engine.
//!
//! Every integrator advances the quaternion through the coordinates' rates
//! `q̇ = ½ q ⊗ (ω, 0)` and puts it back on the unit sphere after each step
//! through the system's `q ⊕ 0`. Checked: energy and the angular momentum
//! in the inertial axes conserved; the axisymmetric body against its closed
//! form (free precession), at the steps and between them; each method's
//! order of convergence.

use std::ops::ControlFlow;

use dalembert::MultibodySystem;
use dalembert::integrate::{
    Adaptive, AdaptiveOptions, ExplicitPair, Gauss, GaussLegendre, Integration, Rk4, Sdirk, State,
    Unconstrained,
};

/// A quaternion `(x, y, z, w)`, Pinocchio's order.
type Quaternion = [f64; 4];

/// `p ⊗ r`.
fn product(p: &Quaternion, r: &Quaternion) -> Quaternion {
    let [px, py, pz, pw] = *p;
    let [rx, ry, rz, rw] = *r;
    [
        pw * rx + rw * px + py * rz - pz * ry,
        pw * ry + rw * py + pz * rx - px * rz,
        pw * rz + rw * pz + px * ry - py * rx,
        pw * rw - px * rx - py * ry - pz * rz,
    ]
}

/// The unit quaternion of the rotation by the vector `theta` (angle
/// `|theta|` about its direction).
fn exponential(theta: [f64; 3]) -> Quaternion {
    let angle = theta.iter().map(|x| x * x).sum::<f64>().sqrt();
    // sin(a/2)/a, to second order near zero.
    let s = if angle < 1e-8 {
        0.5 - angle * angle / 48.0
    } else {
        (angle / 2.0).sin() / angle
    };
    [
        s * theta[0],
        s * theta[1],
        s * theta[2],
        (angle / 2.0).cos(),
    ]
}

/// `x` rotated from the body's axes into the inertial ones by `q`.
fn rotate(q: &Quaternion, x: [f64; 3]) -> [f64; 3] {
    let conjugate = [-q[0], -q[1], -q[2], q[3]];
    let r = product(&product(q, &[x[0], x[1], x[2], 0.0]), &conjugate);
    [r[0], r[1], r[2]]
}

fn norm(x: &[f64]) -> f64 {
    x.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// A rigid body with principal moments of inertia `inertia` about its
/// centre, no load.
#[derive(Clone, Copy)]
struct FreeBody {
    inertia: [f64; 3],
    /// Whether `q ⊕ h ω` returns a unit quaternion from a non-unit one.
    renormalising: bool,
}

impl FreeBody {
    /// The angular momentum in the inertial axes, `R(q) I ω`.
    fn angular_momentum(&self, q: &[f64; 4], w: &[f64; 3]) -> [f64; 3] {
        rotate(q, std::array::from_fn(|i| self.inertia[i] * w[i]))
    }
}

impl MultibodySystem<4, 3, 0> for FreeBody {
    const COORDINATES: [&'static str; 4] = ["qx", "qy", "qz", "qw"];
    const SPEEDS: [&'static str; 3] = ["wx", "wy", "wz"];
    const INPUTS: [&'static str; 0] = [];

    fn mass_matrix(&self, _q: &[f64; 4]) -> [[f64; 3]; 3] {
        let [a, b, c] = self.inertia;
        [[a, 0.0, 0.0], [0.0, b, 0.0], [0.0, 0.0, c]]
    }

    /// Euler's equations: `I ω̇ = (I ω) × ω`.
    fn forcing(&self, _t: f64, _q: &[f64; 4], w: &[f64; 3], _u: &[f64; 0]) -> [f64; 3] {
        let l: [f64; 3] = std::array::from_fn(|i| self.inertia[i] * w[i]);
        [
            l[1] * w[2] - l[2] * w[1],
            l[2] * w[0] - l[0] * w[2],
            l[0] * w[1] - l[1] * w[0],
        ]
    }

    fn kinetic_energy(&self, _q: &[f64; 4], w: &[f64; 3]) -> f64 {
        0.5 * (0..3).map(|i| self.inertia[i] * w[i] * w[i]).sum::<f64>()
    }

    fn potential_energy(&self, _q: &[f64; 4]) -> f64 {
        0.0
    }

    /// `q̇ = ½ q ⊗ (ω, 0)`.
    fn coordinate_rates(&self, q: &[f64; 4], w: &[f64; 3]) -> [f64; 4] {
        product(q, &[w[0], w[1], w[2], 0.0]).map(|x| 0.5 * x)
    }

    /// `q ⊗ exp(h ω)`, normalised when the body renormalises.
    fn integrate_configuration(&self, q: &[f64; 4], w: &[f64; 3], h: f64) -> [f64; 4] {
        let moved = product(q, &exponential(w.map(|x| h * x)));
        if self.renormalising {
            let size = norm(&moved);
            moved.map(|x| x / size)
        } else {
            moved
        }
    }
}

/// `I₁ < I₂ < I₃`, the body of the Dzhanibekov effect.
const TUMBLER: FreeBody = FreeBody {
    inertia: [1.0, 2.0, 3.0],
    renormalising: true,
};

/// Spun about its intermediate axis, with a small perturbation.
const SPIN: State<4, 3> = State {
    t: 0.0,
    q: [0.0, 0.0, 0.0, 1.0],
    v: [1e-3, 2.0, 1e-3],
};

/// An axisymmetric body (`I₁ = I₂`), whose motion has a closed form.
const TOP: FreeBody = FreeBody {
    inertia: [2.0, 2.0, 1.0],
    renormalising: true,
};

/// [`TOP`] tilted and spinning about a tilted axis.
fn top_start() -> State<4, 3> {
    State {
        t: 0.0,
        q: exponential([0.3, -0.2, 0.1]),
        v: [0.4, -0.3, 2.5],
    }
}

/// The closed form of the torque-free axisymmetric body (`I₁ = I₂`):
/// `R(t) = exp(t L/I₁) R₀ exp(t (1/I₃ − 1/I₁) L₃ e₃)` with `L` the constant
/// angular momentum in the inertial axes and `L₃ = I₃ ω₃` the constant spin
/// momentum; the transverse body rate turns at `λ = (I₃ − I₁) ω₃ / I₁`.
fn top_at(start: &State<4, 3>, t: f64) -> State<4, 3> {
    let [i1, _, i3] = TOP.inertia;
    let l = TOP.angular_momentum(&start.q, &start.v);
    let w = start.v;
    let spin = t * (1.0 / i3 - 1.0 / i1) * i3 * w[2];
    let q = product(
        &product(&exponential(l.map(|x| t * x / i1)), &start.q),
        &exponential([0.0, 0.0, spin]),
    );
    let lambda = (i3 - i1) * w[2] / i1;
    let (s, c) = (lambda * t).sin_cos();
    State {
        t,
        q,
        v: [c * w[0] - s * w[1], s * w[0] + c * w[1], w[2]],
    }
}

/// The largest entry of the difference of two states (a quaternion and its
/// negative are the same rotation).
fn distance(a: &State<4, 3>, b: &State<4, 3>) -> f64 {
    let sign = if (0..4).map(|i| a.q[i] * b.q[i]).sum::<f64>() < 0.0 {
        -1.0
    } else {
        1.0
    };
    (0..4)
        .map(|i| (a.q[i] - sign * b.q[i]).abs())
        .chain((0..3).map(|i| (a.v[i] - b.v[i]).abs()))
        .fold(0.0, f64::max)
}

/// A fixed-step method: the final state after `steps` steps to `t_end`.
type FixedStep = fn(&FreeBody, State<4, 3>, f64, u64) -> State<4, 3>;

fn by_rk4(body: &FreeBody, start: State<4, 3>, t_end: f64, steps: u64) -> State<4, 3> {
    let dynamics = Unconstrained::without_inputs(body);
    Integration::new(&dynamics, start, t_end, Rk4 { steps })
        .run()
        .unwrap()
        .end
}

fn by_gauss(
    method: GaussLegendre,
    body: &FreeBody,
    start: State<4, 3>,
    t_end: f64,
    steps: u64,
) -> State<4, 3> {
    let dynamics = Unconstrained::without_inputs(body);
    Integration::new(
        &dynamics,
        start,
        t_end,
        Gauss {
            rule: method,
            steps,
        },
    )
    .run()
    .unwrap()
    .end
}

fn by_gauss4(body: &FreeBody, start: State<4, 3>, t_end: f64, steps: u64) -> State<4, 3> {
    by_gauss(GaussLegendre::Order4, body, start, t_end, steps)
}

fn by_gauss6(body: &FreeBody, start: State<4, 3>, t_end: f64, steps: u64) -> State<4, 3> {
    by_gauss(GaussLegendre::Order6, body, start, t_end, steps)
}

fn by_sdirk(body: &FreeBody, start: State<4, 3>, t_end: f64, steps: u64) -> State<4, 3> {
    let dynamics = Unconstrained::without_inputs(body);
    Integration::new(&dynamics, start, t_end, Sdirk { steps })
        .run()
        .unwrap()
        .end
}

/// The observed order of a fixed-step method on the axisymmetric body: the
/// error against the closed form at `t = 2` with `steps` and twice as many.
fn observed_order(method: FixedStep, steps: u64) -> f64 {
    let start = top_start();
    let exact = top_at(&start, 2.0);
    let error = |steps| distance(&method(&TOP, start, 2.0, steps), &exact);
    (error(steps) / error(2 * steps)).log2()
}

#[test]
fn each_fixed_step_method_reaches_its_order_on_the_quaternion_body() {
    let cases: [(&str, FixedStep, u64, f64); 4] = [
        ("rk4", by_rk4, 40, 4.0),
        ("gauss4", by_gauss4, 20, 4.0),
        ("gauss6", by_gauss6, 10, 6.0),
        ("sdirk", by_sdirk, 80, 3.0),
    ];
    for (name, method, steps, order) in cases {
        let observed = observed_order(method, steps);
        println!("{name}: observed order {observed:.2}");
        assert!(
            (observed - order).abs() < 0.3,
            "{name}: observed order {observed}, expected {order}"
        );
    }
}

#[test]
fn the_adaptive_pairs_follow_the_closed_form_of_free_precession() {
    let start = top_start();
    let dynamics = Unconstrained::without_inputs(&TOP);
    for (pair, tolerance, bound) in [
        (ExplicitPair::DormandPrince54, 1e-10, 1e-8),
        (ExplicitPair::Dop853, 1e-12, 1e-10),
    ] {
        let options = AdaptiveOptions::with_tolerance(tolerance);
        let end = Integration::new(&dynamics, start, 10.0, Adaptive { pair, options })
            .run()
            .unwrap()
            .end;
        let error = distance(&end, &top_at(&start, 10.0));
        assert!(error < bound, "{pair:?}: error {error}");
    }
}

/// Accepted steps of an adaptive run of the tumbler over 10 s.
fn steps_at(pair: ExplicitPair, tolerance: f64) -> u64 {
    let dynamics = Unconstrained::without_inputs(&TUMBLER);
    let options = AdaptiveOptions::with_tolerance(tolerance);
    Integration::new(&dynamics, SPIN, 10.0, Adaptive { pair, options })
        .run()
        .unwrap()
        .statistics
        .accepted_steps
}

#[test]
fn the_adaptive_pairs_work_at_their_order() {
    // An error estimate of order p̂ + 1 per step asks for tol^(−1/(p̂+1)) steps:
    // ten times the steps for a tolerance 10⁵ (DOPRI5) or 10⁸ (DOP853) times
    // smaller. A method fallen to order 2 on the sphere would need 10^(5/3)
    // and 10^(8/3) times more.
    for (pair, loose, tight) in [
        (ExplicitPair::DormandPrince54, 1e-5, 1e-10),
        (ExplicitPair::Dop853, 1e-4, 1e-12),
    ] {
        let ratio = steps_at(pair, tight) as f64 / steps_at(pair, loose) as f64;
        println!("{pair:?}: {ratio:.2} times the steps");
        assert!((7.0..14.0).contains(&ratio), "{pair:?}: {ratio}");
    }
}

#[test]
fn the_dzhanibekov_tumbler_keeps_its_energy_and_angular_momentum() {
    let dynamics = Unconstrained::without_inputs(&TUMBLER);
    let energy = TUMBLER.kinetic_energy(&SPIN.q, &SPIN.v);
    let momentum = TUMBLER.angular_momentum(&SPIN.q, &SPIN.v);
    let (mut energy_error, mut momentum_error, mut flips, mut sign) = (0.0f64, 0.0f64, 0, 1.0);
    let observe = |s: &State<4, 3>| {
        let e = TUMBLER.kinetic_energy(&s.q, &s.v);
        energy_error = energy_error.max((e / energy - 1.0).abs());
        let l = TUMBLER.angular_momentum(&s.q, &s.v);
        let drift: [f64; 3] = std::array::from_fn(|i| l[i] - momentum[i]);
        momentum_error = momentum_error.max(norm(&drift) / norm(&momentum));
        if s.v[1] * sign < 0.0 {
            flips += 1;
            sign = -sign;
        }
    };
    let options = AdaptiveOptions::with_tolerance(1e-12);
    let end = Integration::new(
        &dynamics,
        SPIN,
        100.0,
        Adaptive {
            pair: ExplicitPair::Dop853,
            options,
        },
    )
    .observe(observe)
    .run()
    .unwrap()
    .end;
    assert!(energy_error < 1e-9, "energy {energy_error}");
    assert!(momentum_error < 1e-9, "angular momentum {momentum_error}");
    assert!(flips >= 4, "{flips} flips of the intermediate axis");
    assert!((norm(&end.q) - 1.0).abs() < 1e-15, "{:?}", end.q);
}

#[test]
fn fixed_step_methods_conserve_the_tumbler_invariants() {
    let energy = TUMBLER.kinetic_energy(&SPIN.q, &SPIN.v);
    let momentum = TUMBLER.angular_momentum(&SPIN.q, &SPIN.v);
    for (name, method) in [
        ("rk4", by_rk4 as FixedStep),
        ("gauss6", by_gauss6),
        ("sdirk", by_sdirk),
    ] {
        let end = method(&TUMBLER, SPIN, 20.0, 4_000);
        let e = TUMBLER.kinetic_energy(&end.q, &end.v);
        let l = TUMBLER.angular_momentum(&end.q, &end.v);
        let drift: [f64; 3] = std::array::from_fn(|i| l[i] - momentum[i]);
        let bound = if name == "sdirk" { 1e-3 } else { 1e-7 };
        assert!((e / energy - 1.0).abs() < bound, "{name}: energy {e}");
        assert!(norm(&drift) / norm(&momentum) < bound, "{name}: {drift:?}");
        assert!((norm(&end.q) - 1.0).abs() < 1e-15, "{name}: {:?}", end.q);
    }
}

/// The unit-norm drift of the quaternion after RK4 at `h = 5 ms` for 20 s
/// when the body's update does not renormalise, and the change renormalising
/// makes to the final state: the cost either way.
#[test]
fn renormalising_costs_less_than_the_drift_it_removes() {
    let drifting = FreeBody {
        renormalising: false,
        ..TUMBLER
    };
    let kept = by_rk4(&TUMBLER, SPIN, 20.0, 4_000);
    let drifted = by_rk4(&drifting, SPIN, 20.0, 4_000);
    let drift = (norm(&drifted.q) - 1.0).abs();
    let change = distance(&kept, &drifted);
    println!("|q| − 1 without renormalising: {drift:.2e}; change to the state: {change:.2e}");
    assert!(drift > 0.0 && drift < 1e-6, "{drift}");
    assert!(change < 1e-6, "{change}");
}

#[test]
fn dense_output_follows_free_precession_between_steps() {
    let start = top_start();
    let dynamics = Unconstrained::without_inputs(&TOP);
    let options = AdaptiveOptions::with_tolerance(1e-12);
    let (mut worst, mut unit) = (0.0f64, 0.0f64);
    Integration::new(
        &dynamics,
        start,
        5.0,
        Adaptive {
            pair: ExplicitPair::Dop853,
            options,
        },
    )
    .dense(|step| {
        let (a, b) = (step.start().t, step.end().t);
        for k in 1..4 {
            let s = step.state_at(a + (b - a) * f64::from(k) / 4.0);
            worst = worst.max(distance(&s, &top_at(&start, s.t)));
            unit = unit.max((norm(&s.q) - 1.0).abs());
        }
        ControlFlow::Continue(())
    })
    .run()
    .unwrap();
    assert!(worst < 1e-10, "{worst:e}");
    assert!(
        unit < 1e-15,
        "the interpolated quaternion is renormalised: {unit:e}"
    );
}
