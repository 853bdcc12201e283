//! The looped form of the chains' forward dynamics
//! (`dalembert_fixtures::looped`: the articulated-body loops over a table of
//! per-link constants read from the model's kinematics) against the
//! generated, unrolled `accelerations` (the engine's derivation, folded and
//! unrolled): two independent computations of the same dynamics, at random
//! states, both families, n = 6, 12, 30 (and 60 with the `large` feature).

use dalembert::{DynamicsError, MultibodySystem};
use dalembert_codegen::testing::{Family, chain};
use dalembert_fixtures::looped::Chain;
use dalembert_fixtures::reference::assert_close;
use dalembert_fixtures::states::states;
use dalembert_generated::*;

/// Relative tolerance on `q̈`, as against Pinocchio (`M` gets
/// ill-conditioned with `n`).
const TOLERANCE: f64 = 1e-10;

/// The random states compared per chain.
const STATES: usize = 50;

/// The generated `accelerations` method of a system.
type Accelerations<S, const N: usize> =
    fn(&S, f64, &[f64; N], &[f64; N], &[f64; 0]) -> Result<[f64; N], DynamicsError>;

/// The looped form of `family`'s chain of `N` links against `system`'s
/// generated `unrolled` accelerations.
fn agree<S: MultibodySystem<N, N, 0>, const N: usize>(
    family: Family,
    system: S,
    unrolled: Accelerations<S, N>,
) {
    let looped = Chain::<N>::of_model(&chain(family, N));
    for (index, s) in states::<N, 0>(N as u64).iter().take(STATES).enumerate() {
        let expected = unrolled(&system, s.t, &s.q, &s.v, &s.u).expect("a solvable state");
        let what = format!("{} chain of {N}, state {index}", family.name());
        assert_close(
            &what,
            &looped.accelerations(&s.q, &s.v),
            &expected,
            TOLERANCE,
        );
    }
}

#[test]
fn planar_chains_agree() {
    agree(Family::Planar, PlanarChain6 {}, PlanarChain6::accelerations);
    agree(
        Family::Planar,
        PlanarChain12 {},
        PlanarChain12::accelerations,
    );
    agree(
        Family::Planar,
        PlanarChain30 {},
        PlanarChain30::accelerations,
    );
    #[cfg(feature = "large")]
    agree(
        Family::Planar,
        PlanarChain60 {},
        PlanarChain60::accelerations,
    );
}

#[test]
fn spatial_chains_agree() {
    agree(
        Family::Spatial,
        SpatialChain6 {},
        SpatialChain6::accelerations,
    );
    agree(
        Family::Spatial,
        SpatialChain12 {},
        SpatialChain12::accelerations,
    );
    agree(
        Family::Spatial,
        SpatialChain30 {},
        SpatialChain30::accelerations,
    );
    #[cfg(feature = "large")]
    agree(
        Family::Spatial,
        SpatialChain60 {},
        SpatialChain60::accelerations,
    );
}
