//! The build-script front door, in the style of `prost-build`: read `.dal`
//! models, generate (a pure function of the text), write formatted Rust only
//! when it changed, and tell Cargo to rerun when a model changes.
//!
//! In `build.rs`'s `main`:
//!
//! ```no_run
//! dalembert_codegen::Builder::new()
//!     .model("models/double_pendulum.dal")
//!     .compile()
//!     .unwrap_or_else(|e| panic!("{e}"));
//! ```
//!
//! and in the crate: `include!(concat!(env!("OUT_DIR"), "/double_pendulum.rs"));`.

mod diagnostic;
mod error;
mod import;
mod model_file;

pub use diagnostic::{Diagnostic, Severity};
pub use error::BuildError;
pub use import::ImportOptions;
pub(crate) use import::check_outputs;
pub use model_file::ModelFile;

use crate::Target;
use std::path::{Path, PathBuf};

/// The extension of model files.
const MODEL_EXTENSION: &str = "dal";

/// Generates Rust from `.dal` models in a build script.
///
/// Each model `NAME.dal` becomes `NAME.rs` in the output directory
/// (`OUT_DIR` unless [`out_dir`](Builder::out_dir) chooses another), to be
/// `include!`d by the crate. Files are rewritten only when their contents
/// change, so unchanged models do not trigger recompilation.
#[derive(Clone, Debug)]
pub struct Builder {
    models: Vec<PathBuf>,
    imports: Vec<Import>,
    model_dirs: Vec<PathBuf>,
    out_dir: Option<PathBuf>,
    emit_rerun_if_changed: bool,
    target: Target,
}

impl Default for Builder {
    fn default() -> Self {
        Builder::new()
    }
}

impl Builder {
    /// A builder with no models, writing to `OUT_DIR` and printing
    /// `cargo:rerun-if-changed` lines.
    pub fn new() -> Self {
        Builder {
            models: Vec::new(),
            imports: Vec::new(),
            model_dirs: Vec::new(),
            out_dir: None,
            emit_rerun_if_changed: true,
            target: Target::Std,
        }
    }

    /// Adds the model file at `path`.
    pub fn model(&mut self, path: impl AsRef<Path>) -> &mut Self {
        self.models.push(path.as_ref().to_owned());
        self
    }

    /// Adds the model files at `paths`.
    pub fn models<P: AsRef<Path>>(&mut self, paths: impl IntoIterator<Item = P>) -> &mut Self {
        self.models
            .extend(paths.into_iter().map(|p| p.as_ref().to_owned()));
        self
    }

    /// Adds the URDF robot at `path`, imported as `dalembert urdf` does
    /// (fixed base, no damping): `NAME.urdf` becomes `NAME.rs`, holding the
    /// struct named after the robot. Its errors are reported like a
    /// model's, located in the URDF file.
    pub fn urdf(&mut self, path: impl AsRef<Path>) -> &mut Self {
        self.urdf_with(path, ImportOptions::new())
    }

    /// Adds the URDF robot at `path` imported with `options`, as
    /// `dalembert urdf` does with the same options on its command line
    /// (`--name`, `--floating`, `--damping`, `--outputs`):
    ///
    /// ```no_run
    /// # use dalembert_codegen::{Builder, ImportOptions};
    /// Builder::new()
    ///     .urdf_with("ur5_robot.urdf", ImportOptions::new().outputs("jacobian(tool0_origin)"))
    ///     .compile()
    ///     .unwrap_or_else(|e| panic!("{e}"));
    /// ```
    pub fn urdf_with(&mut self, path: impl AsRef<Path>, options: ImportOptions) -> &mut Self {
        self.import(path, Format::Urdf, options)
    }

    /// Adds the MuJoCo model (MJCF) at `path`, imported as `dalembert mjcf`
    /// does, with the files it includes: `NAME.xml` becomes `NAME.rs`. Its
    /// errors are reported like a model's, located in the MJCF files.
    pub fn mjcf(&mut self, path: impl AsRef<Path>) -> &mut Self {
        self.mjcf_with(path, ImportOptions::new())
    }

    /// Adds the MuJoCo model at `path` imported with `options`, as
    /// `dalembert mjcf` does with the same options on its command line
    /// (`--name`, `--outputs`; an MJCF file says itself which bodies float
    /// and how joints are damped, so the options `floating` and `damping`
    /// are refused there):
    ///
    /// ```no_run
    /// # use dalembert_codegen::{Builder, ImportOptions};
    /// Builder::new()
    ///     .mjcf_with("humanoid.xml", ImportOptions::new().outputs("position(head_origin)"))
    ///     .compile()
    ///     .unwrap_or_else(|e| panic!("{e}"));
    /// ```
    pub fn mjcf_with(&mut self, path: impl AsRef<Path>, options: ImportOptions) -> &mut Self {
        self.import(path, Format::Mjcf, options)
    }

    /// Adds the robot file at `path`, in `format`, imported with `options`.
    fn import(
        &mut self,
        path: impl AsRef<Path>,
        format: Format,
        options: ImportOptions,
    ) -> &mut Self {
        self.imports.push(Import {
            path: path.as_ref().to_owned(),
            format,
            options,
        });
        self
    }

    /// Adds every `*.dal` file directly in `dir`, in file-name order. Cargo
    /// is told to rerun when a file is added to or removed from it.
    pub fn model_dir(&mut self, dir: impl AsRef<Path>) -> &mut Self {
        self.model_dirs.push(dir.as_ref().to_owned());
        self
    }

    /// Writes the generated files to `dir` instead of `OUT_DIR`.
    pub fn out_dir(&mut self, dir: impl AsRef<Path>) -> &mut Self {
        self.out_dir = Some(dir.as_ref().to_owned());
        self
    }

    /// Whether to print `cargo:rerun-if-changed` for every model and model
    /// directory, and the URDF import's warnings as `cargo:warning=`
    /// (default `true`; turn it off outside build scripts).
    pub fn emit_rerun_if_changed(&mut self, on: bool) -> &mut Self {
        self.emit_rerun_if_changed = on;
        self
    }

    /// Generates code for a `#![no_std]` crate depending on `libm` (the
    /// equations only: no runtime traits, no `accelerations`), or, with
    /// `false` (the default), for a crate using the `dalembert` runtime.
    pub fn no_std(&mut self, on: bool) -> &mut Self {
        self.target = if on { Target::NoStd } else { Target::Std };
        self
    }

    /// Generates every model. Returns the files written (or already up to
    /// date), in model order: explicit models first, then directories.
    ///
    /// All models are generated even if one fails; the error then reports
    /// the language errors of all of them.
    pub fn compile(&self) -> Result<Vec<PathBuf>, BuildError> {
        let out_dir = match &self.out_dir {
            Some(dir) => dir.clone(),
            None => std::env::var_os("OUT_DIR")
                .map(PathBuf::from)
                .ok_or(BuildError::NoOutDir)?,
        };
        let mut jobs: Vec<(PathBuf, PathBuf)> = Vec::new();
        let imports = self.imports.iter().map(|import| import.path.clone());
        for model in self.model_paths()?.into_iter().chain(imports) {
            let stem = model.file_stem().ok_or_else(|| BuildError::NoFileName {
                path: model.clone(),
            })?;
            // `NAME.rs`, keeping any dots in NAME (`with_extension` would not).
            let mut file_name = stem.to_owned();
            file_name.push(".rs");
            let output = out_dir.join(file_name);
            if jobs.iter().any(|(_, o)| *o == output) {
                return Err(BuildError::DuplicateOutput { output });
            }
            jobs.push((model, output));
        }
        self.run(&jobs)?;
        Ok(jobs.into_iter().map(|(_, output)| output).collect())
    }

    /// The explicit models, then the models of each directory, sorted.
    fn model_paths(&self) -> Result<Vec<PathBuf>, BuildError> {
        let mut paths = self.models.clone();
        for dir in &self.model_dirs {
            self.rerun_if_changed(dir);
            let entries = std::fs::read_dir(dir).map_err(|e| BuildError::io(dir, e))?;
            let mut found = Vec::new();
            for entry in entries {
                let path = entry.map_err(|e| BuildError::io(dir, e))?.path();
                if path.extension().is_some_and(|x| x == MODEL_EXTENSION) && path.is_file() {
                    found.push(path);
                }
            }
            found.sort();
            paths.extend(found);
        }
        Ok(paths)
    }

    /// Generates each `(model, output)` pair, collecting language errors.
    fn run(&self, jobs: &[(PathBuf, PathBuf)]) -> Result<(), BuildError> {
        let mut diagnostics = Vec::new();
        for (model, output) in jobs {
            self.rerun_if_changed(model);
            let file = match self.imports.iter().find(|import| import.path == *model) {
                Some(import) => self.imported_model(import),
                None => ModelFile::read(model),
            };
            match file.and_then(|file| file.generate_for(self.target)) {
                Ok(code) => write_if_changed(output, &code)?,
                Err(BuildError::Model(found)) => diagnostics.extend(found),
                Err(other) => return Err(other),
            }
        }
        if diagnostics.is_empty() {
            Ok(())
        } else {
            Err(BuildError::Model(diagnostics))
        }
    }

    /// The model imported from the robot file of `import`, reported as
    /// `path (imported)` if the engine finds errors in it. Its warnings go
    /// to Cargo (`cargo:warning=`) when the builder prints Cargo's
    /// directives.
    fn imported_model(&self, import: &Import) -> Result<ModelFile, BuildError> {
        let Import {
            path,
            format,
            options,
        } = import;
        let imported = match format {
            Format::Urdf => crate::Urdf::read(path)?.options(options.clone()).import()?,
            Format::Mjcf => crate::Mjcf::read(path)?.options(options.clone()).import()?,
        };
        if self.emit_rerun_if_changed {
            for warning in &imported.warnings {
                println!("cargo:warning={}", warning.to_string().replace('\n', " "));
            }
        }
        let text = imported.model;
        let mut imported = path.as_os_str().to_owned();
        imported.push(" (imported)");
        Ok(ModelFile::new(imported, text))
    }

    /// Tells Cargo to rerun the build script when `path` changes.
    fn rerun_if_changed(&self, path: &Path) {
        if self.emit_rerun_if_changed {
            println!("cargo:rerun-if-changed={}", path.display());
        }
    }
}

/// A robot file a [`Builder`] imports, and how.
#[derive(Clone, Debug)]
struct Import {
    path: PathBuf,
    format: Format,
    options: ImportOptions,
}

/// The formats of robot files.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Format {
    Urdf,
    Mjcf,
}

/// Generates Rust from the model at `input` and writes it to `output`
/// (creating its directory), unless `output` already holds exactly that.
/// Prints `cargo:rerun-if-changed` for `input`.
///
/// In `build.rs`'s `main`:
///
/// ```no_run
/// let out = std::path::PathBuf::from(std::env::var_os("OUT_DIR").unwrap());
/// dalembert_codegen::generate_file("models/pendulum.dal", out.join("pendulum.rs"))
///     .unwrap_or_else(|e| panic!("{e}"));
/// ```
pub fn generate_file(input: impl AsRef<Path>, output: impl AsRef<Path>) -> Result<(), BuildError> {
    let job = (input.as_ref().to_owned(), output.as_ref().to_owned());
    Builder::new().run(&[job])
}

/// Writes `contents` to `path` unless it already holds them, so that an
/// unchanged model does not make Cargo recompile the crate including it.
fn write_if_changed(path: &Path, contents: &str) -> Result<(), BuildError> {
    if std::fs::read(path).is_ok_and(|old| old == contents.as_bytes()) {
        return Ok(());
    }
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|e| BuildError::io(dir, e))?;
    }
    std::fs::write(path, contents).map_err(|e| BuildError::io(path, e))
}
