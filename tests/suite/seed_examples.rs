//! The three worked examples of the seed document, written exactly as in
//! the language reference (`docs/language.md`), against the independent SymPy reference values of
//! `tests/reference/seed_examples.json` (S1–S3) at all 20 stored states.

use dalembert_fixtures::reference::{array, assert_close, flat, matrix, reference};
use dalembert_fixtures::seeds::{ConstrainedPendulum, DoublePendulum, RotatingBar};
use serde_json::Value;

const TOL: f64 = 1e-12;

fn system(id: &str) -> Value {
    reference("seed_examples.json")["systems"][id].clone()
}

fn parameter(system: &Value, name: &str) -> f64 {
    system["parameters"][name].as_f64().expect("parameter")
}

fn states(system: &Value) -> &[Value] {
    dalembert_fixtures::reference::states(system)
}

/// Checks `M`, `f`, `T`, `V` of a generated system at every reference state.
macro_rules! check_unconstrained {
    ($sys:expr, $reference:expr, $nq:literal, $nu:literal) => {
        for (i, s) in states(&$reference).iter().enumerate() {
            let (t, q, qd, u) = (
                s["t"].as_f64().unwrap(),
                array::<$nq>(&s["q"]),
                array::<$nq>(&s["qd"]),
                array::<$nu>(&s["inputs"]),
            );
            let at = format!("state {i}");
            assert_close(
                &format!("{at} M"),
                &flat(&$sys.mass_matrix(&q)),
                &flat(&matrix::<$nq, $nq>(&s["M"])),
                TOL,
            );
            assert_close(
                &format!("{at} f"),
                &$sys.forcing(t, &q, &qd, &u),
                &array::<$nq>(&s["f"]),
                TOL,
            );
            assert_close(
                &format!("{at} T"),
                &[$sys.kinetic_energy(&q, &qd)],
                &[s["T"].as_f64().unwrap()],
                TOL,
            );
            assert_close(
                &format!("{at} V"),
                &[$sys.potential_energy(&q)],
                &[s["V"].as_f64().unwrap()],
                TOL,
            );
        }
    };
}

#[test]
fn seed_1_double_pendulum_matches_reference() {
    let reference = system("S1");
    let sys = DoublePendulum {
        m: parameter(&reference, "m"),
        L: parameter(&reference, "L"),
        g: parameter(&reference, "g"),
    };
    assert_eq!(states(&reference).len(), 20);
    check_unconstrained!(sys, reference, 2, 0);
}

#[test]
fn seed_2_rotating_bar_matches_reference() {
    let reference = system("S2");
    let sys = RotatingBar {
        m: parameter(&reference, "m"),
        l: parameter(&reference, "l"),
        d: parameter(&reference, "d"),
    };
    check_unconstrained!(sys, reference, 2, 2);
}

#[test]
fn seed_3_constrained_pendulum_matches_reference() {
    let reference = system("S3");
    let sys = ConstrainedPendulum {
        m: parameter(&reference, "m"),
        l: parameter(&reference, "l"),
        g: parameter(&reference, "g"),
    };
    check_unconstrained!(sys, reference, 3, 1);
    for (i, s) in states(&reference).iter().enumerate() {
        let (t, q, qd) = (
            s["t"].as_f64().unwrap(),
            array::<3>(&s["q"]),
            array::<3>(&s["qd"]),
        );
        assert_close(
            &format!("state {i} A"),
            &flat(&sys.constraint_jacobian(&q)),
            &flat(&matrix::<2, 3>(&s["A"])),
            TOL,
        );
        assert_close(
            &format!("state {i} b"),
            &sys.constraint_bias(t, &q, &qd),
            &array::<2>(&s["b"]),
            TOL,
        );
        let residual = sys.constraint_residual(t, &q);
        assert!(
            residual.iter().all(|r| r.abs() < 1e-12),
            "state {i}: residual {residual:?}"
        );
    }
}

#[test]
fn generated_constants_follow_the_declarations() {
    assert_eq!(DoublePendulum::NQ, 2);
    assert_eq!(DoublePendulum::NU, 0);
    assert_eq!(DoublePendulum::NC, 0);
    assert_eq!(DoublePendulum::COORDINATES, ["theta1", "theta2"]);
    assert_eq!(DoublePendulum::PARAMETERS, ["m", "L", "g"]);
    assert_eq!(RotatingBar::INPUTS, ["M_phi", "M_theta"]);
    assert_eq!(ConstrainedPendulum::NC, 2);
    assert_eq!(ConstrainedPendulum::COORDINATES, ["x", "y", "theta"]);
}

#[test]
fn seed_3_velocity_form_vanishes_on_the_reference_states() {
    let reference = system("S3");
    let sys = ConstrainedPendulum {
        m: parameter(&reference, "m"),
        l: parameter(&reference, "l"),
        g: parameter(&reference, "g"),
    };
    for (i, s) in states(&reference).iter().enumerate() {
        let (t, q, qd) = (
            s["t"].as_f64().unwrap(),
            array::<3>(&s["q"]),
            array::<3>(&s["qd"]),
        );
        let expected = array::<2>(&s["constraint_residual_Aqd"]);
        let velocity = sys.constraint_velocity(t, &q, &qd);
        for (v, e) in velocity.iter().zip(expected) {
            assert!(
                (v - e).abs() < 1e-12,
                "state {i}: velocity form {velocity:?}, reference {e}"
            );
        }
    }
}
