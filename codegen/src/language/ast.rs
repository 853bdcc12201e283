//! The syntax tree of the system-description language, exactly as written,
//! with the span of every token a diagnostic may point at.
//!
//! Nothing here is resolved or typed: `B1.y` is a [`Expr::Member`] whether
//! `B1` names a frame or not, and `P1 - L * B1.y` is a binary expression
//! whatever `P1` is. The model layer gives names their meaning.

use proc_macro2::{Ident, Span};

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
    Frame { name: Ident, value: Expr },
    /// `point P = <expr>;`
    Point { name: Ident, value: Expr },
    /// `body NAME { field: value, ... };`
    Body { name: Ident, fields: Vec<Field> },
    /// `particle NAME { field: value, ... };`
    Particle { name: Ident, fields: Vec<Field> },
    /// `joint KIND NAME { field: value, ... };` where KIND is `revolute` or
    /// `prismatic` (checked by the model, kept here as written).
    Joint { kind: Ident, name: Ident, fields: Vec<Field> },
    /// `gravity <vec>;` (`keyword` is the `gravity` token, for diagnostics).
    Gravity { keyword: Ident, value: Expr },
    /// `force <vec> at P;`
    Force { keyword: Ident, value: Expr, at: Expr },
    /// `torque <vec> on F;` or `torque <vec> on F reacting G;`
    Torque { keyword: Ident, value: Expr, on: Expr, reacting: Option<Expr> },
    /// `potential <scalar>;`
    Potential { keyword: Ident, value: Expr },
    /// `dissipation <scalar>;`
    Dissipation { keyword: Ident, value: Expr },
    /// `constraint lhs == rhs;` (`eq` is the span of `==`).
    Constraint { keyword: Ident, lhs: Expr, eq: Span, rhs: Expr },
}

/// `name: value` inside the braces of `body`, `particle` and `joint`.
#[derive(Clone, Debug)]
pub struct Field {
    pub name: Ident,
    pub value: Expr,
}

/// Binary operators, in the order of their precedence groups.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BinOp {
    Add,
    Sub,
    Mul,
    Div,
    /// `^`: binds tighter than `*` and unary `-`, right-associative.
    Pow,
}

/// An expression as written. Every variant can report a span.
#[derive(Clone, Debug)]
pub enum Expr {
    /// A numeric literal; `text` is the literal as written (`1.3`, `2`,
    /// `1e-3`), so the model can read it as an exact decimal.
    Number { text: String, span: Span },
    /// A bare name: parameter, coordinate, input, `t`, frame, point, ...
    Name(Ident),
    /// `base.member`, e.g. `B1.y`.
    Member { base: Ident, member: Ident },
    /// `f(args)`, e.g. `sin(theta1)`, `dt(q1)`.
    Call { func: Ident, args: Vec<Expr>, span: Span },
    /// `receiver.method(args)`, e.g. `N.rotate_z(theta1)`.
    MethodCall { receiver: Ident, method: Ident, args: Vec<Expr>, span: Span },
    /// `[a, b, c]` (inertia lists).
    Array { items: Vec<Expr>, span: Span },
    /// `-operand` (`op` is the span of `-`).
    Neg { op: Span, operand: Box<Expr> },
    /// `lhs op rhs` (`op_span` is the span of the operator token).
    Binary { op: BinOp, op_span: Span, lhs: Box<Expr>, rhs: Box<Expr> },
    /// `( inner )`, kept so that spans cover the parentheses.
    Paren { inner: Box<Expr>, span: Span },
}

impl Expr {
    /// The span a diagnostic about this whole expression should point at:
    /// the first token's span joined to the last where the compiler allows
    /// it, else the first token's span.
    pub fn span(&self) -> Span {
        match self {
            Expr::Number { span, .. }
            | Expr::Call { span, .. }
            | Expr::MethodCall { span, .. }
            | Expr::Array { span, .. }
            | Expr::Paren { span, .. } => *span,
            Expr::Name(ident) => ident.span(),
            Expr::Member { base, member } => join(base.span(), member.span()),
            Expr::Neg { op, operand } => join(*op, operand.span()),
            Expr::Binary { lhs, rhs, .. } => join(lhs.span(), rhs.span()),
        }
    }
}

/// `a.join(b)`, or `a` where spans cannot be joined (outside a proc macro
/// on stable Rust they always can in proc-macro2's fallback).
pub fn join(a: Span, b: Span) -> Span {
    a.join(b).unwrap_or(a)
}
