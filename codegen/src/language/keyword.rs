//! Every word the parser gives a meaning to, in one place.
//!
//! None of them is reserved: a statement is recognised by its first
//! identifier, and `at`, `on` and `reacting` only end the expression before
//! them because an identifier cannot continue an expression.

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

/// `force <vec> at P;`: the point of application.
pub const AT: &str = "at";
/// `torque <vec> on F;`: the frame the torque acts on.
pub const ON: &str = "on";
/// `torque <vec> on F reacting G;`: the frame that takes the reaction.
pub const REACTING: &str = "reacting";
/// `outputs position(P in F);`: the frame whose axes the output is in.
pub const IN: &str = "in";

/// `pub Name { ... }`: the generated struct is public.
pub const PUB: &str = "pub";
/// `#[doc = "..."]`, the form a `///` comment takes in a token stream.
pub const DOC: &str = "doc";

/// The statement keywords as the "expected one of" message lists them:
/// "`parameters`, `coordinates`, ..., `constraint`".
pub fn statement_list() -> String {
    STATEMENTS
        .iter()
        .map(|keyword| format!("`{keyword}`"))
        .collect::<Vec<_>>()
        .join(", ")
}
