//! A model's numbers against one robot entry of Pinocchio's reference
//! (`tests/reference/urdf/pinocchio.json`, or a case of
//! `scripts/urdf_numeric_sweep.py`): the model evaluated by the interpreter
//! at the entry's states, and the worst relative errors of `M`, `f`, `T`,
//! `V` and `q̈`. Shared by `tests/urdf.rs` and `examples/urdf_numeric_sweep.rs`.

use dalembert_codegen::testing::{Interpreter, Route, Values};
use serde_json::Value;

/// The quantities compared, in the order of [`worst_errors`]' result.
pub const QUANTITIES: [&str; 5] = ["M", "f", "T", "V", "qdd"];

pub fn vector(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

pub fn matrix(v: &Value) -> Vec<Vec<f64>> {
    v.as_array().unwrap().iter().map(vector).collect()
}

/// The largest |a − b| over the largest |b|.
pub fn relative_error(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    let scale = b
        .iter()
        .fold(0.0_f64, |m, x| m.max(x.abs()))
        .max(f64::MIN_POSITIVE);
    a.iter()
        .zip(b)
        .fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()))
        / scale
}

/// `x` with `m x = f`, by Gaussian elimination with partial pivoting.
pub fn solve(m: &[Vec<f64>], f: &[f64]) -> Vec<f64> {
    let n = f.len();
    let mut a: Vec<Vec<f64>> = m
        .iter()
        .zip(f)
        .map(|(row, &b)| [row.clone(), vec![b]].concat())
        .collect();
    for k in 0..n {
        let pivot = (k..n)
            .max_by(|&i, &j| a[i][k].abs().total_cmp(&a[j][k].abs()))
            .unwrap();
        a.swap(k, pivot);
        let (upper, lower) = a.split_at_mut(k + 1);
        let pivot_row = &upper[k];
        for row in lower {
            let factor = row[k] / pivot_row[k];
            for (x, p) in row[k..].iter_mut().zip(&pivot_row[k..]) {
                *x -= factor * p;
            }
        }
    }
    let mut x = vec![0.0; n];
    for k in (0..n).rev() {
        x[k] = (a[k][n] - (k + 1..n).map(|j| a[k][j] * x[j]).sum::<f64>()) / a[k][k];
    }
    x
}

/// The worst relative errors of `model` (the text of a `.dal` file)
/// evaluated along `route` over the states of Pinocchio's `entry`, in the
/// order of [`QUANTITIES`]; `q̈` solved from the interpreter's `M` and `f`.
/// Fails with the interpreter's error, or if the sizes differ.
pub fn worst_errors(model: &str, entry: &Value, route: Route) -> Result<[f64; 5], String> {
    let interpreter = Interpreter::new(model, route).map_err(|e| e.to_string())?;
    let sizes = (interpreter.nq(), interpreter.nv());
    let expected = (
        entry["nq"].as_u64().unwrap() as usize,
        entry["nv"].as_u64().unwrap() as usize,
    );
    if sizes != expected {
        return Err(format!("(nq, nv) = {sizes:?}, Pinocchio's {expected:?}"));
    }
    let mut worst = [0.0_f64; 5];
    for_each_state(
        entry,
        |state| vector(&state["tau"]),
        |state, at| {
            let m = interpreter.mass_matrix(at);
            let f = interpreter.forcing(at);
            let errors = [
                relative_error(&m.concat(), &matrix(&state["M"]).concat()),
                relative_error(&f, &vector(&state["f"])),
                relative_error(
                    &[interpreter.kinetic_energy(at)],
                    &[state["T"].as_f64().unwrap()],
                ),
                relative_error(
                    &[interpreter.potential_energy(at)],
                    &[state["V"].as_f64().unwrap()],
                ),
                relative_error(&solve(&m, &f), &vector(&state["qdd"])),
            ];
            keep_worst(&mut worst, errors);
        },
    );
    Ok(worst)
}

/// Calls `visit` with each state of `entry` and its values: `q` and `q̇`
/// from the state, the inputs from `inputs(state)`.
pub fn for_each_state(
    entry: &Value,
    inputs: impl Fn(&Value) -> Vec<f64>,
    mut visit: impl FnMut(&Value, &Values<'_>),
) {
    for state in dalembert_fixtures::reference::states(entry) {
        let (q, qd, u) = (vector(&state["q"]), vector(&state["qd"]), inputs(state));
        let at = Values {
            parameters: &[],
            t: 0.0,
            q: &q,
            qd: &qd,
            u: &u,
        };
        visit(state, &at);
    }
}

/// Raises each worst error to the state's; NaN (a singular `M`) counts as
/// the worst.
pub fn keep_worst(worst: &mut [f64], errors: impl IntoIterator<Item = f64>) {
    for (w, e) in worst.iter_mut().zip(errors) {
        *w = if e.is_nan() { f64::INFINITY } else { w.max(e) };
    }
}
