//! Expansion time of the engine on the three seed systems.
//!
//! * `expand/<seed>`: [`dalembert_codegen::expand`] on the system's tokens,
//!   what the `dalembert!` macro calls (the macro crate is this one call).
//!   The tokens are lexed once, outside the measurement; each iteration
//!   expands a fresh clone of them.
//! * `generate/<seed>`: [`dalembert_codegen::generate`] on the system's text,
//!   what a build script calls: lexing, the same pipeline, then parsing the
//!   output with syn and formatting it with prettyplease.
//!
//! Outside a procedural macro, proc-macro2 uses its own token types instead
//! of the compiler's, so these times leave out the compiler's token bridge.
//! Run with `cargo bench -p dalembert-codegen --bench expand`; see
//! BENCHMARKS.md.

use std::hint::black_box;

use criterion::{BatchSize, Criterion, criterion_group, criterion_main};
use proc_macro2::TokenStream;

/// The seed systems, written exactly as in tests/seed_examples.rs.
const SEEDS: [(&str, &str); 3] = [
    (
        "seed1_double_pendulum",
        r"
/// Seed example 1: double pendulum, absolute angles from the downward vertical.
pub DoublePendulum {
    parameters m, L, g;
    coordinates theta1, theta2;
    frame B1 = N.rotate_z(theta1);
    frame B2 = N.rotate_z(theta2);
    point P1 = O - L * B1.y;
    point G1 = O - L/2 * B1.y;
    point G2 = P1 - L/2 * B2.y;
    body link1 { mass: m, center: G1, frame: B1, inertia: [0, 0, m*L^2/12] };
    body link2 { mass: m, center: G2, frame: B2, inertia: [0, 0, m*L^2/12] };
    gravity -g * N.y;
}
",
    ),
    (
        "seed2_rotating_bar",
        r"
/// Seed example 2: a bar on a rotating massless frame, two motors.
pub RotatingBar {
    parameters m, l, d;
    coordinates phi, theta;
    inputs M_phi, M_theta;
    frame F = N.rotate_z(phi);
    frame B = F.rotate_y(theta);
    point G = O + d * F.y;
    body bar { mass: m, center: G, frame: B, inertia: [0, m*l^2/12, m*l^2/12] };
    torque M_phi * N.z on F;
    torque M_theta * F.y on B reacting F;
}
",
    ),
    (
        "seed3_constrained_pendulum",
        r"
/// Seed example 3: pendulum in dependent coordinates.
pub ConstrainedPendulum {
    parameters m, l, g;
    coordinates x, y, theta;
    inputs M;
    frame B = N.rotate_z(theta);
    point G = O + x * N.x + y * N.y;
    body bar { mass: m, center: G, frame: B, inertia: [0, 0, m*l^2/12] };
    gravity -g * N.y;
    torque M * N.z on B;
    constraint x - l/2 * sin(theta) == 0;
    constraint y + l/2 * cos(theta) == 0;
}
",
    ),
];

fn expand(c: &mut Criterion) {
    let mut group = c.benchmark_group("expand");
    for (name, source) in SEEDS {
        let tokens: TokenStream = source.parse().expect("seed system lexes");
        let output = dalembert_codegen::expand(tokens.clone()).to_string();
        assert!(
            !output.contains("compile_error"),
            "{name} expands with errors: {output}"
        );
        group.bench_function(name, |b| {
            b.iter_batched(
                || tokens.clone(),
                |tokens| dalembert_codegen::expand(black_box(tokens)),
                BatchSize::SmallInput,
            )
        });
    }
    group.finish();
}

fn generate(c: &mut Criterion) {
    let mut group = c.benchmark_group("generate");
    for (name, source) in SEEDS {
        dalembert_codegen::generate(source).expect("seed system generates");
        group.bench_function(name, |b| {
            b.iter(|| dalembert_codegen::generate(black_box(source)))
        });
    }
    group.finish();
}

criterion_group!(benches, expand, generate);
criterion_main!(benches);
