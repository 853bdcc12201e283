//! Structure-aware mutation of XML robot files, shared by the URDF and MJCF
//! fuzz tests: a deterministic generator, the elements and attributes of a
//! file found by a tolerant scan (mutated files need not be well formed),
//! and the mutations every format gets (an element deleted, duplicated or
//! moved, an attribute replaced by an extreme or malformed value, the file
//! truncated).

#![allow(dead_code)] // Each test binary uses its own part of the module.

use std::ops::Range;
use std::path::Path;
use std::process::Command;

/// Values an attribute is replaced with: extreme, malformed, or of the
/// wrong arity.
pub const VALUES: [&str; 16] = [
    "nan",
    "inf",
    "-inf",
    "",
    "abc",
    "1e308 1e308 1e308",
    "0",
    "-1",
    "1e-320",
    "1 2",
    "1 2 3 4",
    "0 0 0",
    "1e400",
    "0x10",
    "1,2,3",
    "NaN 0 0",
];

/// Values that are not a finite number (or not a list of them).
pub fn unreadable(value: &str) -> bool {
    value
        .split_whitespace()
        .map(str::parse::<f64>)
        .any(|v| !v.is_ok_and(f64::is_finite))
        || value.trim().is_empty()
}

/// A deterministic generator (xorshift64*).
pub struct Rng(pub u64);

impl Rng {
    /// A number in `0..n` (zero if `n` is zero).
    pub fn below(&mut self, n: usize) -> usize {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 33) as usize % n.max(1)
    }
}

/// An element of the file: its tag name, its byte range (start tag to end
/// tag), the names of the elements it is in, and its start tag's range.
#[derive(Clone, Debug)]
pub struct Element {
    pub name: String,
    pub range: Range<usize>,
    pub start_tag: Range<usize>,
    pub path: Vec<String>,
}

/// The elements of `text`, in document order (comments, declarations and
/// processing instructions skipped).
pub fn elements(text: &str) -> Vec<Element> {
    let (mut found, mut open): (Vec<Element>, Vec<usize>) = (Vec::new(), Vec::new());
    let mut at = 0;
    while let Some(offset) = text[at..].find('<') {
        let start = at + offset;
        let Some(length) = text[start..].find('>') else {
            break;
        };
        let end = start + length + 1;
        let tag = &text[start + 1..end - 1];
        at = end;
        if tag.starts_with(['?', '!']) {
            continue;
        }
        if tag.starts_with('/') {
            // Closes the innermost open element (a mutated file may not
            // match its tags: the ranges are then only approximate).
            if let Some(k) = open.pop() {
                found[k].range.end = end;
            }
            continue;
        }
        let name: String = tag
            .chars()
            .take_while(|c| !c.is_whitespace() && *c != '/')
            .collect();
        let path = open.iter().map(|&k| found[k].name.clone()).collect();
        found.push(Element {
            name,
            range: start..end,
            start_tag: start..end,
            path,
        });
        if !tag.ends_with('/') {
            open.push(found.len() - 1);
        }
    }
    found
}

/// The attributes `name="value"` of a start tag: the name and the range of
/// the value.
pub fn attributes(text: &str, tag: &Range<usize>) -> Vec<(String, Range<usize>)> {
    let mut found = Vec::new();
    let body = &text[tag.clone()];
    let mut at = 0;
    while let Some(eq) = body[at..].find("=\"") {
        let eq = at + eq;
        let name_start = body[..eq].rfind(char::is_whitespace).map_or(0, |i| i + 1);
        let value_start = eq + 2;
        let Some(length) = body[value_start..].find('"') else {
            break;
        };
        found.push((
            body[name_start..eq].to_owned(),
            tag.start + value_start..tag.start + value_start + length,
        ));
        at = value_start + length + 1;
    }
    found
}

/// The value of attribute `name` of `element`, if it has one.
pub fn attribute<'t>(text: &'t str, element: &Element, name: &str) -> Option<&'t str> {
    attributes(text, &element.start_tag)
        .into_iter()
        .find(|(n, _)| n == name)
        .map(|(_, range)| &text[range])
}

/// One mutation of a file, and whether the import must fail.
pub struct Mutant {
    pub text: String,
    pub what: String,
    pub must_fail: bool,
}

impl Mutant {
    /// A mutant the import may take or refuse.
    pub fn new(text: String, what: String) -> Mutant {
        Mutant {
            text,
            what,
            must_fail: false,
        }
    }

    /// `text` itself (no element to mutate).
    pub fn unchanged(text: &str) -> Mutant {
        Mutant::new(text.to_owned(), "unchanged".into())
    }

    /// A second mutation on top of this one (which may undo the first's
    /// bad value: deleting its element, truncating the file before it, so
    /// only the second's counts for the oracle).
    pub fn then(self, second: Mutant) -> Mutant {
        Mutant {
            what: format!("{}; {}", self.what, second.what),
            must_fail: second.must_fail,
            text: second.text,
        }
    }
}

/// `text` with `range` replaced by `by`.
pub fn splice(text: &str, range: Range<usize>, by: &str) -> String {
    format!("{}{by}{}", &text[..range.start], &text[range.end..])
}

/// `element` deleted.
pub fn delete(text: &str, element: &Element) -> Mutant {
    Mutant::new(
        splice(text, element.range.clone(), ""),
        format!("deleted <{}>", element.name),
    )
}

/// `element` written twice.
pub fn duplicate(text: &str, element: &Element) -> Mutant {
    let copy = &text[element.range.clone()];
    let at = element.range.end..element.range.end;
    Mutant::new(
        splice(text, at, copy),
        format!("duplicated <{}>", element.name),
    )
}

/// `element` moved just before the last `closing` tag (the end of the
/// robot, of the world body).
pub fn move_before(text: &str, element: &Element, closing: &str) -> Mutant {
    let cut = splice(text, element.range.clone(), "");
    let at = cut.rfind(closing).unwrap_or(cut.len());
    let moved = format!(
        "{}{}{}",
        &cut[..at],
        &text[element.range.clone()],
        &cut[at..]
    );
    Mutant::new(moved, format!("moved <{}> before {closing}", element.name))
}

/// The file cut at a random character boundary.
pub fn truncate(text: &str, rng: &mut Rng) -> Mutant {
    let cut = rng.below(text.len());
    let cut = (0..=cut)
        .rev()
        .find(|&i| text.is_char_boundary(i))
        .unwrap_or(0);
    Mutant::new(text[..cut].to_owned(), format!("truncated at byte {cut}"))
}

/// A random attribute of `element` replaced by one of [`VALUES`]: the
/// mutant, the attribute's name and the value written; `None` if the
/// element has no attribute.
pub fn bad_value(
    text: &str,
    element: &Element,
    rng: &mut Rng,
) -> Option<(Mutant, String, &'static str)> {
    let attrs = attributes(text, &element.start_tag);
    let (name, value) = attrs.get(rng.below(attrs.len())).cloned()?;
    let new = VALUES[rng.below(VALUES.len())];
    let mutant = Mutant::new(
        splice(text, value, new),
        format!("<{} {name}> = {new:?} in {:?}", element.name, element.path),
    );
    Some((mutant, name, new))
}

/// The command `dalembert SUBCOMMAND FILE` prints on stdout exactly when
/// it succeeds.
pub fn assert_command_prints_only_on_success(subcommand: &str, file: &Path, what: &str) {
    let output = Command::new(env!("CARGO_BIN_EXE_dalembert"))
        .arg(subcommand)
        .arg(file)
        .output()
        .unwrap();
    let printed = !output.stdout.is_empty();
    assert_eq!(printed, output.status.success(), "{what}: {output:?}");
}

/// A fresh scratch directory for one run (two tests may run at once).
pub fn scratch(tag: &str, seed: u64) -> std::path::PathBuf {
    let run = format!("dalembert-{tag}-fuzz-{}-{seed:x}", std::process::id());
    let dir = std::env::temp_dir().join(run);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}
