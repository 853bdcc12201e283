//! Every bad input of the language gives a `compile_error!` at the
//! offending token with a message that says what is expected: one case per
//! diagnostic under `tests/ui/<category>/`, with its expected `.stderr`.

#[test]
fn bad_input_is_reported_at_the_offending_token() {
    let cases = trybuild::TestCases::new();
    cases.compile_fail("tests/ui/*/*.rs");
}
