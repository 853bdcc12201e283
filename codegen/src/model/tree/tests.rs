//! Which models are trees, for both spellings, and which are not.

use super::{JointKind, Tree};
use crate::language::parse_system;
use crate::seeds::{CONSTRAINED_PENDULUM, DOUBLE_PENDULUM, ROTATING_BAR};

fn tree(source: &str) -> Option<Tree> {
    let system = parse_system(source.parse().expect("tokens")).expect("parses");
    let (model, _) = crate::model::resolve(&system).unwrap_or_else(|e| panic!("{e}"));
    model.tree
}

/// `(parent, kind, coordinate)` of each link.
fn shape(tree: &Tree) -> Vec<(Option<usize>, JointKind, usize)> {
    tree.links
        .iter()
        .map(|l| (l.parent, l.kind, l.coordinate))
        .collect()
}

const SEED_SPELLING: &str = "pub Chain {
    parameters m1, m2, m3, L1, L2, L3, g;
    coordinates q1, q2, q3;
    inputs tau1, tau2, tau3;
    frame B1 = N.rotate_z(q1);
    point P1 = O - L1 * B1.y;
    body link1 { mass: m1, center: O - L1/2 * B1.y, frame: B1, inertia: [0, 0, m1*L1^2/12] };
    frame B2 = B1.rotate_z(q2);
    point P2 = P1 - L2 * B2.y;
    body link2 { mass: m2, center: P1 - L2/2 * B2.y, frame: B2, inertia: [0, 0, m2*L2^2/12] };
    frame B3 = B2.rotate_x(q3);
    body link3 { mass: m3, center: P2 - L3/2 * B3.y, frame: B3, inertia: [m3, m3, m3] };
    gravity -g * N.y;
    torque tau1 * N.z on B1;
    torque tau2 * B1.z on B2 reacting B1;
    torque tau3 * B2.x on B3 reacting B2;
}";

#[test]
fn frames_and_points_relative_to_the_parent_are_joints() {
    let tree = tree(SEED_SPELLING).expect("a tree");
    use JointKind::Revolute;
    assert_eq!(
        shape(&tree),
        [
            (None, Revolute, 0),
            (Some(0), Revolute, 1),
            (Some(1), Revolute, 2)
        ]
    );
}

#[test]
fn absolute_angles_are_not_a_relative_joint_tree() {
    assert!(tree(DOUBLE_PENDULUM).is_none());
}

#[test]
fn a_massless_frame_is_a_link_and_the_body_sits_on_its_childs_joint() {
    let tree = tree(ROTATING_BAR).expect("a tree");
    use JointKind::Revolute;
    assert_eq!(shape(&tree), [(None, Revolute, 0), (Some(0), Revolute, 1)]);
}

#[test]
fn two_slides_in_one_point_are_not_a_tree() {
    assert!(tree(CONSTRAINED_PENDULUM).is_none());
}

#[test]
fn a_slide_carries_the_links_placed_from_its_points() {
    let cart_pole = "pub CartPole {
        parameters m, M, l, g;
        coordinates theta, s;
        inputs F;
        frame B = N.rotate([0, 0, 1], theta);
        point C = O + s * N.x + l * N.y;
        body cart { mass: M, center: C, frame: N, inertia: [M, M, M] };
        body pole { mass: m, center: C - l * B.y, frame: B, inertia: [0, 0, m*l^2/12] };
        particle tip { mass: m, at: O + l * N.y + s * N.x - 2 * l * B.y };
        gravity -g * N.y;
        force F * N.x at C;
    }";
    let tree = tree(cart_pole).expect("a tree");
    use JointKind::{Prismatic, Revolute};
    assert_eq!(shape(&tree), [(None, Prismatic, 1), (Some(0), Revolute, 0)]);
}

#[test]
fn joint_statements_make_the_same_tree() {
    let joints = "pub Chain {
        parameters L, m;
        coordinates q1, q2, q3;
        joint revolute J1 { parent: N, child: A, axis: [1, 1, 0], coordinate: q1, at: O };
        frame T = A.rotate_x(-1.8);
        joint prismatic J2 { parent: T, child: B, axis: y, coordinate: q2, at: J1 + L * A.x };
        joint revolute J3 { parent: B, child: C, axis: z, coordinate: q3, at: J2 + L * T.z };
        body a { mass: m, center: J1 + L * T.x, frame: T, inertia: [m, m, m] };
        body b { mass: m, center: J2, frame: B, inertia: [m, m, m] };
        body c { mass: m, center: J3 + L * C.y, frame: C, inertia: [m, m, m] };
    }";
    let tree = tree(joints).expect("a tree");
    use JointKind::{Prismatic, Revolute};
    assert_eq!(
        shape(&tree),
        [
            (None, Revolute, 0),
            (Some(0), Prismatic, 1),
            (Some(1), Revolute, 2)
        ]
    );
}

/// A pendulum with `extra` statements.
fn pendulum(extra: &str) -> String {
    format!(
        "pub P {{
            parameters m, l, k;
            coordinates q1, q2;
            frame B = N.rotate_z(q1);
            {extra}
        }}"
    )
}

#[test]
fn other_geometry_keeps_the_general_route() {
    for extra in [
        // A coordinate inside a point's position.
        "point P = O + sin(q2) * N.x; body b { mass: m, center: P - l * B.y, frame: B, inertia: [m, m, m] };",
        // A frame turned by two coordinates.
        "frame C = B.rotate_x(q1 + q2); body b { mass: m, center: O, frame: C, inertia: [m, m, m] };",
        // A coordinate that no joint moves (only a potential).
        "body b { mass: m, center: O - l * B.y, frame: B, inertia: [m, m, m] }; potential k * q2^2;",
        // One frame's points placed from two different joint points.
        "frame C = B.rotate_z(q2); point P = O - l * B.y; body b { mass: m, center: P - l * C.y, frame: C, inertia: [m, m, m] }; particle p { mass: m, at: O - l * C.y };",
        // A point placed from a child link along the parent's frame.
        "frame C = B.rotate_z(q2); point P = O - l * C.y + l * B.x; body b { mass: m, center: P, frame: C, inertia: [m, m, m] };",
    ] {
        assert!(tree(&pendulum(extra)).is_none(), "{extra}");
    }
}
