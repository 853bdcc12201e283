//! The options of a robot import, shared by the importers (URDF, MJCF), the
//! build script's entries and the command line, which all take the same:
//! the struct's name, a floating base, joint damping, and outputs to ask
//! for.

/// What the user chose besides the file, for an importer
/// ([`Urdf`](crate::Urdf)), a [`Builder`](crate::Builder) entry, or the
/// `dalembert` command line (`--name`, `--floating`, `--damping`,
/// `--outputs`). Each method sets one option, in `prost-build`'s style:
///
/// ```no_run
/// use dalembert_codegen::{Builder, ImportOptions};
///
/// Builder::new()
///     .urdf_with(
///         "robots/ur5_robot.urdf",
///         ImportOptions::new()
///             .name("Arm")
///             .outputs("position(tool0_origin), jacobian(tool0_origin), rotation(tool0)"),
///     )
///     .compile()
///     .unwrap_or_else(|e| panic!("{e}"));
/// ```
///
/// An importer that has no use for an option (a floating base where the
/// file says which bodies float) says so in its documentation.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ImportOptions {
    pub(crate) name: Option<String>,
    pub(crate) floating: bool,
    pub(crate) damping: bool,
    pub(crate) outputs: Option<String>,
}

impl ImportOptions {
    /// The defaults: the struct named after the robot, a fixed base, no
    /// damping, no outputs.
    pub fn new() -> Self {
        ImportOptions::default()
    }

    /// Names the generated struct `name` instead of the robot's name in
    /// UpperCamelCase (`--name NAME`).
    pub fn name(mut self, name: impl Into<String>) -> Self {
        self.name = Some(name.into());
        self
    }

    /// A free joint between the ground and the root link (`--floating`).
    pub fn floating(mut self, on: bool) -> Self {
        self.floating = on;
        self
    }

    /// Joint damping as a dissipation function (`--damping`).
    pub fn damping(mut self, on: bool) -> Self {
        self.damping = on;
        self
    }

    /// Appends `outputs LIST;` to the model (`--outputs "LIST"`): `list` is
    /// what the language's `outputs` statement takes, such as
    /// `"jacobian(tool0_origin), linearize"`. Several calls add up.
    pub fn outputs(mut self, list: impl Into<String>) -> Self {
        let list = list.into();
        self.outputs = Some(match self.outputs.take() {
            Some(before) => format!("{before}, {list}"),
            None => list,
        });
        self
    }

    /// `model` (the text of a `.dal` model, ending with its system's `}`)
    /// with `outputs LIST;` before that brace; `model` itself when no
    /// output was asked for. The caller checks the result (see
    /// [`check_outputs`]).
    pub(crate) fn with_outputs(&self, model: &str) -> String {
        let (Some(list), Some(end)) = (&self.outputs, model.rfind('}')) else {
            return model.to_owned();
        };
        format!("{}    outputs {list};\n{}", &model[..end], &model[end..])
    }
}

/// Whether the outputs of `options`, appended to `model` by
/// [`ImportOptions::with_outputs`] as `with_outputs`, name what the model
/// has: `Err` with one line saying what is wrong with the list (a list
/// that is not one, an unknown output, point or frame) when the language
/// rejects the appended statement. Errors elsewhere in the model are left
/// to the generator, which reports them in full.
pub(crate) fn check_outputs(
    options: &ImportOptions,
    model: &str,
    with_outputs: &str,
) -> Result<(), String> {
    let Some(list) = &options.outputs else {
        return Ok(());
    };
    let malformed = || {
        format!(
            "the outputs \"{list}\" are not a list of outputs: expected names such as \
             `linearize` or `jacobian(tool0_origin)` separated by commas"
        )
    };
    if list.trim().is_empty() || list.contains([';', '{', '}']) {
        return Err(malformed());
    }
    // The statement starts where the model's closing brace was.
    let start = model.rfind('}').unwrap_or(model.len());
    let end = with_outputs.len() - (model.len() - start);
    let in_statement = |e: &syn::Error| {
        let range = e.span().byte_range();
        range.start >= start && range.start < end
    };
    let tokens = crate::lex(with_outputs).map_err(|_| malformed())?;
    let errors = match crate::language::parse_system(tokens) {
        Ok(system) => match crate::model::resolve(&system) {
            Ok(_) => return Ok(()),
            Err(errors) => errors,
        },
        Err(errors) if errors.clone().into_iter().any(|e| in_statement(&e)) => {
            return Err(malformed());
        }
        Err(_) => return Ok(()),
    };
    let messages: Vec<String> = errors
        .into_iter()
        .filter(in_statement)
        .map(|e| e.to_string())
        .collect();
    if messages.is_empty() {
        return Ok(());
    }
    Err(format!("the outputs \"{list}\": {}", messages.join("; ")))
}

#[cfg(test)]
mod tests {
    use super::*;

    const MODEL: &str = "pub A {\n    coordinates q;\n    frame B = N.rotate_z(q);\n    \
                         point P = O + B.x;\n    body b { mass: 1, center: P, frame: B, inertia: [1, 1, 1] };\n}\n";

    fn checked(list: &str) -> Result<(), String> {
        let options = ImportOptions::new().outputs(list);
        check_outputs(&options, MODEL, &options.with_outputs(MODEL))
    }

    #[test]
    fn outputs_are_appended_inside_the_system() {
        let options = ImportOptions::new()
            .outputs("position(P)")
            .outputs("linearize");
        let text = options.with_outputs(MODEL);
        assert!(
            text.ends_with("    outputs position(P), linearize;\n}\n"),
            "{text}"
        );
        assert_eq!(ImportOptions::new().with_outputs(MODEL), MODEL);
        assert_eq!(checked("position(P), rotation(B), jacobian(P)"), Ok(()));
    }

    #[test]
    fn a_bad_list_is_one_line() {
        for (list, expected) in [
            ("jacobian(Q)", "unknown"),
            ("jacobian(P", "not a list of outputs"),
            ("position(P) linearize", "not a list of outputs"),
            ("linearize; }", "not a list of outputs"),
            ("", "not a list of outputs"),
            ("speed(P)", "speed"),
        ] {
            let error = checked(list).unwrap_err();
            assert!(
                error.contains(expected) && !error.contains('\n'),
                "{list}: {error}"
            );
        }
    }
}
