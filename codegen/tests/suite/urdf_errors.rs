//! Bad URDF input: every error names the file, the line and the link or
//! joint, says what is wrong, and nothing is written — through the library
//! (`Urdf::model`), `Builder::urdf` and the `dalembert urdf` command (empty
//! stdout, the error on stderr, a non-zero exit status). Input that real
//! files have and Pinocchio imports (inertias no mass distribution has,
//! rounding, a robot name that is not an identifier) imports with a
//! warning, located the same way.

use std::path::{Path, PathBuf};
use std::process::Output;

use dalembert_codegen::{BuildError, Builder, Severity, Urdf};

/// Two links joined by `joint` (a fragment of `<joint>` children), with
/// `link_b` as the second link's body.
fn robot(joint_type: &str, joint: &str, link_b: &str) -> String {
    format!(
        r#"<robot name="r">
  <link name="a"/>
  <link name="b">{link_b}</link>
  <joint name="j" type="{joint_type}">
    <parent link="a"/>
    <child link="b"/>{joint}
  </joint>
</robot>
"#
    )
}

/// A kilogram with unit principal moments: a link that moves mass.
fn unit_mass() -> String {
    inertial("1", [1.0, 1.0, 1.0, 0.0, 0.0, 0.0])
}

/// An inertial with this mass and `ixx iyy izz ixy iyz ixz`.
fn inertial(mass: &str, [xx, yy, zz, xy, yz, xz]: [f64; 6]) -> String {
    format!(
        r#"<inertial><mass value="{mass}"/><inertia ixx="{xx}" iyy="{yy}" izz="{zz}" ixy="{xy}" iyz="{yz}" ixz="{xz}"/></inertial>"#
    )
}

/// The errors of importing `text` as `robot.urdf`: (line, message) each.
fn errors(text: &str) -> Vec<(Option<usize>, String)> {
    let error = Urdf::new("robot.urdf", text)
        .model()
        .expect_err("the import fails");
    let found: Vec<_> = error
        .diagnostics()
        .iter()
        .map(|d| {
            assert_eq!(d.path(), Path::new("robot.urdf"));
            (d.line(), d.message().to_owned())
        })
        .collect();
    assert!(!found.is_empty(), "{error}");
    found
}

/// Exactly one error, on `line`, containing every piece of `expected`.
fn assert_error(text: &str, line: usize, expected: &[&str]) {
    let found = errors(text);
    assert_eq!(found.len(), 1, "{found:?}");
    let (at, message) = &found[0];
    assert_eq!(*at, Some(line), "{message}");
    for piece in expected {
        assert!(message.contains(piece), "`{piece}` not in: {message}");
    }
}

#[test]
fn malformed_xml() {
    assert_error(
        "<robot name=\"r\">\n  <link name=\"a\">\n</robot>\n",
        3,
        &["malformed XML"],
    );
}

#[test]
fn unknown_parent_and_child() {
    let text = robot("revolute", "", "").replace("<parent link=\"a\"/>", "<parent link=\"x\"/>");
    assert_error(&text, 5, &["joint `j`", "unknown parent link `x`"]);
    let text = robot("revolute", "", "").replace("<child link=\"b\"/>", "<child link=\"y\"/>");
    assert_error(&text, 6, &["joint `j`", "unknown child link `y`"]);
}

#[test]
fn a_cycle() {
    let text = r#"<robot name="r">
  <link name="root"/>
  <link name="a"/>
  <link name="b"/>
  <joint name="up" type="revolute"><parent link="a"/><child link="b"/></joint>
  <joint name="down" type="revolute"><parent link="b"/><child link="a"/></joint>
</robot>"#;
    assert_error(text, 5, &["the joints `up`, `down` form a cycle"]);
}

#[test]
fn two_roots() {
    let text = robot("revolute", "", "")
        .replace("<link name=\"a\"/>", "<link name=\"a\"/><link name=\"c\"/>");
    assert_error(&text, 2, &["2 root links (`a`, `c`)", "link `c`"]);
}

#[test]
fn nothing_moves() {
    assert_error(
        &robot("fixed", "", ""),
        1,
        &[
            "the robot `r` has no revolute, continuous or prismatic joint",
            "--floating",
        ],
    );
    assert_error("<robot name=\"r\">\n</robot>", 1, &["no `<link>`"]);
}

#[test]
fn a_link_with_two_parents() {
    let text = r#"<robot name="r">
  <link name="a"/>
  <link name="b"/>
  <joint name="j" type="revolute"><parent link="a"/><child link="b"/></joint>
  <joint name="k" type="revolute"><parent link="a"/><child link="b"/></joint>
</robot>"#;
    assert_error(text, 5, &["joint `k`", "already the child of joint `j`"]);
}

#[test]
fn a_negative_mass() {
    let text = robot(
        "revolute",
        "",
        &inertial("-1", [1.0, 1.0, 1.0, 0.0, 0.0, 0.0]),
    );
    assert_error(&text, 3, &["link `b`", "negative mass -1"]);
}

#[test]
fn an_inertia_not_positive_semi_definite() {
    let text = robot(
        "revolute",
        "",
        &inertial("1", [1.0, 1.0, 1.0, 2.0, 0.0, 0.0]),
    );
    assert_error(&text, 3, &["link `b`", "not positive semi-definite"]);
}

/// The warnings of importing `text` as `robot.urdf`, which succeeds: (line,
/// message) each.
fn warnings(text: &str) -> Vec<(Option<usize>, String)> {
    let imported = Urdf::new("robot.urdf", text)
        .import()
        .unwrap_or_else(|e| panic!("the import fails: {e}"));
    dalembert_codegen::check(&imported.model).unwrap();
    imported
        .warnings
        .iter()
        .map(|d| {
            assert_eq!(d.severity(), Severity::Warning);
            assert!(d.to_string().starts_with("warning: "), "{d}");
            (d.line(), d.message().to_owned())
        })
        .collect()
}

#[test]
fn an_inertia_breaking_the_triangle_inequality_is_imported_with_a_warning() {
    let text = robot(
        "revolute",
        "",
        &inertial("1", [1.0, 1.0, 3.0, 0.0, 0.0, 0.0]),
    );
    let found = warnings(&text);
    assert_eq!(found.len(), 1, "{found:?}");
    assert_eq!(found[0].0, Some(3));
    for piece in ["link `b`", "triangle inequality", "as Pinocchio does"] {
        assert!(found[0].1.contains(piece), "`{piece}` not in {found:?}");
    }
    let model = Urdf::new("robot.urdf", text.as_str()).model().unwrap();
    assert!(model.contains("inertia: [1, 1, 3]"), "{model}");
}

#[test]
fn inertias_are_checked_once_welded() {
    // Alone, the tool's tensor is not positive semi-definite (moments −1,
    // 1, 3, as Tiago's antennas); welded to `b` it is part of a body that
    // is, and the dynamics see only that body.
    let text = robot("revolute", "", &unit_mass()).replace(
        "</robot>",
        &format!(
            r#"  <link name="tool">{}</link>
  <joint name="weld" type="fixed"><parent link="b"/><child link="tool"/></joint>
</robot>"#,
            inertial("0.001", [1e-6, 1e-6, 1e-6, 2e-6, 0.0, 0.0])
        ),
    );
    assert_eq!(warnings(&text), []);
    // Welded to a fixed root, it never moves: nothing to check.
    let on_the_root = text.replace(
        "<parent link=\"b\"/><child link=\"tool\"/>",
        "<parent link=\"a\"/><child link=\"tool\"/>",
    );
    assert_eq!(warnings(&on_the_root), []);
}

#[test]
fn rounding_in_an_inertia_is_written_as_zero() {
    // iCub's hips: diagonal entries of −5e-20 kg m², which the language
    // would take for negative moments.
    let text = robot(
        "revolute",
        "",
        &inertial("0.5", [-5.42101e-20, -5.42101e-20, 0.0, 0.0, 2.4e-35, 0.0]),
    )
    .replace(
        "<child link=\"b\"/>",
        "<child link=\"b\"/><origin xyz=\"0 0 0\"/>",
    )
    .replace("<inertial>", "<inertial><origin xyz=\"0 0.1 0\"/>");
    assert_eq!(warnings(&text), []);
    let model = Urdf::new("robot.urdf", text.as_str()).model().unwrap();
    assert!(model.contains("inertia: [0, 0, 0]"), "{model}");
}

#[test]
fn a_joint_that_moves_no_mass() {
    // Romeo's fingers: links without `<inertial>` beyond a moving joint.
    assert_error(
        &robot("revolute", "", ""),
        4,
        &["joint `j` moves no mass", "link `b`", "singular"],
    );
    let massless = inertial("0", [0.0; 6]);
    assert_error(
        &robot("prismatic", "", &massless),
        4,
        &["joint `j` moves no mass"],
    );
}

#[test]
fn a_robot_name_that_is_not_an_identifier_is_prefixed() {
    let text = robot("revolute", "", &unit_mass()).replace("name=\"r\"", "name=\"2dof_planar\"");
    let found = warnings(&text);
    assert_eq!(found.len(), 1, "{found:?}");
    assert!(found[0].1.contains("`Robot2dofPlanar`"), "{found:?}");
    let model = Urdf::new("robot.urdf", text.as_str()).model().unwrap();
    assert!(model.contains("pub Robot2dofPlanar {"), "{model}");
}

#[test]
fn a_zero_axis() {
    let text = robot("revolute", "\n    <axis xyz=\"0 0 0\"/>", "");
    assert_error(&text, 7, &["joint `j`", "axis is zero"]);
}

#[test]
fn unsupported_joint_types() {
    assert_error(
        &robot("planar", "", ""),
        4,
        &["joint `j`", "`planar` is not supported"],
    );
    assert_error(
        &robot("floating", "", ""),
        4,
        &[
            "joint `j`",
            "`floating` is not supported",
            "only at the root",
        ],
    );
    assert_error(&robot("hinge", "", ""), 4, &["unknown joint type `hinge`"]);
}

#[test]
fn numbers_are_checked() {
    let text = robot("revolute", "\n    <origin xyz=\"1 oops 2 3\"/>", "");
    assert_error(
        &text,
        7,
        &["joint `j`", "`xyz=\"1 oops 2 3\"` is not 3 finite numbers"],
    );
}

#[test]
fn quaternion_origins_are_not_supported() {
    let text = robot("revolute", "\n    <origin quat_xyzw=\"0 0 0 1\"/>", "");
    assert_error(
        &text,
        7,
        &["joint `j`", "`quat_xyzw` orientations are not supported"],
    );
}

#[test]
fn all_errors_are_reported_together() {
    let text = r#"<robot name="r">
  <link name="a"><inertial><mass value="-2"/><inertia ixx="1" iyy="1" izz="1" ixy="0" iyz="0" ixz="0"/></inertial></link>
  <link name="b"/>
  <joint name="j" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 0"/></joint>
</robot>"#;
    let lines: Vec<_> = errors(text).into_iter().map(|(line, _)| line).collect();
    assert_eq!(lines, [Some(2), Some(4)]);
}

#[test]
fn damping_becomes_a_dissipation_function() {
    let text = robot(
        "revolute",
        "\n    <dynamics damping=\"0.25\"/>",
        &unit_mass(),
    );
    let plain = Urdf::new("robot.urdf", text.as_str()).model().unwrap();
    assert!(!plain.contains("dissipation"), "{plain}");
    let damped = Urdf::new("robot.urdf", text.as_str())
        .damping(true)
        .model()
        .unwrap();
    assert!(
        damped.contains("dissipation 1/2 * (0.25 * dt(j)^2);"),
        "{damped}"
    );
    // The damping force −d q̇ is all that changes.
    use dalembert_codegen::testing::{Interpreter, Route, Values};
    let at = Values {
        parameters: &[],
        t: 0.0,
        q: &[0.3],
        qd: &[2.0],
        u: &[0.5],
    };
    let f = |model: &str| {
        Interpreter::new(model, Route::Dalembert)
            .unwrap()
            .forcing(&at)[0]
    };
    assert!((f(&damped) - (f(&plain) - 0.25 * 2.0)).abs() < 1e-15);
}

#[test]
fn names_and_struct_name() {
    let text = robot("continuous", "", &unit_mass())
        .replace("name=\"j\"", "name=\"my-joint\"")
        .replace("name=\"r\"", "name=\"small_arm\"");
    let model = Urdf::new("robot.urdf", text.as_str()).model().unwrap();
    assert!(model.contains("pub SmallArm {"), "{model}");
    assert!(model.contains("coordinates my_joint;"), "{model}");
    assert!(model.contains("inputs tau_my_joint;"), "{model}");
    let named = Urdf::new("robot.urdf", text.as_str())
        .name("Arm")
        .model()
        .unwrap();
    assert!(named.contains("pub Arm {"), "{named}");
    let bad = Urdf::new("robot.urdf", text.as_str())
        .name("2Arm")
        .model()
        .unwrap_err();
    assert!(
        bad.to_string().contains("expected a Rust identifier"),
        "{bad}"
    );
    let builtin = Urdf::new("robot.urdf", text.as_str())
        .name("N")
        .model()
        .unwrap_err();
    assert!(
        builtin
            .to_string()
            .contains("nor a built-in name of the language (`N`, `O`"),
        "{builtin}"
    );
}

#[test]
fn a_robot_without_a_name_needs_the_struct_named() {
    let text = robot("continuous", "", &unit_mass()).replace("<robot name=\"r\">", "<robot>");
    assert_error(&text, 1, &["`<robot>` has no attribute `name`", "`--name`"]);
    let named = Urdf::new("robot.urdf", text.as_str())
        .name("Arm")
        .model()
        .expect("imports with the struct named");
    assert!(named.contains("pub Arm {"), "{named}");
    assert!(named.starts_with("/// The robot of robot.urdf"), "{named}");
}

#[test]
fn a_robot_without_a_name_and_a_broken_tree_reports_both() {
    let text = robot("continuous", "", &unit_mass())
        .replace("<robot name=\"r\">", "<robot>")
        .replace("<parent link=\"a\"/>", "<parent link=\"x\"/>");
    let found = errors(&text);
    assert_eq!(found.len(), 2, "{found:?}");
    assert_eq!(found[0].0, Some(1), "{found:?}");
    assert!(found[0].1.contains("no attribute `name`"), "{found:?}");
    assert_eq!(found[1].0, Some(5), "{found:?}");
    assert!(found[1].1.contains("unknown parent link `x`"), "{found:?}");
}

#[test]
fn joint_names_that_cannot_be_coordinates() {
    let mass = unit_mass();
    let keyword = robot("revolute", "", &mass).replace("name=\"j\"", "name=\"type\"");
    assert_error(
        &keyword,
        4,
        &["joint `type`", "coordinate would be named `type`"],
    );
    let twins = format!(
        r#"<robot name="r">
  <link name="a"/>
  <link name="b">{mass}</link>
  <link name="c">{mass}</link>
  <joint name="a-b" type="revolute"><parent link="a"/><child link="b"/></joint>
  <joint name="a_b" type="revolute"><parent link="a"/><child link="c"/></joint>
</robot>"#
    );
    assert_error(
        &twins,
        6,
        &["joint `a_b`", "coordinate would be named `a_b`"],
    );
}

fn scratch(test: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("urdf_errors_{test}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn builder_reports_the_error_and_writes_nothing() {
    let dir = scratch("builder");
    let input = dir.join("bad.urdf");
    std::fs::write(&input, robot("planar", "", "")).unwrap();
    let error = Builder::new()
        .urdf(&input)
        .out_dir(dir.join("out"))
        .emit_rerun_if_changed(false)
        .compile()
        .unwrap_err();
    let BuildError::Model(diagnostics) = &error else {
        panic!("{error}")
    };
    assert_eq!(diagnostics[0].line(), Some(4));
    assert!(error.to_string().contains("bad.urdf:4:"), "{error}");
    assert!(!dir.join("out/bad.rs").exists());
}

#[test]
fn builder_writes_the_robot_named_after_the_file() {
    let dir = scratch("builder_ok");
    let input = dir.join("arm.urdf");
    let text = robot("revolute", "", &unit_mass());
    std::fs::write(&input, &text).unwrap();
    let written = Builder::new()
        .urdf(&input)
        .out_dir(&dir)
        .emit_rerun_if_changed(false)
        .compile()
        .unwrap();
    assert_eq!(written, [dir.join("arm.rs")]);
    let model = Urdf::new(&input, text).model().unwrap();
    let code = std::fs::read_to_string(dir.join("arm.rs")).unwrap();
    assert_eq!(code, dalembert_codegen::generate(&model).unwrap());
}

fn dalembert(args: &[&str]) -> Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_dalembert"))
        .args(args)
        .output()
        .expect("run dalembert")
}

#[test]
fn the_command_prints_nothing_on_error() {
    let dir = scratch("cli");
    let input = dir.join("bad.urdf");
    std::fs::write(&input, robot("revolute", "\n    <axis xyz=\"0 0 0\"/>", "")).unwrap();
    let out = dalembert(&["urdf", input.to_str().unwrap()]);
    assert!(!out.status.success());
    assert!(out.stdout.is_empty());
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert!(
        stderr.contains("bad.urdf:7:") && stderr.contains("axis is zero"),
        "{stderr}"
    );
    let floating = dalembert(&["urdf", input.to_str().unwrap(), "--floating"]);
    assert!(!floating.status.success() && floating.stdout.is_empty());
}

#[test]
fn the_command_prints_the_model() {
    let panda = Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/reference/urdf/panda.urdf");
    let out = dalembert(&["urdf", panda.to_str().unwrap(), "--name", "Arm"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    let expected = Urdf::read(&panda).unwrap().name("Arm").model().unwrap();
    assert_eq!(text, expected);
    dalembert_codegen::check(&text).unwrap();
}

#[test]
fn the_command_prints_the_model_and_its_warnings() {
    let dir = scratch("cli_warnings");
    let input = dir.join("odd.urdf");
    let text = robot(
        "revolute",
        "",
        &inertial("1", [1.0, 1.0, 3.0, 0.0, 0.0, 0.0]),
    );
    std::fs::write(&input, &text).unwrap();
    let out = dalembert(&["urdf", input.to_str().unwrap()]);
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert!(out.status.success(), "{stderr}");
    assert!(
        stderr.starts_with("warning: link `b`") && stderr.contains("odd.urdf:3:"),
        "{stderr}"
    );
    let expected = Urdf::new(&input, text).model().unwrap();
    assert_eq!(String::from_utf8(out.stdout).unwrap(), expected);
}
