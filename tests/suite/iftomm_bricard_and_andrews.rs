//! The IFToMM benchmark's Bricard mechanism (A04) with its energy and closure
//! kept, the least-norm multipliers of a redundant four-bar against their
//! closed form, the `closure` statements against the same rows written as
//! coordinate equations, and Andrews' squeezer (A03) against the closed forms
//! of Hairer and Wanner and by two formulations and integrators agreeing.

use crate::iftomm_four_bars::PROJECTION;

use dalembert::constrained::{ConstraintSolver, constrained_accelerations, constraint_drift};
use dalembert::integrate::{Adaptive, Integration, Rk4};
use dalembert::{Constrained, ConstrainedSystem, State, energy};
use dalembert_fixtures::iftomm::{
    ANDREWS, ANDREWS_EQUATIONS, Andrews, Bricard, BricardEquations, FourBars2, FourBarsEquations2,
    andrews_start,
};
use dalembert_fixtures::states::states;

/// Bricard's mechanism at rest in its cube configuration.
fn bricard_start() -> State<5, 5> {
    State {
        t: 0.0,
        q: [0.0; 5],
        v: [0.0; 5],
    }
}

const BRICARD: Bricard = Bricard {
    m: 1.0,
    L: 1.0,
    g: 9.81,
};

/// Seconds in a debug build (20 000 projected RK4 steps): CI runs it in its
/// release step (`cargo test --release -p dalembert --test suite -- --ignored`).
#[test]
#[ignore = "long: run in release"]
fn bricard_keeps_its_energy_and_its_closure_for_ten_seconds() {
    let dynamics = Constrained::without_inputs(&BRICARD, PROJECTION);
    let start = bricard_start();
    let initial = energy(&BRICARD, &start.q, &start.v);
    let (mut drift, mut residual, mut travel) = (0.0f64, 0.0f64, 0.0f64);
    Integration::new(&dynamics, start, 10.0, Rk4 { steps: 20_000 })
        .observe(|s| {
            drift = drift.max((energy(&BRICARD, &s.q, &s.v) - initial).abs());
            residual = residual.max(constraint_drift(&BRICARD, s));
            travel = travel.max(s.q[0].abs());
        })
        .run()
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(travel > 0.1, "the mechanism moves: max |q1| = {travel}");
    assert!(drift < 1e-6, "energy drift {drift:e}");
    assert!(residual < 1e-10, "constraint residual {residual:e}");
}

#[test]
fn bricard_has_rank_four_closure_rows() {
    // Grübler: 5 coordinates − 5 rows = 0; the rows have rank 4, so the
    // Schur complement route stops and the rank-revealing one goes on.
    let start = bricard_start();
    let schur =
        ConstraintSolver::SchurComplement.accelerations(&BRICARD, 0.0, &start.q, &start.v, &[]);
    assert!(
        matches!(
            schur,
            Err(dalembert::DynamicsError::DependentConstraints { .. })
        ),
        "{schur:?}"
    );
    let (vdot, _) = ConstraintSolver::RankRevealing
        .accelerations(&BRICARD, 0.0, &start.q, &start.v, &[])
        .unwrap();
    let a = BRICARD.constraint_jacobian(&start.q);
    for row in a {
        let achieved: f64 = row.iter().zip(&vdot).map(|(a, x)| a * x).sum();
        assert!(achieved.abs() < 1e-12, "{achieved:e}");
    }
}

/// One four-bar window (crank, rocker, coupler; unit rods) named `$name`,
/// closed by its x and y rows and the rows `$extra`.
macro_rules! four_bar_window {
    ($name:ident { $($extra:tt)* }) => {
        dalembert::dalembert! {
            /// A four-bar window closed by its x and y rows (and, in
            /// `RedundantFourBar`, by their sum as a redundant third row).
            pub $name {
                parameters m, L, g;
                coordinates phi0, phi1, psi1;
                frame C0 = N.rotate_z(phi0);
                frame C1 = N.rotate_z(phi1);
                frame D1 = N.rotate_z(psi1);
                point B0 = O + L * C0.x;
                point G0 = O + L/2 * C0.x;
                point G1 = O + L * N.x + L/2 * C1.x;
                point H1 = B0 + L/2 * D1.x;
                body crank { mass: m, center: G0, frame: C0, inertia: [0, 0, m*L^2/12] };
                body rocker { mass: m, center: G1, frame: C1, inertia: [0, 0, m*L^2/12] };
                body coupler { mass: m, center: H1, frame: D1, inertia: [0, 0, m*L^2/12] };
                gravity -g * N.y;
                constraint L*cos(phi0) + L*cos(psi1) == L + L*cos(phi1);
                constraint L*sin(phi0) + L*sin(psi1) == L*sin(phi1);
                $($extra)*
            }
        }
    };
}

four_bar_window! {
    FourBar {}
}

four_bar_window! {
    RedundantFourBar {
        constraint L*cos(phi0) + L*cos(psi1) + L*sin(phi0) + L*sin(psi1) == L + L*cos(phi1) + L*sin(phi1);
    }
}

#[test]
fn redundant_row_gets_the_least_norm_share_of_the_multipliers() {
    let (independent, redundant) = (
        FourBar {
            m: 1.0,
            L: 1.0,
            g: 9.81,
        },
        RedundantFourBar {
            m: 1.0,
            L: 1.0,
            g: 9.81,
        },
    );
    // A parallelogram at 1 rad, moving: closure holds with psi = 0.
    let (q, v) = ([1.0, 1.0, 0.0], [-0.7, -0.7, 0.0]);
    let (vdot, [lx, ly]) = ConstraintSolver::SchurComplement
        .accelerations(&independent, 0.0, &q, &v, &[])
        .unwrap();
    let (vdot_redundant, lambda) = constrained_accelerations(&redundant, 0.0, &q, &v, &[]).unwrap();
    for (a, b) in vdot.iter().zip(&vdot_redundant) {
        assert!((a - b).abs() < 1e-12, "{vdot:?} {vdot_redundant:?}");
    }
    // Every (lx − s, ly − s, s) gives the same force; the least norm has
    // s = (lx + ly)/3.
    let s = (lx + ly) / 3.0;
    for (got, want) in lambda.iter().zip([lx - s, ly - s, s]) {
        assert!(
            (got - want).abs() < 1e-11 * (1.0 + want.abs()),
            "{lambda:?} vs ({lx}, {ly})"
        );
    }
}

/// The largest difference between the rows (`A`, `b` and the residual) of
/// `closed` and of `written` over a table of pseudo-random states.
fn largest_row_difference<S, W, const NQ: usize, const NC: usize>(closed: &S, written: &W) -> f64
where
    S: ConstrainedSystem<NQ, NQ, 0, NC>,
    W: ConstrainedSystem<NQ, NQ, 0, NC>,
{
    let mut largest = 0.0f64;
    let mut compare = |a: &[f64], b: &[f64]| {
        for (x, y) in a.iter().zip(b) {
            largest = largest.max((x - y).abs());
        }
    };
    for sample in states::<NQ, 0>(14) {
        let (t, q, v) = (sample.t, &sample.q, &sample.v);
        for (a, b) in closed
            .constraint_jacobian(q)
            .iter()
            .zip(&written.constraint_jacobian(q))
        {
            compare(a, b);
        }
        compare(
            &closed.constraint_bias(t, q, v),
            &written.constraint_bias(t, q, v),
        );
        compare(
            &closed.constraint_residual(t, q),
            &written.constraint_residual(t, q),
        );
    }
    largest
}

#[test]
fn closure_statements_give_the_rows_written_as_coordinate_equations() {
    let (m, l, g) = (1.3, 0.7, 9.81);
    let four_bars = largest_row_difference(
        &FourBars2 { m, L: l, g },
        &FourBarsEquations2 { m, L: l, g },
    );
    assert!(four_bars < 1e-13, "A02: {four_bars:e}");
    let bricard = largest_row_difference(&Bricard { m, L: l, g }, &BricardEquations { m, L: l, g });
    assert!(bricard < 1e-13, "A04: {bricard:e}");
}

/// Hairer and Wanner's mass matrix and forces of Andrews' squeezer (Solving
/// ODEs II, section VII.7), written out by hand: the independent check of
/// the model in the language.
fn andrews_closed_form(p: &Andrews, q: &[f64; 7], v: &[f64; 7]) -> ([[f64; 7]; 7], [f64; 7]) {
    let [_beta, theta, gamma, phi, _delta, omega, _epsilon] = *q;
    let [bd, td, _gd, pd, dd, od, ed] = *v;
    let (ee, zz) = (p.e - p.ea, p.zf - p.fa);
    let mut m = [[0.0; 7]; 7];
    m[0][0] = p.m1 * p.ra.powi(2)
        + p.m2 * (p.rr.powi(2) - 2.0 * p.da * p.rr * theta.cos() + p.da.powi(2))
        + p.I1
        + p.I2;
    m[0][1] = p.m2 * (p.da.powi(2) - p.da * p.rr * theta.cos()) + p.I2;
    m[1][1] = p.m2 * p.da.powi(2) + p.I2;
    m[2][2] = p.m3 * (p.sa.powi(2) + p.sb.powi(2)) + p.I3;
    m[3][3] = p.m4 * ee.powi(2) + p.I4;
    m[3][4] = p.m4 * (ee.powi(2) + p.zt * ee * phi.sin()) + p.I4;
    m[4][4] = p.m4 * (p.zt.powi(2) + 2.0 * p.zt * ee * phi.sin() + ee.powi(2))
        + p.m5 * (p.ta.powi(2) + p.tb.powi(2))
        + p.I4
        + p.I5;
    m[5][5] = p.m6 * zz.powi(2) + p.I6;
    m[5][6] = p.m6 * (zz.powi(2) - p.u * zz * omega.sin()) + p.I6;
    m[6][6] = p.m6 * (zz.powi(2) - 2.0 * p.u * zz * omega.sin() + p.u.powi(2))
        + p.m7 * (p.ua.powi(2) + p.ub.powi(2))
        + p.I6
        + p.I7;
    for (i, j) in [(0, 1), (3, 4), (5, 6)] {
        m[j][i] = m[i][j];
    }
    let xd = p.sd * gamma.cos() + p.sc * gamma.sin() + p.xb;
    let yd = p.sd * gamma.sin() - p.sc * gamma.cos() + p.yb;
    let length = ((xd - p.xc).powi(2) + (yd - p.yc).powi(2)).sqrt();
    let force = -p.c0 * (length - p.l0) / length;
    let (fx, fy) = (force * (xd - p.xc), force * (yd - p.yc));
    let f = [
        p.mom - p.m2 * p.da * p.rr * td * (td + 2.0 * bd) * theta.sin(),
        p.m2 * p.da * p.rr * bd.powi(2) * theta.sin(),
        fx * (p.sc * gamma.cos() - p.sd * gamma.sin())
            + fy * (p.sd * gamma.cos() + p.sc * gamma.sin()),
        p.m4 * p.zt * ee * dd.powi(2) * phi.cos(),
        -p.m4 * p.zt * ee * pd * (pd + 2.0 * dd) * phi.cos(),
        -p.m6 * p.u * zz * ed.powi(2) * omega.cos(),
        p.m6 * p.u * zz * od * (od + 2.0 * ed) * omega.cos(),
    ];
    (m, f)
}

#[test]
fn andrews_squeezer_has_hairer_and_wanners_equations() {
    for sample in states::<7, 0>(3) {
        let (q, v) = (&sample.q, &sample.v);
        let (m, f) = andrews_closed_form(&ANDREWS, q, v);
        let (mass, forcing) = (ANDREWS.mass_matrix(q), ANDREWS.forcing(0.0, q, v, &[]));
        for i in 0..7 {
            for j in 0..7 {
                assert!((mass[i][j] - m[i][j]).abs() < 1e-15, "M[{i}][{j}]");
            }
            let scale = 1.0 + f[i].abs();
            assert!(
                (forcing[i] - f[i]).abs() < 1e-12 * scale,
                "f[{i}]: {forcing:?} {f:?}"
            );
        }
    }
    let closures = largest_row_difference(&ANDREWS, &ANDREWS_EQUATIONS);
    assert!(closures < 1e-15, "A03 closure rows: {closures:e}");
    let start = andrews_start();
    for residual in ANDREWS.constraint_residual(0.0, &start.q) {
        assert!(
            residual.abs() < 1e-15,
            "the start closes the loops: {residual:e}"
        );
    }
}

/// Tens of seconds in a debug build (30 000 projected RK4 steps on the
/// written rows): CI runs it in its release step (`cargo test --release -p
/// dalembert --test suite -- --ignored`).
#[test]
#[ignore = "long: run in release"]
fn andrews_squeezer_by_two_formulations_and_integrators_agrees_to_1e_8() {
    // The loops closed by `closure` statements, DOP853 with projection...
    let closed = Integration::new(
        &Constrained::without_inputs(&ANDREWS, PROJECTION),
        andrews_start(),
        0.03,
        Adaptive::dop853(1e-12),
    )
    .run()
    .unwrap_or_else(|e| panic!("DOP853: {e}"))
    .end;
    // ... against the coordinate equations, RK4 at a fixed step.
    let mut written = andrews_start();
    Integration::new(
        &Constrained::without_inputs(&ANDREWS_EQUATIONS, PROJECTION),
        andrews_start(),
        0.03,
        Rk4 { steps: 30_000 },
    )
    .observe(|s| written = *s)
    .run()
    .unwrap_or_else(|e| panic!("RK4: {e}"));
    for (a, b) in closed.q.iter().zip(&written.q) {
        assert!((a - b).abs() < 1e-8, "{:?} vs {:?}", closed.q, written.q);
    }
}
