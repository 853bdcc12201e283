//! The benchmark trees beyond the chains, as URDF text, which the engine
//! (`Builder::urdf`, `dalembert urdf`) and the peers' harness (Pinocchio's
//! own URDF parser) read alike: a cart-pole chain, a torso with four limbs
//! and a binary tree. Rods are uniform (`mᵢ = 1 + i/10`, `Lᵢ = 1/2 + i/20`
//! for the `i`-th link in file order, as the chains), with a small inertia
//! about their own axis.

use std::fmt::Write;

/// One benchmark tree.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shape {
    /// A cart sliding along `x` (prismatic joint on the ground) carrying an
    /// inverted pendulum of `links` rods, revolute about `y`, upright at
    /// `q = 0`.
    CartPole {
        /// The number of pendulum rods.
        links: usize,
    },
    /// A torso turning about the vertical, with four limbs of three rods
    /// (hip about `x`, hip and knee about `y`) at its corners: 13 joints.
    Limbs,
    /// A binary tree of 31 rods (five levels): the root turns about `z` on
    /// the ground, and every rod carries two children at its far end, on
    /// joints about `y` (left) and `z` (right).
    BinaryTree,
}

impl Shape {
    /// Every tree of the benchmarks.
    pub const ALL: [Shape; 5] = [
        Shape::CartPole { links: 1 },
        Shape::CartPole { links: 3 },
        Shape::CartPole { links: 6 },
        Shape::Limbs,
        Shape::BinaryTree,
    ];

    /// The file stem: `cart_pole_3`, `limbs`, `binary_tree`.
    pub fn name(self) -> String {
        match self {
            Shape::CartPole { links } => format!("cart_pole_{links}"),
            Shape::Limbs => "limbs".to_owned(),
            Shape::BinaryTree => "binary_tree".to_owned(),
        }
    }

    /// The number of joints (coordinates).
    pub fn joints(self) -> usize {
        match self {
            Shape::CartPole { links } => links + 1,
            Shape::Limbs => 13,
            Shape::BinaryTree => 31,
        }
    }

    /// The URDF text.
    pub fn urdf(self) -> String {
        let mut robot = Robot::default();
        match self {
            Shape::CartPole { links } => {
                robot.joint("cart", "prismatic", "world", [0.0; 3], [1.0, 0.0, 0.0]);
                let mut parent = "cart".to_owned();
                let mut at = 0.0;
                for i in 1..=links {
                    let name = format!("pole{i}");
                    robot.joint(&name, "revolute", &parent, [0.0, 0.0, at], [0.0, 1.0, 0.0]);
                    at = robot.rod_length();
                    parent = name;
                }
            }
            Shape::Limbs => {
                robot.joint(
                    "torso",
                    "revolute",
                    "world",
                    [0.0, 0.0, 1.0],
                    [0.0, 0.0, 1.0],
                );
                let corners = [(0.3, 0.2), (0.3, -0.2), (-0.3, 0.2), (-0.3, -0.2)];
                for (limb, (x, y)) in corners.into_iter().enumerate() {
                    let (mut parent, mut at) = ("torso".to_owned(), [x, y, 0.0]);
                    for (part, axis) in [
                        ("abduction", [1.0, 0.0, 0.0]),
                        ("hip", [0.0, 1.0, 0.0]),
                        ("knee", [0.0, 1.0, 0.0]),
                    ] {
                        let name = format!("limb{limb}_{part}");
                        robot.joint(&name, "revolute", &parent, at, axis);
                        at = [0.0, 0.0, robot.rod_length()];
                        parent = name;
                    }
                }
            }
            Shape::BinaryTree => robot.binary_tree("world", "b", 5, [0.0; 3], [0.0, 0.0, 1.0]),
        }
        robot.finish(&self.name())
    }
}

/// URDF text being written: links and joints, in file order.
#[derive(Default)]
struct Robot {
    body: String,
    /// Rods written so far.
    rods: usize,
}

impl Robot {
    /// The length of the last rod written.
    fn rod_length(&self) -> f64 {
        0.5 + self.rods as f64 / 20.0
    }

    /// A joint from `parent` at `xyz` (in the parent's axes) about or along
    /// `axis`, and its child link, named `name`: a uniform rod along `+z`.
    fn joint(&mut self, name: &str, kind: &str, parent: &str, xyz: [f64; 3], axis: [f64; 3]) {
        self.rods += 1;
        let i = self.rods as f64;
        let (mass, length) = (1.0 + i / 10.0, self.rod_length());
        let transverse = mass * length * length / 12.0;
        let axial = mass * 0.02 * 0.02 / 2.0;
        let [x, y, z] = xyz;
        let [ax, ay, az] = axis;
        let _ = write!(
            self.body,
            "  <joint name=\"{name}\" type=\"{kind}\">\n    <parent link=\"{parent}\"/>\n    \
             <child link=\"{name}\"/>\n    <origin xyz=\"{x} {y} {z}\" rpy=\"0 0 0\"/>\n    \
             <axis xyz=\"{ax} {ay} {az}\"/>\n    <limit effort=\"100\" velocity=\"10\" lower=\"-10\" upper=\"10\"/>\n  \
             </joint>\n  <link name=\"{name}\">\n    <inertial>\n      \
             <origin xyz=\"0 0 {}\" rpy=\"0 0 0\"/>\n      <mass value=\"{mass}\"/>\n      \
             <inertia ixx=\"{transverse}\" ixy=\"0\" ixz=\"0\" iyy=\"{transverse}\" iyz=\"0\" izz=\"{axial}\"/>\n    \
             </inertial>\n  </link>\n",
            length / 2.0
        );
    }

    /// A subtree of `levels` levels: a rod named `name` on a joint about
    /// `axis` at `xyz`, and two subtrees at its far end.
    fn binary_tree(
        &mut self,
        parent: &str,
        name: &str,
        levels: u32,
        xyz: [f64; 3],
        axis: [f64; 3],
    ) {
        self.joint(name, "revolute", parent, xyz, axis);
        if levels > 1 {
            let length = self.rod_length();
            let (left, right) = (format!("{name}l"), format!("{name}r"));
            self.binary_tree(
                name,
                &left,
                levels - 1,
                [0.05, 0.0, length],
                [0.0, 1.0, 0.0],
            );
            self.binary_tree(
                name,
                &right,
                levels - 1,
                [-0.05, 0.0, length],
                [0.0, 0.0, 1.0],
            );
        }
    }

    fn finish(self, name: &str) -> String {
        format!(
            "<?xml version=\"1.0\"?>\n<!-- A benchmark tree written by dalembert_codegen::testing::Shape. -->\n\
             <robot name=\"{name}\">\n  <link name=\"world\"/>\n{}</robot>\n",
            self.body
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::interpret::{Interpreter, Route, Sample};

    /// The `.dal` model of a tree, imported as `dalembert urdf` does.
    fn model(shape: Shape) -> String {
        crate::Urdf::new(format!("{}.urdf", shape.name()), shape.urdf())
            .model()
            .unwrap_or_else(|e| panic!("{e}"))
    }

    #[test]
    fn every_tree_has_its_joints_and_takes_the_recursive_route() {
        for shape in Shape::ALL {
            let text = model(shape);
            let ours = Interpreter::new(&text, Route::Dalembert).unwrap_or_else(|e| panic!("{e}"));
            assert_eq!(ours.nq(), shape.joints(), "{}", shape.name());
            let state = Sample::random(&ours, 1);
            assert!(ours.articulated_accelerations(&state.values()).is_some());
        }
    }

    /// Both interpreter routes (d'Alembert's recursion and Lagrange's
    /// equations from `T` and `V`) agree on `M` and `f`, and the
    /// articulated-body recursion solves them.
    #[test]
    fn both_routes_agree_on_every_tree() {
        for shape in Shape::ALL {
            let text = model(shape);
            let ours = Interpreter::new(&text, Route::Dalembert).unwrap_or_else(|e| panic!("{e}"));
            let theirs = Interpreter::new(&text, Route::Lagrange).unwrap_or_else(|e| panic!("{e}"));
            for seed in 0..3 {
                let state = Sample::random(&ours, seed);
                let at = state.values();
                let (m, f) = (theirs.mass_matrix(&at), theirs.forcing(&at));
                let scale = m
                    .concat()
                    .iter()
                    .chain(&f)
                    .fold(1.0_f64, |s, x| s.max(x.abs()));
                let close = |a: f64, b: f64| (a - b).abs() <= 1e-10 * scale;
                let ours_m = ours.mass_matrix(&at);
                for (row, theirs_row) in ours_m.iter().zip(&m) {
                    for (a, b) in row.iter().zip(theirs_row) {
                        assert!(close(*a, *b), "{}: M {a} vs {b}", shape.name());
                    }
                }
                for (a, b) in ours.forcing(&at).iter().zip(&f) {
                    assert!(close(*a, *b), "{}: f {a} vs {b}", shape.name());
                }
                let qdd = ours.articulated_accelerations(&at).expect("a tree");
                for (row, fk) in m.iter().zip(&f) {
                    let mq: f64 = row.iter().zip(&qdd).map(|(a, b)| a * b).sum();
                    assert!(close(mq, *fk), "{}: M q̈ {mq} vs f {fk}", shape.name());
                }
            }
        }
    }
}
