//! The emitted code of the random models that `build.rs` generated and
//! compiled (the optimised equations) agrees at random states with the
//! interpreter's evaluation of the equations as derived, before
//! optimisation, on both routes: this checks the optimiser and the emitter.
//! And its mass matrix is positive definite.

use dalembert::MultibodySystem;
use dalembert_codegen::testing::{Interpreter, Route, Sample};
use dalembert_differential::{EMITTED_MODELS, Evaluation, assert_positive_definite};

include!(concat!(env!("OUT_DIR"), "/random_models.rs"));

/// States checked per model.
const STATES: u64 = 8;

/// The emitted functions of `system` at `sample`.
fn evaluate<S, const NQ: usize, const NU: usize>(system: &S, sample: &Sample) -> Evaluation
where
    S: MultibodySystem<NQ, NQ, NU>,
{
    let array =
        |values: &[f64]| -> [f64; NQ] { values.try_into().expect("one value per coordinate") };
    let (q, qd) = (array(&sample.q), array(&sample.qd));
    let u: [f64; NU] = sample.u.as_slice().try_into().expect("one value per input");
    Evaluation {
        mass_matrix: system
            .mass_matrix(&q)
            .iter()
            .map(|row| row.to_vec())
            .collect(),
        forcing: system.forcing(sample.t, &q, &qd, &u).to_vec(),
        kinetic_energy: system.kinetic_energy(&q, &qd),
        potential_energy: system.potential_energy(&q),
    }
}

#[test]
fn emitted_code_agrees_with_both_routes_of_the_interpreter() {
    for (index, source) in SOURCES.iter().enumerate() {
        let routes = [Route::Dalembert, Route::Lagrange].map(|route| {
            Interpreter::new(source, route).unwrap_or_else(|e| panic!("{e}\n{source}"))
        });
        for seed in 0..STATES {
            let sample = Sample::random(&routes[0], seed);
            let emitted = evaluate_model(index, &sample);
            let context = format!("random model {index} at state {seed}:\n{source}");
            for interpreter in &routes {
                let interpreted = Evaluation::interpreted(interpreter, &sample.values());
                emitted.assert_agrees(&interpreted, &context);
            }
            assert_positive_definite(&emitted.mass_matrix, &context);
        }
    }
    assert_eq!(SOURCES.len(), EMITTED_MODELS);
}
