//! A `.dal` file read from disk, and the engine's entry points run on it
//! with their errors located in the file.

use std::path::{Path, PathBuf};

use super::{BuildError, Diagnostic};

/// U+FEFF at the start of a UTF-8 file.
const BYTE_ORDER_MARK: char = '\u{feff}';

/// The text of a `.dal` model file (the `dalembert!` macro's language) and
/// where it was read from.
#[derive(Clone, Debug)]
pub struct ModelFile {
    path: PathBuf,
    source: String,
}

impl ModelFile {
    /// Reads the model at `path`.
    pub fn read(path: impl AsRef<Path>) -> Result<Self, BuildError> {
        let path = path.as_ref();
        let source = std::fs::read_to_string(path).map_err(|e| BuildError::io(path, e))?;
        Ok(ModelFile::new(path, source))
    }

    /// A model with text `source`, reported as read from `path`. A leading
    /// byte-order mark, which some editors write and rustc ignores, is
    /// dropped, so that columns on the first line count from its first
    /// character.
    pub fn new(path: impl AsRef<Path>, source: impl Into<String>) -> Self {
        let mut source = source.into();
        if source.starts_with(BYTE_ORDER_MARK) {
            source.drain(..BYTE_ORDER_MARK.len_utf8());
        }
        ModelFile {
            path: path.as_ref().to_owned(),
            source,
        }
    }

    /// The path errors are reported against.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The text of the model.
    pub fn source(&self) -> &str {
        &self.source
    }

    /// Checks the model as the macro does, without deriving its equations.
    pub fn check(&self) -> Result<(), BuildError> {
        self.located(crate::check(&self.source))
    }

    /// The estimated size of each generated function (see
    /// [`crate::function_sizes`]).
    pub fn function_sizes(&self) -> Result<Vec<crate::FunctionSize>, BuildError> {
        self.located(crate::function_sizes(&self.source))
    }

    /// The estimate of the engine's work on the model (see
    /// [`crate::derivation_estimate`]).
    pub fn derivation_estimate(&self) -> Result<crate::DerivationEstimate, BuildError> {
        self.located(crate::derivation_estimate(&self.source))
    }

    /// The functions generated for the model, listed (see [`crate::api`]).
    pub fn api(&self) -> Result<String, BuildError> {
        self.located(crate::api(&self.source))
    }

    /// The generated Rust source (see [`crate::generate`]).
    pub fn generate(&self) -> Result<String, BuildError> {
        self.generate_for(crate::Target::Std)
    }

    /// The generated Rust source for a kind of crate (see
    /// [`crate::generate_for`]).
    pub fn generate_for(&self, target: crate::Target) -> Result<String, BuildError> {
        self.located(crate::generate_for(&self.source, target))
    }

    /// The derived equations in the seed document's style (see
    /// [`crate::equations`]).
    pub fn equations(&self, style: crate::Style) -> Result<String, BuildError> {
        self.located(crate::equations(&self.source, style))
    }

    /// Locates the errors of `result` in this file.
    fn located<T>(&self, result: syn::Result<T>) -> Result<T, BuildError> {
        result.map_err(|e| BuildError::Model(Diagnostic::from_syn(&self.path, &self.source, e)))
    }
}
