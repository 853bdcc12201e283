//! The knife edge and the Chaplygin sleigh: a body on a blade at `(x, y)`
//! heading `θ`, which may not slip sideways (`−sin θ ẋ + cos θ ẏ = 0`), no
//! forces; its mass centre `a` ahead of the blade along it (`a = 0`: the
//! knife edge); and the sleigh in Kane's speeds (a `speeds` statement, the
//! row `u2 = 0` on a speed), through `outputs taylor` and `linearize`.
//! Expected values derived by hand below.
//!
//! With `v = cos θ ẋ + sin θ ẏ` the speed along the blade and `ω = θ̇`, the
//! centre `G = P + a B.x` moves at `v B.x + a ω B.y` and accelerates at
//! `(v̇ − a ω²) B.x + (v ω + a ω̇) B.y`. The blade's reaction `F B.y` is
//! all the force, and its moment about `G` is `−a F`:
//! `m (v̇ − a ω²) = 0`, `m (v ω + a ω̇) = F`, `I ω̇ = −a F`, so
//!
//! * `v̇ = a ω²`, `(I + m a²) ω̇ = −m a v ω`;
//! * the knife edge (`a = 0`) turns at a constant `ω` and speed `v`: the
//!   blade goes round the circle of radius `v/ω` about
//!   `(x₀ − (v/ω) sin θ₀, y₀ + (v/ω) cos θ₀)`, at
//!   `x = x₀ + (v/ω)(sin θ − sin θ₀)`, `y = y₀ − (v/ω)(cos θ − cos θ₀)`,
//!   `θ = θ₀ + ω t`;
//! * the sleigh (`a ≠ 0`, `J = I + m a²`) keeps its energy
//!   `E = ½ m v² + ½ J ω²`; with `V = √(2E/m)` and `k = m a V / J`,
//!   `v = V tanh(k t + c)` solves `v̇ = (m a / J)(V² − v²) = a ω²`
//!   (`c = artanh(v₀/V)`), then `ω = ±√(m/J) V sech(k t + c)` (the sign of
//!   `ω₀`), and `θ = θ₀ ± (√(J/m) / a)(gd(k t + c) − gd(c))` with the
//!   Gudermannian `gd(u) = atan(sinh u)`, `gd′ = sech`: the sleigh turns
//!   through a finite angle and goes on straight at the speed `V`.

use dalembert::integrate::{Adaptive, AdaptiveOptions, ExplicitPair, Integration, State, Taylor};
use dalembert::{Constrained, Stabilisation};
use dalembert_fixtures::reference::{assert_close, flat};

dalembert::dalembert! {
    /// A body of mass `m` and central inertia `I` on a blade at `(x, y)`,
    /// its mass centre `a` ahead of the blade.
    pub ChaplyginSleigh {
        parameters m, I, a;
        coordinates x, y, theta;
        frame B = N.rotate_z(theta);
        point G = O + x * N.x + y * N.y + a * B.x;
        body sleigh { mass: m, center: G, frame: B, inertia: [0, 0, I] };
        constraint -sin(theta) * dt(x) + cos(theta) * dt(y) == 0;
        outputs taylor;
    }
}

const KNIFE_EDGE: ChaplyginSleigh = ChaplyginSleigh {
    m: 2.0,
    I: 0.3,
    a: 0.0,
};

const SLEIGH: ChaplyginSleigh = ChaplyginSleigh {
    m: 2.0,
    I: 0.3,
    a: 0.4,
};

/// The blade at `(x, y)` heading `theta`, at `speed` along itself,
/// turning at `omega`.
fn on_the_blade(x: f64, y: f64, theta: f64, speed: f64, omega: f64) -> State<3, 3> {
    let (s, c) = theta.sin_cos();
    State {
        t: 0.0,
        q: [x, y, theta],
        v: [speed * c, speed * s, omega],
    }
}

/// `(v, ω)` of a state: the speed along the blade and the turning rate.
fn blade_speeds(state: &State<3, 3>) -> [f64; 2] {
    let (s, c) = state.q[2].sin_cos();
    [c * state.v[0] + s * state.v[1], state.v[2]]
}

/// The knife edge's closed form at `t` from `start` (module docs).
fn on_the_circle(start: &State<3, 3>, t: f64) -> [f64; 6] {
    let [speed, omega] = blade_speeds(start);
    let [x0, y0, theta0] = start.q;
    let theta = theta0 + omega * t;
    let radius = speed / omega;
    let (s, c) = theta.sin_cos();
    [
        x0 + radius * (s - theta0.sin()),
        y0 - radius * (c - theta0.cos()),
        theta,
        speed * c,
        speed * s,
        omega,
    ]
}

/// `(x, y, θ, ẋ, ẏ, θ̇)` of a state.
fn entries(state: &State<3, 3>) -> [f64; 6] {
    let [x, y, theta] = state.q;
    let [vx, vy, omega] = state.v;
    [x, y, theta, vx, vy, omega]
}

fn knife_edge_start() -> State<3, 3> {
    on_the_blade(0.3, -0.7, 0.4, 1.5, 0.8)
}

/// `Taylor` at 1e-15 on the index-1 form (no projection): after
/// 10 s (1.3 turns) the state is the closed form's to 1e-12 (to 1e-15
/// measured), the constraint holding to rounding.
#[test]
fn knife_edge_taylor_series_go_round_the_circle() {
    let start = knife_edge_start();
    let dynamics = Constrained::without_inputs(&KNIFE_EDGE, Stabilisation::None);
    let options = Taylor::with_tolerance(1e-15);
    let end = Integration::new(&dynamics, start, 10.0, options)
        .run()
        .expect("integrates")
        .end;
    assert_close(
        "Taylor at 10 s",
        &entries(&end),
        &on_the_circle(&start, 10.0),
        1e-12,
    );
    let [slip] = KNIFE_EDGE.constraint_velocity(end.t, &end.q, &end.v);
    assert!(slip.abs() < 1e-14, "slip {slip:e}");
}

/// DOP853 at 1e-13, projected after each step: the closed form at every
/// step over 10 s to 1e-11 (1.5e-13 measured).
#[test]
fn knife_edge_dop853_goes_round_the_circle() {
    let start = knife_edge_start();
    let projection = Stabilisation::Projection {
        tolerance: 1e-14,
        max_iterations: 5,
    };
    let dynamics = Constrained::without_inputs(&KNIFE_EDGE, projection);
    let options = AdaptiveOptions::with_tolerance(1e-13);
    let observe = |s: &State<3, 3>| {
        let what = format!("DOP853 at {} s", s.t);
        assert_close(&what, &entries(s), &on_the_circle(&start, s.t), 1e-11);
    };
    let end = Integration::new(
        &dynamics,
        start,
        10.0,
        Adaptive {
            pair: ExplicitPair::Dop853,
            options,
        },
    )
    .observe(observe)
    .run()
    .expect("integrates")
    .end;
    assert_eq!(end.t, 10.0);
}

/// The sleigh's closed form at `t` from `start`: `(θ, v, ω)` (module docs).
fn sleigh_closed_form(start: &State<3, 3>, t: f64) -> [f64; 3] {
    let ChaplyginSleigh { m, I: inertia, a } = SLEIGH;
    let j = inertia + m * a * a;
    let [v0, omega0] = blade_speeds(start);
    let terminal = (v0 * v0 + j * omega0 * omega0 / m).sqrt();
    let k = m * a * terminal / j;
    let c = (v0 / terminal).atanh();
    let u = k * t + c;
    let gd = |u: f64| u.sinh().atan();
    let sign = omega0.signum();
    [
        start.q[2] + sign * (j / m).sqrt() / a * (gd(u) - gd(c)),
        terminal * u.tanh(),
        sign * (m / j).sqrt() * terminal / u.cosh(),
    ]
}

/// `(θ, v, ω)` of a state.
fn heading_and_speeds(state: &State<3, 3>) -> [f64; 3] {
    let [v, omega] = blade_speeds(state);
    [state.q[2], v, omega]
}

/// From a slow start turning fast (and one backing up), over 60 s: the
/// sleigh turns through its finite angle and runs straight on at `V`;
/// Taylor at 1e-15 follows the closed form of `(θ, v, ω)` at every step
/// to 1e-13 and keeps the energy to 1e-14 (1.8e-15 and 8.9e-16
/// measured); DOP853 at 1e-13 to 1e-11 and 1e-12 (3.2e-13 and 1.5e-14).
#[test]
fn chaplygin_sleigh_follows_its_closed_form_and_keeps_its_energy() {
    for start in [
        on_the_blade(0.0, 0.0, 0.2, 0.5, 3.0),
        on_the_blade(1.0, 2.0, -1.0, -0.8, -2.0),
    ] {
        let energy = dalembert::energy(&SLEIGH, &start.q, &start.v);
        let check = |s: &State<3, 3>, tol: f64, energy_tol: f64| {
            let what = format!("{start:?} at {} s", s.t);
            let expected = sleigh_closed_form(&start, s.t);
            assert_close(&what, &heading_and_speeds(s), &expected, tol);
            let change = dalembert::energy(&SLEIGH, &s.q, &s.v) / energy - 1.0;
            assert!(change.abs() < energy_tol, "{what}: energy {change:e}");
        };
        let dynamics = Constrained::without_inputs(&SLEIGH, Stabilisation::None);
        let options = Taylor::with_tolerance(1e-15);
        Integration::new(&dynamics, start, 60.0, options)
            .observe(|s| check(s, 1e-13, 1e-14))
            .run()
            .expect("integrates");
        let options = AdaptiveOptions::with_tolerance(1e-13);
        let dop853 = ExplicitPair::Dop853;
        Integration::new(
            &dynamics,
            start,
            60.0,
            Adaptive {
                pair: dop853,
                options,
            },
        )
        .observe(|s| check(s, 1e-11, 1e-12))
        .run()
        .expect("integrates");
    }
}

dalembert::dalembert! {
    /// The same sleigh in Kane's speeds: `u1` along the blade, `u2` across
    /// it (held at zero by a row on the speed), `w` the turning rate.
    pub KaneSleigh {
        parameters m, I, a;
        coordinates x, y, theta;
        speeds u1, u2, w {
            x: cos(theta) * u1 - sin(theta) * u2,
            y: sin(theta) * u1 + cos(theta) * u2,
            theta: w
        };
        frame B = N.rotate_z(theta);
        point G = O + x * N.x + y * N.y + a * B.x;
        body sleigh { mass: m, center: G, frame: B, inertia: [0, 0, I] };
        constraint u2 == 0;
        outputs taylor, linearize(x, y, theta; u1, w);
    }
}

const KANE_SLEIGH: KaneSleigh = KaneSleigh {
    m: SLEIGH.m,
    I: SLEIGH.I,
    a: SLEIGH.a,
};

/// In Kane's speeds (a `speeds` statement, the row on a speed's name) the
/// Taylor series follow the same closed form over 60 s, to 1e-13, the
/// speed across the blade zero to rounding.
#[test]
fn chaplygin_sleigh_in_kanes_speeds_follows_the_closed_form() {
    let start = on_the_blade(0.0, 0.0, 0.2, 0.5, 3.0);
    let kane_start = State {
        t: 0.0,
        q: start.q,
        v: [0.5, 0.0, 3.0],
    };
    let dynamics = Constrained::without_inputs(&KANE_SLEIGH, Stabilisation::None);
    let options = Taylor::with_tolerance(1e-15);
    let check = |s: &State<3, 3>| {
        let what = format!("at {} s", s.t);
        let reached = [s.q[2], s.v[0], s.v[2]];
        assert_close(&what, &reached, &sleigh_closed_form(&start, s.t), 1e-13);
        assert!(s.v[1].abs() < 1e-14, "{what}: u2 = {:e}", s.v[1]);
    };
    Integration::new(&dynamics, kane_start, 60.0, options)
        .observe(check)
        .run()
        .expect("integrates");
}

/// `linearize` in Kane's speeds, `(x, y, θ)` and `(u1, w)` independent, is
/// the hand-derived: `ẋ = cos θ u1`, `ẏ = sin θ u1` (`u2 = 0`), `θ̇ = w`,
/// `u̇1 = a w²`, `ẇ = −(m a / J) u1 w`; the columns of `u2` zero.
#[test]
fn chaplygin_sleigh_in_kanes_speeds_linearises_by_hand() {
    let KaneSleigh { m, I: inertia, a } = KANE_SLEIGH;
    let ratio = m * a / (inertia + m * a * a);
    for (theta, u1, w) in [(0.2, 0.5, 3.0), (-2.0, -1.5, 0.7)] {
        let (a_matrix, _) = KANE_SLEIGH
            .linearize(0.0, &[0.3, -0.1, theta], &[u1, 0.0, w], &[])
            .expect("linearisable");
        let (s, c) = f64::sin_cos(theta);
        let expected = [
            [0.0, 0.0, -s * u1, c, 0.0, 0.0],
            [0.0, 0.0, c * u1, s, 0.0, 0.0],
            [0.0, 0.0, 0.0, 0.0, 0.0, 1.0],
            [0.0, 0.0, 0.0, 0.0, 0.0, 2.0 * a * w],
            [0.0; 6],
            [0.0, 0.0, 0.0, -ratio * w, 0.0, -ratio * u1],
        ];
        assert_close("A", &flat(&a_matrix), &flat(&expected), 1e-12);
    }
}
