//! How big the engine's work and the emitted functions will be, and the
//! two guards: one refuses, before derivation, a model whose derivation
//! the engine would spend minutes on; the other, before emission, a model
//! whose largest function rustc could not compile in reasonable time and
//! memory (or at all: its stack overflows on very long straight-line
//! bodies).

use crate::expr::Pool;
use crate::model::{Model, OutputKind};
use crate::outputs::Function;
use crate::plan::cost::operations;

/// The largest estimated derivation a model may ask for, in the units of
/// [`DerivationEstimate::units`]: `1 000 000`, about 52 s of the engine's
/// CPU time by the fit below, about a minute measured. Measured with
/// `dalembert check --stats` (the engine at `opt-level = 2`, as the
/// workspace builds it for the macro) on the seed-spelled spatial chain
/// with `outputs accelerations_jacobian, linearize` (`docs/reliability.md`):
/// 0.31 s of CPU at 20 links, 1.6 s at 40, 4.1 s at 60, 8.9 s at 80, 15.0 s
/// at 100, 40.6 s at 140, 132 s and 2.7 GB at 200. `5.2e-5 s` a unit is
/// within 25 % of each of those up to 140 links, of the chain without
/// outputs (0.58 s at 40 links, 3.9 s at 80) and of the floating G1
/// humanoid (35 speeds: 0.27 s without outputs, 1.5 s with every output),
/// but 33 % under at 200 links, where the growth steepens. The limit falls
/// at 162 speeds with derivatives asked for (the 200-link chain is
/// refused), 251 without.
pub const DERIVATION_LIMIT: f64 = 1.0e6;

/// Seconds of the engine's CPU time a unit of [`DerivationEstimate::units`]
/// took where [`DERIVATION_LIMIT`] was measured.
const SECONDS_PER_UNIT: f64 = 5.2e-5;

/// The outputs whose derivation grows fastest with the speeds: the
/// partial derivatives of the dynamics (`linearize` through
/// `accelerations_jacobian`'s).
const DERIVATIVE_OUTPUTS: [OutputKind; 3] = [
    OutputKind::AccelerationsJacobian,
    OutputKind::Linearize,
    OutputKind::InverseDynamicsJacobian,
];

/// A cheap estimate of the engine's work on a model, from its number of
/// speeds and the outputs it asks for, before anything is derived.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DerivationEstimate {
    /// The model's speeds `n`.
    pub speeds: usize,
    /// Whether it asks for partial derivatives of the dynamics
    /// (`accelerations_jacobian`, `linearize`, `inverse_dynamics_jacobian`).
    pub derivatives: bool,
    /// `n^2.5`, three times that with derivatives: the measured growth of
    /// the derivation's time (the exponent of the seed-spelled chain's
    /// times between 20 and 80 links is 2.4 to 2.8).
    pub units: f64,
}

impl DerivationEstimate {
    /// The estimate for `model`.
    pub(crate) fn of(model: &Model) -> DerivationEstimate {
        let derivatives = model
            .outputs
            .iter()
            .any(|output| DERIVATIVE_OUTPUTS.contains(&output.kind));
        DerivationEstimate::new(model.nv(), derivatives)
    }

    /// The estimate for `speeds` speeds, with or without derivatives.
    fn new(speeds: usize, derivatives: bool) -> DerivationEstimate {
        let factor = if derivatives { 3.0 } else { 1.0 };
        DerivationEstimate {
            speeds,
            derivatives,
            units: factor * (speeds as f64).powf(2.5),
        }
    }

    /// The seconds of CPU time the units took where [`DERIVATION_LIMIT`]
    /// was measured.
    pub fn seconds(&self) -> f64 {
        self.units * SECONDS_PER_UNIT
    }
}

/// An error at the model's name if its derivation is estimated over
/// [`DERIVATION_LIMIT`], saying the estimate and what to do.
pub(crate) fn check_derivation(model: &Model) -> syn::Result<()> {
    check_estimate(model, DerivationEstimate::of(model))
}

/// An error at the model's name if `estimate` is over [`DERIVATION_LIMIT`].
fn check_estimate(model: &Model, estimate: DerivationEstimate) -> syn::Result<()> {
    if estimate.units <= DERIVATION_LIMIT {
        return Ok(());
    }
    let asked = if estimate.derivatives {
        "; without `accelerations_jacobian`, `linearize` and `inverse_dynamics_jacobian` it \
         would be a third of that"
    } else {
        ""
    };
    Err(syn::Error::new(
        model.name.span(),
        format!(
            "this model is too large to derive in reasonable time: with {} speeds its \
             derivation is estimated at {:.1e} units (the limit is {DERIVATION_LIMIT:.1e}), \
             about {:.0} s of the engine's time and gigabytes of memory{asked}; ask for fewer \
             outputs, or model fewer speeds (lump links that move together, fix joints that \
             do not move)",
            estimate.speeds,
            estimate.units,
            estimate.seconds(),
        ),
    ))
}

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
        .map(|function| FunctionSize {
            name: function.name.to_string(),
            operations: operations(pool, &function.roots()),
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
    fn a_derivation_over_the_limit_is_refused_before_it_starts() {
        let system = parse_system(DOUBLE_PENDULUM.parse().unwrap()).unwrap();
        let (model, _) = resolve(&system).unwrap();
        let small = DerivationEstimate::of(&model);
        assert_eq!(small, DerivationEstimate::new(2, false));
        assert!((small.units - 2.0_f64.powf(2.5)).abs() < 1e-12);
        assert!(check_derivation(&model).is_ok());
        // The speeds at which derivatives reach the limit: 162.
        let reach = (DERIVATION_LIMIT / 3.0).powf(0.4);
        assert!((reach - 162.0).abs() < 0.5, "{reach}");
        let within = DerivationEstimate::new(reach as usize, true);
        assert!(check_estimate(&model, within).is_ok());
        let over = DerivationEstimate::new(reach as usize + 1, true);
        let message = check_estimate(&model, over).unwrap_err().to_string();
        let speeds = format!("with {} speeds", reach as usize + 1);
        let parts = [
            "too large to derive",
            speeds.as_str(),
            "a third of that",
            "fewer outputs",
            "fewer speeds",
        ];
        for part in parts {
            assert!(message.contains(part), "{part}: {message}");
        }
    }

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
