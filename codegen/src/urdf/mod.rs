//! URDF import: a robot description file in, a model in the language of the
//! `dalembert!` macro out, readable and editable.
//!
//! Layers, data flowing one way: [`xml`] reads the file (with the byte
//! range of every element, for errors that name a line), [`tree`] resolves
//! and checks the robot's tree and orders its joints as Pinocchio does,
//! [`inertia`] holds the placement and mass-property algebra that merges
//! links welded by fixed joints, and [`write`] writes the model text.
//!
//! The model: one coordinate per revolute, continuous or prismatic joint,
//! named after it, in Pinocchio's order (depth-first from the root link, a
//! link's child joints sorted by name); every link's frame `L` and point
//! `L_origin`; one input `tau_<coordinate>` each, acting along the joint axis
//! between the two bodies, so `forcing = tau − (velocity and gravity
//! terms)`; gravity `(0, 0, −9.81)` in the root link's axes. Mimic joints
//! are independent coordinates, as in Pinocchio by default. Geometry,
//! limits and meshes are ignored. The [`ImportOptions`] add a name, a
//! floating base, damping and `outputs`.

pub(crate) mod inertia;
mod tree;
pub(crate) mod write;
pub(crate) mod xml;

use std::ops::Range;
use std::path::{Path, PathBuf};

use crate::build::{BuildError, Diagnostic, ImportOptions, Severity, check_outputs};

/// A URDF robot read from disk, and the options of its import.
///
/// ```no_run
/// let model = dalembert_codegen::Urdf::read("panda.urdf")?.model()?;
/// println!("{model}"); // pub Panda { coordinates panda_joint1, ...; ... }
/// # Ok::<(), dalembert_codegen::BuildError>(())
/// ```
#[derive(Clone, Debug)]
pub struct Urdf {
    path: PathBuf,
    source: String,
    options: Options,
}

/// What the user chose besides the file, and the file's name for the
/// model's documentation.
#[derive(Clone, Debug, Default)]
pub(crate) struct Options {
    /// The options of the command line and the build script.
    pub chosen: ImportOptions,
    /// The file's name, for the model's documentation.
    pub file_name: String,
}

/// Something wrong with the robot, at the bytes `range` of the file
/// (`None`: the whole file): an error, or a warning that lets the import
/// go on.
#[derive(Clone, Debug)]
pub(crate) struct Problem {
    severity: Severity,
    range: Option<Range<usize>>,
    message: String,
}

impl Problem {
    fn new(range: Option<Range<usize>>, message: String) -> Self {
        Problem {
            severity: Severity::Error,
            range,
            message,
        }
    }

    fn warning(range: Option<Range<usize>>, message: String) -> Self {
        Problem {
            severity: Severity::Warning,
            range,
            message,
        }
    }

    fn is_error(&self) -> bool {
        self.severity == Severity::Error
    }
}

/// A robot imported: the model's text and what the user should know about
/// it (see [`Urdf::import`]).
#[derive(Clone, Debug)]
pub struct Imported {
    /// The text of the `.dal` model.
    pub model: String,
    /// Warnings located in the URDF file: inertias that no mass
    /// distribution has (imported as written, as Pinocchio does), a struct
    /// name made from a robot name that is not an identifier.
    pub warnings: Vec<Diagnostic>,
}

impl Urdf {
    /// Reads the URDF file at `path`.
    pub fn read(path: impl AsRef<Path>) -> Result<Self, BuildError> {
        let path = path.as_ref();
        let source = std::fs::read_to_string(path).map_err(|e| BuildError::io(path, e))?;
        Ok(Urdf::new(path, source))
    }

    /// The URDF text `source`, reported as read from `path`.
    pub fn new(path: impl AsRef<Path>, source: impl Into<String>) -> Self {
        let path = path.as_ref().to_owned();
        let file_name = path.file_name().map_or_else(
            || path.display().to_string(),
            |n| n.to_string_lossy().into_owned(),
        );
        Urdf {
            path,
            source: source.into(),
            options: Options {
                file_name,
                ..Options::default()
            },
        }
    }

    /// Names the generated struct `name` instead of the robot's name in
    /// UpperCamelCase.
    pub fn name(mut self, name: impl Into<String>) -> Self {
        self.options.chosen = self.options.chosen.name(name);
        self
    }

    /// Puts a free joint `root_joint` between the ground and the root link,
    /// first in `q` (`root_joint_x … root_joint_qw`: position in `N` and
    /// unit quaternion) and `v` (`root_joint_vx … root_joint_wz`: velocity
    /// and angular velocity in the root link's axes), as Pinocchio's
    /// free flyer; the root link's masses become its body.
    pub fn floating(mut self, on: bool) -> Self {
        self.options.chosen = self.options.chosen.floating(on);
        self
    }

    /// Turns each joint's `<dynamics damping="d">` into the dissipation
    /// function `½ d q̇²` (off by default, as in Pinocchio's dynamics).
    pub fn damping(mut self, on: bool) -> Self {
        self.options.chosen = self.options.chosen.damping(on);
        self
    }

    /// Appends `outputs LIST;` to the model: `list` as the language's
    /// `outputs` statement takes it, naming the links' frames `L` and
    /// points `L_origin` (`"jacobian(tool0_origin), rotation(tool0)"`).
    /// An output naming what the model does not have, or a list that is
    /// not one, is an error of one line.
    pub fn outputs(mut self, list: impl Into<String>) -> Self {
        self.options.chosen = self.options.chosen.outputs(list);
        self
    }

    /// Takes every option of `options` (the struct's name, the floating
    /// base, the damping, the outputs), replacing those set before.
    pub fn options(mut self, options: ImportOptions) -> Self {
        self.options.chosen = options;
        self
    }

    /// The path errors are reported against.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The robot as the text of a `.dal` model, or every error found,
    /// located in the URDF file. Warnings are dropped: [`Urdf::import`]
    /// returns them.
    pub fn model(&self) -> Result<String, BuildError> {
        self.import().map(|imported| imported.model)
    }

    /// The robot as the text of a `.dal` model with the warnings found, or
    /// every error (and warning) found, located in the URDF file.
    pub fn import(&self) -> Result<Imported, BuildError> {
        let (model, problems) = match self.model_text() {
            Ok((model, warnings)) => (Some(model), warnings),
            Err(problems) => (None, problems),
        };
        let diagnostics = problems
            .into_iter()
            .map(|p| Diagnostic::in_text(&self.path, &self.source, p.severity, p.range, p.message))
            .collect();
        let Some(model) = model else {
            return Err(BuildError::Model(diagnostics));
        };
        let chosen = &self.options.chosen;
        let with_outputs = chosen.with_outputs(&model);
        check_outputs(chosen, &model, &with_outputs).map_err(|message| {
            BuildError::ImportOption {
                path: self.path.clone(),
                message: format!(
                    "{message} (each link `L` of the robot has a frame `L` and a point `L_origin`, \
                 unless the model's comment at the link names others)"
                ),
            }
        })?;
        Ok(Imported {
            model: with_outputs,
            warnings: diagnostics,
        })
    }

    /// The model text and its warnings, or the problems (at least one an
    /// error).
    fn model_text(&self) -> Result<(String, Vec<Problem>), Vec<Problem>> {
        let robot = xml::read(&self.source)?;
        // The struct's name is checked before the tree, so that a file
        // with faults in both reports both at once.
        let mut problems = Vec::new();
        let struct_name = write::struct_name(&robot, &self.options, &mut problems);
        let tree = match tree::tree(&robot) {
            Ok(tree) => tree,
            Err(faults) => {
                problems.extend(faults);
                return Err(problems);
            }
        };
        write::model_text(&robot, &tree, &self.options, &struct_name, problems)
    }
}
