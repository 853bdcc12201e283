//! The two doors of the MJCF import take the same options and give the
//! same model (DESIGN §8: "the build script's URDF and MJCF entries take
//! the same options as the command line"): `Builder::mjcf_with` writes
//! the code of the model `dalembert mjcf` prints with `--name` and
//! `--outputs`, and both refuse `floating` and `damping`, which the
//! command line does not take for MJCF (the file says which bodies float
//! and how joints are damped). The model is one no other test reads:
//! nested `<default>` classes, `childclass` on a body and its override by
//! a class on a joint and a geom (MuJoCo 3.3's compiled model of it has the
//! joints, damping, armature, stiffness and `springref` the test reads in
//! the model's text, and its bodies' masses).

use std::path::PathBuf;

use crate::urdf_cli::dalembert;

use dalembert_codegen::{BuildError, Builder, ImportOptions, Mjcf};

const GRIPPER: &str = r#"<mujoco model="two finger gripper">
  <compiler angle="degree"/>
  <option gravity="0 0 -9.8"/>
  <default>
    <joint damping="0.2"/>
    <geom density="500"/>
    <default class="finger">
      <joint type="hinge" axis="0 1 0" armature="0.01" stiffness="2" springref="10"/>
      <geom type="capsule" size="0.01" fromto="0 0 0 0 0 -0.06"/>
      <default class="tip">
        <joint axis="1 0 0" damping="0.05"/>
        <geom type="box" size="0.01 0.01 0.01" fromto="0 0 0 0 0 -0.02"/>
      </default>
    </default>
  </default>
  <worldbody>
    <body name="palm" pos="0 0 0.5" euler="0 0 30">
      <joint name="lift" type="slide" axis="0 0 1"/>
      <geom type="box" size="0.04 0.02 0.01"/>
      <body name="left" pos="0.03 0 -0.01" childclass="finger">
        <joint name="left_base" range="-30 30"/>
        <geom/>
        <body name="left_tip" pos="0 0 -0.06">
          <joint name="left_roll" class="tip"/>
          <geom class="tip"/>
        </body>
      </body>
      <body name="right" pos="-0.03 0 -0.01" childclass="finger">
        <joint name="right_base"/>
        <geom/>
      </body>
    </body>
  </worldbody>
</mujoco>
"#;

/// The gripper's file in a directory of this test's own.
fn gripper(test: &str) -> (PathBuf, PathBuf) {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("mjcf_doors_{test}"));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("gripper.xml");
    std::fs::write(&file, GRIPPER).unwrap();
    (dir, file)
}

#[test]
fn the_build_script_writes_the_code_of_the_model_the_command_prints() {
    let (dir, file) = gripper("same");
    let outputs = "position(left_tip_origin), rotation(left_tip)";
    let printed = dalembert(&[
        "mjcf",
        file.to_str().unwrap(),
        "--name",
        "Gripper",
        "--outputs",
        outputs,
    ]);
    assert!(printed.status.success(), "{printed:?}");
    let model = String::from_utf8(printed.stdout).unwrap();
    let options = ImportOptions::new().name("Gripper").outputs(outputs);
    assert_eq!(
        model,
        Mjcf::read(&file)
            .unwrap()
            .options(options.clone())
            .model()
            .unwrap()
    );
    let written = Builder::new()
        .mjcf_with(&file, options)
        .out_dir(&dir)
        .emit_rerun_if_changed(false)
        .compile()
        .unwrap();
    let code = std::fs::read_to_string(&written[0]).unwrap();
    assert_eq!(code, dalembert_codegen::generate(&model).unwrap());
    assert!(code.contains("pub struct Gripper"));
    assert!(code.contains("pub fn position_left_tip_origin("));
    // The defaults as the classes say: the finger's class on `left_base`
    // and `right_base` (childclass), `tip` on `left_roll` (its own class
    // over the body's childclass), the top default's damping on `lift`.
    let declared: Vec<usize> = ["lift", "left_base", "left_roll", "right_base"]
        .iter()
        .map(|c| model.find(&format!("coordinates {c};")).expect(c))
        .collect();
    assert!(declared.is_sorted(), "MuJoCo's order: {model}");
    for line in [
        "0.2 * dt(lift)^2 + 0.2 * dt(left_base)^2 + 0.05 * dt(left_roll)^2 + 0.2 * dt(right_base)^2",
        "armature 0.01 on dt(left_roll);",
        "body left_tip_mass { mass: 0.004000000000000001, center: left_tip_origin - 0.01 * left_tip.z,",
        "joint revolute left_roll_anchor { parent: left, child: left_tip, axis: x,",
    ] {
        assert!(model.contains(line), "`{line}` in\n{model}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn both_doors_refuse_floating_and_damping() {
    let (dir, file) = gripper("refused");
    for (flag, options) in [
        ("--floating", ImportOptions::new().floating(true)),
        ("--damping", ImportOptions::new().damping(true)),
    ] {
        let out = dalembert(&["mjcf", file.to_str().unwrap(), flag]);
        assert_eq!(out.status.code(), Some(2), "{flag}");
        assert!(out.stdout.is_empty(), "{flag}");
        let stderr = String::from_utf8(out.stderr).unwrap();
        assert_eq!(stderr.lines().count(), 1, "{flag}: {stderr}");
        assert!(
            stderr.starts_with(&format!("error: `mjcf` does not take the option `{flag}`")),
            "{flag}: {stderr}"
        );
        let error = Builder::new()
            .mjcf_with(&file, options)
            .out_dir(&dir)
            .emit_rerun_if_changed(false)
            .compile()
            .expect_err(flag);
        assert!(
            matches!(error, BuildError::ImportOption { .. }),
            "{error:?}"
        );
        let message = error.to_string();
        assert!(
            message.contains("takes no `floating` or `damping` option"),
            "{flag}: {message}"
        );
        assert!(!dir.join("gripper.rs").exists(), "{flag}: nothing written");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
