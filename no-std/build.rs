//! Generates the seed examples and a spatial chain for a `#![no_std]` crate.

fn main() -> Result<(), dalembert_codegen::BuildError> {
    dalembert_codegen::Builder::new()
        .no_std(true)
        .models([
            "../generated/models/double_pendulum.dal",
            "../generated/models/rotating_bar.dal",
            "../generated/models/constrained_pendulum.dal",
            "../generated/models/spatial_chain_06.dal",
        ])
        .compile()?;
    Ok(())
}
