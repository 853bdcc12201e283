//! The error of the build step and the command-line tool: what went wrong,
//! with enough context (file, line, column, source text) to fix it without a
//! backtrace.

use std::fmt;
use std::io;
use std::path::{Path, PathBuf};

use super::Diagnostic;

/// Why generating from `.dal` files failed.
///
/// Its `Display` is the full report: every language error with its file,
/// line, column, source line and caret, as the `dalembert!` macro reports
/// it. `Debug` prints the same report on a fresh line, so a build script
/// that calls `.unwrap()`, or returns the error from `main` (which prints
/// `Error: {e:?}`), shows it readably too.
#[non_exhaustive]
pub enum BuildError {
    /// A model has language errors (all of them, across all models).
    Model(Vec<Diagnostic>),
    /// A file or directory could not be read or written.
    Io {
        /// The file or directory.
        path: PathBuf,
        /// What failed.
        error: io::Error,
    },
    /// No output directory was chosen and `OUT_DIR` is not set (the build
    /// step runs outside a build script).
    NoOutDir,
    /// Two models would be written to the same output file.
    DuplicateOutput {
        /// The output file both models map to.
        output: PathBuf,
    },
    /// An import's option does not fit the file: its outputs name a point
    /// or frame the imported model does not have, or are not a list.
    ImportOption {
        /// The imported file.
        path: PathBuf,
        /// What is wrong, on one line.
        message: String,
    },
    /// The model path has no file name to name the output after.
    NoFileName {
        /// The model path.
        path: PathBuf,
    },
}

impl BuildError {
    /// An I/O error on `path`.
    pub(crate) fn io(path: &Path, error: io::Error) -> Self {
        BuildError::Io {
            path: path.to_owned(),
            error,
        }
    }

    /// The language errors, if this is [`BuildError::Model`]; empty otherwise.
    pub fn diagnostics(&self) -> &[Diagnostic] {
        match self {
            BuildError::Model(diagnostics) => diagnostics,
            _ => &[],
        }
    }
}

impl fmt::Display for BuildError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            BuildError::Model(diagnostics) => {
                for (i, d) in diagnostics.iter().enumerate() {
                    let separator = if i == 0 { "" } else { "\n\n" };
                    write!(f, "{separator}{d}")?;
                }
                Ok(())
            }
            BuildError::Io { path, error } => {
                write!(f, "error: {}: {error}", path.display())
            }
            BuildError::NoOutDir => f.write_str(
                "error: no output directory: OUT_DIR is not set (not in a build script?); \
                 choose one with `Builder::out_dir`",
            ),
            BuildError::DuplicateOutput { output } => write!(
                f,
                "error: two models would both be written to {}: rename one of them",
                output.display()
            ),
            BuildError::ImportOption { path, message } => {
                write!(f, "error: {}: {message}", path.display())
            }
            BuildError::NoFileName { path } => write!(
                f,
                "error: model path {} has no file name to name the output after",
                path.display()
            ),
        }
    }
}

impl fmt::Debug for BuildError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "\n{self}")
    }
}

impl std::error::Error for BuildError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            BuildError::Io { error, .. } => Some(error),
            _ => None,
        }
    }
}
