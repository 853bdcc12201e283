//! MJCF import: a MuJoCo model file in, a model in the language of the
//! `dalembert!` macro out, with MuJoCo's coordinates, speeds, masses and
//! passive forces.
//!
//! Layers, data flowing one way: [`files`] reads the main file and the
//! files it includes (each element keeps its file and byte range, for
//! errors that name a line), [`read`] resolves the defaults and computes
//! what MuJoCo's compiler computes (placements, inertias from geoms),
//! with the numeric rules in [`pose`], and [`write`] writes the model text.

mod files;
mod pose;
mod read;
mod write;

use std::ops::Range;
use std::path::{Path, PathBuf};

use crate::Imported;
use crate::build::{BuildError, Diagnostic, Severity};

/// A MuJoCo model (MJCF) read from disk, and the options of its import.
///
/// ```no_run
/// let model = dalembert_codegen::Mjcf::read("humanoid.xml")?.model()?;
/// println!("{model}"); // pub Humanoid { joint free root { .. }; ... }
/// # Ok::<(), dalembert_codegen::BuildError>(())
/// ```
#[derive(Clone, Debug)]
pub struct Mjcf {
    path: PathBuf,
    source: String,
    options: Options,
}

/// What the user chose besides the file.
#[derive(Clone, Debug, Default)]
pub(crate) struct Options {
    /// The struct's name instead of the model's in UpperCamelCase.
    pub name: Option<String>,
    /// The list of an `outputs` statement appended to the model.
    pub outputs: Option<String>,
    /// The file's name, for the model's documentation.
    pub file_name: String,
}

/// Where something is: a file (index into the files read) and a byte
/// range in it.
#[derive(Clone, Debug)]
pub(crate) struct Loc {
    file: usize,
    range: Range<usize>,
}

/// An error in the model at `loc`.
#[derive(Clone, Debug)]
pub(crate) struct Problem {
    loc: Loc,
    message: String,
}

impl Problem {
    fn new(loc: Loc, message: String) -> Self {
        Problem { loc, message }
    }
}

impl Mjcf {
    /// Reads the MJCF file at `path` (the files it includes are read
    /// when importing).
    pub fn read(path: impl AsRef<Path>) -> Result<Self, BuildError> {
        let path = path.as_ref();
        let source = std::fs::read_to_string(path).map_err(|e| BuildError::io(path, e))?;
        Ok(Mjcf::new(path, source))
    }

    /// The MJCF text `source`, reported as read from `path` (its includes
    /// are looked up beside `path`).
    pub fn new(path: impl AsRef<Path>, source: impl Into<String>) -> Self {
        let path = path.as_ref().to_owned();
        let file_name = path.file_name().map_or_else(
            || path.display().to_string(),
            |n| n.to_string_lossy().into_owned(),
        );
        Mjcf {
            path,
            source: source.into(),
            options: Options {
                file_name,
                ..Options::default()
            },
        }
    }

    /// Names the generated struct `name` instead of the model's name in
    /// UpperCamelCase.
    pub fn name(mut self, name: impl Into<String>) -> Self {
        self.options.name = Some(name.into());
        self
    }

    /// Appends `outputs LIST;` to the model (`LIST` as the language
    /// writes it: `"inverse_dynamics, position(torso_origin)"`).
    pub fn outputs(mut self, list: impl Into<String>) -> Self {
        self.options.outputs = Some(list.into());
        self
    }

    /// The path errors are reported against.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The model as the text of a `.dal` model, or every error found,
    /// located in the MJCF files.
    pub fn model(&self) -> Result<String, BuildError> {
        self.import().map(|imported| imported.model)
    }

    /// The model as the text of a `.dal` model (with no warnings: what
    /// the import leaves out is listed in the model's documentation), or
    /// every error found, located in the MJCF files.
    pub fn import(&self) -> Result<Imported, BuildError> {
        let (sources, problems) = files::load(&self.path, self.source.clone());
        if !problems.is_empty() {
            return Err(located(&sources, problems));
        }
        let model = files::Files::new(&sources)
            .and_then(|files| read::read(&files))
            .and_then(|model| write::model_text(&model, &self.options));
        match model {
            Ok(model) => Ok(Imported {
                model,
                warnings: Vec::new(),
            }),
            Err(problems) => Err(located(&sources, problems)),
        }
    }
}

/// The problems as diagnostics in their files.
fn located(sources: &[files::Source], problems: Vec<Problem>) -> BuildError {
    let mut diagnostics = Vec::new();
    for problem in problems {
        let source = sources.get(problem.loc.file).unwrap_or(&sources[0]);
        diagnostics.push(Diagnostic::in_text(
            &source.path,
            &source.text,
            Severity::Error,
            Some(problem.loc.range),
            problem.message,
        ));
    }
    BuildError::Model(diagnostics)
}
