//! `mass_matrix`: its entries unrolled, or, for a tree whose unrolled `M`
//! is large, two vectors a speed in straight-line code whose dot products
//! a loop of the runtime takes (see `equations::tree_mass`), the armatures
//! added to its diagonal after.

use super::{Argument, Body, Function, SpeedTree, Value};
use crate::equations::{Equations, tree_mass};
use crate::expr::Pool;
use crate::model::Model;
use crate::plan::MassMatrix;

/// The docs of `mass_matrix`.
const DOCS: &str = "The mass matrix `M(q)` (symmetric, positive definite where the\n\
                    coordinates are independent).";

/// `mass_matrix(q)`: by the route the plan chose, a tree's
/// [`MassMatrix::Looped`] returning each speed's vectors for the runtime's
/// loop.
pub fn mass_matrix(
    model: &Model,
    equations: &Equations,
    pool: &mut Pool,
    route: MassMatrix,
) -> Function {
    let nv = model.nv();
    let unrolled = || {
        Function::new(
            "mass_matrix",
            DOCS,
            &[Argument::Coordinates],
            Value::matrix(&equations.mass_matrix, nv),
        )
    };
    if route == MassMatrix::Unrolled {
        return unrolled();
    }
    let Some(speeds) = tree_mass(equations, pool) else {
        return unrolled();
    };
    let tree = SpeedTree {
        ends: speeds.iter().map(|s| s.end).collect(),
        speeds: speeds.iter().map(|s| s.speed).collect(),
        armature: model.armature.iter().map(|&(speed, _)| speed).collect(),
    };
    let vectors: Vec<Vec<_>> = speeds
        .iter()
        .map(|s| s.vectors.iter().flatten().copied().collect())
        .collect();
    let docs = format!(
        "{DOCS}\n\n\
         By composite rigid bodies, in `N`'s axes about `O`: for each speed\n\
         `j`, the column `Sⱼ` of its joint's motion subspace (`(e, o × e)`\n\
         for a turn about the unit axis `e` through `o`, `(0, e)` for a\n\
         slide) and the momentum `Fⱼ = Iᶜⱼ Sⱼ` of the subtree beyond the\n\
         joint moving at the speed's unit rate, in straight-line code; then\n\
         `Mᵢⱼ = Mⱼᵢ = Sᵢ · Fⱼ` for each speed `i` and each `j` of its subtree\n\
         (`i` itself, its joint's later speeds and its descendants'; the\n\
         other pairs are zero), by a loop of the runtime over the tree's\n\
         table, depth-first (`dalembert::__private::tree_mass_matrix`); the\n\
         armatures, if any, then added to the diagonal."
    );
    let mut function = Function::new(
        "mass_matrix",
        &docs,
        &[Argument::Coordinates],
        Value::matrix(&vectors, 12),
    );
    if !model.armature.is_empty() {
        let armature = model.armature.iter().map(|&(_, value)| value).collect();
        function.results.push(Value::vector(armature));
    }
    Function {
        body: Body::MassPairs(tree),
        ..function
    }
}
