//! The partials `∂τ/∂q` and `∂τ/∂v` of the inertia and gravity terms of a
//! tree's inverse dynamics `τ = M v̇ − f`, by a recursion over the tree in
//! the axes of `N` (Carpentier and Mansard, "Analytical derivatives of
//! rigid body dynamics algorithms", RSS 2018: the derivatives of the
//! recursive Newton–Euler algorithm), for trees of revolute, prismatic,
//! spherical and free joints.
//!
//! Every spatial quantity is in `N`'s axes at `N`'s origin: the motion
//! subspace `Sᵢ` of joint `i` (`(e, o × e)` for a turn about the unit axis
//! `e` through `o`, `(0, e)` for a slide), the twist `vᵢ = v_λ + Sᵢ q̇ᵢ` and
//! the acceleration `aᵢ = a_λ + Sᵢ q̈ᵢ + Ψ̇ᵢ q̇ᵢ` of link `i` (parent `λ`,
//! `Ψ̇ᵢ = v_λ × Sᵢ`, the base accelerating at `−g`), the link's inertia
//! `Iᵢ`, its inertia force `fᵢ = Iᵢ aᵢ + vᵢ ×* Iᵢ vᵢ`, and `τᵢ = Sᵢ · Fᵢ`
//! with `Fᵢ` the sum of the `f` of subtree `i`. Turning joint `j` moves its
//! subtree rigidly: anything fixed in it changes by `Sⱼ ×` (`Sⱼ ×*` for a
//! force), the twists beyond `j` by `Sⱼ × v + Ψ̇ⱼ` and the accelerations
//! by `Sⱼ × a + Ψ̈ⱼ − v × Ψ̇ⱼ` (`Ψ̈ⱼ = a_λ × Sⱼ + v_λ × Ψ̇ⱼ`). With the
//! composites of subtree `i`, `Iᶜᵢ`, its rate `İᶜᵢ` (`İ = v ×* I − I v×` per
//! link) and its momentum `hᶜᵢ`, and `Lᶜᵢ x = İᶜᵢ x + x ×* hᶜᵢ`:
//!
//! ```text
//! j ⪯ i:  ∂τᵢ/∂qⱼ = Sᵢ · (Iᶜᵢ Ψ̈ⱼ + Lᶜᵢ Ψ̇ⱼ)        ∂τᵢ/∂q̇ⱼ = Sᵢ · (Lᶜᵢ Sⱼ + 2 Iᶜᵢ Ψ̇ⱼ)
//! i ≺ j:  ∂τᵢ/∂qⱼ = Sᵢ · (Sⱼ ×* Fⱼ + Iᶜⱼ Ψ̈ⱼ + Lᶜⱼ Ψ̇ⱼ)  ∂τᵢ/∂q̇ⱼ = Sᵢ · (Lᶜⱼ Sⱼ + 2 Iᶜⱼ Ψ̇ⱼ)
//! ```
//!
//! and zero where neither joint is beyond the other. The first row is
//! `yᵢ · Ψ̈ⱼ + zᵢ · Ψ̇ⱼ` and `zᵢ · Sⱼ + 2 yᵢ · Ψ̇ⱼ` with `yᵢ = Iᶜᵢ Sᵢ` and
//! `zᵢ = Lᶜᵢᵀ Sᵢ = İᶜᵢ Sᵢ − Sᵢ ×* hᶜᵢ`, the second `Sᵢ` dotted with one
//! vector per `j`: a few dot products of six per entry, against a sweep
//! differentiated link by link in the body-frame recursion.
//!
//! A joint of several speeds (spherical, free) is one column `Sₖ` a speed,
//! each fixed in the link (the link's own axes at its origin), its `∂/∂q`
//! along the tangent direction that moves the link by `Sₖ` (as the
//! symbolic route's `tangent_directions`). Three things differ from a
//! chain of one-speed joints: every column's `Ψ̇ₖ`, `Ψ̈ₖ` are taken from
//! the joint's parent (`v_λ`, `a_λ`), and the link's twist and
//! acceleration are `v_λ + Σ Sₖ q̇ₖ` and `a_λ + Σ (Sₖ q̈ₖ + Ψ̇ₖ q̇ₖ)`;
//! in `∂τ/∂q̇` the rate of a column through the link's own twist,
//! `Φₖ = vᵢ × Sₖ`, replaces one of the two `Ψ̇ₖ` (for a one-speed joint
//! `Φ = Ψ̇`: the `2` above), so each link carries `Ψ̇ₖ + Φₖ`; and since
//! each column turns with the others, every pair of columns of one joint
//! takes the first row's formulas both ways, none the second's.

use super::recursive::{
    Column, Composite, JointTree, Link, group3, grouped as grouped_composite, rotate_tensor,
    shifted,
};
use crate::expr::{ExprId, Pool, Sym};
use crate::kinematics::{Mat3, Vec3, add3, cross, dot, identity, mat_mul, mat_vec, transpose_mul};
use crate::model::JointKind;

/// A square block of partials, `[i][j]` by the `j`-th variable.
type Block = Vec<Vec<ExprId>>;

/// A spatial vector in `N`'s axes at `N`'s origin: `(ω, v)` for a motion,
/// `(n, f)` for a force.
#[derive(Clone, Copy)]
pub(super) struct Spatial {
    pub(super) angular: Vec3,
    pub(super) linear: Vec3,
}

/// The recursion's state of one link.
struct Moving {
    /// Maps the link's components to `N`'s.
    rotation: Mat3,
    /// The link's origin, from `N`'s.
    origin: Vec3,
    /// One per speed of the joint.
    columns: Vec<ColumnMotion>,
    /// The link's twist and acceleration.
    twist: Spatial,
    acceleration: Spatial,
}

/// One column of a joint's motion subspace and its rates.
struct ColumnMotion {
    /// `S`.
    subspace: Spatial,
    /// `Ψ̇ = v_λ × S`.
    rate: Spatial,
    /// `Ψ̈ = a_λ × S + v_λ × Ψ̇`.
    second_rate: Spatial,
    /// `Ψ̇ + Φ` with `Φ = v × S` (`2 Ψ̇` for a one-speed joint).
    driven: Spatial,
    /// The speed's index.
    speed: usize,
}

/// The composites of a subtree: inertia `(m, first moment c, inertia about
/// the origin K)`, its rate `(ċ, K̇)`, momentum and inertia force. The rate
/// of the first moment is the linear momentum (`ċ = m v + ω × c`, the mass
/// times the velocity of the centre), so `ċ` is `momentum.linear`: one
/// node, whose terms cancel where `İᶜ` and `hᶜ` meet in `z` and `u`.
#[derive(Clone, Copy)]
struct Subtree {
    inertia: Composite,
    inertia_rate: Mat3,
    momentum: Spatial,
    force: Spatial,
}

/// What the partials of one speed of a link's joint pair with those of
/// its ancestors and descendants, in `N`'s axes: its parent, joint and
/// speed, and eight spatial vectors of six entries (angular then linear),
/// `Sⱼ`, `Ψ̇ⱼ`, `Ψ̈ⱼ`, `Ψ̇ⱼ + Φⱼ`, `yⱼ`, `zⱼ`, `wⱼ`, `uⱼ`, in that order. A
/// joint of several speeds is as many entries, each the parent of the
/// next.
pub struct LinkVectors {
    /// The parent's index among the entries (parents before children):
    /// the previous speed of the same joint, else the last of the parent
    /// link's joint.
    pub parent: Option<usize>,
    /// The index of the entry of the joint's first speed (its own for a
    /// one-speed joint).
    pub joint: usize,
    /// The index of the speed.
    pub speed: usize,
    /// `Sⱼ`, `Ψ̇ⱼ`, `Ψ̈ⱼ`, `Ψ̇ⱼ + Φⱼ`, `yⱼ`, `zⱼ`, `wⱼ`, `uⱼ`.
    pub vectors: [[ExprId; 6]; 8],
}

/// One speed of a link of the tree at a state, what the runtime's
/// recursion (`dalembert::__private::TreeRecursion`) computes its
/// [`LinkVectors`] from, with the accelerations it is given after its
/// first pass: its placement in its parent entry, its column `(e, 0)` of a
/// turn or `(0, e)` of a slide in the link's axes, the speed, and the
/// inertia about the link's origin in its axes. A joint of several speeds
/// puts the link's placement on its first entry and its inertia on its
/// last; the others are placed at their parent entry (the identity, no
/// offset) and carry no mass. A free or spherical root is placed at the
/// identity too: the recursion runs in its axes ([`frame_root`]).
pub struct LinkState {
    /// Maps the link's components to its parent's.
    pub rotation: Mat3,
    /// From the parent's origin to the link's, in the parent's axes.
    pub offset: Vec3,
    pub axis: [ExprId; 6],
    pub speed: ExprId,
    pub mass: ExprId,
    /// The first moment about the link's origin, in its axes.
    pub moment: Vec3,
    /// The inertia tensor about the link's origin, in its axes.
    pub inertia: Mat3,
}

impl LinkState {
    /// How many entries [`LinkState::entries`] has.
    pub const ENTRIES: usize = 32;

    /// Every entry in the order of the runtime's `LinkState` fields
    /// (`rotation` and `inertia` row by row).
    pub fn entries(&self) -> [ExprId; Self::ENTRIES] {
        let mut entries = self.rotation.concat();
        entries.extend(self.offset);
        entries.extend(self.axis);
        entries.extend([self.speed, self.mass]);
        entries.extend(self.moment);
        entries.extend(self.inertia.concat());
        entries.try_into().expect("32 entries")
    }
}

/// The root link whose axes at its origin the runtime's recursion takes
/// as its frame: the tree's one root, if it is a free or spherical joint.
/// The frame is the inertial one that coincides with the link at the
/// state: the pairs are dot products, the same in any frame, and in it the
/// root's columns are unit vectors (which the runtime's pairs read rather
/// than multiply, `dalembert::__private::add_tree_pairs`) and its rotation
/// enters only gravity ([`recursion_gravity`]).
fn frame_root(tree: &JointTree) -> Option<usize> {
    let mut roots = tree
        .links
        .iter()
        .enumerate()
        .filter(|(_, l)| l.parent.is_none());
    match (roots.next(), roots.next()) {
        (Some((k, link)), None) => {
            matches!(link.kind, JointKind::Free | JointKind::Spherical).then_some(k)
        }
        _ => None,
    }
}

/// Gravity in the axes of the runtime's recursion (see [`frame_root`]):
/// `Rᵀ g` in the root's, `g` in `N`'s.
pub(super) fn recursion_gravity(tree: &JointTree, pool: &mut Pool) -> Vec3 {
    match frame_root(tree) {
        Some(root) => transpose_mul(pool, &tree.links[root].rotation, &tree.gravity),
        None => tree.gravity,
    }
}

/// The [`LinkState`] of every speed of `tree` (whose [`link_vectors`] are
/// found), in the order of its [`LinkVectors`], in the frame of
/// [`frame_root`] (the root placed at the identity, at the origin).
pub(super) fn link_states(tree: &JointTree, pool: &mut Pool) -> Vec<LinkState> {
    let zero = pool.zero();
    let inertias = tree.link_inertias(pool);
    let root = frame_root(tree);
    let mut states = Vec::new();
    for (l, (link, inertia)) in tree.links.iter().zip(inertias).enumerate() {
        let last = link.columns.len() - 1;
        for (c, column) in link.columns.iter().enumerate() {
            let [a, b, d] = column.axis;
            let axis = match column.turns {
                true => [a, b, d, zero, zero, zero],
                false => [zero, zero, zero, a, b, d],
            };
            let (rotation, offset) = match c == 0 && root != Some(l) {
                true => (link.rotation, link.offset),
                false => (identity(pool), [zero; 3]),
            };
            let massless = Composite {
                mass: zero,
                moment: [zero; 3],
                inertia: [[zero; 3]; 3],
            };
            let inertia = if c == last { inertia } else { massless };
            states.push(LinkState {
                rotation,
                offset,
                axis,
                speed: pool.sym(Sym::Speed(column.speed as u32)),
                mass: inertia.mass,
                moment: inertia.moment,
                inertia: inertia.inertia,
            });
        }
    }
    states
}

/// The [`LinkVectors`] of every speed of `tree`, link by link and each
/// joint's speeds in order; `None` if a joint is of another kind than
/// revolute, prismatic, spherical or free.
pub(super) fn link_vectors(tree: &JointTree, pool: &mut Pool) -> Option<Vec<LinkVectors>> {
    let known = |l: &Link| match l.kind {
        JointKind::Revolute | JointKind::Prismatic => l.columns.len() == 1,
        _ => !l.columns.is_empty(),
    };
    if !tree.links.iter().all(known) {
        return None;
    }
    let links = forward(tree, pool);
    let subtrees = backward(tree, &links, pool);
    let mut vectors: Vec<LinkVectors> = Vec::new();
    let mut last_entry: Vec<usize> = Vec::with_capacity(links.len());
    for ((link, subtree), joint) in links.iter().zip(&subtrees).zip(&tree.links) {
        let first = vectors.len();
        for column in &link.columns {
            let Columns { y, z, w, u } = columns(pool, column, subtree);
            let parts = [
                column.subspace,
                column.rate,
                column.second_rate,
                column.driven,
                y,
                z,
                w,
                u,
            ];
            let parent = match vectors.len() {
                k if k > first => Some(k - 1),
                _ => joint.parent.map(|p| last_entry[p]),
            };
            vectors.push(LinkVectors {
                parent,
                joint: first,
                speed: column.speed,
                vectors: parts.map(|x| x.entries()),
            });
        }
        last_entry.push(vectors.len() - 1);
    }
    Some(vectors)
}

/// `(∂τ/∂q, ∂τ/∂v)` of the inertia and gravity terms of a tree of `n`
/// speeds from its links' [`LinkVectors`], entry by entry:
///
/// ```text
/// j ⪯ i:  ∂τᵢ/∂qⱼ = yᵢ · Ψ̈ⱼ + zᵢ · Ψ̇ⱼ    ∂τᵢ/∂q̇ⱼ = zᵢ · Sⱼ + yᵢ · (Ψ̇ⱼ + Φⱼ)
/// j ≺ i:  ∂τⱼ/∂qᵢ = Sⱼ · wᵢ              ∂τⱼ/∂q̇ᵢ = Sⱼ · uᵢ
/// ```
///
/// the second row the first's with `i` and `j` exchanged where both are
/// speeds of one joint.
pub(super) fn paired(links: &[LinkVectors], n: usize, pool: &mut Pool) -> (Block, Block) {
    let zero = pool.zero();
    let (mut by_q, mut by_v) = (vec![vec![zero; n]; n], vec![vec![zero; n]; n]);
    for (i, link) in links.iter().enumerate() {
        let mut ancestor = Some(i);
        while let Some(j) = ancestor {
            let other = &links[j];
            let (q, v) = ancestor_pair(pool, link, other);
            by_q[link.speed][other.speed] = q;
            by_v[link.speed][other.speed] = v;
            if j != i {
                let (q, v) = match other.joint == link.joint {
                    true => ancestor_pair(pool, other, link),
                    false => {
                        let ([s, ..], [.., w, u]) = (&other.vectors, &link.vectors);
                        (dot6(pool, s, w), dot6(pool, s, u))
                    }
                };
                by_q[other.speed][link.speed] = q;
                by_v[other.speed][link.speed] = v;
            }
            ancestor = other.parent;
        }
    }
    (by_q, by_v)
}

/// `(∂τᵢ/∂qⱼ, ∂τᵢ/∂q̇ⱼ)` of `i = link` and `j = other`, `j` an ancestor of
/// `i`, `i` itself, or a speed of its joint: `yᵢ · Ψ̈ⱼ + zᵢ · Ψ̇ⱼ` and
/// `zᵢ · Sⱼ + yᵢ · (Ψ̇ⱼ + Φⱼ)`.
fn ancestor_pair(pool: &mut Pool, link: &LinkVectors, other: &LinkVectors) -> (ExprId, ExprId) {
    let [.., y, z, _, _] = &link.vectors;
    let [s, rate, second_rate, driven, ..] = &other.vectors;
    let terms = [dot6(pool, y, second_rate), dot6(pool, z, rate)];
    let by_q = pool.sum(terms);
    let terms = [dot6(pool, z, s), dot6(pool, y, driven)];
    (by_q, pool.sum(terms))
}

/// `a · b` of a motion and a force, six entries each.
pub(super) fn dot6(pool: &mut Pool, a: &[ExprId; 6], b: &[ExprId; 6]) -> ExprId {
    let (a_angular, a_linear) = ([a[0], a[1], a[2]], [a[3], a[4], a[5]]);
    let (b_angular, b_linear) = ([b[0], b[1], b[2]], [b[3], b[4], b[5]]);
    let terms = [
        dot(pool, &a_angular, &b_angular),
        dot(pool, &a_linear, &b_linear),
    ];
    pool.sum(terms)
}

/// What the entries of one speed `i`'s row and column are dot products
/// with: `yᵢ = Iᶜᵢ Sᵢ`, `zᵢ = Lᶜᵢᵀ Sᵢ` (with the `Ψ` of the joints up to
/// `i`), `wᵢ = Sᵢ ×* Fᵢ + Iᶜᵢ Ψ̈ᵢ + Lᶜᵢ Ψ̇ᵢ` and
/// `uᵢ = Lᶜᵢ Sᵢ + Iᶜᵢ (Ψ̇ᵢ + Φᵢ)` (with the `S` of its ancestors).
struct Columns {
    y: Spatial,
    z: Spatial,
    w: Spatial,
    u: Spatial,
}

/// The [`Columns`] of one speed of a link, from its subtree's composites,
/// sharing `İᶜ S` and `S ×* hᶜ` between `Lᶜ S` and `Lᶜᵀ S`.
fn columns(pool: &mut Pool, link: &ColumnMotion, subtree: &Subtree) -> Columns {
    let (s, rate) = (&link.subspace, &link.rate);
    let y = inertia_times(pool, &subtree.inertia, s);
    let turned = rate_times(pool, subtree, s);
    let carried = force_cross(pool, s, &subtree.momentum);
    let z = sub(pool, &turned, &carried);
    let pushed = inertia_times(pool, &subtree.inertia, &link.driven);
    let terms = [turned, carried, pushed];
    let u = sum(pool, &terms);
    let terms = [
        force_cross(pool, s, &subtree.force),
        inertia_times(pool, &subtree.inertia, &link.second_rate),
        rate_times(pool, subtree, rate),
        force_cross(pool, rate, &subtree.momentum),
    ];
    let w = sum(pool, &terms);
    let [y, z, w, u] = [y, z, w, u].map(|x| grouped(pool, &x));
    Columns { y, z, w, u }
}

/// The links outwards: placement in `N`, twist, acceleration (the symbols
/// `q̈`, the base at `−g`), and each speed's column of the motion subspace
/// with its rates `Ψ̇`, `Ψ̈`, `Ψ̇ + Φ`.
fn forward(tree: &JointTree, pool: &mut Pool) -> Vec<Moving> {
    let zero = pool.zero();
    let base = Moving {
        rotation: identity(pool),
        origin: [zero; 3],
        columns: Vec::new(),
        twist: Spatial::zero(pool),
        acceleration: Spatial {
            angular: [zero; 3],
            linear: tree.gravity.map(|g| pool.neg(g)),
        },
    };
    let mut links: Vec<Moving> = Vec::with_capacity(tree.links.len());
    for link in &tree.links {
        let parent = link.parent.map_or(&base, |p| &links[p]);
        let (rotation, origin) = placed(pool, (&parent.rotation, &parent.origin), link);
        let (v, a) = (&parent.twist, &parent.acceleration);
        let mut twist_terms = vec![*v];
        let mut acceleration_terms = vec![*a];
        let mut columns: Vec<ColumnMotion> = Vec::with_capacity(link.columns.len());
        for column in &link.columns {
            let subspace = subspace(pool, (&rotation, &origin), column);
            let rate = motion_cross(pool, v, &subspace);
            let rate = grouped(pool, &rate);
            let turned = motion_cross(pool, a, &subspace);
            let carried = motion_cross(pool, v, &rate);
            let second_rate = add(pool, &turned, &carried);
            let second_rate = grouped(pool, &second_rate);
            let speed = pool.sym(Sym::Speed(column.speed as u32));
            let accel = pool.sym(Sym::Accel(column.speed as u32));
            twist_terms.push(scale(pool, speed, &subspace));
            acceleration_terms.push(scale(pool, accel, &subspace));
            acceleration_terms.push(scale(pool, speed, &rate));
            columns.push(ColumnMotion {
                subspace,
                rate,
                second_rate,
                driven: add(pool, &rate, &rate),
                speed: column.speed,
            });
        }
        let twist = sum(pool, &twist_terms);
        let twist = grouped(pool, &twist);
        if columns.len() > 1 {
            for column in &mut columns {
                let through_link = motion_cross(pool, &twist, &column.subspace);
                let driven = add(pool, &column.rate, &through_link);
                column.driven = grouped(pool, &driven);
            }
        }
        let acceleration = sum(pool, &acceleration_terms);
        let acceleration = grouped(pool, &acceleration);
        links.push(Moving {
            rotation,
            origin,
            columns,
            twist,
            acceleration,
        });
    }
    links
}

/// The rotation to `N`'s axes and the origin from `N`'s of `link`, from
/// those of its parent.
pub(super) fn placed(pool: &mut Pool, parent: (&Mat3, &Vec3), link: &Link) -> (Mat3, Vec3) {
    let (parent_rotation, parent_origin) = parent;
    let offset = mat_vec(pool, parent_rotation, &link.offset);
    let origin = add3(pool, parent_origin, &offset);
    let origin = group3(pool, &origin);
    let rotation = mat_mul(pool, parent_rotation, &link.rotation);
    let rotation = rotation.map(|row| group3(pool, &row));
    (rotation, origin)
}

/// The motion subspace `S` of one speed `column` of a link placed at
/// `placement` (rotation to `N`'s axes, origin): `(e, o × e)` for a turn
/// about `e` through `o`, `(0, e)` for a slide.
pub(super) fn subspace(pool: &mut Pool, placement: (&Mat3, &Vec3), column: &Column) -> Spatial {
    let (rotation, origin) = placement;
    let axis = mat_vec(pool, rotation, &column.axis);
    let axis = group3(pool, &axis);
    match column.turns {
        true => Spatial {
            angular: axis,
            linear: {
                let moment = cross(pool, origin, &axis);
                group3(pool, &moment)
            },
        },
        false => Spatial {
            angular: [pool.zero(); 3],
            linear: axis,
        },
    }
}

/// The composites of every subtree inwards, from each link's inertia moved
/// into `N`.
fn backward(tree: &JointTree, links: &[Moving], pool: &mut Pool) -> Vec<Subtree> {
    let own = tree.link_inertias(pool);
    let mut subtrees: Vec<Subtree> = own
        .iter()
        .zip(links)
        .map(|(inertia, link)| link_subtree(pool, inertia, link))
        .collect();
    for l in (0..links.len()).rev() {
        let grouped = subtree_grouped(pool, &subtrees[l]);
        subtrees[l] = grouped;
        if let Some(p) = tree.links[l].parent {
            subtrees[p] = subtree_sum(pool, &subtrees[p], &grouped);
        }
    }
    subtrees
}

/// One link's inertia `inertia` (about its origin, in its axes) in `N`,
/// with its rate, momentum and inertia force.
fn link_subtree(pool: &mut Pool, inertia: &Composite, link: &Moving) -> Subtree {
    let (rotation, origin) = (&link.rotation, &link.origin);
    let moment = mat_vec(pool, rotation, &inertia.moment);
    let turned = Composite {
        mass: inertia.mass,
        moment,
        inertia: rotate_tensor(pool, rotation, &inertia.inertia),
    };
    let carried = origin.map(|o| pool.mul(inertia.mass, o));
    let moved = add3(pool, &moment, &carried);
    let moved = group3(pool, &moved);
    let world = shifted(pool, &turned, origin, &moved);
    let world = grouped_composite(pool, &world);
    let Spatial {
        angular: w,
        linear: v,
    } = link.twist;
    // K̇ = A + Aᵀ + 2 (c·v) 1 − v cᵀ − c vᵀ with A = [ω]× K.
    let columns = [0, 1, 2].map(|j| {
        let column = [0, 1, 2].map(|i| world.inertia[i][j]);
        cross(pool, &w, &column)
    });
    let c_dot_v = dot(pool, &world.moment, &v);
    let twice = pool.add(c_dot_v, c_dot_v);
    let inertia_rate = [0, 1, 2].map(|i| {
        [0, 1, 2].map(|j| {
            let outer = [
                pool.mul(v[i], world.moment[j]),
                pool.mul(world.moment[i], v[j]),
            ];
            let mut terms = vec![columns[j][i], columns[i][j]];
            terms.extend(outer.map(|x| pool.neg(x)));
            if i == j {
                terms.push(twice);
            }
            pool.sum(terms)
        })
    });
    let momentum = inertia_times(pool, &world, &link.twist);
    let momentum = grouped(pool, &momentum);
    let inertial = inertia_times(pool, &world, &link.acceleration);
    let gyroscopic = force_cross(pool, &link.twist, &momentum);
    Subtree {
        inertia: world,
        inertia_rate,
        momentum,
        force: add(pool, &inertial, &gyroscopic),
    }
}

/// `I x` for the spatial inertia `(m, c, K)`: `(K ω + c × v, m v − c × ω)`.
fn inertia_times(pool: &mut Pool, inertia: &Composite, x: &Spatial) -> Spatial {
    let (w, v) = (&x.angular, &x.linear);
    let turned = mat_vec(pool, &inertia.inertia, w);
    let lever = cross(pool, &inertia.moment, v);
    let pushed = v.map(|x| pool.mul(inertia.mass, x));
    let swung = cross(pool, &inertia.moment, w);
    Spatial {
        angular: add3(pool, &turned, &lever),
        linear: sub3(pool, &pushed, &swung),
    }
}

/// `İᶜ x = (K̇ ω + ċ × v, −ċ × ω)` for the rate of a subtree's inertia,
/// `ċ` its linear momentum.
fn rate_times(pool: &mut Pool, subtree: &Subtree, x: &Spatial) -> Spatial {
    let moment_rate = &subtree.momentum.linear;
    let turned = mat_vec(pool, &subtree.inertia_rate, &x.angular);
    let lever = cross(pool, moment_rate, &x.linear);
    let swung = cross(pool, &x.angular, moment_rate);
    Spatial {
        angular: add3(pool, &turned, &lever),
        linear: swung,
    }
}

/// `m₁ × m₂ = (ω₁ × ω₂, ω₁ × v₂ + v₁ × ω₂)`.
fn motion_cross(pool: &mut Pool, a: &Spatial, b: &Spatial) -> Spatial {
    let first = cross(pool, &a.angular, &b.linear);
    let second = cross(pool, &a.linear, &b.angular);
    Spatial {
        angular: cross(pool, &a.angular, &b.angular),
        linear: add3(pool, &first, &second),
    }
}

/// `m ×* f = (ω × n + v × f, ω × f)`.
fn force_cross(pool: &mut Pool, m: &Spatial, f: &Spatial) -> Spatial {
    let first = cross(pool, &m.angular, &f.angular);
    let second = cross(pool, &m.linear, &f.linear);
    Spatial {
        angular: add3(pool, &first, &second),
        linear: cross(pool, &m.angular, &f.linear),
    }
}

fn add(pool: &mut Pool, a: &Spatial, b: &Spatial) -> Spatial {
    Spatial {
        angular: add3(pool, &a.angular, &b.angular),
        linear: add3(pool, &a.linear, &b.linear),
    }
}

fn sub(pool: &mut Pool, a: &Spatial, b: &Spatial) -> Spatial {
    Spatial {
        angular: sub3(pool, &a.angular, &b.angular),
        linear: sub3(pool, &a.linear, &b.linear),
    }
}

fn sum(pool: &mut Pool, terms: &[Spatial]) -> Spatial {
    let first = terms[0];
    terms[1..]
        .iter()
        .fold(first, |total, x| add(pool, &total, x))
}

/// `s x`.
fn scale(pool: &mut Pool, s: ExprId, x: &Spatial) -> Spatial {
    Spatial {
        angular: x.angular.map(|e| pool.mul(s, e)),
        linear: x.linear.map(|e| pool.mul(s, e)),
    }
}

fn sub3(pool: &mut Pool, a: &Vec3, b: &Vec3) -> Vec3 {
    [0, 1, 2].map(|i| pool.sub(a[i], b[i]))
}

fn grouped(pool: &mut Pool, x: &Spatial) -> Spatial {
    Spatial {
        angular: group3(pool, &x.angular),
        linear: group3(pool, &x.linear),
    }
}

impl Spatial {
    /// The six entries, angular then linear.
    pub(super) fn entries(&self) -> [ExprId; 6] {
        let [a, b, c] = self.angular;
        let [d, e, f] = self.linear;
        [a, b, c, d, e, f]
    }

    fn zero(pool: &Pool) -> Spatial {
        let zero = pool.zero();
        Spatial {
            angular: [zero; 3],
            linear: [zero; 3],
        }
    }
}

/// Every entry of a subtree's composites grouped.
fn subtree_grouped(pool: &mut Pool, s: &Subtree) -> Subtree {
    Subtree {
        inertia: grouped_composite(pool, &s.inertia),
        inertia_rate: s.inertia_rate.map(|row| group3(pool, &row)),
        momentum: grouped(pool, &s.momentum),
        force: grouped(pool, &s.force),
    }
}

/// `a + b`, entry by entry.
fn subtree_sum(pool: &mut Pool, a: &Subtree, b: &Subtree) -> Subtree {
    let matrix_sum = |pool: &mut Pool, x: &Mat3, y: &Mat3| -> Mat3 {
        [0, 1, 2].map(|i| add3(pool, &x[i], &y[i]))
    };
    Subtree {
        inertia: Composite {
            mass: pool.add(a.inertia.mass, b.inertia.mass),
            moment: add3(pool, &a.inertia.moment, &b.inertia.moment),
            inertia: matrix_sum(pool, &a.inertia.inertia, &b.inertia.inertia),
        },
        inertia_rate: matrix_sum(pool, &a.inertia_rate, &b.inertia_rate),
        momentum: add(pool, &a.momentum, &b.momentum),
        force: add(pool, &a.force, &b.force),
    }
}
