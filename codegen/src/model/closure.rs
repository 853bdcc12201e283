//! Loop closures: the holonomic rows that join two points, and for a
//! revolute or welded closure two frames, of a kinematic tree.
//!
//! A closure adds no body and no coordinate: it is the set of ordinary
//! constraint rows that state "these two points coincide" (spherical),
//! "... and these two axes are parallel" (revolute) or "... and these two
//! frames are aligned" (welded). Rows that vanish identically are dropped,
//! so a closure in a planar model gives the rows of a planar joint (two
//! for a point, one more for a weld) and no 3-D work. Rows that stay but
//! depend on the others (an overconstrained loop such as Bricard's) are
//! kept: the runtime's rank-revealing solver finds the rank of `A` at every
//! step and gives the least-norm multipliers.

use super::{FrameId, Model, PointId, Vector};
use crate::expr::{ExprId, Pool};
use crate::kinematics::{Kinematics, Vec3};

/// A unit vector of a frame: the frame and the axis (0, 1, 2 for x, y, z).
pub type FrameAxis = (FrameId, usize);

/// What a closure joins besides its two points.
#[derive(Clone, Copy, Debug)]
pub enum ClosureKind {
    /// The points only (a ball joint): three rows, `r_at − r_to` in `N`'s
    /// axes.
    Spherical,
    /// The points, and `axis` kept parallel to `along` (a hinge): two more
    /// rows, the components of `axis` along the two unit vectors of
    /// `along`'s frame that are perpendicular to `along`.
    Revolute {
        /// The hinge axis on one side.
        axis: FrameAxis,
        /// The hinge axis on the other side.
        along: FrameAxis,
    },
    /// The points, and the two frames aligned (a weld): three more rows,
    /// `F.y · G.z`, `F.z · G.x` and `F.x · G.y`, the small rotations of `G`
    /// from `F` about x, y and z.
    Welded {
        /// The frame on one side.
        frame: FrameId,
        /// The frame welded to it.
        welded: FrameId,
    },
}

/// One row of a closure before the zero rows are dropped: its residual and
/// what it measures (for diagnostics).
pub struct ClosureRow {
    /// The residual, zero when the loop is closed.
    pub residual: ExprId,
    /// What the row measures, e.g. "the y-component of `at − to`".
    pub what: String,
}

/// The rows of a closure joining `at` to `to` in `model` (whose frames and
/// points so far are all it reads), in the order: the point rows (x, y, z
/// in `N`'s axes), then the frame rows.
pub fn closure_rows(
    model: &Model,
    pool: &mut Pool,
    at: PointId,
    to: PointId,
    kind: ClosureKind,
) -> Vec<ClosureRow> {
    let kinematics = Kinematics::new(model, pool);
    let (r_at, r_to) = (kinematics.position(at), kinematics.position(to));
    let mut rows: Vec<ClosureRow> = (0..3)
        .map(|i| ClosureRow {
            residual: pool.sub(r_at[i], r_to[i]),
            what: format!("the {}-component of `at − to`", AXIS_NAMES[i]),
        })
        .collect();
    match kind {
        ClosureKind::Spherical => {}
        ClosureKind::Revolute { axis, along } => {
            let components = components_in(&kinematics, model, pool, axis, along.0);
            for i in (0..3).filter(|&i| i != along.1) {
                rows.push(ClosureRow {
                    residual: components[i],
                    what: format!(
                        "the component of `axis` along `{}` of `along`'s frame",
                        AXIS_NAMES[i]
                    ),
                });
            }
        }
        ClosureKind::Welded { frame, welded } => {
            for (i, j) in [(1, 2), (2, 0), (0, 1)] {
                let components = components_in(&kinematics, model, pool, (frame, i), welded);
                rows.push(ClosureRow {
                    residual: components[j],
                    what: format!("`frame`.{} · `welded`.{}", AXIS_NAMES[i], AXIS_NAMES[j]),
                });
            }
        }
    }
    rows
}

const AXIS_NAMES: [&str; 3] = ["x", "y", "z"];

/// The components of a frame's unit vector in `frame`'s axes (through
/// their common ancestor, so a planar pair meets no 3-D rotation).
fn components_in(
    kinematics: &Kinematics,
    model: &Model,
    pool: &mut Pool,
    (from, axis): FrameAxis,
    frame: FrameId,
) -> Vec3 {
    let unit = Vector::unit(pool, from, axis);
    kinematics.express(pool, model, &unit, frame)
}

#[cfg(test)]
mod tests;
