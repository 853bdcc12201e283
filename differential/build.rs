//! Generates and compiles the code of [`EMITTED_MODELS`] random models from
//! a fixed seed: `OUT_DIR/random_models.rs` holds one module per model,
//! with its `.dal` text, and `evaluate_model(i, sample)`, which runs the
//! emitted functions of model `i` (through `crate::evaluate`, defined by
//! the test that includes the file).

use std::fmt::Write;
use std::path::PathBuf;

use proptest::strategy::{Strategy, ValueTree};
use proptest::test_runner::TestRunner;

#[path = "src/random_model.rs"]
#[allow(dead_code)]
mod random_model;

use random_model::{EMITTED_MODELS, random_model};

fn main() {
    println!("cargo:rerun-if-changed=src/random_model.rs");
    let out = PathBuf::from(std::env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    let mut runner = TestRunner::deterministic();
    let strategy = random_model();
    let mut modules = String::new();
    let mut arms = String::new();
    for i in 0..EMITTED_MODELS {
        let model = strategy
            .new_tree(&mut runner)
            .expect("the strategy makes models")
            .current();
        let name = format!("Random{i}");
        let source = model.source(&name);
        let code = dalembert_codegen::generate(&source)
            .unwrap_or_else(|e| panic!("random model {i} does not generate: {e}\n{source}"));
        std::fs::write(out.join(format!("random_{i}.rs")), code).expect("OUT_DIR is writable");
        std::fs::write(out.join(format!("random_{i}.dal")), &source).expect("OUT_DIR is writable");
        writeln!(
            modules,
            "#[allow(dead_code)] // The test calls the functions, not every constant.\nmod random_{i} {{ include!(concat!(env!(\"OUT_DIR\"), \"/random_{i}.rs\")); }}"
        )
        .expect("writing to a String");
        let fields: Vec<String> = model
            .parameter_names()
            .iter()
            .enumerate()
            .map(|(k, p)| format!("{p}: sample.parameters[{k}]"))
            .collect();
        writeln!(
            arms,
            "        {i} => crate::evaluate(&random_{i}::{name} {{ {} }}, sample),",
            fields.join(", ")
        )
        .expect("writing to a String");
    }
    let sources: Vec<String> = (0..EMITTED_MODELS)
        .map(|i| format!("    include_str!(concat!(env!(\"OUT_DIR\"), \"/random_{i}.dal\")),"))
        .collect();
    let file = format!(
        "{modules}
/// The `.dal` text of each model.
const SOURCES: [&str; {EMITTED_MODELS}] = [
{}
];

/// The emitted functions of model `index` at `sample`.
fn evaluate_model(index: usize, sample: &Sample) -> Evaluation {{
    match index {{
{arms}        _ => panic!(\"no model {{index}}\"),
    }}
}}
",
        sources.join("\n")
    );
    std::fs::write(out.join("random_models.rs"), file).expect("OUT_DIR is writable");
}
