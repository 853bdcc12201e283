//! Very long input through the whole engine: an expression with the most
//! operators the parser allows is derived and emitted (within a test
//! thread's 2 MiB stack, in a debug build), and a sum of 100 000 terms is an
//! error, not a stack overflow (a sum of 12 000 terms used to crash rustc
//! through the macro).

/// A particle on a line whose potential and force are the sums given.
fn model(potential: &str, force: &str) -> String {
    format!(
        "pub Bead {{ parameters m; coordinates q; point P = O + q * N.x; \
         particle p {{ mass: m, at: P }}; potential {potential}; force {force} at P; }}"
    )
}

/// `q + q + ...` with `terms` terms.
fn sum(terms: usize) -> String {
    vec!["q"; terms].join(" + ")
}

#[test]
fn the_longest_expression_goes_through_the_engine() {
    let longest = sum(2049);
    let almost = format!("({}) * N.x", sum(2048));
    let source = dalembert_codegen::generate(&model(&longest, &almost)).expect("a valid model");
    assert!(source.contains("pub fn forcing"));
}

#[test]
fn a_longer_expression_is_an_error_not_a_stack_overflow() {
    let error = dalembert_codegen::check(&model(&sum(100_000), "N.x")).expect_err("too long");
    assert!(
        error
            .to_string()
            .starts_with("expression too long (more than 2048 operators)")
    );
}
