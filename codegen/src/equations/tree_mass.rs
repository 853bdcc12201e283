//! The mass matrix of a tree as a few vectors per speed, for trees large
//! enough that the unrolled entries of `M` (one straight-line formula for
//! each of its `n (n + 1) / 2` entries) are more code than the processor
//! keeps close.
//!
//! With every spatial quantity in `N`'s axes at `N`'s origin (as in
//! `tree_partials`), the composite-rigid-body algorithm gives
//!
//! ```text
//! Mᵢⱼ = Mⱼᵢ = Sᵢ · Fⱼ    for each speed i of j's joint or of an ancestor's,
//! ```
//!
//! with `Sⱼ` the motion subspace column of speed `j` (`(e, o × e)` for a
//! turn about the unit axis `e` through `o`, `(0, e)` for a slide) and
//! `Fⱼ = Iᶜⱼ Sⱼ` the momentum of the subtree beyond the joint moving at unit
//! rate of speed `j`. `Fⱼ` is the momentum of `recursive`'s body-frame
//! composite (in the link's axes, about its origin), turned into `N`'s axes
//! and moved to `N`'s origin: `f = R fⱼ`, `n = R nⱼ + o × f`. Two vectors of
//! six a speed, in straight-line code with the model's constants folded;
//! their dot products, a loop of the runtime.

use super::recursive::{JointTree, group3};
use super::tree_partials::{Spatial, placed, subspace};
use crate::expr::{ExprId, Pool};
use crate::kinematics::{Mat3, Vec3, add3, cross, identity, mat_vec};

/// One speed of a tree and its two vectors.
pub struct SpeedVectors {
    /// The speed before it towards the root, among the tree's speeds:
    /// the previous speed of the same joint, else the last of the parent
    /// link's joint (`None` at the root).
    pub parent: Option<usize>,
    /// One past the last of the speeds after it in its subtree: the
    /// speeds are in depth-first order, so those it moves (itself, the
    /// later speeds of its joint, its descendants') are the ones from it
    /// to before `end`.
    pub end: usize,
    /// The index of the speed.
    pub speed: usize,
    /// `Sⱼ` and `Fⱼ`, six entries each (angular then linear).
    pub vectors: [[ExprId; 6]; 2],
}

/// The [`SpeedVectors`] of every speed of `tree`: the links depth-first
/// (each subtree's speeds together, after its joint's), each joint's
/// speeds in order.
pub(super) fn speed_vectors(tree: &JointTree, pool: &mut Pool) -> Vec<SpeedVectors> {
    let composites = tree.composites(pool);
    let zero = pool.zero();
    let n = tree.links.len();
    let mut placements: Vec<(Mat3, Vec3)> = vec![(identity(pool), [zero; 3]); n];
    let mut last_speed = vec![0; n];
    let mut speeds: Vec<SpeedVectors> = Vec::new();
    let parents: Vec<Option<usize>> = tree.links.iter().map(|l| l.parent).collect();
    for l in depth_first(&parents) {
        let link = &tree.links[l];
        let base = (identity(pool), [zero; 3]);
        let (parent_rotation, parent_origin) = link.parent.map_or(base, |p| placements[p]);
        let (rotation, origin) = placed(pool, (&parent_rotation, &parent_origin), link);
        let mut parent = link.parent.map(|p| last_speed[p]);
        for column in &link.columns {
            let s = subspace(pool, (&rotation, &origin), column);
            let (linear, angular) = composites[l].momentum(pool, column);
            let force = in_newtonian(pool, (&rotation, &origin), &linear, &angular);
            speeds.push(SpeedVectors {
                parent,
                end: 0,
                speed: column.speed,
                vectors: [s.entries(), force.entries()],
            });
            parent = Some(speeds.len() - 1);
        }
        last_speed[l] = speeds.len() - 1;
        placements[l] = (rotation, origin);
    }
    let parents: Vec<Option<usize>> = speeds.iter().map(|s| s.parent).collect();
    for (speed, end) in speeds.iter_mut().zip(subtree_ends(&parents)) {
        speed.end = end;
    }
    speeds
}

/// Where each subtree ends among the nodes of `parents` (each node's
/// parent, depth-first: each subtree is the nodes from its root to before
/// its end): where its last descendant's does.
pub fn subtree_ends(parents: &[Option<usize>]) -> Vec<usize> {
    let mut ends: Vec<usize> = (1..=parents.len()).collect();
    for (i, parent) in parents.iter().enumerate().rev() {
        if let Some(&p) = parent.as_ref() {
            ends[p] = ends[p].max(ends[i]);
        }
    }
    ends
}

/// The links of the tree of `parents` (each link's parent, parents before
/// children) depth-first (preorder), children in their order: each
/// subtree's links together, from its root.
pub fn depth_first(parents: &[Option<usize>]) -> Vec<usize> {
    let children =
        |parent: Option<usize>| (0..parents.len()).filter(move |&l| parents[l] == parent);
    let mut order = Vec::with_capacity(parents.len());
    let mut stack: Vec<usize> = children(None).rev().collect();
    while let Some(l) = stack.pop() {
        order.push(l);
        stack.extend(children(Some(l)).rev());
    }
    order
}

/// A wrench (resultant, moment about the link's origin, in its axes) of a
/// link placed at `placement` (rotation to `N`'s axes, origin), in `N`'s
/// axes about `N`'s origin: `(R n + o × R f, R f)`.
fn in_newtonian(
    pool: &mut Pool,
    placement: (&Mat3, &Vec3),
    resultant: &Vec3,
    moment: &Vec3,
) -> Spatial {
    let (rotation, origin) = placement;
    let linear = mat_vec(pool, rotation, resultant);
    let linear = group3(pool, &linear);
    let turned = mat_vec(pool, rotation, moment);
    let lever = cross(pool, origin, &linear);
    let angular = add3(pool, &turned, &lever);
    Spatial {
        angular: group3(pool, &angular),
        linear,
    }
}

#[cfg(test)]
mod tests {
    use super::SpeedVectors;
    use crate::chain::{Family, Spelling, chain_spelled};
    use crate::equations::quaternion_check::LOADED;
    use crate::equations::tree_partials::dot6;
    use crate::equations::{derive, tree_mass};
    use crate::expr::{ExprId, Pool};
    use crate::geometry::Values;
    use crate::random::Random;
    use crate::trees::Shape;

    /// A trunk of four links whose last carries two limbs of three listed
    /// interleaved (as the branching tree of 14 lists them) comes out each
    /// limb together, in the order of their first links.
    #[test]
    fn depth_first_puts_each_subtree_together() {
        let parents = [
            None,
            Some(0),
            Some(1),
            Some(2),
            Some(3),
            Some(3),
            Some(4),
            Some(5),
            Some(6),
            Some(7),
        ];
        assert_eq!(super::depth_first(&parents), [0, 1, 2, 3, 4, 6, 8, 5, 7, 9]);
    }

    /// The pairs of the vectors give the recursion's `M` at random states
    /// (unit quaternions) of chains in every spelling, a branching tree
    /// (the binary tree of 31 joints, floating and fixed) and a free body
    /// with a pendulum on it, off their joints' origins.
    #[test]
    fn the_pairs_of_the_vectors_are_the_recursions_mass_matrix() {
        let tree = |floating| {
            crate::Urdf::new("binary_tree.urdf", Shape::BinaryTree.urdf())
                .floating(floating)
                .model()
                .unwrap_or_else(|e| panic!("{e}"))
        };
        let chains = Spelling::ALL.map(|s| chain_spelled(Family::Spatial, 6, s));
        let sources = chains
            .into_iter()
            .chain([
                chain_spelled(Family::Planar, 5, Spelling::Joints),
                tree(false),
                tree(true),
            ])
            .chain([LOADED.to_owned()]);
        for source in sources {
            let system =
                crate::language::parse_system(source.parse().expect("tokens")).expect("parses");
            let (model, mut pool) =
                crate::model::resolve(&system).unwrap_or_else(|e| panic!("{e}"));
            let equations = derive(&model, &mut pool);
            let speeds = tree_mass(&equations, &mut pool).expect("a tree");
            let paired = paired(&speeds, model.nv(), &mut pool);
            let mut random = Random::new(7);
            for _ in 0..3 {
                let mut draw =
                    |n: usize| -> Vec<f64> { (0..n).map(|_| random.uniform(-1.5, 1.5)).collect() };
                let (parameters, mut q) = (draw(model.parameters.len()), draw(model.nq()));
                for quaternion in model.balls.iter().map(|b| b.quaternion) {
                    let norm = quaternion.iter().map(|&k| q[k] * q[k]).sum::<f64>().sqrt();
                    quaternion.iter().for_each(|&k| q[k] /= norm);
                }
                let at = Values {
                    parameters: &parameters,
                    t: 0.0,
                    q: &q,
                    qd: &[],
                    u: &[],
                };
                for (ours, theirs) in paired.iter().zip(&equations.mass_matrix) {
                    let (ours, theirs) = (pool.eval_many(ours, &at), pool.eval_many(theirs, &at));
                    for (a, b) in ours.iter().zip(&theirs) {
                        assert!(
                            (a - b).abs() <= 1e-12 * b.abs().max(1.0),
                            "{}: {a} vs {b}",
                            model.name
                        );
                    }
                }
            }
        }
    }

    /// `Sᵢ · Fⱼ` for every speed `i` and each `j` from it to before its
    /// `end` in both `[i][j]` and `[j][i]` of the `n × n` matrix: `M` as
    /// the runtime's loop computes it.
    fn paired(speeds: &[SpeedVectors], n: usize, pool: &mut Pool) -> Vec<Vec<ExprId>> {
        let mut m = vec![vec![pool.zero(); n]; n];
        for (i, own) in speeds.iter().enumerate() {
            for other in &speeds[i..own.end] {
                let entry = dot6(pool, &own.vectors[0], &other.vectors[1]);
                m[own.speed][other.speed] = entry;
                m[other.speed][own.speed] = entry;
            }
        }
        m
    }
}
