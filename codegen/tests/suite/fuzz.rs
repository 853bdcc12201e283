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

/// One imported mutant of a sample checked against a peer's reading of
/// the same file (Pinocchio's of URDF, MuJoCo's of MJCF).
pub struct Sampled {
    /// `case_NNN`, its name in the reference and its file's stem.
    pub name: String,
    /// The file mutated and the mutations.
    pub what: String,
    pub text: String,
    /// The model the import wrote.
    pub model: String,
}

/// The first `size` mutants of `files` (name, text) that differ from
/// their file and that `import` takes, from `seed`: deterministic, so a
/// stored reference is theirs.
pub fn sample(
    files: &[(String, String)],
    seed: u64,
    size: usize,
    mutant_of: impl Fn(&str, &mut Rng) -> Mutant,
    import: impl Fn(&str, &str) -> Option<String>,
) -> Vec<Sampled> {
    let mut rng = Rng(seed);
    let mut found = Vec::new();
    for case in 0..20 * size {
        let (file, text) = &files[case % files.len()];
        let mutant = mutant_of(text, &mut rng);
        if mutant.text == *text {
            continue;
        }
        if let Some(model) = import(file, &mutant.text) {
            found.push(Sampled {
                name: format!("case_{:03}", found.len()),
                what: format!("{file}: {}", mutant.what),
                text: mutant.text,
                model,
            });
            if found.len() == size {
                return found;
            }
        }
    }
    panic!("only {} of {size} mutants imported", found.len());
}

/// The 64-bit FNV-1a hash of `text`, which a reference records of each
/// mutant (the scripts compute it the same way).
pub fn fnv1a(text: &str) -> String {
    let hash = text.bytes().fold(0xcbf2_9ce4_8422_2325_u64, |h, b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    });
    format!("{hash:016x}")
}

/// Writes the sample's files (`case_NNN.EXTENSION`) into the folder named
/// by `FUZZ_SAMPLE`, for the script that has the peer read them.
pub fn write_sample(sample: &[Sampled], extension: &str) {
    let dir = std::env::var("FUZZ_SAMPLE").expect("FUZZ_SAMPLE=FOLDER");
    std::fs::create_dir_all(&dir).unwrap();
    for sampled in sample {
        let file = Path::new(&dir).join(format!("{}.{extension}", sampled.name));
        std::fs::write(file, &sampled.text).unwrap();
        println!("{}: {}", sampled.name, sampled.what);
    }
}

/// What the peer made of a sample.
#[derive(Debug, Default)]
pub struct Agreement {
    pub matched: usize,
    /// Files the peer refuses, or whose numbers fail its script's
    /// self-checks: their names and the peer's words.
    pub peer_refuses: Vec<String>,
}

/// Every case of `sample` against the peer's reference at `reference`
/// (under the repository's `tests/reference/`): the mutant is the one the
/// reference was written for (its hash), and the model's `M`, `f`, `T`,
/// `V` agree with the peer's to `tolerance` of their largest entry and
/// `q̈` to `tolerance` times `M`'s condition number; or the peer has no
/// numbers and its words, or the mutation, contain one of the patterns
/// of `peer_alone_refuses` (each with why that is no difference in the
/// dynamics); at least `matched` cases with numbers.
pub fn check_sample(
    reference: &str,
    sample: &[Sampled],
    peer_alone_refuses: &[(&str, &str)],
    tolerance: f64,
    matched: usize,
) -> Agreement {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../tests/reference")
        .join(reference);
    let reference: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let cases = reference["cases"].as_array().unwrap();
    assert_eq!(cases.len(), sample.len());
    let mut agreement = Agreement::default();
    for (case, sampled) in cases.iter().zip(sample) {
        let what = format!("{}, {}", sampled.name, sampled.what);
        assert_eq!(case["name"], sampled.name.as_str());
        assert_eq!(
            case["fnv1a"],
            fnv1a(&sampled.text).as_str(),
            "{what}: not the mutant the reference was written for; regenerate it"
        );
        if let Some(error) = case["error"].as_str() {
            let explained = peer_alone_refuses
                .iter()
                .any(|(pattern, _)| sampled.what.contains(pattern) || error.contains(pattern));
            assert!(explained, "{what}: imported, but the peer says {error}");
            agreement.peer_refuses.push(format!("{what}: {error}"));
            continue;
        }
        let worst = crate::pinocchio::worst_errors(
            &sampled.model,
            &case["entry"],
            dalembert_codegen::testing::Route::Dalembert,
        )
        .unwrap_or_else(|error| panic!("{what}: {error}\n{}", sampled.model));
        let condition = case["cond"].as_f64().unwrap();
        for ((error, quantity), scale) in worst
            .iter()
            .zip(crate::pinocchio::QUANTITIES)
            .zip([1.0, 1.0, 1.0, 1.0, condition])
        {
            assert!(
                *error <= tolerance * scale,
                "{what}: {quantity} off by {error:e} relative\n{}",
                sampled.model
            );
        }
        agreement.matched += 1;
    }
    println!("{} mutants: {agreement:#?}", sample.len());
    assert!(agreement.matched >= matched, "{agreement:#?}");
    agreement
}

/// One mutant of `text` by `mutate`, and a second mutation on top one time
/// in three.
pub fn mutant_of(text: &str, rng: &mut Rng, mutate: impl Fn(&str, &mut Rng) -> Mutant) -> Mutant {
    let mutant = mutate(text, rng);
    if rng.below(3) == 0 {
        let second = mutate(&mutant.text, rng);
        mutant.then(second)
    } else {
        mutant
    }
}

/// What the imports of a run's mutants did.
#[derive(Debug, Default)]
pub struct Tally {
    pub imported: usize,
    pub refused: usize,
    /// Imported models also put through the macro's checks.
    pub checked: usize,
}

/// How one format is fuzzed: its files, its mutations, its import and its
/// command.
pub struct Format<M, I> {
    /// The files mutated, (path, text) each.
    pub files: Vec<(String, String)>,
    pub mutate: M,
    /// The import of a mutant's text read as from the given path: the
    /// model, or the error's text.
    pub import: I,
    /// The `dalembert` subcommand that imports a file.
    pub subcommand: &'static str,
    /// Where a mutant is written for the command (beside the files the
    /// formats' files include).
    pub command_file: std::path::PathBuf,
}

/// Runs `cases` mutants of `format`'s files from `seed`, the command on
/// every `command_every`th: no panic, no import of a mutant that must
/// fail, the macro's checks of every fourth imported model (of files under
/// 20 KB) without panic, stdout only on success.
pub fn run<M, I>(format: &Format<M, I>, cases: usize, seed: u64, command_every: usize) -> Tally
where
    M: Fn(&str, &mut Rng) -> Mutant,
    I: Fn(&str, &str) -> Result<String, String>,
{
    use std::panic::{AssertUnwindSafe, catch_unwind};
    let mut rng = Rng(seed);
    let mut tally = Tally::default();
    for case in 0..cases {
        let (path, text) = &format.files[case % format.files.len()];
        let mutant = mutant_of(text, &mut rng, &format.mutate);
        let what = format!("case {case}, {path}: {}", mutant.what);
        let imported = catch_unwind(AssertUnwindSafe(|| (format.import)(path, &mutant.text)))
            .unwrap_or_else(|_| panic!("{what}: the importer panicked"));
        match imported {
            Ok(model) => {
                tally.imported += 1;
                assert!(!mutant.must_fail, "{what}: imported\n{model}");
                if mutant.text.len() < 20_000 && case % 4 == 0 {
                    let checked = catch_unwind(|| dalembert_codegen::check(&model));
                    assert!(checked.is_ok(), "{what}: check panicked");
                    tally.checked += 1;
                }
            }
            Err(_) => tally.refused += 1,
        }
        if case % command_every == 0 {
            std::fs::write(&format.command_file, &mutant.text).unwrap();
            assert_command_prints_only_on_success(format.subcommand, &format.command_file, &what);
        }
    }
    tally
}
