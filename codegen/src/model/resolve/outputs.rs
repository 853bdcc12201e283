//! The `outputs` statement: each requested function, its point, frame or
//! independent coordinates and speeds, and its axes, each asked for once.

use super::Resolver;
use super::scope::Binding;
use crate::expr::Sym;
use crate::language::ast::OutputRequest;
use crate::model::output::{KINDS, Subject, function_name, kind, kind_list};
use crate::model::{FrameId, NEWTONIAN, Output, OutputKind, PointId};
use proc_macro2::Ident;

/// What `linearize(..)` names as independent: coordinates (before `;`,
/// where a free or spherical joint's speeds stand for its tangent
/// directions) or speeds (after `;`).
#[derive(Clone, Copy, PartialEq, Eq)]
enum Independent {
    Coordinates,
    Speeds,
}

impl Independent {
    /// The word for them in messages.
    fn noun(self) -> &'static str {
        match self {
            Independent::Coordinates => "coordinates",
            Independent::Speeds => "speeds",
        }
    }

    /// Whether a coordinate's name, written as its rate `dt(..)` or not,
    /// names one of them: any coordinate among the coordinates, only its
    /// rate among the speeds.
    fn takes_coordinate(self, rate: bool) -> bool {
        rate || self == Independent::Coordinates
    }
}

/// What an output request names in its parentheses.
#[derive(Default)]
struct Named {
    point: Option<PointId>,
    frame: Option<FrameId>,
    independent: Vec<(Sym, Ident)>,
    independent_speeds: Vec<(Sym, Ident)>,
}

impl Resolver {
    /// One item of `outputs`: a known name, with a point or a frame in
    /// parentheses when it needs one, asked for once.
    pub(super) fn output(&mut self, request: &OutputRequest) {
        let name = &request.name;
        let Some(subject) = self.output_subject_kind(name) else {
            return;
        };
        if !self.check_one_subject(request, subject) {
            return;
        }
        let Some(named) = self.output_subject(request, subject) else {
            return;
        };
        let axes = match &request.axes {
            Some(f) => self.frame_name(f),
            None => Some(NEWTONIAN),
        };
        let (Some(kind), Some(axes)) = (kind(&name.to_string(), named.point, named.frame), axes)
        else {
            return;
        };
        if request.axes.is_some() && subject == Subject::None {
            self.errors.push(
                name.span(),
                format!("`{name}` has no axes to choose: remove `in`"),
            );
            return;
        }
        let of = request
            .of
            .as_ref()
            .filter(|_| subject != Subject::Coordinates);
        let function = function_name(name, of, request.axes.as_ref());
        if !self.check_asked_once(name, &function, kind, axes) {
            return;
        }
        self.model.outputs.push(Output {
            kind,
            axes,
            function,
            subject: of.map(Ident::to_string),
            axes_name: request
                .axes
                .as_ref()
                .map_or("N".to_string(), Ident::to_string),
            independent: named.independent,
            independent_speeds: named.independent_speeds,
            chart: None,
        });
    }

    /// What the output `name` needs in parentheses, if it is a known
    /// output.
    fn output_subject_kind(&mut self, name: &Ident) -> Option<Subject> {
        let Some(&(_, subject)) = KINDS.iter().find(|(k, _)| name == k) else {
            self.errors.push(
                name.span(),
                format!("unknown output `{name}`; expected one of {}", kind_list()),
            );
            return None;
        };
        Some(subject)
    }

    /// Whether `request` names at most one point or frame and no speeds,
    /// unless it names independent coordinates (`linearize(..)`).
    fn check_one_subject(&mut self, request: &OutputRequest, subject: Subject) -> bool {
        let name = &request.name;
        if subject == Subject::Coordinates {
            return true;
        }
        if let Some(extra) = request.more.first() {
            let message = format!("`{name}` takes one point or frame: remove `, {extra}`");
            self.errors.push(extra.span(), message);
            return false;
        }
        if let Some(extra) = request.speeds.first() {
            let written = match extra.rate {
                true => format!("dt({})", extra.name),
                false => extra.name.to_string(),
            };
            let message = format!("`{name}` takes no speeds: remove `; {written}`");
            self.errors.push(extra.name.span(), message);
            return false;
        }
        true
    }

    /// What `request` names in parentheses, checked against what its kind
    /// needs (`subject`).
    fn output_subject(&mut self, request: &OutputRequest, subject: Subject) -> Option<Named> {
        let name = &request.name;
        let mut named = Named::default();
        match (subject, &request.of) {
            (Subject::None | Subject::Coordinates, None) => {}
            (Subject::Coordinates, Some(of)) => {
                named.independent = self.independent_coordinates(of, &request.more);
                let speeds: Vec<(Ident, bool)> = request
                    .speeds
                    .iter()
                    .map(|s| (s.name.clone(), s.rate))
                    .collect();
                named.independent_speeds = self.independent_symbols(&speeds, Independent::Speeds);
                if named.independent.len() != 1 + request.more.len()
                    || named.independent_speeds.len() != speeds.len()
                {
                    return None;
                }
            }
            (Subject::None, Some(of)) => {
                let message = format!("`{name}` takes no point or frame: write `{name}` alone");
                self.errors.push(of.span(), message);
                return None;
            }
            (_, None) => {
                let what = if subject == Subject::Point {
                    "a point: `(P)`"
                } else {
                    "a frame: `(B)`"
                };
                self.errors
                    .push(name.span(), format!("`{name}` needs {what} after its name"));
                return None;
            }
            (Subject::Point, Some(of)) => {
                match self.lookup_expecting(of, "a point defined above") {
                    Some(Binding::Point(p)) => named.point = Some(p),
                    Some(other) => {
                        let message =
                            format!("`{of}` is {}; `{name}` expects a point", other.describe());
                        self.errors.push(of.span(), message);
                    }
                    None => {}
                }
            }
            (Subject::Frame, Some(of)) => named.frame = self.frame_name(of),
        }
        Some(named)
    }

    /// Whether no earlier output has the same function name, or the same
    /// kind in the same axes.
    fn check_asked_once(
        &mut self,
        name: &Ident,
        function: &Ident,
        kind: OutputKind,
        axes: FrameId,
    ) -> bool {
        let same = |o: &&Output| o.function == *function || (o.kind, o.axes) == (kind, axes);
        let Some(earlier) = self.model.outputs.iter().find(same) else {
            return true;
        };
        let message = format!(
            "this output is already asked for, as `{}`; ask for it once",
            earlier.function
        );
        self.errors.push(name.span(), message);
        false
    }

    /// `linearize(a, b)`'s names as coordinates (or a free or spherical
    /// joint's speeds, for its tangent directions), each once; an error at
    /// each name that is neither.
    fn independent_coordinates(&mut self, first: &Ident, more: &[Ident]) -> Vec<(Sym, Ident)> {
        let names: Vec<(Ident, bool)> = std::iter::once(first)
            .chain(more)
            .map(|n| (n.clone(), false))
            .collect();
        self.independent_symbols(&names, Independent::Coordinates)
    }

    /// The symbols of `names` (with whether each was written `dt(..)`) as
    /// `linearize(..)` names its independent coordinates or speeds (`which`);
    /// each once, an error at each that is neither.
    fn independent_symbols(
        &mut self,
        names: &[(Ident, bool)],
        which: Independent,
    ) -> Vec<(Sym, Ident)> {
        let mut independent: Vec<(Sym, Ident)> = Vec::new();
        for (name, rate) in names {
            let sym = match self.lookup(name) {
                Some(Binding::Scalar(sym @ Sym::Coord(_))) if which.takes_coordinate(*rate) => {
                    Some(sym)
                }
                Some(Binding::Scalar(sym @ Sym::Speed(_))) if !rate => Some(sym),
                Some(other) => {
                    let hint = match which {
                        Independent::Speeds => format!(" (a coordinate's speed as `dt({name})`)"),
                        Independent::Coordinates => String::new(),
                    };
                    let message = format!(
                        "`{name}` is {}; `linearize(..)` names the independent {}{hint}",
                        other.describe(),
                        which.noun()
                    );
                    self.errors.push(name.span(), message);
                    None
                }
                None => None,
            };
            match sym {
                Some(sym) if independent.iter().any(|(s, _)| *s == sym) => {
                    self.errors
                        .push(name.span(), format!("`{name}` is named twice"));
                }
                Some(sym) => independent.push((sym, name.clone())),
                None => {}
            }
        }
        independent
    }
}
