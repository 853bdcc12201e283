//! Generates one Rust file per `models/*.dal`, and per URDF robot of
//! `tests/reference/urdf/`, into `OUT_DIR`; `src/lib.rs` includes each into
//! its own module.

fn main() {
    dalembert_codegen::Builder::new()
        .model_dir("models")
        .urdf("../tests/reference/urdf/panda.urdf")
        .urdf("../tests/reference/urdf/ur5_robot.urdf")
        .urdf("../tests/reference/urdf/solo12.urdf")
        .urdf("../tests/reference/urdf/features.urdf")
        .compile()
        .unwrap_or_else(|e| panic!("\n{e}\n"));
}
