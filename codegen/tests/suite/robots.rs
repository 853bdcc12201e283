//! The reference robots of `tests/reference/robots/` (Pinocchio's values
//! for branching robots and every link's frame, written by
//! `scripts/robots_reference.py`), shared by `urdf_branching.rs` and
//! `urdf_frames.rs`.

use serde_json::Value;

/// `tests/reference/`, where the robots' URDF paths start.
pub fn reference_dir() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/reference")
}

/// The entry of `robot` in the section `section` (`dynamics` or `frames`)
/// of `robots/pinocchio.json`.
pub fn entry(section: &str, robot: &str) -> Value {
    let path = reference_dir().join("robots/pinocchio.json");
    let document: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    document["models"][section]
        .as_array()
        .unwrap()
        .iter()
        .find(|m| m["robot"] == robot)
        .unwrap_or_else(|| panic!("{robot} in the {section} of robots/pinocchio.json"))
        .clone()
}
