//! Compile-fail UI tests of the `dalembert!` macro: `tests/ui/<category>/`
//! holds one file per diagnostic and, beside it, the compiler output it
//! must give (`.stderr`), so that every message and the token it points at
//! are reviewed like code. Run them with `cargo test -p dalembert-ui`;
//! regenerate the expected output with `TRYBUILD=overwrite` and review the
//! diff.
//!
//! The crate has no items: it exists to keep the dependency tree that
//! trybuild rebuilds small (the macro crate only).

#![warn(missing_docs, rust_2018_idioms, unused_qualifications)]
