//! Several top-level `<default>` elements, as a model gets when it
//! includes a file with defaults of its own (dm_control's Jaco arm
//! includes `common.xml`): MuJoCo reads them as one class `main`, merged
//! attribute by attribute with the later winning, and a class nested in
//! an earlier one keeps `main`'s attributes as they were when it was made
//! (MuJoCo copies the parent class into the child). The import used to
//! refuse such a model ("the default class `main` is defined twice").
//!
//! The expected values are MuJoCo 4.0's, from
//! `mujoco.MjModel.from_xml_path` of the two files below: `dof_damping`
//! `[0.5, 0.5, 0.5]`, `dof_armature` `[0.25, 0.125, 0.25]`,
//! `jnt_stiffness` `[0, 3, 0]`, `body_mass` `[0, 1.7802358370342164,
//! 0.9114807485615186, 0.3619114736935441]` (the second block's geom
//! density, 400, applies to every geom).

use dalembert_codegen::Mjcf;

/// The included file: `main`'s damping and armature, and the class
/// `early` made from them.
const PARTS: &str = r#"<mujoco>
  <default>
    <joint damping="0.5" armature="0.125"/>
    <default class="early">
      <joint stiffness="3"/>
    </default>
  </default>
</mujoco>
"#;

/// The model: a second top-level `<default>` changes `main`'s armature
/// (not `early`'s) and adds a density and the class `late`.
const MODEL: &str = r#"<mujoco model="merged_defaults">
  <include file="parts.xml"/>
  <default>
    <joint armature="0.25" frictionloss="0.1"/>
    <geom density="400"/>
    <default class="late">
      <joint springref="10"/>
    </default>
  </default>
  <worldbody>
    <body name="upper">
      <joint name="shoulder" type="hinge" axis="0 1 0"/>
      <geom type="capsule" fromto="0 0 0 0 0 -0.5" size="0.05"/>
      <body name="lower" pos="0 0 -0.5">
        <joint name="elbow" class="early" type="hinge" axis="0 1 0"/>
        <geom type="capsule" fromto="0 0 0 0 0 -0.4" size="0.04"/>
        <body name="hand" pos="0 0 -0.4">
          <joint name="wrist" class="late" type="hinge" axis="1 0 0"/>
          <geom type="sphere" size="0.06"/>
        </body>
      </body>
    </body>
  </worldbody>
</mujoco>
"#;

/// The model imported from `main.xml` beside `parts.xml` in a fresh
/// directory.
fn imported(tag: &str, model: &str) -> Result<String, String> {
    let dir = std::env::temp_dir().join(format!("dalembert-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("parts.xml"), PARTS).unwrap();
    std::fs::write(dir.join("main.xml"), model).unwrap();
    let result = Mjcf::read(dir.join("main.xml"))
        .and_then(|m| m.model())
        .map_err(|e| e.to_string());
    std::fs::remove_dir_all(&dir).unwrap();
    result
}

#[test]
fn top_level_defaults_merge_into_main_as_in_mujoco() {
    let text = imported("mjcf-defaults", MODEL).unwrap_or_else(|e| panic!("{e}"));
    for statement in [
        // Damping from the first block, on every joint.
        "dissipation 1/2 * (0.5 * dt(shoulder)^2 + 0.5 * dt(elbow)^2 + 0.5 * dt(wrist)^2);",
        // The second block's armature, but `early` kept the first's.
        "armature 0.25 on dt(shoulder);",
        "armature 0.125 on dt(elbow);",
        "armature 0.25 on dt(wrist);",
        // `early`'s stiffness; `late`'s springref alone adds no spring.
        "potential 1/2 * (3 * elbow^2);",
        // The second block's density on every geom: MuJoCo's body masses.
        "mass: 1.7802358370342164,",
        "mass: 0.9114807485615186,",
        "mass: 0.3619114736935441,",
    ] {
        assert!(text.contains(statement), "`{statement}` not in:\n{text}");
    }
}

#[test]
fn a_renamed_top_level_default_is_refused_as_by_mujoco() {
    // MuJoCo: "top-level default class 'main' cannot be renamed".
    let renamed = MODEL.replacen(
        "<default>\n    <joint armature",
        "<default class=\"extra\">\n    <joint armature",
        1,
    );
    assert_ne!(renamed, MODEL);
    let error = imported("mjcf-renamed-default", &renamed).expect_err("refused");
    assert!(error.contains("cannot be renamed"), "{error}");
    assert!(error.contains("main.xml:3:"), "{error}");
}
