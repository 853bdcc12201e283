//! On many random models, the d'Alembert route and the independent
//! Lagrange route of the interpreter agree at random states, and `M` is
//! symmetric positive definite.

use dalembert_codegen::testing::{Interpreter, Route, Sample};
use dalembert_differential::{Evaluation, RANDOM_MODELS, assert_positive_definite, random_model};
use proptest::test_runner::{Config, TestRunner};

/// States checked per model.
const STATES: u64 = 3;

#[test]
fn dalembert_and_lagrange_agree_on_random_models() {
    let config = Config {
        cases: RANDOM_MODELS,
        failure_persistence: None,
        ..Config::default()
    };
    TestRunner::new_with_rng(
        config,
        proptest::test_runner::TestRng::deterministic_rng(config_algorithm()),
    )
    .run(&random_model(), |model| {
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
}

fn config_algorithm() -> proptest::test_runner::RngAlgorithm {
    proptest::test_runner::RngAlgorithm::ChaCha
}
