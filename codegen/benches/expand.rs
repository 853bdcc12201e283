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

/// The seed systems: the model files of `generated/models`.
const SEEDS: [(&str, &str); 3] = [
    (
        "seed1_double_pendulum",
        include_str!("../../generated/models/double_pendulum.dal"),
    ),
    (
        "seed2_rotating_bar",
        include_str!("../../generated/models/rotating_bar.dal"),
    ),
    (
        "seed3_constrained_pendulum",
        include_str!("../../generated/models/constrained_pendulum.dal"),
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
