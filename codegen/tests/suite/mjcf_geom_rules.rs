//! MuJoCo's rules for a geom that the import must keep: a `fromto` lays a
//! capsule, cylinder, box or ellipsoid along a segment, and MuJoCo refuses
//! it on a sphere ("fromto requires capsule, cylinder, box or ellipsoid in
//! geom", MuJoCo 3.3), also when the sphere inherits the `fromto` from a
//! default class. The import once placed such a sphere at the segment's
//! middle; it is an error at the geom's line.

use dalembert_codegen::Mjcf;

/// A pendulum whose bob is a sphere of the class `bob`, inheriting the
/// rod class's `fromto` unless `own` overrides the geom's attributes.
fn pendulum(own: &str) -> String {
    format!(
        r#"<mujoco model="bob">
  <default>
    <default class="rod">
      <geom type="capsule" size="0.01" fromto="0 0 0 0 0 -0.5"/>
      <default class="bob"><geom type="sphere" size="0.05"/></default>
    </default>
  </default>
  <worldbody>
    <body name="arm">
      <joint name="swing" axis="0 1 0"/>
      <geom class="rod"/>
      <geom class="bob" {own}/>
    </body>
  </worldbody>
</mujoco>
"#
    )
}

#[test]
fn a_sphere_with_a_fromto_is_refused_at_the_geom() {
    for own in ["", r#"fromto="0 0 0 0 0 -0.4""#] {
        let error = Mjcf::new("bob.xml", pendulum(own))
            .model()
            .expect_err("MuJoCo refuses it");
        let [diagnostic] = error.diagnostics() else {
            panic!("one error: {error}")
        };
        assert_eq!(diagnostic.line(), Some(12), "{own}: {error}");
        assert!(
            diagnostic.message().starts_with(
                "geom: `fromto` places a capsule, cylinder, box or ellipsoid; found a sphere"
            ),
            "{own}: {error}"
        );
    }
}

#[test]
fn a_capsule_of_the_same_class_is_laid_along_its_fromto() {
    let model = Mjcf::new("bob.xml", pendulum(r#"type="capsule""#))
        .model()
        .unwrap();
    // Two capsules from the pivot to 0.5 below: their centre at 0.25.
    assert!(
        model.contains("center: arm_origin - 0.25 * arm.z"),
        "{model}"
    );
}
