//! The URDF importer fuzzed by structure-aware mutations of the real robot
//! files of the repository (`tests/reference/urdf/`, `generated/trees/`):
//! elements deleted, duplicated or moved, attribute values replaced by
//! extreme or malformed numbers, link references redirected, joint types
//! changed, files truncated. For every case:
//!
//! * no panic, through `Urdf::import`, and, for the models it returns,
//!   through `check` (the macro's checks);
//! * a quantity the dynamics depend on (a mass, an inertia, an origin, a
//!   moving joint's axis) made NaN, infinite or unreadable is an error,
//!   never a model (that would compile, and differ from the file);
//! * on a sample, the `dalembert urdf` command prints nothing on stdout when
//!   it exits with an error, and a model when it succeeds.
//!
//! `FUZZ_CASES` cases run in CI (300); the ignored test runs 10 000
//! (`cargo test -p dalembert-codegen --test suite urdf_fuzz:: -- --ignored`).

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};
use std::process::Command;

use dalembert_codegen::Urdf;

/// Cases run in CI.
const FUZZ_CASES: usize = 300;

/// Values an attribute is replaced with: extreme, malformed, or of the
/// wrong arity.
const VALUES: [&str; 16] = [
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
fn unreadable(value: &str) -> bool {
    value
        .split_whitespace()
        .map(str::parse::<f64>)
        .any(|v| !v.is_ok_and(f64::is_finite))
        || value.trim().is_empty()
}

/// The real robot files, read once.
fn robots() -> Vec<(PathBuf, String)> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut files = Vec::new();
    for dir in [
        "tests/reference/urdf",
        "tests/reference/urdf/regressions",
        "generated/trees",
    ] {
        let mut paths: Vec<_> = std::fs::read_dir(root.join(dir))
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.extension().is_some_and(|e| e == "urdf"))
            .collect();
        paths.sort();
        files.extend(paths.into_iter().map(|p| {
            let text = std::fs::read_to_string(&p).unwrap();
            (p, text)
        }));
    }
    assert!(files.len() >= 10, "{files:?}");
    files
}

/// A deterministic generator (xorshift64*).
struct Rng(u64);

impl Rng {
    fn below(&mut self, n: usize) -> usize {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 33) as usize % n.max(1)
    }
}

/// An element of the file: its tag name, its byte range (start tag to end
/// tag), the names of the elements it is in, and its start tag's range.
#[derive(Clone, Debug)]
struct Element {
    name: String,
    range: std::ops::Range<usize>,
    start_tag: std::ops::Range<usize>,
    path: Vec<String>,
}

/// The elements of `text`, in document order (comments, declarations and
/// processing instructions skipped).
fn elements(text: &str) -> Vec<Element> {
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
fn attributes(text: &str, tag: &std::ops::Range<usize>) -> Vec<(String, std::ops::Range<usize>)> {
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

/// One mutation of a file, and whether the import must fail.
struct Mutant {
    text: String,
    what: String,
    must_fail: bool,
}

/// A random structure-aware mutation of `text`.
fn mutate(text: &str, rng: &mut Rng) -> Mutant {
    let all = elements(text);
    let Some(element) = all.get(rng.below(all.len())) else {
        return Mutant {
            text: text.to_owned(),
            what: "unchanged (no element)".into(),
            must_fail: false,
        };
    };
    let splice = |range: std::ops::Range<usize>, by: &str| {
        format!("{}{by}{}", &text[..range.start], &text[range.end..])
    };
    let mutant = |text, what: String| Mutant {
        text,
        what,
        must_fail: false,
    };
    match rng.below(7) {
        0 => mutant(
            splice(element.range.clone(), ""),
            format!("deleted <{}>", element.name),
        ),
        1 => {
            let copy = &text[element.range.clone()];
            let at = element.range.end..element.range.end;
            mutant(splice(at, copy), format!("duplicated <{}>", element.name))
        }
        2 => {
            // Moved to the end of the robot.
            let cut = splice(element.range.clone(), "");
            let at = cut.rfind("</robot>").unwrap_or(cut.len());
            let moved = format!(
                "{}{}{}",
                &cut[..at],
                &text[element.range.clone()],
                &cut[at..]
            );
            mutant(moved, format!("moved <{}>", element.name))
        }
        3 => {
            let cut = rng.below(text.len());
            let cut = (0..=cut)
                .rev()
                .find(|&i| text.is_char_boundary(i))
                .unwrap_or(0);
            mutant(text[..cut].to_owned(), format!("truncated at byte {cut}"))
        }
        4 => {
            // A link reference redirected to another link, or to a missing one.
            let links: Vec<_> = all
                .iter()
                .filter(|e| e.name == "link" && e.path.len() == 1)
                .collect();
            let references: Vec<_> = all
                .iter()
                .filter(|e| e.name == "parent" || e.name == "child")
                .collect();
            if links.is_empty() || references.is_empty() {
                return mutant(text.to_owned(), "unchanged".into());
            }
            let reference = references[rng.below(references.len())];
            let Some((_, value)) = attributes(text, &reference.start_tag).into_iter().next() else {
                return mutant(text.to_owned(), "unchanged".into());
            };
            let target = if rng.below(4) == 0 {
                "no_such_link".to_owned()
            } else {
                let link = links[rng.below(links.len())];
                attributes(text, &link.start_tag)
                    .into_iter()
                    .find(|(n, _)| n == "name")
                    .map_or_else(String::new, |(_, r)| text[r].to_owned())
            };
            mutant(
                splice(value, &target),
                format!("<{}> redirected to {target}", reference.name),
            )
        }
        5 => {
            let joints: Vec<_> = all
                .iter()
                .filter(|e| e.name == "joint" && e.path.len() == 1)
                .collect();
            let Some(joint) = joints.get(rng.below(joints.len())) else {
                return mutant(text.to_owned(), "unchanged".into());
            };
            let kinds = [
                "revolute",
                "continuous",
                "prismatic",
                "fixed",
                "floating",
                "planar",
                "spherical",
                "",
            ];
            let kind = kinds[rng.below(kinds.len())];
            match attributes(text, &joint.start_tag)
                .into_iter()
                .find(|(n, _)| n == "type")
            {
                Some((_, value)) => mutant(splice(value, kind), format!("joint type {kind:?}")),
                None => mutant(text.to_owned(), "unchanged".into()),
            }
        }
        _ => {
            let attrs = attributes(text, &element.start_tag);
            let Some((name, value)) = attrs.get(rng.below(attrs.len())).cloned() else {
                return mutant(text.to_owned(), "unchanged".into());
            };
            let new = VALUES[rng.below(VALUES.len())];
            let must_fail = unreadable(new) && matters(text, &all, element, &name);
            Mutant {
                text: splice(value, new),
                what: format!("<{} {name}> = {new:?} in {:?}", element.name, element.path),
                must_fail,
            }
        }
    }
}

/// Whether attribute `name` of `element` is a quantity the dynamics depend
/// on: a mass, an inertia or their origin, a joint's origin, a moving
/// joint's axis.
fn matters(text: &str, all: &[Element], element: &Element, name: &str) -> bool {
    let parent = element.path.last().map(String::as_str);
    match (parent, element.name.as_str(), name) {
        (Some("inertial"), "mass", "value") => true,
        (Some("inertial"), "inertia", _) => true,
        (Some("inertial"), "origin", "xyz" | "rpy") => true,
        (Some("joint"), "origin", "xyz" | "rpy") => true,
        (Some("joint"), "axis", "xyz") => {
            // The joint holding this axis: the last one starting before it.
            let joint = all
                .iter()
                .rev()
                .find(|e| e.name == "joint" && e.range.start < element.range.start);
            joint.is_some_and(|j| {
                attributes(text, &j.start_tag)
                    .iter()
                    .any(|(n, r)| n == "type" && &text[r.clone()] != "fixed")
            })
        }
        _ => false,
    }
}

/// What the import of one mutant did.
#[derive(Debug, Default)]
struct Tally {
    imported: usize,
    refused: usize,
    checked: usize,
}

/// Runs `cases` mutants from `seed`; the command on every `command_every`th.
fn fuzz(cases: usize, seed: u64, command_every: usize) -> Tally {
    let robots = robots();
    let mut rng = Rng(seed);
    let mut tally = Tally::default();
    // One directory per run: the two tests may run at once.
    let run = format!("dalembert-urdf-fuzz-{}-{seed:x}", std::process::id());
    let dir = std::env::temp_dir().join(run);
    std::fs::create_dir_all(&dir).unwrap();
    for case in 0..cases {
        let (path, text) = &robots[case % robots.len()];
        let mut mutant = mutate(text, &mut rng);
        if rng.below(3) == 0 {
            // A second mutation on top (which may undo the first's bad
            // value: deleting its element, truncating the file before it,
            // so only the second's counts for the oracle).
            let second = mutate(&mutant.text, &mut rng);
            mutant = Mutant {
                what: format!("{}; {}", mutant.what, second.what),
                must_fail: second.must_fail,
                text: second.text,
            };
        }
        let what = format!("case {case}, {}: {}", path.display(), mutant.what);
        let imported = catch_unwind(AssertUnwindSafe(|| Urdf::new(path, &mutant.text).import()))
            .unwrap_or_else(|_| panic!("{what}: the importer panicked"));
        match imported {
            Ok(imported) => {
                tally.imported += 1;
                assert!(!mutant.must_fail, "{what}: imported\n{}", imported.model);
                // The models of the small robots go through the macro's checks.
                if mutant.text.len() < 20_000 && case % 4 == 0 {
                    let checked = catch_unwind(AssertUnwindSafe(|| {
                        dalembert_codegen::check(&imported.model)
                    }));
                    assert!(checked.is_ok(), "{what}: check panicked");
                    tally.checked += 1;
                }
            }
            Err(_) => tally.refused += 1,
        }
        if case % command_every == 0 {
            let file = dir.join(format!("case{case}.urdf"));
            std::fs::write(&file, &mutant.text).unwrap();
            let output = Command::new(env!("CARGO_BIN_EXE_dalembert"))
                .arg("urdf")
                .arg(&file)
                .output()
                .unwrap();
            let printed = !output.stdout.is_empty();
            assert_eq!(printed, output.status.success(), "{what}: {output:?}");
        }
    }
    std::fs::remove_dir_all(&dir).ok();
    tally
}

#[test]
fn mutated_robot_files_are_imported_or_refused_never_garbled() {
    let tally = fuzz(FUZZ_CASES, 0x5EED_F022, 10);
    println!("{FUZZ_CASES} cases: {tally:?}");
    assert!(tally.imported > 10 && tally.refused > 10, "{tally:?}");
    assert!(tally.checked > 0);
}

#[test]
#[ignore = "10 000 cases: a few minutes; run once outside CI"]
fn ten_thousand_mutated_robot_files() {
    let tally = fuzz(10_000, 0xF0CC_AC1A, 100);
    println!("10 000 cases: {tally:?}");
    assert!(tally.imported > 100 && tally.refused > 100, "{tally:?}");
}
