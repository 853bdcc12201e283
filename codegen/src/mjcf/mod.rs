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
use crate::build::{BuildError, Diagnostic, ImportOptions, Severity, check_outputs};

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

/// What the user chose besides the file, and the file's name.
#[derive(Clone, Debug, Default)]
pub(crate) struct Options {
    /// The options of the import (`floating` and `damping` are refused:
    /// an MJCF file says itself which bodies float and how joints are
    /// damped).
    pub chosen: ImportOptions,
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
    /// UpperCamelCase (`--name NAME`).
    pub fn name(mut self, name: impl Into<String>) -> Self {
        self.options.chosen = self.options.chosen.name(name);
        self
    }

    /// Appends `outputs LIST;` to the model (`LIST` as the language
    /// writes it: `"inverse_dynamics, position(torso_origin)"`).
    pub fn outputs(mut self, list: impl Into<String>) -> Self {
        self.options.chosen = self.options.chosen.outputs(list);
        self
    }

    /// Imports with `options`, as `dalembert mjcf` does with the same
    /// options on its command line. Of the [`ImportOptions`], an MJCF import
    /// takes the struct's name and the outputs; `floating` and `damping`
    /// are reported as errors by [`import`](Mjcf::import), since the file
    /// says itself which bodies float and how its joints are damped.
    pub fn options(mut self, options: ImportOptions) -> Self {
        self.options.chosen = options;
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
        let chosen = &self.options.chosen;
        if chosen.floating || chosen.damping {
            return Err(BuildError::ImportOption {
                path: self.path.clone(),
                message: "an MJCF import takes no `floating` or `damping` option: the file \
                          says which bodies float (free joints) and how joints are damped"
                    .to_owned(),
            });
        }
        let (sources, problems) = files::load(&self.path, self.source.clone());
        if !problems.is_empty() {
            return Err(located(&sources, problems));
        }
        let model = files::Files::new(&sources)
            .and_then(|files| read::read(&files))
            .and_then(|model| write::model_text(&model, &self.options));
        let model = model.map_err(|problems| located(&sources, problems))?;
        let with_outputs = chosen.with_outputs(&model);
        check_outputs(chosen, &model, &with_outputs).map_err(|message| {
            BuildError::ImportOption {
                path: self.path.clone(),
                message: format!(
                    "{message} (each body `B` of the model has a frame `B` and a point \
                     `B_origin`)"
                ),
            }
        })?;
        Ok(Imported {
            model: with_outputs,
            warnings: Vec::new(),
        })
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
