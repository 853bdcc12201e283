//! The `dalembert!` procedural macro: a thin front door over
//! [`dalembert_codegen`], which parses the system description, derives its
//! equations of motion with d'Alembert's principle and emits them as flat
//! Rust. Errors become `compile_error!`s at the offending tokens.
//!
//! Use it through the `dalembert` crate, which re-exports it with the
//! runtime the generated code implements.

#![deny(missing_docs)]
#![warn(rust_2018_idioms, unused_qualifications)]

use proc_macro::TokenStream;

/// Derives the equations of motion of a mechanical system at compile time.
///
/// ```ignore
/// dalembert::dalembert! {
///     /// A simple pendulum.
///     pub Pendulum {
///         parameters m, l, g;
///         coordinates theta;
///         frame B = N.rotate_z(theta);
///         particle bob { mass: m, at: O - l * B.y };
///         gravity -g * N.y;
///     }
/// }
/// ```
///
/// expands into `pub struct Pendulum { pub m: f64, pub l: f64, pub g: f64 }`
/// with `mass_matrix`, `forcing`, `kinetic_energy` and `potential_energy`
/// (and, with constraints, `constraint_jacobian`, `constraint_bias` and
/// `constraint_residual`). The language is described in the `dalembert`
/// crate's documentation.
#[proc_macro]
pub fn dalembert(input: TokenStream) -> TokenStream {
    dalembert_codegen::expand(input.into()).into()
}
