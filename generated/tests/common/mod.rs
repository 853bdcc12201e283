//! The models of `models/` and the files `build.rs` generated from them.

use std::path::Path;

/// A model file and its name (the file stem, also its module's name).
pub struct Model {
    pub name: String,
    pub source: String,
}

impl Model {
    /// The Rust source `build.rs` wrote for this model: what the crate
    /// compiles.
    pub fn generated(&self) -> String {
        let path = Path::new(env!("OUT_DIR")).join(format!("{}.rs", self.name));
        std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
    }
}

/// Every `models/*.dal`, in file-name order (the order `build.rs` uses).
pub fn models() -> Vec<Model> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("models");
    let mut paths: Vec<_> = std::fs::read_dir(&dir)
        .expect("models/")
        .map(|entry| entry.expect("models/ entry").path())
        .filter(|path| path.extension().is_some_and(|x| x == "dal"))
        .collect();
    paths.sort();
    assert!(!paths.is_empty(), "no models in {}", dir.display());
    paths
        .into_iter()
        .map(|path| Model {
            name: path.file_stem().unwrap().to_string_lossy().into_owned(),
            source: std::fs::read_to_string(&path).expect("model"),
        })
        .collect()
}
