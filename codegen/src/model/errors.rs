//! Diagnostics collected while checking, reported together at the end (the
//! habit of serde_derive's `Ctxt`): one mistake does not hide the next.

use std::fmt::Display;

use crate::language::ast::SpanRange;

/// Accumulates spanned errors.
#[derive(Default)]
pub struct Errors {
    first: Option<syn::Error>,
}

impl Errors {
    /// Records an error at `at`: a token's span, or the range of an
    /// expression.
    pub fn push(&mut self, at: impl Into<SpanRange>, message: impl Display) {
        let error = at.into().error(message);
        match &mut self.first {
            Some(first) => first.combine(error),
            None => self.first = Some(error),
        }
    }

    /// `Ok(value)` if no error was recorded, else all of them.
    pub fn finish<T>(self, value: T) -> syn::Result<T> {
        match self.first {
            Some(error) => Err(error),
            None => Ok(value),
        }
    }
}
