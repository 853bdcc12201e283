// build.rs: OUT_DIR/NAME.rs from every models/NAME.dal
fn main() -> Result<(), dalembert_codegen::BuildError> {
    dalembert_codegen::Builder::new()
        .model_dir("models")
        .compile()?;
    Ok(())
}
