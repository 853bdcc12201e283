//! Language errors (and the URDF import's warnings) located in a file and
//! shown the way rustc shows them: message, `path:line:column`, the
//! offending source line and a caret under the offending text.
//!
//! Positions come from the spans of the [`syn::Error`]s the engine returns:
//! outside a procedural macro, `proc-macro2` (with its `span-locations`
//! feature) records where every token of a parsed string came from.

use std::fmt;
use std::path::{Path, PathBuf};

/// One error (or warning) in a model file, with its position when it points
/// at text of the file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Diagnostic {
    path: PathBuf,
    severity: Severity,
    message: String,
    location: Option<Location>,
}

/// Whether a [`Diagnostic`] stops the build.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Severity {
    /// Nothing is written.
    Error,
    /// The output is written; the user should know (a URDF file's inertia
    /// that no mass distribution has, say).
    Warning,
}

/// Where in the file a [`Diagnostic`] points.
#[derive(Clone, Debug, PartialEq, Eq)]
struct Location {
    /// 1-based line number.
    line: usize,
    /// 1-based column, counted in characters.
    column: usize,
    /// The whole line the error starts on, without its line break.
    text: String,
    /// Characters to underline, at least 1, at most to the end of the line.
    width: usize,
}

impl Diagnostic {
    /// One diagnostic per message of `error`, located in `source`, the text
    /// the erroneous tokens were parsed from, read from `path`.
    pub(crate) fn from_syn(path: &Path, source: &str, error: syn::Error) -> Vec<Self> {
        error
            .into_iter()
            .map(|e| Diagnostic {
                path: path.to_owned(),
                severity: Severity::Error,
                message: e.to_string(),
                location: locate(source, e.span()),
            })
            .collect()
    }

    /// A diagnostic for text read from `path` that is not in the macro's
    /// language (a URDF file): `message` at the bytes `range` of `source`,
    /// or at the whole file when `range` is `None`.
    pub(crate) fn in_text(
        path: &Path,
        source: &str,
        severity: Severity,
        range: Option<std::ops::Range<usize>>,
        message: String,
    ) -> Self {
        Diagnostic {
            path: path.to_owned(),
            severity,
            message,
            location: range.and_then(|r| locate_range(source, r)),
        }
    }

    /// The model file.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Whether it is an error or a warning.
    pub fn severity(&self) -> Severity {
        self.severity
    }

    /// What is wrong (and what is expected).
    pub fn message(&self) -> &str {
        &self.message
    }

    /// The 1-based line the error starts on, if it points at text.
    pub fn line(&self) -> Option<usize> {
        self.location.as_ref().map(|l| l.line)
    }

    /// The 1-based column (in characters) the error starts at, if it points
    /// at text.
    pub fn column(&self) -> Option<usize> {
        self.location.as_ref().map(|l| l.column)
    }
}

/// The position of `span` in `source`, or `None` if the span does not point
/// into it (a call-site span, or tokens made up by the engine).
fn locate(source: &str, span: proc_macro2::Span) -> Option<Location> {
    // A span with no source text is a call-site span: it has no position.
    span.source_text()?;
    locate_range(source, span.byte_range())
}

/// The position of the bytes `range` in `source`, or `None` if they are
/// not in it.
fn locate_range(source: &str, range: std::ops::Range<usize>) -> Option<Location> {
    let start = range.start;
    if range.end > source.len() || !source.is_char_boundary(start) {
        return None;
    }
    let line_start = source[..start].rfind('\n').map_or(0, |i| i + 1);
    let line_end = source[start..]
        .find('\n')
        .map_or(source.len(), |i| start + i);
    let text = source[line_start..line_end].trim_end_matches('\r');
    let before = source[line_start..start].chars().count();
    let end = range.end.clamp(start, line_start + text.len());
    let width = source
        .get(start..end)
        .map_or(0, |s| s.chars().count())
        .max(1);
    Some(Location {
        line: source[..start].matches('\n').count() + 1,
        column: before + 1,
        text: text.to_owned(),
        width,
    })
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let label = match self.severity {
            Severity::Error => "error",
            Severity::Warning => "warning",
        };
        writeln!(f, "{label}: {}", self.message)?;
        let Some(l) = &self.location else {
            return write!(f, "  --> {}", self.path.display());
        };
        let gutter = " ".repeat(l.line.to_string().len());
        // Tabs stay tabs under the line so the caret lines up in any terminal.
        let indent: String = l
            .text
            .chars()
            .take(l.column - 1)
            .map(|c| if c == '\t' { '\t' } else { ' ' })
            .collect();
        writeln!(
            f,
            "{gutter}--> {}:{}:{}",
            self.path.display(),
            l.line,
            l.column
        )?;
        writeln!(f, "{gutter} |")?;
        writeln!(f, "{} | {}", l.line, l.text)?;
        write!(f, "{gutter} | {indent}{}", "^".repeat(l.width))
    }
}
