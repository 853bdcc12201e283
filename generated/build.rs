//! Generates one Rust file per `models/*.dal` into `OUT_DIR`; `src/lib.rs`
//! includes each into its own module.

fn main() {
    dalembert_codegen::Builder::new()
        .model_dir("models")
        .compile()
        .unwrap_or_else(|e| panic!("\n{e}\n"));
}
