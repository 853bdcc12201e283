//! The benchmark trees of `trees/` (imported by `Builder::urdf` in
//! `build.rs`, and timed by the peers' harness from the same files): the
//! committed URDF files are what `dalembert_codegen::testing::Shape` writes
//! (run with `DALEMBERT_WRITE_TREES=1` to rewrite them after changing the
//! generator), and the generated systems hold one coordinate per joint.
//! `Shape`'s own tests check the imported models against both interpreter
//! routes.

use dalembert_codegen::testing::Shape;
use dalembert_generated::{BinaryTree, CartPole1, CartPole3, CartPole6, Limbs};

#[test]
fn committed_trees_match_the_generator() {
    let write = std::env::var_os("DALEMBERT_WRITE_TREES").is_some();
    for shape in Shape::ALL {
        let path = format!("{}/trees/{}.urdf", env!("CARGO_MANIFEST_DIR"), shape.name());
        let text = shape.urdf();
        if write {
            std::fs::write(&path, &text).expect("trees/ is writable");
        }
        let committed = std::fs::read_to_string(&path).unwrap_or_default();
        assert!(
            committed == text,
            "{path} differs from Shape::urdf(): rerun with DALEMBERT_WRITE_TREES=1"
        );
    }
}

#[test]
fn generated_trees_have_one_coordinate_per_joint() {
    assert_eq!(
        [
            CartPole1::NQ,
            CartPole3::NQ,
            CartPole6::NQ,
            Limbs::NQ,
            BinaryTree::NQ
        ],
        Shape::ALL.map(Shape::joints)
    );
}
