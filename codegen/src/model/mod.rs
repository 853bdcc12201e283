//! The model layer: a syntax tree resolved into a checked mechanical model.
//!
//! Names are bound to parameters, coordinates, inputs, frames and points;
//! every scalar is an expression of the engine's [`Pool`], which
//! [`resolve`] returns beside the model (the model holds ids into it, not
//! the pool); every rule of the
//! language (types, what may depend on what, required fields) is checked
//! here, once, and all violations are reported together, each at the user's
//! token. What only the derived equations tell (a speed that moves no
//! mass, a regressor the model does not have) is checked in one later
//! phase, `crate::checks`, after the derivation; the other later layers
//! trust the model and report nothing about the text, but for the size
//! guard (`crate::size`), which refuses a model too large for rustc.

mod algebra;
mod closure;
mod errors;
mod output;
pub mod quaternion;
mod resolve;
mod rolling;
mod singular;
mod tree;
mod vector;

pub use errors::Errors;
pub use output::{Chart, KINDS, Output, OutputKind, Subject, kind as output_kind};
pub use resolve::resolve;
pub(crate) use resolve::{builtin_names, is_builtin, is_plain};
pub use singular::RateDivisor;
pub use tree::{JointKind, Tree};
pub use vector::{FrameId, NEWTONIAN, Vector};

use crate::expr::{ExprId, Pool};
use proc_macro2::Ident;

/// Index of a point in [`Model::points`]; `PointId(0)` is `O`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct PointId(pub usize);

/// The point `O`, fixed in `N`.
pub const ORIGIN: PointId = PointId(0);

/// A checked system, ready for kinematics.
pub struct Model {
    /// Doc comment lines written before the system's name.
    pub docs: Vec<String>,
    /// Whether the system was declared `pub`.
    pub public: bool,
    /// The system's (and generated struct's) name.
    pub name: Ident,
    /// Parameters in declaration order: `Sym::Param(i)` is `parameters[i]`.
    pub parameters: Vec<Ident>,
    /// Coordinates in declaration order: `Sym::Coord(i)` is `coordinates[i]`.
    pub coordinates: Vec<Ident>,
    /// Speeds in declaration order: `Sym::Speed(k)` is `speeds[k]`. A
    /// coordinate's rate `q̇ᵢ` is `pool.rate(i)`, linear in the speeds; it is
    /// `Sym::Speed(i)` unless a joint or statement says otherwise.
    pub speeds: Vec<Speed>,
    /// The quaternion (free and spherical) joints, in declaration order.
    pub balls: Vec<Ball>,
    /// The divisors of the rates of `speeds` statements that depend on the
    /// coordinates: where one vanishes, `q̇ = N(q) v` is undefined.
    pub rate_divisors: Vec<RateDivisor>,
    /// Inputs in declaration order: `Sym::Input(i)` is `inputs[i]`.
    pub inputs: Vec<Ident>,
    /// Frames; `frames[0]` is `N`.
    pub frames: Vec<Frame>,
    /// Points; `points[0]` is `O`.
    pub points: Vec<Point>,
    /// Rigid bodies, in declaration order.
    pub bodies: Vec<Body>,
    /// Point masses, in declaration order.
    pub particles: Vec<Particle>,
    /// The uniform gravity field (sum of all `gravity` statements), if any.
    pub gravity: Option<Vector>,
    /// Applied forces.
    pub forces: Vec<Force>,
    /// Applied torques.
    pub torques: Vec<Torque>,
    /// Sum of the `potential` statements (zero if none).
    pub potential: ExprId,
    /// Sum of the `dissipation` statements (zero if none).
    pub dissipation: ExprId,
    /// Inertias added to `M`'s diagonal (`armature a on v;`): the speed's
    /// index and `a` (parameters only), in declaration order; a speed may
    /// appear more than once (the entries add up).
    pub armature: Vec<(usize, ExprId)>,
    /// Constraints, in declaration order.
    pub constraints: Vec<Constraint>,
    /// The kinematic tree, if the model is one (see [`Tree`]): decided
    /// once, here, for every spelling.
    pub tree: Option<Tree>,
    /// The outputs asked for beyond `M`, `f`, the energies and the
    /// constraints, in the order written.
    pub outputs: Vec<Output>,
    /// The names the statements bound to frames, points, bodies and
    /// particles: the resolver's name table, kept for the stages that
    /// speak of the model's parts by name.
    pub names: Names,
}

/// The names of a model's parts, each in the order its statements define
/// them.
#[derive(Default)]
pub struct Names {
    /// The frames of `frame` statements and the children of joints, with
    /// their ids (`N` not included).
    pub frames: Vec<(Ident, FrameId)>,
    /// The points of `point` statements and of joints, with their ids (`O`
    /// not included; the anonymous points of expressions such as
    /// `force F at P + r` neither).
    pub points: Vec<(Ident, PointId)>,
    /// The bodies, as [`Model::bodies`].
    pub bodies: Vec<Ident>,
    /// The particles, as [`Model::particles`].
    pub particles: Vec<Ident>,
}

/// A speed: a coordinate's rate `dt(q)`, or a speed of its own (a
/// quaternion joint's angular velocity components, say).
pub struct Speed {
    /// The coordinate whose rate it is, or the speed's own name.
    pub name: Ident,
    /// Whether it is `dt(name)` of the coordinate `name`.
    pub rate_of_coordinate: bool,
}

impl Speed {
    /// The name as the language writes it: `dt(q)`, or the speed's name.
    pub fn written(&self) -> String {
        if self.rate_of_coordinate {
            format!("dt({})", self.name)
        } else {
            self.name.to_string()
        }
    }
}

/// A joint whose child turns by a unit quaternion: spherical (three
/// angular speeds) or, with a translation, free (six speeds).
#[derive(Clone, Debug)]
pub struct Ball {
    /// The child frame.
    pub frame: FrameId,
    /// The child's origin.
    pub origin: PointId,
    /// Coordinate indices of the quaternion `(qx, qy, qz, qw)`.
    pub quaternion: [usize; 4],
    /// Speed indices of the angular velocity `(wx, wy, wz)` in the child's
    /// axes.
    pub angular: [usize; 3],
    /// A free joint's position `(x, y, z)` in the parent's axes (coordinate
    /// indices) and velocity `(vx, vy, vz)` in the child's (speed indices).
    pub translation: Option<([usize; 3], [usize; 3])>,
}

/// A reference frame: `N`, or a rotation of a parent frame.
pub struct Frame {
    /// The parent and the rotation about one of the parent's axes; `None`
    /// for `N`.
    pub placement: Option<FramePlacement>,
}

/// How a frame sits in its parent.
pub struct FramePlacement {
    /// The frame it is rotated from.
    pub parent: FrameId,
    /// The rotation axis: a constant unit vector, by its components in the
    /// parent's axes (which are also its components in the frame's own).
    pub axis: [ExprId; 3],
    /// The rotation angle (right-handed); zero for a parallel frame.
    pub angle: ExprId,
    /// `Some(i)` when the frame turns by the quaternion of
    /// [`Model::balls`]`[i]` instead (then `axis` and `angle` are unused:
    /// `x` and `0`).
    pub ball: Option<usize>,
}

/// `Some(i)` if `axis` is exactly the `i`-th unit vector.
pub fn principal_axis(pool: &Pool, axis: &[ExprId; 3]) -> Option<usize> {
    let i = axis.iter().position(|&c| c == pool.one())?;
    axis.iter()
        .enumerate()
        .all(|(j, &c)| j == i || pool.is_zero(c))
        .then_some(i)
}

/// The `i`-th unit vector (`x`, `y`, `z` for 0, 1, 2).
pub fn unit_axis(pool: &Pool, i: usize) -> [ExprId; 3] {
    let mut axis = [pool.zero(); 3];
    axis[i] = pool.one();
    axis
}

/// A point: `O`, or a point located from another by a vector.
pub struct Point {
    /// The base point and the offset from it; `None` for `O`.
    pub placement: Option<(PointId, Vector)>,
}

/// A rigid body.
pub struct Body {
    /// Its mass (parameters only).
    pub mass: ExprId,
    /// Its centre of mass.
    pub center: PointId,
    /// The frame it is fixed in, whose axes the inertia is given in.
    pub frame: FrameId,
    /// Central inertia tensor in the body frame's axes (symmetric).
    pub inertia: [[ExprId; 3]; 3],
}

/// A point mass.
pub struct Particle {
    /// Its mass (parameters only).
    pub mass: ExprId,
    /// Where it is.
    pub at: PointId,
}

/// `force vec at P`.
pub struct Force {
    /// The force.
    pub vector: Vector,
    /// Its point of application.
    pub at: PointId,
}

/// `torque vec on F` or `torque vec on F reacting G`.
pub struct Torque {
    /// The torque acting on `on`.
    pub vector: Vector,
    /// The frame the torque acts on.
    pub on: FrameId,
    /// The frame that receives the opposite torque, if any.
    pub reacting: Option<FrameId>,
}

/// `constraint lhs == rhs`, as `lhs − rhs = 0`.
pub struct Constraint {
    /// `lhs − rhs`.
    pub residual: ExprId,
    /// Whether it involves speeds (then linear in them).
    pub nonholonomic: bool,
    /// Whether the row vanishes identically (a `rolling` row of a wheel
    /// that cannot leave its plane): kept so that the rows stay where the
    /// contract puts them, with its Jacobian, bias and residual zero, and
    /// treated as absent wherever rows are counted or solved.
    pub vanishes: bool,
}

impl Model {
    /// The rows that do not vanish identically: those that constrain.
    pub fn acting_constraints(&self) -> impl Iterator<Item = &Constraint> {
        self.constraints.iter().filter(|c| !c.vanishes)
    }

    /// Whether each row vanishes identically, if one does.
    pub fn vanishing_rows(&self) -> Option<Vec<bool>> {
        let rows: Vec<bool> = self.constraints.iter().map(|c| c.vanishes).collect();
        rows.contains(&true).then_some(rows)
    }

    /// Number of generalized coordinates.
    pub fn nq(&self) -> usize {
        self.coordinates.len()
    }

    /// Number of speeds.
    pub fn nv(&self) -> usize {
        self.speeds.len()
    }
}

#[cfg(test)]
mod tests;
