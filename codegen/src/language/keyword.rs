//! Every word the language gives a meaning to, in one place.
//!
//! None of them is reserved: a statement is recognised by its first
//! identifier, and `at`, `on` and `reacting` only end the expression before
//! them because an identifier cannot continue an expression.
//!
//! The statement keywords are `&str` constants, so that the parser can
//! `match` on a statement's first word; every other word is a [`Symbol`]
//! (serde_derive's pattern), compared with an identifier by `==`, so that
//! no layer spells a word of the language as a string literal.

use proc_macro2::Ident;
use std::fmt;

/// A word of the language beyond the statement keywords: a field's name,
/// a joint's kind, a frame's method, `dt`, a separator such as `at`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Symbol(&'static str);

impl Symbol {
    /// The word as written.
    pub const fn as_str(self) -> &'static str {
        self.0
    }
}

impl PartialEq<Symbol> for Ident {
    fn eq(&self, word: &Symbol) -> bool {
        self == word.0
    }
}

impl PartialEq<Symbol> for &Ident {
    fn eq(&self, word: &Symbol) -> bool {
        *self == word.0
    }
}

impl fmt::Display for Symbol {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.0)
    }
}

/// `parameters a, b, ...;`
pub const PARAMETERS: &str = "parameters";
/// `coordinates q1, q2, ...;`
pub const COORDINATES: &str = "coordinates";
/// `inputs u1, ...;`
pub const INPUTS: &str = "inputs";
/// `frame B = <expr>;`
pub const FRAME: &str = "frame";
/// `point P = <expr>;`
pub const POINT: &str = "point";
/// `body NAME { field: value, ... };`
pub const BODY: &str = "body";
/// `particle NAME { field: value, ... };`
pub const PARTICLE: &str = "particle";
/// `joint KIND NAME { field: value, ... };`
pub const JOINT: &str = "joint";
/// `gravity <vec>;`
pub const GRAVITY: &str = "gravity";
/// `force <vec> at P;`
pub const FORCE: &str = "force";
/// `torque <vec> on F;` or `torque <vec> on F reacting G;`
pub const TORQUE: &str = "torque";
/// `potential <scalar>;`
pub const POTENTIAL: &str = "potential";
/// `dissipation <scalar>;`
pub const DISSIPATION: &str = "dissipation";
/// `armature <scalar> on <speed>;`
pub const ARMATURE: &str = "armature";
/// `constraint lhs == rhs;`
pub const CONSTRAINT: &str = "constraint";
/// `closure NAME { at: P, to: Q, ... };`
pub const CLOSURE: &str = "closure";
/// `rolling NAME { wheel: F, axle: F.y, center: P, radius: r, plane: N.z };`
pub const ROLLING: &str = "rolling";
/// `outputs inverse_dynamics, position(P), ...;`
pub const OUTPUTS: &str = "outputs";
/// `speeds w1, w2 { q1: rate, q2: rate };`
pub const SPEEDS: &str = "speeds";

/// The statement keywords, in the order the "expected one of" message
/// lists them.
pub const STATEMENTS: [&str; 19] = [
    PARAMETERS,
    COORDINATES,
    INPUTS,
    FRAME,
    POINT,
    BODY,
    PARTICLE,
    JOINT,
    GRAVITY,
    FORCE,
    TORQUE,
    POTENTIAL,
    DISSIPATION,
    CONSTRAINT,
    CLOSURE,
    ROLLING,
    OUTPUTS,
    SPEEDS,
    ARMATURE,
];

/// `force <vec> at P;`: the point of application (and the field `at` of
/// particles, joints and closures, see [`field::AT`]).
pub const AT: Symbol = Symbol("at");
/// `torque <vec> on F;`: the frame the torque acts on.
pub const ON: Symbol = Symbol("on");
/// `torque <vec> on F reacting G;`: the frame that takes the reaction.
pub const REACTING: Symbol = Symbol("reacting");
/// `outputs position(P in F);`: the frame whose axes the output is in.
pub const IN: Symbol = Symbol("in");

/// `pub Name { ... }`: the generated struct is public.
pub const PUB: Symbol = Symbol("pub");
/// `#[doc = "..."]`, the form a `///` comment takes in a token stream.
pub const DOC: Symbol = Symbol("doc");

/// `dt(q)`: the rate of a coordinate (a speed).
pub const DT: Symbol = Symbol("dt");

/// `F.rotate_x(angle)`, `F.rotate_y(angle)`, `F.rotate_z(angle)`: the
/// rotations of a frame about its parent's axes, by axis.
pub const ROTATIONS: [Symbol; 3] = [Symbol("rotate_x"), Symbol("rotate_y"), Symbol("rotate_z")];
/// `F.rotate([ax, ay, az], angle)`: a rotation about a constant axis.
pub const ROTATE: Symbol = Symbol("rotate");

/// The kinds of `joint KIND NAME { .. }`.
pub mod joint {
    use super::Symbol;

    /// A child turned about an axis by a coordinate.
    pub const REVOLUTE: Symbol = Symbol("revolute");
    /// A child slid along an axis by a coordinate.
    pub const PRISMATIC: Symbol = Symbol("prismatic");
    /// A child turned by a unit quaternion.
    pub const SPHERICAL: Symbol = Symbol("spherical");
    /// A child turned by a unit quaternion and moved freely.
    pub const FREE: Symbol = Symbol("free");
}

/// The field names of the `{ field: value }` blocks.
pub mod field {
    use super::Symbol;

    /// A body's, particle's or armature's mass.
    pub const MASS: Symbol = Symbol("mass");
    /// A body's centre of mass, a rolling wheel's centre.
    pub const CENTER: Symbol = Symbol("center");
    /// A body's frame, a welded closure's first frame.
    pub const FRAME: Symbol = Symbol("frame");
    /// A body's central inertia.
    pub const INERTIA: Symbol = Symbol("inertia");
    /// Where a particle is, a joint's or closure's point.
    pub const AT: Symbol = Symbol("at");
    /// A joint's parent frame.
    pub const PARENT: Symbol = Symbol("parent");
    /// A joint's new child frame.
    pub const CHILD: Symbol = Symbol("child");
    /// A joint's axis, a revolute closure's first axis.
    pub const AXIS: Symbol = Symbol("axis");
    /// A revolute or prismatic joint's coordinate.
    pub const COORDINATE: Symbol = Symbol("coordinate");
    /// A closure's second point.
    pub const TO: Symbol = Symbol("to");
    /// A revolute closure's second axis.
    pub const ALONG: Symbol = Symbol("along");
    /// A welded closure's second frame.
    pub const WELDED: Symbol = Symbol("welded");
    /// A rolling contact's wheel frame.
    pub const WHEEL: Symbol = Symbol("wheel");
    /// A rolling contact's axle.
    pub const AXLE: Symbol = Symbol("axle");
    /// A rolling contact's wheel radius.
    pub const RADIUS: Symbol = Symbol("radius");
    /// A rolling contact's plane normal.
    pub const PLANE: Symbol = Symbol("plane");
    /// A rolling contact's tire radius.
    pub const TIRE: Symbol = Symbol("tire");
    /// A point of a rolling contact's plane.
    pub const THROUGH: Symbol = Symbol("through");
}

/// The statement keywords as the "expected one of" message lists them:
/// "`parameters`, `coordinates`, ..., `constraint`".
pub fn statement_list() -> String {
    STATEMENTS
        .iter()
        .map(|keyword| format!("`{keyword}`"))
        .collect::<Vec<_>>()
        .join(", ")
}
