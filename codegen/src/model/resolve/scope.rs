//! Names: what each stands for at the point of use, the built-ins no
//! statement may define again, and the definitions of frames and points.

use super::Resolver;
use super::evaluate::FUNCTIONS;
use crate::expr::{ExprId, Sym};
use crate::language::ast::{Expr, Statement, System};
use crate::language::keyword::field::CHILD;
use crate::model::{Frame, FrameId, FramePlacement, Point, PointId, Vector};
use proc_macro2::{Ident, Span};
use std::collections::HashMap;

/// The built-in names, which no statement may define again.
const BUILTINS: [&str; 3] = ["N", "O", "t"];

/// The variants of `Option` and `Result` in Rust's prelude: in a `let`
/// of the generated code they are patterns, not new variables.
const PRELUDE_VARIANTS: [&str; 4] = ["Some", "None", "Ok", "Err"];

/// What a name stands for at the point of use.
#[derive(Clone, Copy, Debug)]
pub(super) enum Binding {
    Scalar(Sym),
    Frame(FrameId),
    Point(PointId),
    Body,
    Particle,
    Closure,
    Rolling,
    /// A name whose definition had an error (already reported): later uses
    /// stay silent instead of repeating it.
    Invalid,
}

impl Binding {
    pub(super) fn describe(self) -> &'static str {
        match self {
            Binding::Scalar(Sym::Param(_)) => "a parameter",
            Binding::Scalar(Sym::Coord(_)) => "a coordinate",
            Binding::Scalar(Sym::Input(_)) => "an input",
            Binding::Scalar(Sym::Speed(_)) => "a speed",
            Binding::Scalar(Sym::Time) => "time",
            Binding::Scalar(_) => "a built-in scalar",
            Binding::Frame(_) => "a frame",
            Binding::Point(_) => "a point",
            Binding::Body => "a body",
            Binding::Particle => "a particle",
            Binding::Closure => "a loop closure",
            Binding::Rolling => "a rolling contact",
            Binding::Invalid => "a name with an error",
        }
    }
}

/// Whether `name` can be written in the generated Rust as it is and with a
/// suffix (`q_dot`, `ball_qx`): an identifier, not a raw identifier (`r#q`),
/// a Rust keyword (`type`, `self`, `_`) nor a variant of the prelude
/// (`Some`, `Ok`).
pub(crate) fn is_plain(name: &str) -> bool {
    !name.starts_with("r#")
        && !PRELUDE_VARIANTS.contains(&name)
        && syn::parse_str::<Ident>(name).is_ok()
}

/// The language's built-in names, then its functions (`dt` last): names
/// no statement may define again.
pub(crate) fn builtin_names() -> impl Iterator<Item = &'static str> {
    BUILTINS.into_iter().chain(FUNCTIONS.map(|(name, _)| name))
}

/// Whether `name` is one of [`builtin_names`].
pub(crate) fn is_builtin(name: &str) -> bool {
    builtin_names().any(|builtin| builtin == name)
}

impl Resolver {
    /// Reports `name` if it is not [plain](is_plain); whether it is.
    pub(super) fn check_plain(&mut self, name: &Ident) -> bool {
        let text = name.to_string();
        if is_plain(&text) {
            return true;
        }
        let (what, other) = if text.starts_with("r#") {
            ("a raw identifier", "that is not a keyword")
        } else if PRELUDE_VARIANTS.contains(&text.as_str()) {
            (
                "a variant of Rust's prelude (of `Option` or `Result`)",
                "other than `Some`, `None`, `Ok` and `Err`",
            )
        } else {
            ("a Rust keyword", "that is not a keyword")
        };
        self.errors.push(
            name.span(),
            format!(
                "`{name}` is {what}, but the generated code binds every name as a Rust \
                 variable or field and makes other names from it; choose a plain identifier \
                 {other}"
            ),
        );
        false
    }

    pub(super) fn define(&mut self, name: &Ident, binding: Binding) -> bool {
        let text = name.to_string();
        if !self.check_plain(name) {
            self.bindings.insert(text, (Binding::Invalid, name.span()));
            return false;
        }
        if is_builtin(&text) {
            self.errors.push(
                name.span(),
                format!(
                    "`{name}` is a built-in name and cannot be defined again; choose another name"
                ),
            );
            return false;
        }
        if let Some((previous, _)) = self.bindings.get(&text) {
            self.errors.push(
                name.span(),
                format!(
                    "`{name}` is already defined as {}; every name must be unique",
                    previous.describe()
                ),
            );
            return false;
        }
        self.bindings.insert(text, (binding, name.span()));
        true
    }

    /// Defines frame `name`; whether it was new.
    pub(super) fn define_frame(
        &mut self,
        name: &Ident,
        parent: FrameId,
        axis: [ExprId; 3],
        angle: ExprId,
        ball: Option<usize>,
    ) -> bool {
        let id = FrameId(self.model.frames.len());
        let new = self.define(name, Binding::Frame(id));
        if new {
            self.model.frames.push(Frame {
                placement: Some(FramePlacement {
                    parent,
                    axis,
                    angle,
                    ball,
                }),
            });
            self.model.names.frames.push((name.clone(), id));
        }
        new
    }

    /// Defines point `name`; whether it was new.
    pub(super) fn define_point(
        &mut self,
        name: &Ident,
        placement: Option<(PointId, Vector)>,
    ) -> bool {
        let id = PointId(self.model.points.len());
        let new = self.define(name, Binding::Point(id));
        if new {
            self.model.points.push(Point { placement });
            self.model.names.points.push((name.clone(), id));
        }
        new
    }

    /// The binding of `ident`, or `None` with an error at it (used before
    /// its definition, a function's name, or unknown).
    pub(super) fn lookup(&mut self, ident: &Ident) -> Option<Binding> {
        self.lookup_expecting(
            ident,
            "a parameter, coordinate, input, frame or point defined above, or `t`",
        )
    }

    /// [`Self::lookup`] where only one kind of name fits: an unknown name
    /// is reported as not the `expected` one.
    pub(super) fn lookup_expecting(&mut self, ident: &Ident, expected: &str) -> Option<Binding> {
        let text = ident.to_string();
        if let Some((binding, _)) = self.bindings.get(&text) {
            return match binding {
                Binding::Invalid => None,
                valid => Some(*valid),
            };
        }
        let message = if self.defined_anywhere.contains_key(&text) {
            format!("`{ident}` is used before its definition; move its statement above this one")
        } else if FUNCTIONS.iter().any(|(f, _)| *f == text) {
            format!("`{ident}` is a function: call it as `{ident}(...)`")
        } else {
            format!("unknown name `{ident}`; expected {expected}")
        };
        self.errors.push(ident.span(), message);
        None
    }

    pub(super) fn frame_name(&mut self, ident: &Ident) -> Option<FrameId> {
        match self.lookup_expecting(ident, "a frame defined above")? {
            Binding::Frame(f) => Some(f),
            other => {
                self.errors.push(
                    ident.span(),
                    format!("`{ident}` is {}; expected a frame", other.describe()),
                );
                None
            }
        }
    }
}

/// Every name that some statement defines, with its span.
pub(super) fn defined_names(system: &System) -> HashMap<String, Span> {
    let mut names = HashMap::new();
    let mut add = |ident: &Ident| {
        names.entry(ident.to_string()).or_insert(ident.span());
    };
    for statement in &system.statements {
        match statement {
            Statement::Parameters(list)
            | Statement::Coordinates(list)
            | Statement::Inputs(list) => list.iter().for_each(&mut add),
            Statement::Frame { name, .. }
            | Statement::Point { name, .. }
            | Statement::Body { name, .. }
            | Statement::Particle { name, .. }
            | Statement::Closure { name, .. }
            | Statement::Rolling { name, .. } => add(name),
            Statement::Joint { name, fields, .. } => {
                add(name);
                for field in fields {
                    if let (true, Expr::Name(child)) = (field.name == CHILD, &field.value) {
                        add(child);
                    }
                }
            }
            Statement::Speeds { names, .. } => names.iter().for_each(&mut add),
            _ => {}
        }
    }
    names
}
