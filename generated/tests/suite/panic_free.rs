//! The generated code has no panic path: the code that `build.rs`
//! generated for every model in `models/` and every URDF robot of
//! `tests/reference/urdf/` (in `OUT_DIR`) contains no
//! indexing (`x[i]`: arrays are destructured, `let [a, b] = *q;`), no
//! `unwrap`, `expect`, `panic!` or other panicking macro. A check on the
//! tokens.

use std::path::Path;

use proc_macro2::{Delimiter, TokenStream, TokenTree};

/// Names that panic or may panic when called.
const PANICKING: [&str; 9] = [
    "unwrap",
    "expect",
    "panic",
    "unreachable",
    "todo",
    "unimplemented",
    "assert",
    "assert_eq",
    "assert_ne",
];

/// Keywords after which `[` starts a pattern or an array, not an index.
const BEFORE_PATTERNS: [&str; 4] = ["let", "mut", "return", "in"];

/// Every panic path in `tokens`, described.
fn panic_paths(tokens: TokenStream, found: &mut Vec<String>) {
    let mut previous: Option<TokenTree> = None;
    for token in tokens {
        match &token {
            TokenTree::Ident(ident) if PANICKING.iter().any(|p| ident == p) => {
                found.push(format!("`{ident}`"));
            }
            TokenTree::Group(group) => {
                let indexing = group.delimiter() == Delimiter::Bracket
                    && match &previous {
                        Some(TokenTree::Ident(ident)) => {
                            !BEFORE_PATTERNS.iter().any(|k| ident == k)
                        }
                        Some(TokenTree::Group(before)) => before.delimiter() != Delimiter::Brace,
                        _ => false,
                    };
                if indexing {
                    let before = previous
                        .as_ref()
                        .map(ToString::to_string)
                        .unwrap_or_default();
                    found.push(format!("indexing `{before}[{}]`", group.stream()));
                }
                panic_paths(group.stream(), found);
            }
            _ => {}
        }
        previous = Some(token);
    }
}

#[test]
fn the_scan_finds_indexing_and_unwrap() {
    let mut found = Vec::new();
    let code = "fn f(q: &[f64; 2]) -> f64 { let [a, b] = *q; let x = [a, b]; q[0] + x[1] + g(a).unwrap() }";
    panic_paths(code.parse().expect("lexes"), &mut found);
    assert_eq!(found, ["indexing `q[0]`", "indexing `x[1]`", "`unwrap`"]);
}

#[test]
fn generated_code_has_no_panic_path() {
    let out = Path::new(env!("OUT_DIR"));
    let mut checked = 0;
    for entry in std::fs::read_dir(out).expect("OUT_DIR exists") {
        let path = entry.expect("a directory entry").path();
        if path.extension().is_none_or(|e| e != "rs") {
            continue;
        }
        let code = std::fs::read_to_string(&path).expect("readable generated code");
        let mut found = Vec::new();
        panic_paths(code.parse().expect("generated code lexes"), &mut found);
        assert!(found.is_empty(), "{}: {found:?}", path.display());
        // Besides one file per model, build.rs writes `chain_references.rs`.
        checked += usize::from(path.file_stem().is_some_and(|s| s != "chain_references"));
    }
    let crate_dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let models = std::fs::read_dir(crate_dir.join("models")).expect("models/ exists");
    let robots = std::fs::read_dir(crate_dir.join("../tests/reference/urdf"))
        .expect("tests/reference/urdf/ exists")
        .filter(|e| {
            e.as_ref()
                .is_ok_and(|e| e.path().extension().is_some_and(|x| x == "urdf"))
        });
    let trees = std::fs::read_dir(crate_dir.join("trees")).expect("trees/ exists");
    // The 60-link chains of the `large` feature.
    let large = if cfg!(feature = "large") { 2 } else { 0 };
    // The two floating humanoids of the `humanoids` feature.
    let humanoids = if cfg!(feature = "humanoids") { 2 } else { 0 };
    // build.rs's MJCF entries: dm_control's cheetah and humanoid.
    let mjcf = 2;
    assert_eq!(
        checked,
        models.count() + robots.count() + trees.count() + large + humanoids + mjcf,
        "one generated file per model, per URDF robot, per tree and per MJCF model"
    );
}

/// The same scan over the copies asking for `accelerations_x4`
/// (`OUT_DIR/lanes/`): the solve over lanes has no panic path either (its
/// states are destructured and handed to the runtime, never indexed).
#[test]
fn code_over_lanes_has_no_panic_path() {
    let dir = Path::new(env!("OUT_DIR")).join("lanes");
    let mut checked = 0;
    for entry in std::fs::read_dir(&dir).expect("OUT_DIR/lanes exists") {
        let path = entry.expect("a directory entry").path();
        if path.extension().is_none_or(|e| e != "rs") {
            continue;
        }
        let code = std::fs::read_to_string(&path).expect("readable generated code");
        assert!(
            code.contains("pub fn accelerations_x4"),
            "{}",
            path.display()
        );
        let mut found = Vec::new();
        panic_paths(code.parse().expect("generated code lexes"), &mut found);
        assert!(found.is_empty(), "{}: {found:?}", path.display());
        checked += 1;
    }
    assert!(checked >= 10, "the lanes' copies: {checked}");
}
