//! Diagnostics collected while checking, reported together at the end (the
//! habit of serde_derive's `Ctxt`): one mistake does not hide the next.

use proc_macro2::Span;
use std::fmt::Display;

/// Accumulates spanned errors.
#[derive(Default)]
pub struct Errors {
    first: Option<syn::Error>,
}

impl Errors {
    /// Records an error at `span`.
    pub fn push(&mut self, span: Span, message: impl Display) {
        let error = syn::Error::new(span, message);
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
