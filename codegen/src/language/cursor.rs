//! A cursor over one level of token trees (the contents of one group), and
//! the "expected ..., found ..." errors that point at its current token.
//!
//! Groups are single tokens here; parsing a group's contents means opening
//! a new cursor on it with [`Cursor::group`], which knows the closing
//! delimiter so that running out of tokens points at it.

use super::keyword::Symbol;
use std::fmt::Display;

use proc_macro2::{Delimiter, Group, Ident, Punct, Spacing, Span, TokenStream, TokenTree};

/// The tokens of one group (or of the whole input) and a position in them.
#[derive(Clone)]
pub struct Cursor {
    tokens: Vec<TokenTree>,
    position: usize,
    /// Where an error about running out of tokens points.
    end_span: Span,
    /// How such an error names the end: "`}`", "end of input", ...
    end_name: &'static str,
}

impl Cursor {
    /// A cursor over a whole input; its end is reported as "end of input"
    /// at `end_span`.
    pub fn new(input: TokenStream, end_span: Span) -> Self {
        Cursor {
            tokens: input.into_iter().collect(),
            position: 0,
            end_span,
            end_name: "end of input",
        }
    }

    /// A cursor over the contents of `group`; its end is the closing
    /// delimiter.
    pub fn group(group: &Group) -> Self {
        Cursor {
            tokens: group.stream().into_iter().collect(),
            position: 0,
            end_span: group.span_close(),
            end_name: closing_delimiter(group.delimiter()),
        }
    }

    /// The current token, if any.
    pub fn peek(&self) -> Option<&TokenTree> {
        self.tokens.get(self.position)
    }

    /// The token after the current one, if any.
    fn peek_second(&self) -> Option<&TokenTree> {
        self.tokens.get(self.position + 1)
    }

    /// `true` when every token has been consumed.
    pub fn is_end(&self) -> bool {
        self.position >= self.tokens.len()
    }

    /// Consumes and returns the current token.
    pub fn next_token(&mut self) -> Option<TokenTree> {
        let token = self.peek().cloned();
        if token.is_some() {
            self.position += 1;
        }
        token
    }

    /// The current token if it is the punctuation `ch`.
    pub fn peek_punct(&self, ch: char) -> Option<&Punct> {
        match self.peek() {
            Some(TokenTree::Punct(punct)) if punct.as_char() == ch => Some(punct),
            _ => None,
        }
    }

    /// Consumes the punctuation `ch` and returns its span, if it is the
    /// current token.
    pub fn eat_punct(&mut self, ch: char) -> Option<Span> {
        let span = self.peek_punct(ch)?.span();
        self.position += 1;
        Some(span)
    }

    /// Consumes `==` (a joint `=` followed by `=`) and returns its span.
    pub fn eat_double_equals(&mut self) -> Option<Span> {
        let first = self
            .peek_punct('=')
            .filter(|p| p.spacing() == Spacing::Joint)?;
        let first = first.span();
        let second = match self.peek_second() {
            Some(TokenTree::Punct(punct)) if punct.as_char() == '=' => punct.span(),
            _ => return None,
        };
        self.position += 2;
        Some(super::ast::join(first, second))
    }

    /// The current token if it is an identifier.
    pub fn peek_ident(&self) -> Option<&Ident> {
        match self.peek() {
            Some(TokenTree::Ident(ident)) => Some(ident),
            _ => None,
        }
    }

    /// Consumes the current token if it is an identifier.
    pub fn eat_ident(&mut self) -> Option<Ident> {
        let ident = self.peek_ident()?.clone();
        self.position += 1;
        Some(ident)
    }

    /// Consumes the identifier `keyword` if it is the current token.
    pub fn eat_keyword(&mut self, keyword: Symbol) -> Option<Ident> {
        if self.peek_ident()? == keyword {
            self.eat_ident()
        } else {
            None
        }
    }

    /// Consumes the current token if it is a group delimited by `delimiter`.
    pub fn eat_group(&mut self, delimiter: Delimiter) -> Option<Group> {
        match self.peek() {
            Some(TokenTree::Group(group)) if group.delimiter() == delimiter => {
                let group = group.clone();
                self.position += 1;
                Some(group)
            }
            _ => None,
        }
    }

    /// Consumes an identifier, or reports "expected {what}, found ...".
    pub fn expect_ident(&mut self, what: impl Display) -> syn::Result<Ident> {
        self.eat_ident().ok_or_else(|| self.expected(what))
    }

    /// Consumes the punctuation `ch`, or reports "expected {what}, found ...".
    pub fn expect_punct(&mut self, ch: char, what: impl Display) -> syn::Result<Span> {
        self.eat_punct(ch).ok_or_else(|| self.expected(what))
    }

    /// Consumes the identifier `keyword`, or reports "expected {what},
    /// found ...".
    pub fn expect_keyword(&mut self, keyword: Symbol, what: impl Display) -> syn::Result<Ident> {
        self.eat_keyword(keyword).ok_or_else(|| self.expected(what))
    }

    /// Consumes tokens up to and including the next punctuation `ch` (or to
    /// the end): the recovery after an error.
    pub fn skip_past(&mut self, ch: char) {
        while let Some(token) = self.next_token() {
            if matches!(&token, TokenTree::Punct(punct) if punct.as_char() == ch) {
                return;
            }
        }
    }

    /// How an error names the end of this cursor's tokens: "`)`", "`}`",
    /// "end of input", ...
    pub fn end_name(&self) -> &'static str {
        self.end_name
    }

    /// The span of the current token, or of the end.
    fn span(&self) -> Span {
        self.peek().map_or(self.end_span, TokenTree::span)
    }

    /// The current token as an error message names it: "`frame`", "`;`",
    /// "`(`", or the end ("`}`", "end of input").
    pub fn found(&self) -> String {
        match self.peek() {
            None => self.end_name.to_owned(),
            Some(TokenTree::Group(group)) => match group.delimiter() {
                Delimiter::Parenthesis => "`(`".to_owned(),
                Delimiter::Bracket => "`[`".to_owned(),
                Delimiter::Brace => "`{`".to_owned(),
                Delimiter::None => format!("`{}`", group.stream()),
            },
            Some(token) => format!("`{token}`"),
        }
    }

    /// "expected {what}, found {current token}", pointing at the current
    /// token.
    pub fn expected(&self, what: impl Display) -> syn::Error {
        self.error(format!("expected {what}, found {}", self.found()))
    }

    /// An error with `message`, pointing at the current token.
    pub fn error(&self, message: impl Display) -> syn::Error {
        syn::Error::new(self.span(), message)
    }
}

/// How an error names the end of a group's contents.
fn closing_delimiter(delimiter: Delimiter) -> &'static str {
    match delimiter {
        Delimiter::Parenthesis => "`)`",
        Delimiter::Bracket => "`]`",
        Delimiter::Brace => "`}`",
        Delimiter::None => "the end of the group",
    }
}
