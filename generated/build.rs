//! Generates one Rust file per `models/*.dal`, per URDF robot of
//! `tests/reference/urdf/`, per benchmark tree of `trees/` and for two MuJoCo
//! models of `tests/reference/mjcf/`, into `OUT_DIR`; `src/lib.rs` includes each into
//! its own module; with the `large` feature, also the 60-link chains
//! (`dalembert_codegen::chain::chain`). For the chains spelled with symbolic
//! parameters it also writes `chain_references.rs`: a `reference()`
//! constructor per system, holding the reference data's masses, lengths and
//! gravity. Into `OUT_DIR/derivatives/` it writes a copy of some of those
//! models (seed examples, chains, a branching tree, two robots) asking for the exact
//! derivatives, and their code, which `src/lib.rs` includes in the module
//! `derivatives`.

use std::fmt::Write;
use std::path::PathBuf;

use dalembert_codegen::chain::{Family, Spelling, chain, chain_parameters};

/// The models whose copy asks for the derivatives: `models/NAME.dal`, or a
/// URDF robot by its file name.
const WITH_DERIVATIVES: [&str; 13] = [
    "double_pendulum",
    "rotating_bar",
    "dzhanibekov",
    "floating_solo12",
    "planar_chain_02",
    "planar_chain_06",
    "planar_chain_12",
    "spatial_chain_02",
    "spatial_chain_06",
    "spatial_chain_12",
    "spatial_tree_14",
    "panda.urdf",
    "ur5_robot.urdf",
];

/// The statement the copies add.
const DERIVATIVES: &str = "outputs accelerations_jacobian, linearize, inverse_dynamics_jacobian, inverse_dynamics_adjoint;";

/// The statement the copies of the spatial chains of 30 and 60 links add
/// (the adjoint's bench, with the `large` feature).
const ADJOINT: &str = "outputs accelerations_jacobian, inverse_dynamics_adjoint;";

/// The models whose copy asks for `accelerations_x4` (four states in SIMD
/// lanes): every route of `accelerations` (factorised, articulated), every
/// elementary function, time, a ball joint, a floating base, two robots.
const WITH_LANES: [&str; 10] = [
    "double_pendulum",
    "dzhanibekov",
    "taylor_functions",
    "planar_chain_06",
    "spatial_chain_06",
    "spatial_chain_12",
    "spatial_chain_30",
    "floating_solo12",
    "panda.urdf",
    "ur5_robot.urdf",
];

/// The copies of the models `names` (`models/NAME.dal`, or a URDF robot by
/// its file name), each with `statement`: (name, source, statement).
fn copies<'a>(names: &[&str], statement: &'a str) -> Vec<(String, String, &'a str)> {
    names
        .iter()
        .map(|name| {
            let source = match name.strip_suffix(".urdf") {
                Some(robot) => {
                    dalembert_codegen::Urdf::read(format!("../tests/reference/urdf/{robot}.urdf"))
                        .and_then(|urdf| urdf.model())
                        .unwrap_or_else(|e| panic!("\n{e}\n"))
                }
                None => std::fs::read_to_string(format!("models/{name}.dal")).expect("a model"),
            };
            (
                name.trim_end_matches(".urdf").to_string(),
                source,
                statement,
            )
        })
        .collect()
}

/// Writes `copies` (each source with its statement added) into
/// `OUT_DIR/dir/`, and generates them.
fn with_outputs(out: &std::path::Path, dir: &str, copies: Vec<(String, String, &str)>) {
    let dir = out.join(dir);
    std::fs::create_dir_all(&dir).expect("OUT_DIR is writable");
    let mut builder = dalembert_codegen::Builder::new();
    builder.out_dir(&dir).emit_rerun_if_changed(false);
    for (name, source, statement) in copies {
        let end = source.rfind('}').expect("a system ends with `}`");
        let copy = format!("{}    {statement}\n{}", &source[..end], &source[end..]);
        let path = dir.join(format!("{name}.dal"));
        if std::fs::read_to_string(&path).ok().as_deref() != Some(copy.as_str()) {
            std::fs::write(&path, copy).expect("OUT_DIR is writable");
        }
        builder.model(path);
    }
    builder.compile().unwrap_or_else(|e| panic!("\n{e}\n"));
}

/// Removes the generated files of models that no longer exist (renamed or
/// deleted `.dal` files, the 60-link chains after a build without the
/// `large` feature): `OUT_DIR` outlives them, and the panic-free scan reads
/// every file in it. `chain_references.rs` is written below.
fn remove_stale(out: &std::path::Path, written: &[PathBuf]) {
    for entry in std::fs::read_dir(out).expect("OUT_DIR exists") {
        let path = entry.expect("an OUT_DIR entry").path();
        let generated = path.extension().is_some_and(|e| e == "rs")
            && path.file_name().is_some_and(|n| n != "chain_references.rs");
        if generated && !written.contains(&path) {
            std::fs::remove_file(&path).expect("OUT_DIR is writable");
        }
    }
}

fn main() {
    let out = PathBuf::from(std::env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    let mut builder = dalembert_codegen::Builder::new();
    if std::env::var_os("CARGO_FEATURE_LARGE").is_some() {
        // The 60-link chains, for the benches only: their build costs more
        // than every other model together.
        for family in [Family::Planar, Family::Spatial] {
            // Written only when it changed: Cargo reruns this script (and
            // rebuilds the crate) whenever a model's time stamp moves.
            let path = out.join(format!("{}_chain_60.dal", family.name()));
            let text = chain(family, 60);
            if std::fs::read_to_string(&path).ok() != Some(text.clone()) {
                std::fs::write(&path, text).expect("OUT_DIR is writable");
            }
            builder.model(path);
        }
    }
    if std::env::var_os("CARGO_FEATURE_HUMANOIDS").is_some() {
        // The floating humanoids of `tests/reference/humanoids/`, with their
        // derivatives, for the benches only.
        for (file, name) in [("g1", "G1"), ("talos_reduced", "Talos")] {
            builder.urdf_with(
                format!("../tests/reference/humanoids/{file}.urdf"),
                dalembert_codegen::ImportOptions::new()
                    .floating(true)
                    .name(name)
                    .outputs("accelerations_jacobian, linearize"),
            );
        }
    }
    let written = builder
        .model_dir("models")
        .urdf("../tests/reference/urdf/panda.urdf")
        // The tool flange's outputs, for the example `ur5_reach`.
        .urdf_with(
            "../tests/reference/urdf/ur5_robot.urdf",
            dalembert_codegen::ImportOptions::new()
                .outputs("position(tool0_origin), jacobian(tool0_origin), rotation(tool0)"),
        )
        .urdf("../tests/reference/urdf/solo12.urdf")
        .urdf("../tests/reference/urdf/features.urdf")
        .urdf("../tests/reference/urdf/anymal_c.urdf")
        .urdf("trees/cart_pole_1.urdf")
        .urdf("trees/cart_pole_3.urdf")
        .urdf("trees/cart_pole_6.urdf")
        .urdf("trees/limbs.urdf")
        .urdf("trees/binary_tree.urdf")
        .mjcf("../tests/reference/mjcf/dm_control/cheetah.xml")
        .mjcf("../tests/reference/mjcf/dm_control/humanoid.xml")
        .compile()
        .unwrap_or_else(|e| panic!("\n{e}\n"));
    remove_stale(&out, &written);
    let mut references = String::new();
    let mut names: Vec<String> = std::fs::read_dir("models")
        .expect("models/")
        .filter_map(|entry| {
            let path = entry.expect("models/ entry").path();
            let stem = path.file_stem()?.to_string_lossy().into_owned();
            (path.extension()? == "dal").then_some(stem)
        })
        .collect();
    names.sort();
    for name in names {
        let parts: Vec<&str> = name.split('_').collect();
        let [spelling, family, "chain", n] = parts.as_slice() else {
            continue;
        };
        let (Some(spelling), Some(family), Ok(n)) = (
            Spelling::from_name(spelling),
            Family::from_name(family),
            n.parse::<usize>(),
        ) else {
            continue;
        };
        let prefix = match spelling {
            Spelling::FramesAndPoints => "Seed",
            _ => "Symbolic",
        };
        let fields: Vec<String> = chain_parameters(n)
            .into_iter()
            .map(|(name, value)| format!("{name}: {value:?}"))
            .collect();
        writeln!(
            references,
            "impl {prefix}{} {{\n    /// The system with the reference data's parameters.\n    \
             pub const fn reference() -> Self {{\n        Self {{ {} }}\n    }}\n}}",
            family.system_name(n),
            fields.join(", ")
        )
        .expect("writing to a String");
    }
    std::fs::write(out.join("chain_references.rs"), references).expect("OUT_DIR is writable");
    let mut derivatives = copies(&WITH_DERIVATIVES, DERIVATIVES);
    if std::env::var_os("CARGO_FEATURE_LARGE").is_some() {
        for n in [30, 60] {
            derivatives.push((
                format!("spatial_chain_{n}"),
                chain(Family::Spatial, n),
                ADJOINT,
            ));
        }
    }
    with_outputs(&out, "derivatives", derivatives);
    with_outputs(
        &out,
        "lanes",
        copies(&WITH_LANES, "outputs accelerations_x4;"),
    );
}
