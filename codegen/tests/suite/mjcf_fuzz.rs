//! The MJCF importer fuzzed by structure-aware mutations of the MuJoCo
//! models of the repository (`tests/reference/mjcf/`: eleven of
//! dm_control's suite and the model of every feature the import reads):
//! elements deleted, duplicated or moved, attribute values replaced by
//! extreme or malformed numbers, joint types changed, default classes
//! redirected to missing ones, includes of missing files and of the file
//! itself (a cycle), files truncated. For every case:
//!
//! * no panic, through `Mjcf::import` and, for the models it returns,
//!   through `check` (the macro's checks);
//! * a missing or circular include, a class that does not exist, and an
//!   unreadable number of a body's placement, a joint's axis or position,
//!   or an explicit inertial are errors, never a model;
//! * on a sample, the `dalembert mjcf` command prints nothing on stdout
//!   when it exits with an error, and a model when it succeeds;
//! * a sample of the mutants that import matches MuJoCo's reading of the
//!   same file (`tests/reference/mjcf_fuzz/mujoco.json`, written by
//!   `scripts/mjcf_fuzz_reference.sh`).
//!
//! `FUZZ_CASES` cases run in CI; the ignored test runs 10 000
//! (`cargo test -p dalembert-codegen --test suite mjcf_fuzz:: -- --ignored`).

use std::path::{Path, PathBuf};

use crate::fuzz::{self, Element, Mutant, Rng, attribute, attributes, splice, unreadable};
use dalembert_codegen::Mjcf;
use serde_json::Value;

/// Cases run in CI.
const FUZZ_CASES: usize = 300;

/// Imported mutants compared with MuJoCo's reading of the same file (of
/// which MuJoCo, stricter about what does not enter the dynamics, refuses
/// more than half).
const SAMPLE_SIZE: usize = 100;

/// The seed of that sample's mutations.
const SAMPLE_SEED: u64 = 0x3EC0_F022_5A3B_1E00;

/// Relative agreement required of `M`, `f`, `T` and `V` against the
/// largest entry of each, and of `q̈` times `M`'s condition number.
const TOLERANCE: f64 = 1e-10;

/// The name every mutant is imported under (beside the files the models
/// include), so that a mutant including itself names this file.
const MUTANT: &str = "mutant.xml";

/// The folder of the repository's MuJoCo models.
fn models_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/reference/mjcf")
}

/// The models' main files (not the files they include), read once.
fn models() -> Vec<(String, String)> {
    let reference: Value =
        serde_json::from_str(&std::fs::read_to_string(models_dir().join("mujoco.json")).unwrap())
            .unwrap();
    let files: Vec<(String, String)> = reference["models"]
        .as_array()
        .unwrap()
        .iter()
        .map(|entry| {
            let file = entry["file"].as_str().unwrap().to_owned();
            let text = std::fs::read_to_string(models_dir().join(&file)).unwrap();
            (file, text)
        })
        .collect();
    assert!(files.len() >= 10, "{files:?}");
    files
}

/// A scratch folder holding the files the models include (dm_control's
/// `common/`, the features' defaults), where mutants are written as
/// [`MUTANT`].
fn workspace(tag: &str, seed: u64) -> PathBuf {
    let dir = fuzz::scratch(tag, seed);
    std::fs::create_dir_all(dir.join("common")).unwrap();
    for included in [
        "dm_control/common/materials.xml",
        "dm_control/common/skybox.xml",
        "dm_control/common/visual.xml",
        "features/features_defaults.xml",
    ] {
        let to = if included.starts_with("dm_control") {
            dir.join("common")
                .join(Path::new(included).file_name().unwrap())
        } else {
            dir.join(Path::new(included).file_name().unwrap())
        };
        std::fs::copy(models_dir().join(included), to).unwrap();
    }
    dir
}

/// An `<include>` inserted after the model's start tag: of a missing file,
/// or of the file itself.
fn include(text: &str, all: &[Element], rng: &mut Rng) -> Mutant {
    let Some(root) = all.iter().find(|e| e.name == "mujoco") else {
        return Mutant::unchanged(text);
    };
    let file = if rng.below(2) == 0 {
        "no_such_file.xml"
    } else {
        MUTANT
    };
    let at = root.start_tag.end..root.start_tag.end;
    Mutant {
        text: splice(text, at, &format!("<include file=\"{file}\"/>")),
        what: format!("included {file}"),
        must_fail: true,
    }
}

/// A joint's type changed (to another, or to one MuJoCo does not have).
fn retype(text: &str, all: &[Element], rng: &mut Rng) -> Mutant {
    let joints: Vec<_> = all.iter().filter(|e| e.name == "joint").collect();
    let Some(joint) = joints.get(rng.below(joints.len())) else {
        return Mutant::unchanged(text);
    };
    let kinds = ["hinge", "slide", "ball", "free", "screw", ""];
    let kind = kinds[rng.below(kinds.len())];
    let start = &text[joint.start_tag.clone()];
    let mutated = match attributes(text, &joint.start_tag)
        .into_iter()
        .find(|(n, _)| n == "type")
    {
        Some((_, value)) => splice(text, value, kind),
        None => {
            let at = joint.start_tag.start + "<joint".len();
            splice(text, at..at, &format!(" type=\"{kind}\""))
        }
    };
    Mutant::new(mutated, format!("{start} given type {kind:?}"))
}

/// A `class` or `childclass` made to name a class that does not exist.
fn missing_class(text: &str, all: &[Element], rng: &mut Rng) -> Mutant {
    let in_bodies: Vec<_> = all
        .iter()
        .filter(|e| e.path.iter().any(|p| p == "worldbody"))
        .collect();
    // The import reads the class of every joint and body; of the others,
    // only those whose dynamics it reads (not a geom outside the inertia's
    // groups, a camera, a light, a site), where MuJoCo refuses any unknown
    // class.
    let read = |e: &Element| e.name == "joint" || e.name == "body";
    let Some(element) = in_bodies.get(rng.below(in_bodies.len())) else {
        return Mutant::unchanged(text);
    };
    let (name, mutated) = match attributes(text, &element.start_tag)
        .into_iter()
        .find(|(n, _)| n == "class" || n == "childclass")
    {
        Some((name, value)) => (name, splice(text, value, "no_such_class")),
        None => {
            let name = if element.name == "body" {
                "childclass"
            } else {
                "class"
            };
            let at = element.start_tag.start + 1 + element.name.len();
            (
                name.to_owned(),
                splice(text, at..at, &format!(" {name}=\"no_such_class\"")),
            )
        }
    };
    Mutant {
        text: mutated,
        what: format!("<{} {name}> = no_such_class", element.name),
        must_fail: read(element),
    }
}

/// A random structure-aware mutation of `text`.
fn mutate(text: &str, rng: &mut Rng) -> Mutant {
    let all = fuzz::elements(text);
    let Some(element) = all.get(rng.below(all.len())) else {
        return Mutant::new(text.to_owned(), "unchanged (no element)".into());
    };
    match rng.below(8) {
        0 => fuzz::delete(text, element),
        1 => fuzz::duplicate(text, element),
        2 => fuzz::move_before(text, element, "</worldbody>"),
        3 => fuzz::truncate(text, rng),
        4 => include(text, &all, rng),
        5 => retype(text, &all, rng),
        6 => missing_class(text, &all, rng),
        _ => match fuzz::bad_value(text, element, rng) {
            Some((mut mutant, name, new)) => {
                mutant.must_fail = unreadable(new) && matters(text, element, &name);
                mutant
            }
            None => Mutant::unchanged(text),
        },
    }
}

/// Whether attribute `name` of `element` is a number the import reads
/// whatever else the file says: a body's placement, a joint's axis and
/// position (outside the defaults), an explicit inertial's.
fn matters(text: &str, element: &Element, name: &str) -> bool {
    if !element.path.iter().any(|p| p == "worldbody") {
        return false;
    }
    match (element.name.as_str(), name) {
        ("body", "pos") => true,
        ("joint", "axis" | "pos") => {
            // A free or ball joint has no axis.
            !matches!(attribute(text, element, "type"), Some("free" | "ball"))
        }
        ("inertial", "pos" | "mass" | "diaginertia" | "fullinertia") => true,
        _ => false,
    }
}

/// One mutant of `text`, and a second mutation on top one time in three.
fn mutant_of(text: &str, rng: &mut Rng) -> Mutant {
    fuzz::mutant_of(text, rng, mutate)
}

/// Runs `cases` mutants from `seed`; the command on every `command_every`th.
fn fuzz(cases: usize, seed: u64, command_every: usize) -> fuzz::Tally {
    let dir = workspace("mjcf", seed);
    let file = dir.join(MUTANT);
    let format = fuzz::Format {
        files: models(),
        mutate,
        import: |_: &str, text: &str| {
            Mjcf::new(&file, text)
                .model()
                .map_err(|error| error.to_string())
        },
        subcommand: "mjcf",
        command_file: file.clone(),
    };
    let tally = fuzz::run(&format, cases, seed, command_every);
    std::fs::remove_dir_all(&dir).ok();
    tally
}

#[test]
fn mutated_mujoco_models_are_imported_or_refused_never_garbled() {
    let tally = fuzz(FUZZ_CASES, 0x5EED_3EC0, 10);
    println!("{FUZZ_CASES} cases: {tally:?}");
    assert!(tally.imported > 10 && tally.refused > 10, "{tally:?}");
    assert!(tally.checked > 0);
}

#[test]
#[ignore = "10 000 cases: a few minutes; run once outside CI"]
fn ten_thousand_mutated_mujoco_models() {
    let tally = fuzz(10_000, 0xF0CC_3EC0, 100);
    println!("10 000 cases: {tally:?}");
    assert!(tally.imported > 100 && tally.refused > 100, "{tally:?}");
}

/// The sample checked against MuJoCo: mutants of the models that import.
fn sample() -> Vec<fuzz::Sampled> {
    let dir = workspace("mjcf-sample", SAMPLE_SEED);
    let sample = fuzz::sample(&models(), SAMPLE_SEED, SAMPLE_SIZE, mutant_of, |_, text| {
        Mjcf::new(dir.join(MUTANT), text).model().ok()
    });
    std::fs::remove_dir_all(&dir).ok();
    sample
}

/// Writes the sample's files into the folder named by `FUZZ_SAMPLE`, for
/// `scripts/mjcf_fuzz_reference.sh` (which adds the files they include and
/// has MuJoCo read them).
#[test]
#[ignore = "writes the sample for scripts/mjcf_fuzz_reference.sh"]
fn write_the_sample_for_mujoco() {
    fuzz::write_sample(&sample(), "xml");
}

/// What MuJoCo says when it has no numbers for a file the import takes,
/// and why that is no difference in the dynamics: MuJoCo's compiler checks
/// the whole file, the import reads the elements of the dynamics (and
/// checks every number it reads).
const MUJOCO_ALONE_REFUSES: [(&str, &str); 11] = [
    (
        "repeated name",
        "names must be unique in MuJoCo; the import reads the joints' names only (a repeated \
         one is refused by the model's checks) and names no other element",
    ),
    (
        "Schema violation",
        "an element or attribute where MuJoCo's schema has none (a second `<visual>`, an \
         option or actuator moved into the world body, a `type` on a tendon's joint): the \
         import does not read them there (a second `<inertial>` of a body or element of a \
         default class it refuses, as MuJoCo does)",
    ),
    (
        "not found",
        "a material, site or wrap reference: none enters the dynamics",
    ),
    (
        "unknown default class name",
        "the class of an element the import does not read (a site, light or camera)",
    ),
    (
        "in attribute",
        "a malformed value (`bad format`, `invalid keyword`, `too much data`, `number is too \
         large`) of an attribute the import does not read (options, flags, actuators, \
         tendons); every number it reads is checked",
    ),
    (
        "transmission target",
        "an actuator of a joint renamed or deleted: the import reads no actuator",
    ),
    (
        "sensor",
        "a sensor's object renamed or deleted: the import reads no sensor",
    ),
    (
        "invalid keyword",
        "a keyword the import does not read: a flag's, or the type of a default's joint \
         that every joint of the file overrides (a type the import reads is checked)",
    ),
    (
        "has too much data",
        "as above, in a tendon's joint (`coef`)",
    ),
    (
        "must be larger than mjMINVAL",
        "MuJoCo's compiler refuses a moving body without mass of its own (its geom moved \
         away) even when its children give the joint inertia; the import takes it as written",
    ),
    (
        "must be positive",
        "a geom of size 0 with an explicit mass: a point mass to the import, refused by \
         MuJoCo's compiler",
    ),
];

#[test]
fn imported_mutants_match_mujoco() {
    fuzz::check_sample(
        "mjcf_fuzz/mujoco.json",
        &sample(),
        &MUJOCO_ALONE_REFUSES,
        TOLERANCE,
        SAMPLE_SIZE / 3,
    );
}
