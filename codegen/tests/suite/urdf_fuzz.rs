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

use std::path::{Path, PathBuf};

use crate::fuzz::{self, Element, Mutant, Rng, attribute, attributes, splice, unreadable};
use dalembert_codegen::Urdf;

/// Cases run in CI.
const FUZZ_CASES: usize = 300;

/// Imported mutants compared with Pinocchio's reading of the same file.
const SAMPLE_SIZE: usize = 80;

/// The seed of that sample's mutations.
const SAMPLE_SEED: u64 = 0x51A7_E5EE_D5A1_7E00;

/// Relative agreement required of `M`, `f`, `T` and `V` against the
/// largest entry of each, and of `q̈` times `M`'s condition number (the
/// most any solver can promise).
const TOLERANCE: f64 = 1e-10;

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

/// A link reference (`<parent>`, `<child>`) redirected to another link, or
/// to a missing one.
fn redirect(text: &str, all: &[Element], rng: &mut Rng) -> Mutant {
    let links: Vec<_> = all
        .iter()
        .filter(|e| e.name == "link" && e.path.len() == 1)
        .collect();
    let references: Vec<_> = all
        .iter()
        .filter(|e| e.name == "parent" || e.name == "child")
        .collect();
    if links.is_empty() || references.is_empty() {
        return Mutant::unchanged(text);
    }
    let reference = references[rng.below(references.len())];
    let Some((_, value)) = attributes(text, &reference.start_tag).into_iter().next() else {
        return Mutant::unchanged(text);
    };
    let target = if rng.below(4) == 0 {
        "no_such_link"
    } else {
        let link = links[rng.below(links.len())];
        attribute(text, link, "name").unwrap_or_default()
    };
    Mutant::new(
        splice(text, value, target),
        format!("<{}> redirected to {target}", reference.name),
    )
}

/// A joint's type changed (to another, or to nothing).
fn retype(text: &str, all: &[Element], rng: &mut Rng) -> Mutant {
    let joints: Vec<_> = all
        .iter()
        .filter(|e| e.name == "joint" && e.path.len() == 1)
        .collect();
    let Some(joint) = joints.get(rng.below(joints.len())) else {
        return Mutant::unchanged(text);
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
        Some((_, value)) => Mutant::new(splice(text, value, kind), format!("joint type {kind:?}")),
        None => Mutant::unchanged(text),
    }
}

/// A random structure-aware mutation of `text`.
fn mutate(text: &str, rng: &mut Rng) -> Mutant {
    let all = fuzz::elements(text);
    let Some(element) = all.get(rng.below(all.len())) else {
        return Mutant::new(text.to_owned(), "unchanged (no element)".into());
    };
    match rng.below(7) {
        0 => fuzz::delete(text, element),
        1 => fuzz::duplicate(text, element),
        2 => fuzz::move_before(text, element, "</robot>"),
        3 => fuzz::truncate(text, rng),
        4 => redirect(text, &all, rng),
        5 => retype(text, &all, rng),
        _ => match fuzz::bad_value(text, element, rng) {
            Some((mut mutant, name, new)) => {
                mutant.must_fail = unreadable(new) && matters(text, &all, element, &name);
                mutant
            }
            None => Mutant::unchanged(text),
        },
    }
}

/// One mutant of `text`, and a second mutation on top one time in three.
fn mutant_of(text: &str, rng: &mut Rng) -> Mutant {
    fuzz::mutant_of(text, rng, mutate)
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

/// Runs `cases` mutants from `seed`; the command on every `command_every`th.
fn fuzz(cases: usize, seed: u64, command_every: usize) -> fuzz::Tally {
    let dir = fuzz::scratch("urdf", seed);
    let files = robots()
        .into_iter()
        .map(|(path, text)| (path.display().to_string(), text))
        .collect();
    let format = fuzz::Format {
        files,
        mutate,
        import: |path: &str, text: &str| {
            Urdf::new(path, text)
                .import()
                .map(|imported| imported.model)
                .map_err(|error| error.to_string())
        },
        subcommand: "urdf",
        command_file: dir.join("mutant.urdf"),
    };
    let tally = fuzz::run(&format, cases, seed, command_every);
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

/// The sample checked against Pinocchio: mutants of the robots under
/// 16 KB (every robot but the largest three) that import.
fn sample() -> Vec<fuzz::Sampled> {
    let robots: Vec<_> = robots()
        .into_iter()
        .filter(|(_, text)| text.len() < 16_000)
        .map(|(path, text)| {
            (
                path.file_name().unwrap().to_string_lossy().into_owned(),
                text,
            )
        })
        .collect();
    fuzz::sample(
        &robots,
        SAMPLE_SEED,
        SAMPLE_SIZE,
        mutant_of,
        |file, text| {
            Urdf::new(file, text)
                .import()
                .ok()
                .map(|imported| imported.model)
        },
    )
}

/// Writes the sample's files into the folder named by `FUZZ_SAMPLE`, for
/// `scripts/urdf_fuzz_reference.sh` (which then has Pinocchio read them).
#[test]
#[ignore = "writes the sample for scripts/urdf_fuzz_reference.sh"]
fn write_the_sample_for_pinocchio() {
    fuzz::write_sample(&sample(), "urdf");
}

/// The mutations after which Pinocchio has no numbers for a file the
/// import takes, and why that is no difference in the dynamics.
const PINOCCHIO_ALONE_REFUSES: [(&str, &str); 2] = [
    (
        "<limit",
        "urdfdom requires a `<limit>` of every revolute and prismatic joint and reads its \
         numbers strictly (`1e400`); limits do not enter the equations of motion, and the \
         import reads none",
    ),
    (
        "1e308",
        "a length or axis near `f64::MAX`: Pinocchio's `M` is infinite (`origin`) or fails \
         `T = ½ vᵀ M v` (an `axis`, whose squares overflow); the import normalises such an \
         axis without overflow and writes such a length as it is, whose `M` is then not finite, \
         which the generated code reports as a `DynamicsError`",
    ),
];

#[test]
fn imported_mutants_match_pinocchio() {
    fuzz::check_sample(
        "urdf_fuzz/pinocchio.json",
        &sample(),
        &PINOCCHIO_ALONE_REFUSES,
        TOLERANCE,
        SAMPLE_SIZE * 3 / 4,
    );
}
