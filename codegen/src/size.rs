//! How big the emitted functions will be, and the guard that refuses a
//! model whose largest function rustc could not compile in reasonable time
//! and memory (or at all: its stack overflows on very long straight-line
//! bodies), before anything is emitted.

use crate::expr::Pool;
use crate::model::Model;
use crate::outputs::Function;
use crate::plan::cost::operations;

/// The largest estimated operation count of one generated function that a
/// model may have: `250 000`. Measured with rustc 1.95 in a debug build on
/// a shared two-core machine (`docs/reliability.md`): one straight-line
/// function of 100 000 operations takes 112 s and 0.55 GB to compile, one
/// of 400 000 takes 279 s and 1.95 GB (memory grows by about 5 KB an
/// operation). The limit keeps a function under about three minutes and
/// 1.2 GB, forty times the largest function of the repository's models
/// (about 6 000: the spatial chain of 30 links' kinetic energy).
pub const OPERATION_LIMIT: usize = 250_000;

/// One generated function's estimated size.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FunctionSize {
    /// The function's name (`mass_matrix`, `forcing`, …).
    pub name: String,
    /// Its arithmetic operations and elementary functions, each shared
    /// subexpression counted once (the engine's cost model).
    pub operations: usize,
}

/// The estimated size of each of `functions`, in order.
pub(crate) fn sizes(pool: &Pool, functions: &[Function]) -> Vec<FunctionSize> {
    functions
        .iter()
        .map(|function| {
            let roots: Vec<_> = function
                .results
                .iter()
                .flat_map(|value| value.expressions.iter().copied())
                .collect();
            FunctionSize {
                name: function.name.to_string(),
                operations: operations(pool, &roots),
            }
        })
        .collect()
}

/// An error at the model's name if its largest function exceeds
/// [`OPERATION_LIMIT`], saying how large and what to do.
pub(crate) fn check_size(model: &Model, sizes: &[FunctionSize]) -> syn::Result<()> {
    let Some(largest) = sizes.iter().max_by_key(|size| size.operations) else {
        return Ok(());
    };
    if largest.operations <= OPERATION_LIMIT {
        return Ok(());
    }
    Err(syn::Error::new(
        model.name.span(),
        format!(
            "this model is too large to compile: its largest generated function, `{}`, \
             has about {} operations (the limit is {OPERATION_LIMIT}), more than rustc \
             compiles in reasonable time and memory; ask for fewer outputs \
             (`accelerations_jacobian` and `linearize` grow fastest with the links), or \
             write the mechanism as a tree of `joint` statements (the looped tree route: \
             its mass matrix and derivatives are computed by loops over the links at run \
             time instead of unrolled)",
            largest.name, largest.operations
        ),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::language::parse_system;
    use crate::model::resolve;
    use crate::seeds::DOUBLE_PENDULUM;

    #[test]
    fn a_model_over_the_limit_is_refused_with_its_largest_function_and_what_to_do() {
        let system = parse_system(DOUBLE_PENDULUM.parse().unwrap()).unwrap();
        let (model, _) = resolve(&system).unwrap();
        let size = |name: &str, operations| FunctionSize {
            name: name.into(),
            operations,
        };
        let within = [size("mass_matrix", 10), size("forcing", OPERATION_LIMIT)];
        assert!(check_size(&model, &within).is_ok());
        let over = [
            size("mass_matrix", 10),
            size("linearize", OPERATION_LIMIT + 1),
        ];
        let message = check_size(&model, &over).unwrap_err().to_string();
        let count = (OPERATION_LIMIT + 1).to_string();
        let parts = [
            "too large to compile",
            "`linearize`",
            count.as_str(),
            "fewer outputs",
            "looped tree route",
        ];
        for part in parts {
            assert!(message.contains(part), "{part}: {message}");
        }
    }
}
