//! The accelerations of a kinematic tree by the articulated-body recursion
//! (Featherstone's ABA), on the same DAG as `M` and `f`: `O(n)` operations
//! where factorising a chain's dense `M` takes `O(n³)`.
//!
//! It reuses the forcing `f` (every velocity, gravity and applied-load term
//! at `q̈ = 0`, from the Newton–Euler sweeps) and adds what `M q̈` needs. With
//! `δₖ` the part of link `k`'s spatial acceleration due to `q̈` (zero at the
//! root), the wrench that link `k`'s subtree needs beyond its `q̈ = 0` share
//! is `Iᴬₖ δₖ + Δₖ`, where the articulated inertia `Iᴬₖ` and the bias `Δₖ`
//! come from the leaves inwards:
//!
//! ```text
//! Uₖ = Iᴬₖ Sₖ,   Dₖ = Sₖᵀ Uₖ,   uₖ = fₖ − Sₖᵀ Δₖ,
//! Iᴬₚ += Xₖᵀ (Iᴬₖ − Uₖ Uₖᵀ / Dₖ) Xₖ,   Δₚ += Xₖᵀ (Δₖ + Uₖ uₖ / Dₖ),
//! ```
//!
//! (`Sₖ` the joint's motion, `Xₖ` the motion transform from the parent `p`
//! to link `k`), then from the root outwards
//! `q̈ₖ = (uₖ − Uₖᵀ Xₖ δₚ) / Dₖ`, `δₖ = Xₖ δₚ + Sₖ q̈ₖ`. The pivots `Dₖ` are
//! those of the factorisation `M = Lᵀ D L` in tree order, so a singular `M`
//! shows as a vanishing `Dₖ`.
//!
//! Spatial vectors are pairs in the link's axes, about its origin: motions
//! `(ω, v)`, wrenches `(moment, resultant)`; an inertia is the symmetric
//! block matrix `[[A, B], [Bᵀ, C]]` mapping motions to wrenches (for a rigid
//! body `A` is the inertia about the origin, `B = [h×]` with `h` the first
//! moment and `C = m 1`).

use super::recursive::{Column, Composite, JointTree, Link};
use crate::expr::{ExprId, Pool};
use crate::kinematics::{Mat3, Vec3, add3, cross, dot, mat_vec, transpose, transpose_mul};

/// The tree's accelerations, per speed.
#[derive(Clone, Debug)]
pub struct Articulated {
    /// The forcing `f` the recursion starts from.
    pub forcing: Vec<ExprId>,
    /// The pivots `Dₖ = Sₖᵀ Iᴬₖ Sₖ`, positive where `M` is.
    pub pivots: Vec<ExprId>,
    /// `q̈`, which is `M⁻¹ f`.
    pub accelerations: Vec<ExprId>,
}

impl Articulated {
    /// `f`, the pivots and `q̈`, in this order: what the code computes.
    pub fn roots(&self) -> Vec<ExprId> {
        let outputs = [&self.forcing, &self.pivots, &self.accelerations];
        outputs.into_iter().flatten().copied().collect()
    }
}

/// The symmetric spatial inertia `[[A, B], [Bᵀ, C]]`.
#[derive(Clone, Copy)]
struct Spatial {
    a: Mat3,
    b: Mat3,
    c: Mat3,
}

/// A spatial vector: the angular and the linear half.
type Pair = (Vec3, Vec3);

/// What the outward sweep needs of one speed.
struct Pivot {
    /// `Uₖ = Iᴬₖ Sₖ`.
    u: Pair,
    /// `1 / Dₖ`.
    reciprocal: ExprId,
    /// `uₖ = fₖ − Sₖᵀ Δₖ`.
    force: ExprId,
}

/// `q̈` of `tree` with forcing `forcing` and the armature `armature` added
/// to each pivot (both indexed by speed); `None` if the tree's joints do
/// not hold every speed.
///
/// A joint of several speeds (spherical, free) is taken as that many
/// one-speed joints in series, fixed to each other with no offset and no
/// mass: their velocities add up to the joint's, so `M` and `f` are the
/// same and the recursion above applies speed by speed, with the identity
/// transform between the speeds of one joint (a block `L D Lᵀ` of the
/// joint's `Sᵀ Iᴬ S`, done column by column).
pub fn articulated(
    tree: &JointTree,
    forcing: &[ExprId],
    armature: &[ExprId],
    pool: &mut Pool,
) -> Option<Articulated> {
    let n = forcing.len();
    let speeds: usize = tree.links.iter().map(|l| l.columns.len()).sum();
    if speeds != n || n == 0 {
        return None;
    }
    let zero = pool.zero();
    let mut inertia: Vec<Spatial> = tree
        .link_inertias(pool)
        .iter()
        .map(|c| rigid(pool, c))
        .collect();
    let mut bias: Vec<Pair> = vec![([zero; 3], [zero; 3]); tree.links.len()];
    let mut pivots = vec![zero; n];
    let mut steps: Vec<Vec<Pivot>> = Vec::with_capacity(tree.links.len());
    for l in (0..tree.links.len()).rev() {
        let link = &tree.links[l];
        let mut i_a = inertia[l];
        let mut delta = bias[l];
        let mut link_steps = Vec::with_capacity(link.columns.len());
        for (k, column) in link.columns.iter().enumerate().rev() {
            let step = pivot_step(
                pool,
                column,
                (forcing[column.speed], armature[column.speed]),
                &i_a,
                &delta,
            );
            pivots[column.speed] = step.pivot;
            let inner = k > 0 || link.parent.is_some();
            if inner {
                (i_a, delta) = articulated_share(pool, &step.outward, &step.i_a, &step.delta);
            }
            link_steps.push(step.outward);
        }
        link_steps.reverse();
        steps.push(link_steps);
        if let Some(p) = link.parent {
            let (moved, wrench) = to_parent(pool, link, &i_a, &delta);
            inertia[p] = sum(pool, &inertia[p], &moved);
            bias[p] = (
                add3(pool, &bias[p].0, &wrench.0),
                add3(pool, &bias[p].1, &wrench.1),
            );
        }
    }
    steps.reverse();
    let mut motions: Vec<Pair> = Vec::with_capacity(tree.links.len());
    let mut accelerations = vec![zero; n];
    for (link, link_steps) in tree.links.iter().zip(&steps) {
        let mut motion = match link.parent {
            Some(p) => from_parent(pool, link, &motions[p]),
            None => ([zero; 3], [zero; 3]),
        };
        for (column, step) in link.columns.iter().zip(link_steps) {
            let (omega, v) = motion;
            let coupling = [dot(pool, &step.u.0, &omega), dot(pool, &step.u.1, &v)];
            let coupling = pool.sum(coupling);
            let free = pool.sub(step.force, coupling);
            let qdd = pool.mul(free, step.reciprocal);
            let qdd = pool.group(qdd);
            accelerations[column.speed] = qdd;
            let rate = scale3(pool, &column.axis, qdd);
            motion = match column.turns {
                true => (add3(pool, &omega, &rate), v),
                false => (omega, add3(pool, &v, &rate)),
            };
            motion = group_pair(pool, &motion);
        }
        motions.push(motion);
    }
    Some(Articulated {
        forcing: forcing.to_vec(),
        pivots,
        accelerations,
    })
}

/// One speed's step of the inward sweep, with the articulated inertia and
/// bias it started from (grouped).
struct Step {
    pivot: ExprId,
    outward: Pivot,
    i_a: Spatial,
    delta: Pair,
}

/// `Uₖ`, `Dₖ` and `uₖ` of one speed with articulated inertia `i_a` and
/// bias `delta` beyond it.
fn pivot_step(
    pool: &mut Pool,
    column: &Column,
    (force, armature): (ExprId, ExprId),
    i_a: &Spatial,
    delta: &Pair,
) -> Step {
    let i_a = grouped(pool, i_a);
    let delta = group_pair(pool, delta);
    let u = motion_subspace_image(pool, column.turns, &column.axis, &i_a);
    let u = group_pair(pool, &u);
    let pivot = project(pool, column.turns, &column.axis, &u);
    let pivot = match pool.is_zero(armature) {
        true => pivot,
        false => pool.add(pivot, armature),
    };
    let pivot = pool.group(pivot);
    let share = project(pool, column.turns, &column.axis, &delta);
    let force = pool.sub(force, share);
    let force = pool.group(force);
    let reciprocal = pool.powi(pivot, -1);
    Step {
        pivot,
        outward: Pivot {
            u,
            reciprocal,
            force,
        },
        i_a,
        delta,
    }
}

/// What a speed passes inwards: `Iᴬ − U Uᵀ / D` and `Δ + U u / D`, in the
/// axes it was given in.
fn articulated_share(
    pool: &mut Pool,
    step: &Pivot,
    i_a: &Spatial,
    delta: &Pair,
) -> (Spatial, Pair) {
    let u = &step.u;
    let per = pool.mul(step.force, step.reciprocal);
    let scaled = (
        scale3(pool, &u.0, step.reciprocal),
        scale3(pool, &u.1, step.reciprocal),
    );
    let reduced = Spatial {
        a: minus_outer(pool, &i_a.a, &u.0, &scaled.0, true),
        b: minus_outer(pool, &i_a.b, &u.0, &scaled.1, false),
        c: minus_outer(pool, &i_a.c, &u.1, &scaled.1, true),
    };
    let reduced = grouped(pool, &reduced);
    let pushed = (scale3(pool, &u.0, per), scale3(pool, &u.1, per));
    let passed = (
        add3(pool, &delta.0, &pushed.0),
        add3(pool, &delta.1, &pushed.1),
    );
    (reduced, group_pair(pool, &passed))
}

/// The rigid inertia of a composite about its link's origin.
fn rigid(pool: &mut Pool, c: &Composite) -> Spatial {
    let zero = pool.zero();
    let mut mass = [[zero; 3]; 3];
    for (i, row) in mass.iter_mut().enumerate() {
        row[i] = c.mass;
    }
    Spatial {
        a: c.inertia,
        b: skew(pool, &c.moment),
        c: mass,
    }
}

/// `[v×]`, the matrix of `x ↦ v × x`.
fn skew(pool: &mut Pool, v: &Vec3) -> Mat3 {
    let zero = pool.zero();
    let minus = v.map(|x| pool.neg(x));
    [
        [zero, minus[2], v[1]],
        [v[2], zero, minus[0]],
        [minus[1], v[0], zero],
    ]
}

/// `I S` for the joint's unit motion `S`: `(A e, Bᵀ e)` about a revolute
/// axis, `(B e, C e)` along a prismatic one.
fn motion_subspace_image(pool: &mut Pool, turns: bool, e: &Vec3, i: &Spatial) -> Pair {
    match turns {
        true => (mat_vec(pool, &i.a, e), transpose_mul(pool, &i.b, e)),
        false => (mat_vec(pool, &i.b, e), mat_vec(pool, &i.c, e)),
    }
}

/// `Sᵀ w` of a wrench `w`: its moment about a revolute axis, its resultant
/// along a prismatic one.
fn project(pool: &mut Pool, turns: bool, e: &Vec3, w: &Pair) -> ExprId {
    match turns {
        true => dot(pool, e, &w.0),
        false => dot(pool, e, &w.1),
    }
}

/// `m − a bᵀ`; only the upper triangle, mirrored, when `symmetric`.
fn minus_outer(pool: &mut Pool, m: &Mat3, a: &Vec3, b: &Vec3, symmetric: bool) -> Mat3 {
    let mut out = *m;
    for i in 0..3 {
        for j in 0..3 {
            if symmetric && j < i {
                out[i][j] = out[j][i];
                continue;
            }
            let ab = pool.mul(a[i], b[j]);
            out[i][j] = pool.sub(m[i][j], ab);
        }
    }
    out
}

/// A link's articulated inertia and bias wrench, given in its axes about
/// its origin, in its parent's axes about the parent's origin (`Xᵀ I X`,
/// `Xᵀ w`): turned by the link's rotation (factor by factor where the
/// link keeps its factors, as the composite inertias are), then moved by
/// its offset `r` (from the parent's origin to the link's):
/// `A + [r×]Bᵀ − B[r×] − [r×]C[r×]`, `B + [r×]C`, `C`; moment `n + r × f`.
fn to_parent(pool: &mut Pool, link: &Link, i: &Spatial, w: &Pair) -> (Spatial, Pair) {
    let offset = &link.offset;
    let a = link.tensor_to_parent(pool, &i.a);
    let b = link.general_tensor_to_parent(pool, &i.b);
    let c = link.tensor_to_parent(pool, &i.c);
    let r = skew(pool, offset);
    let rc = mat_mul(pool, &r, &c);
    let b_moved = add_mat(pool, &b, &rc);
    let b_moved = b_moved.map(|row| row.map(|x| pool.group(x)));
    // −B[r×] − [r×]C[r×] = −B'[r×] with B' = B + [r×]C, and [r×]ᵀ = −[r×]:
    // the (i, j) entry of A + [r×]Bᵀ − B'[r×] is Aᵢⱼ + rᵢ · Bⱼ + B'ᵢ · rⱼ
    // (rows of [r×], B and B'), taken on and above the diagonal.
    let mut a_moved = a;
    for i in 0..3 {
        for j in 0..3 {
            a_moved[i][j] = if j < i {
                a_moved[j][i]
            } else {
                let turned = dot(pool, &r[i], &b[j]);
                let moved = dot(pool, &b_moved[i], &r[j]);
                pool.sum([a[i][j], turned, moved])
            };
        }
    }
    let f = link.to_parent(pool, &w.1);
    let n = link.to_parent(pool, &w.0);
    let lever = cross(pool, offset, &f);
    let moment = add3(pool, &n, &lever);
    (
        Spatial {
            a: a_moved,
            b: b_moved,
            c,
        },
        (moment, f),
    )
}

/// The parent's motion `(ω, v)` in a link's axes at its origin:
/// `(Rᵀ ω, Rᵀ (v + ω × r))`, factor by factor as [`to_parent`].
fn from_parent(pool: &mut Pool, link: &Link, parent: &Pair) -> Pair {
    let (omega, v) = parent;
    let swept = cross(pool, omega, &link.offset);
    let at_origin = add3(pool, v, &swept);
    (link.to_link(pool, omega), link.to_link(pool, &at_origin))
}

fn scale3(pool: &mut Pool, v: &Vec3, s: ExprId) -> Vec3 {
    v.map(|x| pool.mul(x, s))
}

fn mat_mul(pool: &mut Pool, a: &Mat3, b: &Mat3) -> Mat3 {
    let bt = transpose(b);
    [0, 1, 2].map(|i| [0, 1, 2].map(|j| dot(pool, &a[i], &bt[j])))
}

fn add_mat(pool: &mut Pool, a: &Mat3, b: &Mat3) -> Mat3 {
    [0, 1, 2].map(|i| add3(pool, &a[i], &b[i]))
}

fn sum(pool: &mut Pool, x: &Spatial, y: &Spatial) -> Spatial {
    Spatial {
        a: add_mat(pool, &x.a, &y.a),
        b: add_mat(pool, &x.b, &y.b),
        c: add_mat(pool, &x.c, &y.c),
    }
}

/// Every entry as one operand ([`Pool::group`]).
fn grouped(pool: &mut Pool, i: &Spatial) -> Spatial {
    let g = |pool: &mut Pool, m: &Mat3| m.map(|row| row.map(|x| pool.group(x)));
    Spatial {
        a: g(pool, &i.a),
        b: g(pool, &i.b),
        c: g(pool, &i.c),
    }
}

fn group_pair(pool: &mut Pool, p: &Pair) -> Pair {
    (p.0.map(|x| pool.group(x)), p.1.map(|x| pool.group(x)))
}
