//! The syntax tree of the system-description language, exactly as written,
//! with the span of every token a diagnostic may point at.
//!
//! Nothing here is resolved or typed: `B1.y` is a [`Expr::Member`] whether
//! `B1` names a frame or not, and `P1 - L * B1.y` is a binary expression
//! whatever `P1` is. The model layer gives names their meaning.

use std::fmt::Display;

use proc_macro2::{Ident, Punct, Spacing, Span, TokenStream, TokenTree};

/// One `pub Name { ... }` system.
#[derive(Clone, Debug)]
pub struct System {
    /// Text of the `///` doc comments before the name, one entry a line,
    /// without the leading `///` (a leading space is kept as written).
    pub docs: Vec<String>,
    /// `true` when the system is written `pub Name { ... }`.
    pub public: bool,
    /// The system's name, which becomes the generated struct's name.
    pub name: Ident,
    /// The statements, in source order.
    pub statements: Vec<Statement>,
}

/// A statement: everything up to and including its `;`.
#[derive(Clone, Debug)]
pub enum Statement {
    /// `parameters a, b, ...;`
    Parameters(Vec<Ident>),
    /// `coordinates q1, q2, ...;`
    Coordinates(Vec<Ident>),
    /// `inputs u1, ...;`
    Inputs(Vec<Ident>),
    /// `frame B = <expr>;` (the model accepts `F.rotate_x(angle)` and kin).
    Frame {
        /// The new frame's name.
        name: Ident,
        /// Where it is, e.g. `N.rotate_z(theta1)`.
        value: Expr,
    },
    /// `point P = <expr>;`
    Point {
        /// The new point's name.
        name: Ident,
        /// Where it is, e.g. `O - L * B1.y`.
        value: Expr,
    },
    /// `body NAME { field: value, ... };`
    Body {
        /// The body's name.
        name: Ident,
        /// The fields in braces, in source order (unchecked).
        fields: Vec<Field>,
    },
    /// `particle NAME { field: value, ... };`
    Particle {
        /// The particle's name.
        name: Ident,
        /// The fields in braces, in source order (unchecked).
        fields: Vec<Field>,
    },
    /// `joint KIND NAME { field: value, ... };` where KIND is `revolute` or
    /// `prismatic` (checked by the model, kept here as written).
    Joint {
        /// The joint's kind as written (`revolute`, `prismatic`, ...).
        kind: Ident,
        /// The joint's name.
        name: Ident,
        /// The fields in braces, in source order (unchecked).
        fields: Vec<Field>,
    },
    /// `gravity <vec>;`
    Gravity {
        /// The field's acceleration vector.
        value: Expr,
    },
    /// `force <vec> at P;`
    Force {
        /// The force vector.
        value: Expr,
        /// The point of application, after `at`.
        at: Expr,
    },
    /// `torque <vec> on F;` or `torque <vec> on F reacting G;`
    Torque {
        /// The torque vector.
        value: Expr,
        /// The frame it acts on, after `on`.
        on: Expr,
        /// The frame that takes `-value`, after `reacting`, if any.
        reacting: Option<Expr>,
    },
    /// `potential <scalar>;`
    Potential {
        /// The potential `V(q)`.
        value: Expr,
    },
    /// `dissipation <scalar>;`
    Dissipation {
        /// The Rayleigh dissipation function `D(q, q̇)`.
        value: Expr,
    },
    /// `armature <scalar> on <speed>;`
    Armature {
        /// The inertia added to `M`'s diagonal entry of the speed.
        value: Expr,
        /// The speed, after `on`: `dt(q)` or a joint's speed.
        speed: Expr,
    },
    /// `constraint lhs == rhs;`
    Constraint {
        /// The `constraint` token.
        keyword: Ident,
        /// The left-hand side.
        lhs: Expr,
        /// The right-hand side.
        rhs: Expr,
    },
    /// `closure NAME { at: P, to: Q, ... };`: closes a loop by joining two
    /// points (and, with `axis`/`along` or `frame`/`welded`, two frames).
    Closure {
        /// The closure's name.
        name: Ident,
        /// The fields in braces, in source order (unchecked).
        fields: Vec<Field>,
    },
    /// `rolling NAME { wheel: F, axle: F.y, center: P, radius: r, plane: N.z };`:
    /// a wheel rolling without slipping on a fixed plane (optional fields
    /// `tire` and `through`).
    Rolling {
        /// The contact's name.
        name: Ident,
        /// The fields in braces, in source order (unchecked).
        fields: Vec<Field>,
    },
    /// `outputs inverse_dynamics, position(P), rotation(B in F), ...;`
    Outputs(Vec<OutputRequest>),
    /// `speeds w1, w2 { q1: rate1, q2: rate2 };`: speeds of the user's own
    /// with the kinematic differential equations `dt(qᵢ) = rateᵢ`.
    Speeds {
        /// The `speeds` token.
        keyword: Ident,
        /// The new speeds, in order.
        names: Vec<Ident>,
        /// `coordinate: rate` for each coordinate whose speeds they replace.
        rates: Vec<Field>,
    },
}

/// One item of an `outputs` statement: `name`, `name(P)`, `name(P in F)` or
/// `name(a, b)`
/// (unchecked: the model knows which names and arguments exist).
#[derive(Clone, Debug)]
pub struct OutputRequest {
    /// The output's name (`inverse_dynamics`, `position`, ...).
    pub name: Ident,
    /// The point or frame in parentheses, if any (or the first of
    /// `linearize`'s independent coordinates).
    pub of: Option<Ident>,
    /// Further names after commas: `linearize(theta, phi)`'s other
    /// independent coordinates.
    pub more: Vec<Ident>,
    /// The names after `;`: `linearize(x, y, theta; dt(x), w)`'s
    /// independent speeds.
    pub speeds: Vec<SpeedName>,
    /// The frame after `in`, whose axes the output is expressed in.
    pub axes: Option<Ident>,
}

/// A speed as `linearize(..; ..)` names it: `dt(q)`, the rate of a
/// coordinate, or the name of a speed of its own.
#[derive(Clone, Debug)]
pub struct SpeedName {
    /// The coordinate in `dt(..)`, or the speed's name.
    pub name: Ident,
    /// Whether it was written `dt(name)`.
    pub rate: bool,
}

/// `name: value` inside the braces of `body`, `particle` and `joint`.
#[derive(Clone, Debug)]
pub struct Field {
    /// The field's name (`mass`, `center`, ...), unchecked.
    pub name: Ident,
    /// The field's value.
    pub value: Expr,
}

/// Binary operators, in the order of their precedence groups.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BinOp {
    /// `+`
    Add,
    /// `-`
    Sub,
    /// `*`
    Mul,
    /// `/`
    Div,
    /// `^`: binds tighter than `*` and unary `-`, right-associative.
    Pow,
}

/// An expression as written. Every variant can report a span.
#[derive(Clone, Debug)]
pub enum Expr {
    /// A numeric literal; `text` is the literal as written (`1.3`, `2`,
    /// `1e-3`), so the model can read it as an exact decimal.
    Number {
        /// The literal's text as written.
        text: String,
        /// The literal's span.
        span: Span,
    },
    /// A bare name: parameter, coordinate, input, `t`, frame, point, ...
    Name(Ident),
    /// `base.member`, e.g. `B1.y`.
    Member {
        /// The name before the `.`.
        base: Ident,
        /// The name after the `.`.
        member: Ident,
    },
    /// `f(args)`, e.g. `sin(theta1)`, `dt(q1)`.
    Call {
        /// The function's name.
        func: Ident,
        /// The arguments, in order.
        args: Vec<Expr>,
        /// The parentheses and everything between them.
        parens: Span,
    },
    /// `receiver.method(args)`, e.g. `N.rotate_z(theta1)`.
    MethodCall {
        /// The name before the `.`.
        receiver: Ident,
        /// The method's name.
        method: Ident,
        /// The arguments, in order.
        args: Vec<Expr>,
        /// The parentheses and everything between them.
        parens: Span,
    },
    /// `[a, b, c]` (inertia lists).
    Array {
        /// The items, in order.
        items: Vec<Expr>,
        /// The brackets and everything between them.
        span: Span,
    },
    /// `-operand` (`op` is the span of `-`).
    Neg {
        /// The span of `-`.
        op: Span,
        /// The negated expression.
        operand: Box<Expr>,
    },
    /// `lhs op rhs` (`op_span` is the span of the operator token).
    Binary {
        /// The operator.
        op: BinOp,
        /// The span of the operator token.
        op_span: Span,
        /// The left operand.
        lhs: Box<Expr>,
        /// The right operand.
        rhs: Box<Expr>,
    },
    /// `( inner )`, kept so that spans cover the parentheses.
    Paren {
        /// The expression inside.
        inner: Box<Expr>,
        /// The parentheses and everything between them.
        span: Span,
    },
}

impl Expr {
    /// The first and last token of the expression, for diagnostics that
    /// underline all of it (see [`SpanRange`]).
    pub fn range(&self) -> SpanRange {
        match self {
            Expr::Number { span, .. } | Expr::Array { span, .. } | Expr::Paren { span, .. } => {
                SpanRange::from(*span)
            }
            Expr::Name(ident) => SpanRange::from(ident.span()),
            Expr::Member { base, member } => SpanRange::new(base.span(), member.span()),
            Expr::Call { func, parens, .. } => SpanRange::new(func.span(), *parens),
            Expr::MethodCall {
                receiver, parens, ..
            } => SpanRange::new(receiver.span(), *parens),
            Expr::Neg { op, operand } => SpanRange::new(*op, operand.range().end),
            Expr::Binary { lhs, rhs, .. } => SpanRange::new(lhs.range().start, rhs.range().end),
        }
    }
}

/// Where a diagnostic points: from the span of a first token to that of a
/// last one. In a procedural macro on stable Rust spans cannot be joined,
/// but an error carrying both ends is shown over the whole range (as
/// `syn::Error::new_spanned` does), so `m * B.x` is underlined whole rather
/// than at `m`.
#[derive(Clone, Copy, Debug)]
pub struct SpanRange {
    /// The first token's span.
    pub start: Span,
    /// The last token's span.
    pub end: Span,
}

impl SpanRange {
    /// The range from `start` to `end`.
    pub fn new(start: Span, end: Span) -> SpanRange {
        SpanRange { start, end }
    }

    /// An error with `message` over the whole range.
    pub fn error(self, message: impl Display) -> syn::Error {
        let ends: TokenStream = [self.start, self.end]
            .into_iter()
            .map(|span| {
                let mut marker = Punct::new('*', Spacing::Alone);
                marker.set_span(span);
                TokenTree::Punct(marker)
            })
            .collect();
        syn::Error::new_spanned(ends, message)
    }
}

impl From<Span> for SpanRange {
    fn from(span: Span) -> SpanRange {
        SpanRange::new(span, span)
    }
}

/// `a.join(b)`, or `a` where spans cannot be joined (outside a proc macro
/// on stable Rust they always can in proc-macro2's fallback).
pub fn join(a: Span, b: Span) -> Span {
    a.join(b).unwrap_or(a)
}
