//! Bad MJCF input: every error names the file, the line and the element,
//! says what is wrong, and nothing is written — through the library
//! (`Mjcf::model`), `Builder::mjcf` and the `dalembert mjcf` command (empty
//! stdout, the error on stderr, a non-zero exit status).

use std::path::{Path, PathBuf};

use dalembert_codegen::{Builder, ImportOptions, Mjcf};

/// A model with `body` as the only body of the world.
fn model(body: &str) -> String {
    format!("<mujoco model=\"m\">\n  <worldbody>\n    {body}\n  </worldbody>\n</mujoco>\n")
}

/// The errors of importing `text` as `dir/model.xml`: (path, line,
/// message) each.
fn errors_in(dir: &Path, text: &str) -> Vec<(PathBuf, Option<usize>, String)> {
    let error = Mjcf::new(dir.join("model.xml"), text)
        .model()
        .expect_err("the import fails");
    let found: Vec<_> = error
        .diagnostics()
        .iter()
        .map(|d| (d.path().to_owned(), d.line(), d.message().to_owned()))
        .collect();
    assert!(!found.is_empty(), "{error}");
    found
}

/// Exactly one error, in `model.xml` on `line`, containing every piece
/// of `expected`.
fn assert_error(text: &str, line: usize, expected: &[&str]) {
    let found = errors_in(Path::new(""), text);
    assert_eq!(found.len(), 1, "{found:?}");
    let (path, at, message) = &found[0];
    assert_eq!(path, Path::new("model.xml"));
    assert_eq!(*at, Some(line), "{message}");
    for piece in expected {
        assert!(message.contains(piece), "`{piece}` not in: {message}");
    }
}

#[test]
fn malformed_xml() {
    assert_error(
        "<mujoco>\n  <worldbody>\n    <body>\n  </worldbody>\n</mujoco>\n",
        4,
        &["malformed XML"],
    );
}

#[test]
fn unknown_joint_type() {
    assert_error(
        &model("<body>\n      <joint type=\"screw\"/><geom size=\".1\"/></body>"),
        4,
        &[
            "unknown joint type `screw`",
            "`hinge`, `slide`, `ball` or `free`",
        ],
    );
}

#[test]
fn missing_include() {
    assert_error(
        "<mujoco>\n  <include file=\"nowhere.xml\"/>\n</mujoco>\n",
        2,
        &["cannot read the included file `nowhere.xml`"],
    );
}

#[test]
fn a_moving_body_without_mass() {
    assert_error(
        &model("<body name=\"empty\">\n      <joint/></body>"),
        3,
        &["body `empty`", "neither `<inertial>` nor geoms"],
    );
}

#[test]
fn negative_masses() {
    assert_error(
        &model(
            "<body><joint/>\n      <inertial pos=\"0 0 0\" mass=\"-1\" diaginertia=\"1 1 1\"/></body>",
        ),
        4,
        &["negative mass -1"],
    );
    assert_error(
        &model("<body><joint/>\n      <geom size=\".1\" mass=\"-2\"/></body>"),
        4,
        &["negative mass -2"],
    );
}

#[test]
fn a_zero_axis() {
    assert_error(
        &model("<body><geom size=\".1\"/>\n      <joint name=\"j\" axis=\"0 0 0\"/></body>"),
        4,
        &["joint `j`", "the axis is zero"],
    );
}

#[test]
fn a_mesh_geom_whose_inertia_mujoco_computes() {
    assert_error(
        &model("<body><joint/>\n      <geom name=\"shell\" type=\"mesh\" mesh=\"m\"/></body>"),
        4,
        &["geom `shell`", "`mesh` geom"],
    );
}

#[test]
fn equality_constraints_and_fluid_forces_are_refused() {
    let body = "<body><joint/><geom size=\".1\"/></body>";
    assert_error(
        &format!(
            "<mujoco>\n  <worldbody>{body}</worldbody>\n  <equality>\n    <weld body1=\"a\"/>\n  </equality>\n</mujoco>\n"
        ),
        3,
        &["equality constraints are not imported"],
    );
    assert_error(
        &format!(
            "<mujoco>\n  <option density=\"1000\"/>\n  <worldbody>{body}</worldbody>\n</mujoco>\n"
        ),
        2,
        &["fluid forces"],
    );
}

#[test]
fn errors_in_an_included_file_name_that_file() {
    let dir = std::env::temp_dir().join(format!("dalembert-mjcf-errors-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("defaults.xml"),
        "<mujoco>\n  <default>\n    <joint type=\"helical\"/>\n  </default>\n</mujoco>\n",
    )
    .unwrap();
    let text = "<mujoco>\n  <include file=\"defaults.xml\"/>\n  <worldbody>\n    <body><joint/><geom size=\".1\"/></body>\n  </worldbody>\n</mujoco>\n";
    let found = errors_in(&dir, text);
    assert_eq!(found.len(), 1, "{found:?}");
    let (path, line, message) = &found[0];
    assert_eq!(path, &dir.join("defaults.xml"));
    assert_eq!(*line, Some(3));
    assert!(
        message.contains("unknown joint type `helical`"),
        "{message}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn the_builder_reports_the_error_and_writes_nothing() {
    let dir = std::env::temp_dir().join(format!("dalembert-mjcf-builder-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("bad.xml");
    std::fs::write(
        &file,
        model("<body><joint axis=\"0 0 0\"/><geom size=\".1\"/></body>"),
    )
    .unwrap();
    let error = Builder::new()
        .mjcf_with(&file, ImportOptions::new().name("Bad"))
        .out_dir(&dir)
        .emit_rerun_if_changed(false)
        .compile()
        .expect_err("the import fails");
    assert_eq!(error.diagnostics().len(), 1, "{error}");
    assert_eq!(error.diagnostics()[0].line(), Some(3));
    assert!(!dir.join("bad.rs").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn the_command_prints_nothing_and_fails() {
    let dir = std::env::temp_dir().join(format!("dalembert-mjcf-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("bad.xml");
    std::fs::write(
        &file,
        model("<body>\n      <joint type=\"screw\"/><geom size=\".1\"/></body>"),
    )
    .unwrap();
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_dalembert"))
        .arg("mjcf")
        .arg(&file)
        .output()
        .unwrap();
    assert!(!output.status.success());
    assert!(output.stdout.is_empty());
    let stderr = String::from_utf8(output.stderr).unwrap();
    let location = format!("{}:4:", file.display());
    assert!(stderr.contains(&location), "{stderr}");
    assert_eq!(stderr.matches("error:").count(), 1, "{stderr}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn an_unknown_default_class_is_reported_once() {
    assert_error(
        &model("<body><geom size=\".1\"/>\n      <joint class=\"stiff\" axis=\"0 1 0\"/></body>"),
        4,
        &["unknown default class `stiff`"],
    );
}

#[test]
fn an_unknown_childclass_is_reported() {
    // Found by the fuzz (codegen/tests/suite/mjcf_fuzz.rs): a lookup through it
    // missed silently, the `main` class's defaults included.
    assert_error(
        &model(
            "<body\n      childclass=\"limb\"><geom size=\".1\"/><joint axis=\"0 1 0\"/></body>",
        ),
        4,
        &["unknown default class `limb`"],
    );
}

#[test]
fn a_second_inertial_is_reported() {
    // Found by the fuzz: the second silently replaced the first.
    assert_error(
        &model(
            "<body><joint axis=\"0 1 0\"/><inertial mass=\"1\" diaginertia=\"1 1 1\" pos=\"0 0 0\"/>\n      \
             <inertial mass=\"2\" diaginertia=\"1 1 1\" pos=\"0 0 0\"/></body>",
        ),
        4,
        &["a second `<inertial>`"],
    );
}

#[test]
fn a_second_element_of_a_default_class_is_reported() {
    // Found by the fuzz: the second's attributes overrode the first's.
    let text = "<mujoco>\n  <default>\n    <joint damping=\"1\"/>\n    <joint damping=\"2\"/>\n  \
                </default>\n  <worldbody>\n    <body><joint axis=\"0 1 0\"/><geom size=\".1\"/></body>\n  \
                </worldbody>\n</mujoco>\n";
    assert_error(text, 4, &["a second `<joint>` in this `<default>`"]);
}
