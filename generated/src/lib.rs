//! Systems generated at build time from the `.dal` models in `models/`, one
//! module each: `build.rs` runs [`dalembert_codegen::Builder`] on every
//! `models/NAME.dal` and writes `NAME.rs` into `OUT_DIR`, included here.
//!
//! The generated source is reviewed through the insta snapshots in
//! `tests/snapshots/`: a change to a model or to the derivation shows up as
//! a snapshot diff (`cargo insta test`).
//!
//! [`dalembert_codegen::Builder`]: https://docs.rs/dalembert-codegen

#![warn(missing_docs, rust_2018_idioms, unused_qualifications)]

/// Includes the file generated from `models/$name.dal` as module `$name`,
/// under clippy's pedantic and nursery lints too: a generated file must
/// compile in a user's crate that denies them, as the macro's expansion does.
macro_rules! model {
    ($(#[$doc:meta])* $name:ident) => {
        $(#[$doc])*
        #[warn(clippy::pedantic, clippy::nursery)]
        pub mod $name {
            include!(concat!(env!("OUT_DIR"), "/", stringify!($name), ".rs"));
        }
    };
}

// Seed examples, as docs/language.md writes them.
model!(
    /// Seed example 1: double pendulum, absolute angles.
    double_pendulum
);
model!(
    /// Seed example 2: a bar on a rotating massless frame, two motors.
    rotating_bar
);
model!(
    /// Seed example 3: pendulum in dependent coordinates (Lagrange multipliers).
    constrained_pendulum
);
model!(
    /// A brick turning freely on a ball joint (the Dzhanibekov effect).
    dzhanibekov
);
model!(
    /// A two-link arm asking for the control outputs (kinematics, inverse
    /// dynamics, regressor).
    two_link_arm
);

// Systems asking for `outputs taylor;` (the Taylor integrator's tests and
// work-precision charts).
model!(
    /// Seed example 1 with the Taylor coefficients of its motion.
    taylor_double_pendulum
);
model!(
    /// A mass on a linear spring with the Taylor coefficients of its motion.
    taylor_oscillator
);
model!(
    /// A torque-free symmetric body in Euler angles (free precession) with
    /// the Taylor coefficients of its motion.
    taylor_top
);
model!(
    /// A particle in a potential of every elementary function, damped and
    /// driven, with the Taylor coefficients of its motion.
    taylor_functions
);
model!(
    /// Seed example 3 (constrained) with the Taylor coefficients of its
    /// motion.
    taylor_constrained_pendulum
);
model!(
    /// A torque-free symmetric body on a ball joint (a quaternion, speeds
    /// that are not rates) with the Taylor coefficients of its motion.
    taylor_ball_top
);

// Benchmark chains: `models/{planar,spatial}_chain_NN.dal`, written by
// `dalembert chain FAMILY N` (`dalembert_codegen::chain::chain`); tests/chains.rs checks
// them against that generator and against tests/reference/chains.json.
model!(
    /// The planar chain of 1 link.
    planar_chain_01
);
model!(
    /// The planar chain of 2 links.
    planar_chain_02
);
model!(
    /// The planar chain of 3 links.
    planar_chain_03
);
model!(
    /// The planar chain of 4 links.
    planar_chain_04
);
model!(
    /// The planar chain of 5 links.
    planar_chain_05
);
model!(
    /// The planar chain of 6 links.
    planar_chain_06
);
model!(
    /// The planar chain of 12 links.
    planar_chain_12
);
model!(
    /// The planar chain of 30 links.
    planar_chain_30
);
model!(
    /// The spatial chain of 1 link.
    spatial_chain_01
);
model!(
    /// The spatial chain of 2 links.
    spatial_chain_02
);
model!(
    /// The spatial chain of 3 links.
    spatial_chain_03
);
model!(
    /// The spatial chain of 4 links.
    spatial_chain_04
);
model!(
    /// The spatial chain of 5 links.
    spatial_chain_05
);
model!(
    /// The spatial chain of 6 links.
    spatial_chain_06
);
model!(
    /// The spatial chain of 12 links.
    spatial_chain_12
);
model!(
    /// The spatial chain of 30 links.
    spatial_chain_30
);
model!(
    /// A branching tree of 14 links, one joint a slide.
    spatial_tree_14
);

// The 60-link chains, with the `large` feature only (generated from
// `dalembert_codegen::chain::chain` by build.rs, for the benches).
#[cfg(feature = "large")]
model!(
    /// The planar chain of 60 links.
    planar_chain_60
);
#[cfg(feature = "large")]
model!(
    /// The spatial chain of 60 links.
    spatial_chain_60
);

// The floating humanoids of `tests/reference/humanoids/`, with the
// `humanoids` feature only (imported by build.rs with their derivatives).
#[cfg(feature = "humanoids")]
model!(
    /// Unitree G1 (29 joints) on a floating base: 36 coordinates, 35 speeds.
    g1
);
#[cfg(feature = "humanoids")]
model!(
    /// PAL Talos (reduced: 32 joints) on a floating base: 39 coordinates, 38 speeds.
    talos_reduced
);

// URDF robots (`tests/reference/urdf/*.urdf`), imported by `Builder::urdf`;
// tests/urdf.rs checks them against Pinocchio.
model!(
    /// Franka Emika Panda: 7 arm joints and 2 prismatic fingers.
    panda
);
model!(
    /// Universal Robots UR5: 6 revolute joints.
    ur5_robot
);
model!(
    /// Solo12 quadruped on a fixed base: 12 revolute joints.
    solo12
);
model!(
    /// A small robot with every feature of the URDF import.
    features
);
model!(
    /// `ANYmal` C quadruped on a fixed base: 12 revolute joints, its fixed
    /// links (four of them with inertias no mass distribution has) welded.
    anymal_c
);
model!(
    /// Solo12 on a floating base (`dalembert urdf solo12.urdf --floating`,
    /// checked in as `models/floating_solo12.dal`): 19 coordinates, 18 speeds.
    floating_solo12
);

// MuJoCo models (`tests/reference/mjcf/dm_control/*.xml`), imported by
// `Builder::mjcf`; tests/mjcf.rs checks them against MuJoCo.
model!(
    /// The half cheetah of the `dm_control` suite: 9 planar coordinates,
    /// springs and armature.
    cheetah
);
model!(
    /// The humanoid of the `dm_control` suite: a free joint and 21 hinges (28 coordinates,
    /// 27 speeds).
    humanoid
);

// The benchmark trees (`trees/*.urdf`, written by
// `dalembert_codegen::testing::Shape`), imported by `Builder::urdf`;
// tests/trees.rs checks the files against the generator.
model!(
    /// A cart carrying an inverted pendulum of one rod.
    cart_pole_1
);
model!(
    /// A cart carrying an inverted pendulum of three rods.
    cart_pole_3
);
model!(
    /// A cart carrying an inverted pendulum of six rods.
    cart_pole_6
);
model!(
    /// A turning torso with four limbs of three rods: 13 joints.
    limbs
);
model!(
    /// A binary tree of 31 rods.
    binary_tree
);

// The same chains in the other two spellings (`dalembert chain FAMILY N symbolic|seed`);
// tests/spellings.rs checks them against Pinocchio's numbers and against each other,
// and `reference()` (written by build.rs) builds each with the reference parameters.
model!(
    /// The planar chain of 2 links spelled with `joint`s with symbolic parameters.
    symbolic_planar_chain_02
);
model!(
    /// The planar chain of 6 links spelled with `joint`s with symbolic parameters.
    symbolic_planar_chain_06
);
model!(
    /// The planar chain of 12 links spelled with `joint`s with symbolic parameters.
    symbolic_planar_chain_12
);
model!(
    /// The planar chain of 30 links spelled with `joint`s with symbolic parameters.
    symbolic_planar_chain_30
);
model!(
    /// The spatial chain of 2 links spelled with `joint`s with symbolic parameters.
    symbolic_spatial_chain_02
);
model!(
    /// The spatial chain of 6 links spelled with `joint`s with symbolic parameters.
    symbolic_spatial_chain_06
);
model!(
    /// The spatial chain of 12 links spelled with `joint`s with symbolic parameters.
    symbolic_spatial_chain_12
);
model!(
    /// The spatial chain of 30 links spelled with `joint`s with symbolic parameters.
    symbolic_spatial_chain_30
);
model!(
    /// The planar chain of 2 links spelled with the seed's frames and points, symbolic parameters, torque inputs.
    seed_planar_chain_02
);
model!(
    /// The planar chain of 6 links spelled with the seed's frames and points, symbolic parameters, torque inputs.
    seed_planar_chain_06
);
model!(
    /// The planar chain of 12 links spelled with the seed's frames and points, symbolic parameters, torque inputs.
    seed_planar_chain_12
);
model!(
    /// The planar chain of 30 links spelled with the seed's frames and points, symbolic parameters, torque inputs.
    seed_planar_chain_30
);
model!(
    /// The spatial chain of 2 links spelled with the seed's frames and points, symbolic parameters, torque inputs.
    seed_spatial_chain_02
);
model!(
    /// The spatial chain of 6 links spelled with the seed's frames and points, symbolic parameters, torque inputs.
    seed_spatial_chain_06
);
model!(
    /// The spatial chain of 12 links spelled with the seed's frames and points, symbolic parameters, torque inputs.
    seed_spatial_chain_12
);
model!(
    /// The spatial chain of 30 links spelled with the seed's frames and points, symbolic parameters, torque inputs.
    seed_spatial_chain_30
);

pub use anymal_c::Anymal;
pub use binary_tree::BinaryTree;
pub use cart_pole_1::CartPole1;
pub use cart_pole_3::CartPole3;
pub use cart_pole_6::CartPole6;
pub use cheetah::Cheetah;
pub use constrained_pendulum::ConstrainedPendulum;
pub use double_pendulum::DoublePendulum;
pub use dzhanibekov::Dzhanibekov;
pub use features::FeatureTree;
pub use floating_solo12::FloatingSolo;
pub use humanoid::Humanoid;
pub use limbs::Limbs;
pub use panda::Panda;
pub use planar_chain_01::PlanarChain1;
pub use planar_chain_02::PlanarChain2;
pub use planar_chain_03::PlanarChain3;
pub use planar_chain_04::PlanarChain4;
pub use planar_chain_05::PlanarChain5;
pub use planar_chain_06::PlanarChain6;
pub use planar_chain_12::PlanarChain12;
pub use planar_chain_30::PlanarChain30;
#[cfg(feature = "large")]
pub use planar_chain_60::PlanarChain60;
pub use rotating_bar::RotatingBar;
pub use seed_planar_chain_02::SeedPlanarChain2;
pub use seed_planar_chain_06::SeedPlanarChain6;
pub use seed_planar_chain_12::SeedPlanarChain12;
pub use seed_planar_chain_30::SeedPlanarChain30;
pub use seed_spatial_chain_02::SeedSpatialChain2;
pub use seed_spatial_chain_06::SeedSpatialChain6;
pub use seed_spatial_chain_12::SeedSpatialChain12;
pub use seed_spatial_chain_30::SeedSpatialChain30;
pub use solo12::Solo;
pub use spatial_chain_01::SpatialChain1;
pub use spatial_chain_02::SpatialChain2;
pub use spatial_chain_03::SpatialChain3;
pub use spatial_chain_04::SpatialChain4;
pub use spatial_chain_05::SpatialChain5;
pub use spatial_chain_06::SpatialChain6;
pub use spatial_chain_12::SpatialChain12;
pub use spatial_chain_30::SpatialChain30;
#[cfg(feature = "large")]
pub use spatial_chain_60::SpatialChain60;
pub use symbolic_planar_chain_02::SymbolicPlanarChain2;
pub use symbolic_planar_chain_06::SymbolicPlanarChain6;
pub use symbolic_planar_chain_12::SymbolicPlanarChain12;
pub use symbolic_planar_chain_30::SymbolicPlanarChain30;
pub use symbolic_spatial_chain_02::SymbolicSpatialChain2;
pub use symbolic_spatial_chain_06::SymbolicSpatialChain6;
pub use symbolic_spatial_chain_12::SymbolicSpatialChain12;
pub use symbolic_spatial_chain_30::SymbolicSpatialChain30;
pub use ur5_robot::Ur5;

model!(
    /// A cart-pole asking for its linearisation and derivatives.
    cart_pole
);

/// Copies of some models above asking for the exact derivatives
/// (`outputs accelerations_jacobian, linearize, inverse_dynamics_jacobian,
/// inverse_dynamics_adjoint;`),
/// written and generated by `build.rs`; tests/derivatives.rs checks them.
pub mod derivatives {
    /// Includes the file generated from `derivatives/$name.dal` as module `$name`.
    macro_rules! with_derivatives {
        ($($name:ident),*) => {
            $(
                #[doc = concat!("`", stringify!($name), "` with its derivatives.")]
                #[warn(clippy::pedantic, clippy::nursery)]
                pub mod $name {
                    include!(concat!(env!("OUT_DIR"), "/derivatives/", stringify!($name), ".rs"));
                }
            )*
        };
    }
    with_derivatives!(
        double_pendulum,
        rotating_bar,
        dzhanibekov,
        floating_solo12,
        planar_chain_02,
        planar_chain_06,
        planar_chain_12,
        spatial_chain_02,
        spatial_chain_06,
        spatial_chain_12,
        panda,
        ur5_robot,
        spatial_tree_14
    );
    // The spatial chains of 30 and 60 links asking for
    // `accelerations_jacobian, inverse_dynamics_adjoint` (the adjoint's
    // bench), with the `large` feature only.
    #[cfg(feature = "large")]
    with_derivatives!(spatial_chain_30, spatial_chain_60);
}

/// Calls `$callback!` with the chains and robots of [`derivatives`], as
/// `module::System` paths (what the derivatives' tests and bench compare
/// with Pinocchio).
#[macro_export]
macro_rules! chains_and_robots_with_derivatives {
    ($callback:ident) => {
        $callback!(
            planar_chain_02::PlanarChain2,
            planar_chain_06::PlanarChain6,
            planar_chain_12::PlanarChain12,
            spatial_chain_02::SpatialChain2,
            spatial_chain_06::SpatialChain6,
            spatial_chain_12::SpatialChain12,
            panda::Panda,
            ur5_robot::Ur5,
        )
    };
}

pub use cart_pole::CartPole;

// `reference()` of every symbolic chain: its parameters at the reference values.
include!(concat!(env!("OUT_DIR"), "/chain_references.rs"));

/// Copies of some models above asking for `accelerations_x4` (four states
/// at once, in SIMD lanes), written and generated by `build.rs`;
/// tests/suite/lanes.rs checks them against the scalar `accelerations`.
pub mod lanes {
    /// Includes the file generated from `lanes/$name.dal` as module `$name`.
    macro_rules! with_lanes {
        ($($name:ident),*) => {
            $(
                #[doc = concat!("`", stringify!($name), "` with `accelerations_x4`.")]
                #[warn(clippy::pedantic, clippy::nursery)]
                pub mod $name {
                    include!(concat!(env!("OUT_DIR"), "/lanes/", stringify!($name), ".rs"));
                }
            )*
        };
    }
    with_lanes!(
        double_pendulum,
        dzhanibekov,
        taylor_functions,
        planar_chain_06,
        spatial_chain_06,
        spatial_chain_12,
        spatial_chain_30,
        floating_solo12,
        panda,
        ur5_robot
    );
}
