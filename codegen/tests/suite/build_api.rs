//! The build-script API: `generate_file` and `Builder` write what
//! `generate` returns, only when it changed, and report language errors
//! with file, line, column, source line and caret.

use std::path::{Path, PathBuf};

use dalembert_codegen::{BuildError, Builder, ModelFile, generate_file};

const PENDULUM: &str = "\
/// A simple pendulum.
pub Pendulum {
    parameters m, l, g;
    coordinates theta;
    frame B = N.rotate_z(theta);
    point P = O - l * B.y;
    particle bob { mass: m, at: P };
    gravity -g * N.y;
}
";

/// A fresh, empty directory for one test.
fn scratch(test: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("build_api_{test}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn write(path: &Path, text: &str) {
    std::fs::write(path, text).unwrap();
}

#[test]
fn generate_file_writes_generate_output_once() {
    let dir = scratch("generate_file");
    let (input, output) = (dir.join("pendulum.dal"), dir.join("out/nested/pendulum.rs"));
    write(&input, PENDULUM);
    generate_file(&input, &output).unwrap();
    let written = std::fs::read_to_string(&output).unwrap();
    assert_eq!(written, dalembert_codegen::generate(PENDULUM).unwrap());
    assert!(written.starts_with("// @generated"));

    // Unchanged output is not rewritten (its mtime stays), so Cargo does
    // not recompile the including crate.
    let before = std::fs::metadata(&output).unwrap().modified().unwrap();
    generate_file(&input, &output).unwrap();
    assert_eq!(
        std::fs::metadata(&output).unwrap().modified().unwrap(),
        before
    );
}

#[test]
fn builder_generates_a_directory_in_name_order() {
    let dir = scratch("builder_dir");
    let (models, out) = (dir.join("models"), dir.join("out"));
    std::fs::create_dir_all(&models).unwrap();
    write(&models.join("b.dal"), &PENDULUM.replace("Pendulum", "B"));
    write(&models.join("a.v2.dal"), &PENDULUM.replace("Pendulum", "A"));
    write(&models.join("notes.txt"), "not a model");
    let extra = dir.join("extra.dal");
    write(&extra, PENDULUM);
    let written = Builder::new()
        .model(&extra)
        .model_dir(&models)
        .out_dir(&out)
        .emit_rerun_if_changed(false)
        .compile()
        .unwrap();
    assert_eq!(
        written,
        [out.join("extra.rs"), out.join("a.v2.rs"), out.join("b.rs")]
    );
    let a = std::fs::read_to_string(out.join("a.v2.rs")).unwrap();
    assert!(a.contains("pub struct A {"), "{a}");
    assert_eq!(std::fs::read_dir(&out).unwrap().count(), 3);
}

#[test]
fn builder_reports_errors_of_all_models_with_positions() {
    let dir = scratch("builder_errors");
    let (first, second) = (dir.join("first.dal"), dir.join("second.dal"));
    write(&first, &PENDULUM.replace("O - l * B.y", "O - l * B.w"));
    write(
        &second,
        &PENDULUM.replace("rotate_z(theta)", "rotate_z(phi)"),
    );
    let error = Builder::new()
        .models([&first, &second])
        .out_dir(dir.join("out"))
        .emit_rerun_if_changed(false)
        .compile()
        .unwrap_err();
    let found: Vec<_> = error
        .diagnostics()
        .iter()
        .map(|d| (d.path().to_owned(), d.line(), d.column()))
        .collect();
    assert_eq!(found[0], (first.clone(), Some(6), Some(25)));
    assert!(
        found.contains(&(second.clone(), Some(5), Some(26))),
        "{error}"
    );
    let report = error.to_string();
    assert!(
        report.contains(&format!(
            " --> {}:5:26\n  |\n5 |     frame B = N.rotate_z(phi);\n  |                          ^^^",
            second.display()
        )),
        "{report}"
    );
    assert!(!dir.join("out/second.rs").exists());
}

#[test]
fn lexer_errors_are_located() {
    let model = ModelFile::new(
        "unbalanced.dal",
        "pub P {\n  parameters m;\n  frame B = N.rotate_z(m;\n}\n",
    );
    let error = model.check().unwrap_err();
    let [diagnostic] = error.diagnostics() else {
        panic!("expected one diagnostic: {error}");
    };
    assert_eq!(diagnostic.line(), Some(4), "{error}");
}

#[test]
fn caret_keeps_tabs_and_counts_characters() {
    let source = "pub P {\n\tparameters m;\n\tcoordinates θ;\n\tframe B = N.rotate_z(θ + ψ);\n}\n";
    let error = ModelFile::new("tabs.dal", source).check().unwrap_err();
    let report = error.to_string();
    let caret = format!("\t{}^", " ".repeat(25));
    assert!(
        report.ends_with(&format!(
            " --> tabs.dal:4:27\n  |\n4 | \tframe B = N.rotate_z(θ + ψ);\n  | {caret}"
        )),
        "{report}"
    );
}

/// The line and column of the one error of `source`, and the report.
fn only_error_position(source: &str) -> ((Option<usize>, Option<usize>), String) {
    let error = ModelFile::new("bom.dal", source).check().unwrap_err();
    let [diagnostic] = error.diagnostics() else {
        panic!("expected one diagnostic: {error}");
    };
    ((diagnostic.line(), diagnostic.column()), error.to_string())
}

#[test]
fn byte_order_mark_is_not_a_column() {
    // An editor's BOM and CRLF line breaks: rustc ignores the first and
    // the `\r` of the second, so columns count from the line's first
    // character, as the macro's do.
    let (position, _) = only_error_position(
        "\u{feff}pub P {\r\n  parameters m;\r\n  coordinates x;\r\n  particle p { mass: zz, at: O };\r\n}\r\n",
    );
    assert_eq!(position, (Some(4), Some(22)));
    let (position, report) = only_error_position(
        "\u{feff}pub P { coordinates x; parameters m; particle p { mass: zz, at: O }; }",
    );
    assert_eq!(position, (Some(1), Some(57)));
    assert!(
        report.contains("\n1 | pub P {"),
        "the BOM is not shown: {report}"
    );
}

#[test]
fn io_and_configuration_errors_name_the_problem() {
    let dir = scratch("io_errors");
    let missing = dir.join("missing.dal");
    let error = generate_file(&missing, dir.join("out.rs")).unwrap_err();
    assert!(matches!(&error, BuildError::Io { path, .. } if *path == missing));
    assert!(error.to_string().contains("missing.dal"));

    let (a, b) = (dir.join("a"), dir.join("b"));
    for sub in [&a, &b] {
        std::fs::create_dir_all(sub).unwrap();
        write(&sub.join("same.dal"), PENDULUM);
    }
    let error = Builder::new()
        .models([a.join("same.dal"), b.join("same.dal")])
        .out_dir(dir.join("out"))
        .emit_rerun_if_changed(false)
        .compile()
        .unwrap_err();
    assert!(
        matches!(error, BuildError::DuplicateOutput { .. }),
        "{error}"
    );
}

#[test]
fn check_accepts_what_generate_accepts() {
    dalembert_codegen::check(PENDULUM).unwrap();
    let error = dalembert_codegen::check("pub P { parameters m, m; }").unwrap_err();
    assert!(error.to_string().contains('m'), "{error}");
}
