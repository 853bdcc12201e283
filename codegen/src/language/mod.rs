//! The language layer: tokens of `dalembert! { ... }` (or a `.dal` file) to
//! a syntax tree with spans. Parsing reports every syntax error it can
//! recover from, never panics, and gives no meaning to names.

pub mod ast;
mod cursor;
mod expression;
pub mod keyword;
mod parse;
#[cfg(test)]
mod render;

pub use parse::parse_system;
