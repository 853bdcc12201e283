//! Branching robots against Pinocchio with the same `q`: the import orders
//! the coordinates as `pinocchio::buildModelFromUrdf` does (depth first, a
//! link's child joints sorted by name, whatever the file's order), so `q`,
//! `v`, `M` and every derivative are interchangeable with Pinocchio's.
//! Three robots whose files list siblings out of that order:
//! `branches.urdf` (written for these tests: `right_hip` before `left_hip`,
//! `Arm_shoulder` and `_tail` to test byte order, a mimic joint, massless
//! links on fixed joints), the Unitree A1 quadruped (`FR_` before `FL_`)
//! and the simple humanoid of example-robot-data, both on a free flyer.
//!
//! The models, imported with `outputs inverse_dynamics_jacobian` by
//! [`Urdf::outputs`], are evaluated by the interpreter; Pinocchio's values
//! are in `tests/reference/robots/pinocchio.json`
//! (`scripts/robots_reference.py`): `M` (crba), `f = τ − nle`, `q̈` (aba),
//! `T`, `V`, and `computeABADerivatives`, which `accelerations_jacobian`
//! computes the same way: `∂q̈/∂x = −M⁻¹ ∂τ/∂x` at `v̇ = q̈`, and
//! `∂q̈/∂u = M⁻¹ ∂f/∂u`.

// Shared with `tests/urdf.rs`, which uses the rest of it.
#[allow(dead_code)]
use crate::pinocchio;
use crate::robots;

use dalembert_codegen::Urdf;
use dalembert_codegen::testing::{Interpreter, Route, Values};
use pinocchio::{matrix, relative_error, solve, vector};
use robots::{entry, reference_dir};

/// Agreement required, relative to the quantity's largest entry.
const TOLERANCE: f64 = 1e-12;

/// `M⁻¹ B` for the columns of `b` (rows of the result: `M`'s).
fn solve_columns(m: &[Vec<f64>], b: &[Vec<f64>]) -> Vec<Vec<f64>> {
    let columns = b.first().map_or(0, Vec::len);
    let solved: Vec<Vec<f64>> = (0..columns)
        .map(|j| solve(m, &b.iter().map(|row| row[j]).collect::<Vec<_>>()))
        .collect();
    (0..m.len())
        .map(|i| solved.iter().map(|column| column[i]).collect())
        .collect()
}

/// The `n × n` blocks of a flattened output, in order.
fn blocks(flat: &[f64], n: usize) -> Vec<Vec<Vec<f64>>> {
    flat.chunks(n * n)
        .map(|block| block.chunks(n).map(<[f64]>::to_vec).collect())
        .collect()
}

fn negated(m: Vec<Vec<f64>>) -> Vec<Vec<f64>> {
    m.into_iter()
        .map(|row| row.into_iter().map(|x| -x).collect())
        .collect()
}

/// Imports the robot of Pinocchio's `robot` entry and compares every
/// quantity at every state; returns the worst relative error of each.
fn compare(robot: &str) -> Vec<(&'static str, f64)> {
    let entry = entry("dynamics", robot);
    let urdf = Urdf::read(reference_dir().join(entry["urdf"].as_str().unwrap()))
        .unwrap()
        .floating(entry["floating"].as_bool().unwrap())
        .outputs("inverse_dynamics_jacobian");
    let imported = urdf.import().unwrap();
    let interpreter = Interpreter::new(&imported.model, Route::Dalembert).unwrap();
    let names: Vec<&str> = entry["coordinates"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c.as_str().unwrap())
        .collect();
    // The joints in Pinocchio's order: the model's coordinates after the
    // free flyer's (named `root_joint` in both).
    let text = &imported.model;
    let declared = text
        .lines()
        .find_map(|l| l.trim().strip_prefix("coordinates "))
        .unwrap()
        .trim_end_matches(';');
    let floating = names.first() == Some(&"root_joint");
    assert_eq!(
        declared.split(", ").collect::<Vec<_>>(),
        names[usize::from(floating)..],
        "{robot}: coordinates in Pinocchio's order"
    );
    let (nq, nv) = (interpreter.nq(), interpreter.nv());
    assert_eq!(
        (nq, nv),
        (
            entry["nq"].as_u64().unwrap() as usize,
            entry["nv"].as_u64().unwrap() as usize
        )
    );
    let nu = interpreter.nu();
    let states = entry["states"].as_array().unwrap();
    assert!(!states.is_empty());
    let mut worst = vec![
        ("M", 0.0_f64),
        ("f", 0.0),
        ("T", 0.0),
        ("V", 0.0),
        ("qdd", 0.0),
        ("ddq_dq", 0.0),
        ("ddq_dv", 0.0),
        ("ddq_dtau", 0.0),
    ];
    for state in states {
        let (q, v, tau) = (
            vector(&state["q"]),
            vector(&state["v"]),
            vector(&state["tau"]),
        );
        let at = Values {
            parameters: &[],
            t: 0.0,
            q: &q,
            qd: &v,
            u: &tau,
        };
        let m = interpreter.mass_matrix(&at);
        let f = interpreter.forcing(&at);
        let qdd = solve(&m, &f);
        let partials = interpreter
            .output("inverse_dynamics_jacobian", &at, &qdd)
            .unwrap();
        let [dtau_dq, dtau_dv, ..] = &blocks(&partials, nv)[..] else {
            panic!("three blocks")
        };
        // f is linear in the inputs: its partials are its response to each.
        let zero = vec![0.0; nu];
        let f0 = interpreter.forcing(&Values { u: &zero, ..at });
        let df_du: Vec<Vec<f64>> = (0..nv)
            .map(|i| {
                (0..nu)
                    .map(|k| {
                        let mut unit = zero.clone();
                        unit[k] = 1.0;
                        interpreter.forcing(&Values { u: &unit, ..at })[i] - f0[i]
                    })
                    .collect()
            })
            .collect();
        let got = [
            m.concat(),
            f,
            vec![interpreter.kinetic_energy(&at)],
            vec![interpreter.potential_energy(&at)],
            qdd,
            negated(solve_columns(&m, dtau_dq)).concat(),
            negated(solve_columns(&m, dtau_dv)).concat(),
            solve_columns(&m, &df_du).concat(),
        ];
        let want = [
            matrix(&state["M"]).concat(),
            vector(&state["f"]),
            vec![state["T"].as_f64().unwrap()],
            vec![state["V"].as_f64().unwrap()],
            vector(&state["qdd"]),
            matrix(&state["ddq_dq"]).concat(),
            matrix(&state["ddq_dv"]).concat(),
            matrix(&state["ddq_dtau"]).concat(),
        ];
        for ((_, w), (got, want)) in worst.iter_mut().zip(got.iter().zip(&want)) {
            *w = w.max(relative_error(got, want));
        }
    }
    eprintln!("{robot}: worst relative errors {worst:?}");
    worst
}

fn matches_pinocchio(robot: &str) {
    for (what, error) in compare(robot) {
        assert!(
            error <= TOLERANCE,
            "{robot}: {what} off by {error:e} relative"
        );
    }
}

#[test]
fn unsorted_siblings_and_a_mimic_joint_match_pinocchio() {
    matches_pinocchio("branches");
}

#[test]
fn floating_quadruped_matches_pinocchio() {
    matches_pinocchio("a1_floating");
}

#[test]
fn floating_humanoid_matches_pinocchio() {
    matches_pinocchio("simple_humanoid_floating");
}
