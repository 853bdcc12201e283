//! On many random models, the d'Alembert route and the independent
//! Lagrange route of the interpreter agree at random states, and `M` is
//! symmetric positive definite. The models come from one deterministic
//! stream; two tests check every other one, so that the test threads share
//! the work (one test ran alone on one core for most of the binary's time).

use std::cell::Cell;

use dalembert_codegen::testing::{Interpreter, Route, Sample};
use dalembert_differential::{Evaluation, RANDOM_MODELS, assert_positive_definite, random_model};
use proptest::test_runner::{Config, TestRunner};

/// States checked per model.
const STATES: u64 = 3;

#[test]
fn dalembert_and_lagrange_agree_on_the_even_random_models() {
    agree_on_every_other_model(0);
}

#[test]
fn dalembert_and_lagrange_agree_on_the_odd_random_models() {
    agree_on_every_other_model(1);
}

/// Draws the [`RANDOM_MODELS`] models of the deterministic stream and checks
/// those whose index has the parity `parity`.
fn agree_on_every_other_model(parity: u32) {
    let config = Config {
        cases: RANDOM_MODELS,
        failure_persistence: None,
        ..Config::default()
    };
    let (index, checked) = (Cell::new(0u32), Cell::new(0u32));
    TestRunner::new_with_rng(
        config,
        proptest::test_runner::TestRng::deterministic_rng(config_algorithm()),
    )
    .run(&random_model(), |model| {
        let this = index.replace(index.get() + 1);
        if this % 2 != parity {
            return Ok(());
        }
        checked.set(checked.get() + 1);
        let source = model.source("Random");
        let [ours, theirs] = [Route::Dalembert, Route::Lagrange].map(|route| {
            Interpreter::new(&source, route).unwrap_or_else(|e| panic!("{e}\n{source}"))
        });
        for seed in 0..STATES {
            let sample = Sample::random(&ours, seed);
            let at = sample.values();
            let context = format!("state {seed} of\n{source}");
            let a = Evaluation::interpreted(&ours, &at);
            a.assert_agrees(&Evaluation::interpreted(&theirs, &at), &context);
            assert_positive_definite(&a.mass_matrix, &context);
        }
        Ok(())
    })
    .unwrap_or_else(|failure| panic!("{failure}"));
    assert_eq!(checked.get(), RANDOM_MODELS / 2, "half the models checked");
}

fn config_algorithm() -> proptest::test_runner::RngAlgorithm {
    proptest::test_runner::RngAlgorithm::ChaCha
}
