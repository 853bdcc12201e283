//! `dalembert urdf` as a user runs it, and its build-script twin: the
//! subcommand's own help, `--outputs` appending the statement, and the
//! errors a user meets first (an output naming an unknown link, a list
//! that is not one, an option the subcommand does not take), each one line
//! on stderr with nothing on stdout and a non-zero exit. `Builder::urdf_with`
//! takes the same options and writes the same model.

use std::path::{Path, PathBuf};
use std::process::Output;

use dalembert_codegen::{Builder, ImportOptions, Urdf};

fn robot(file: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../tests/reference")
        .join(file)
        .to_str()
        .unwrap()
        .to_owned()
}

/// The `dalembert` command run with `args` (shared with `mjcf_doors.rs`).
pub(crate) fn dalembert(args: &[&str]) -> Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_dalembert"))
        .args(args)
        .output()
        .expect("run dalembert")
}

/// The one line on stderr of a failed run, which printed nothing on stdout.
fn one_line_error(args: &[&str]) -> String {
    let out = dalembert(args);
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert!(!out.status.success(), "{args:?} succeeded");
    assert!(out.stdout.is_empty(), "{args:?} printed on stdout");
    assert_eq!(stderr.lines().count(), 1, "{args:?}:\n{stderr}");
    assert!(stderr.starts_with("error: "), "{stderr}");
    stderr
}

#[test]
fn every_subcommand_prints_its_own_help() {
    for command in ["urdf", "eom", "generate", "check", "chain"] {
        for flag in ["--help", "-h"] {
            let out = dalembert(&[command, flag]);
            assert_eq!(out.status.code(), Some(0), "{command} {flag}");
            let help = String::from_utf8(out.stdout).unwrap();
            assert!(
                help.starts_with(&format!("Usage: dalembert {command} ")),
                "{command} {flag}:\n{help}"
            );
        }
    }
    let out = dalembert(&["urdf", robot("urdf/ur5_robot.urdf").as_str(), "--help"]);
    let help = String::from_utf8(out.stdout).unwrap();
    for option in [
        "--floating",
        "--name NAME",
        "--damping",
        "--outputs \"LIST\"",
    ] {
        assert!(help.contains(option), "{help}");
    }
}

#[test]
fn outputs_are_appended_to_the_model() {
    let ur5 = robot("urdf/ur5_robot.urdf");
    let list = "position(tool0_origin), jacobian(tool0_origin), rotation(tool0), linearize";
    let out = dalembert(&["urdf", &ur5, "--outputs", list]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let model = String::from_utf8(out.stdout).unwrap();
    assert!(
        model.ends_with(&format!("    outputs {list};\n}}\n")),
        "{model}"
    );
    // The library route writes the same text.
    let library = Urdf::read(&ur5).unwrap().outputs(list).model().unwrap();
    assert_eq!(model, library);
}

#[test]
fn an_output_naming_an_unknown_link_is_one_line() {
    let ur5 = robot("urdf/ur5_robot.urdf");
    let error = one_line_error(&["urdf", &ur5, "--outputs", "jacobian(tool1_origin)"]);
    assert!(
        error.contains("unknown name `tool1_origin`") && error.contains("L_origin"),
        "{error}"
    );
    let error = one_line_error(&["urdf", &ur5, "--outputs", "rotation(tool0_origin)"]);
    assert!(error.contains("tool0_origin"), "{error}");
}

#[test]
fn a_malformed_output_list_is_one_line() {
    let ur5 = robot("urdf/ur5_robot.urdf");
    for list in [
        "jacobian(tool0_origin",
        "position(tool0_origin) rotation(tool0)",
        "linearize; }",
        "",
    ] {
        let error = one_line_error(&["urdf", &ur5, "--outputs", list]);
        assert!(error.contains("not a list of outputs"), "{list}: {error}");
    }
    let error = one_line_error(&["urdf", &ur5, "--outputs"]);
    assert!(error.contains("`--outputs` needs"), "{error}");
}

#[test]
fn an_option_the_subcommand_does_not_take_is_one_line() {
    let ur5 = robot("urdf/ur5_robot.urdf");
    for (args, expected) in [
        (
            &["urdf", &ur5, "--latex"][..],
            "unknown option `--latex` of `urdf`",
        ),
        (
            &["urdf", &ur5, "--frobnicate"],
            "unknown option `--frobnicate`",
        ),
        (
            &["eom", &ur5, "--outputs", "linearize"],
            "`eom` takes no option `--outputs`",
        ),
        (&["urdf", &ur5, &ur5], "unexpected argument"),
    ] {
        let error = one_line_error(args);
        assert!(error.contains(expected), "{args:?}: {error}");
        assert_eq!(dalembert(args).status.code(), Some(2));
    }
}

/// `Builder::urdf_with` takes the command line's options and generates the
/// model it prints: the struct's name, the floating base and the outputs.
#[test]
fn the_build_script_takes_the_command_line_options() {
    let ur5 = robot("urdf/ur5_robot.urdf");
    let out_dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("urdf_cli_builder");
    let options = ImportOptions::new()
        .name("Arm")
        .floating(true)
        .outputs("jacobian(tool0_origin)");
    let written = Builder::new()
        .urdf_with(&ur5, options.clone())
        .out_dir(&out_dir)
        .emit_rerun_if_changed(false)
        .compile()
        .unwrap();
    let code = std::fs::read_to_string(&written[0]).unwrap();
    assert!(code.contains("pub struct Arm"), "the struct's name");
    assert!(code.contains("pub fn jacobian_tool0_origin("), "the output");
    assert!(code.contains("root_joint_qw"), "the floating base");
    let printed = dalembert(&[
        "urdf",
        &ur5,
        "--name",
        "Arm",
        "--floating",
        "--outputs",
        "jacobian(tool0_origin)",
    ]);
    let model = String::from_utf8(printed.stdout).unwrap();
    assert_eq!(
        model,
        Urdf::read(&ur5).unwrap().options(options).model().unwrap()
    );
    assert_eq!(code, dalembert_codegen::generate(&model).unwrap());
    // An unknown link in a build script's outputs: the same one line.
    let error = Builder::new()
        .urdf_with(
            &ur5,
            ImportOptions::new().outputs("position(flange_origin)"),
        )
        .out_dir(&out_dir)
        .emit_rerun_if_changed(false)
        .compile()
        .unwrap_err()
        .to_string();
    assert!(
        error.contains("unknown name `flange_origin`") && !error.contains('\n'),
        "{error}"
    );
}
