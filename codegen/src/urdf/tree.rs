//! The robot as a tree: every joint's parent and child resolved to links,
//! the one root found, and the rules of a tree checked (known links, one
//! parent per link, one root, no cycle), with the joint rules the import
//! needs (a supported type, a non-zero axis) and masses that are not
//! negative (the inertias are checked body by body, once welded links are
//! merged, where the model is written). The joints come out in Pinocchio's
//! order: depth-first from the root, the children of a link in ascending
//! byte order of their joint names (urdfdom keeps a link's child joints in
//! a `std::map` keyed by name, whatever their order in the file).

use std::collections::HashMap;

use super::Problem;
use super::xml::{JointType, Robot};

/// The checked tree of a [`Robot`], by index into its links and joints.
#[derive(Debug)]
pub(super) struct Tree {
    /// The root link.
    pub root: usize,
    /// Per link, the joints whose parent it is, in ascending byte order of
    /// their names.
    pub children: Vec<Vec<usize>>,
    /// Per joint, its child link.
    pub child: Vec<usize>,
    /// Per joint, its parent link.
    pub parent: Vec<usize>,
}

impl Tree {
    /// The joints in depth-first order from the root, children by name:
    /// `pinocchio::buildModelFromUrdf`'s order.
    pub fn depth_first(&self) -> Vec<usize> {
        let mut order = Vec::new();
        let mut stack: Vec<usize> = self.children[self.root].iter().rev().copied().collect();
        while let Some(joint) = stack.pop() {
            order.push(joint);
            stack.extend(self.children[self.child[joint]].iter().rev());
        }
        order
    }
}

/// Builds and checks the tree of `robot`, or every problem found.
pub(super) fn tree(robot: &Robot) -> Result<Tree, Vec<Problem>> {
    let mut problems = Vec::new();
    if robot.links.is_empty() {
        problems.push(Problem::new(
            Some(robot.range.start..robot.range.start + 1),
            format!(
                "the {} has no `<link>`: expected at least the root link",
                robot.called()
            ),
        ));
        return Err(problems);
    }
    check_masses(robot, &mut problems);
    check_joints(robot, &mut problems);
    let mut index: HashMap<&str, usize> = HashMap::new();
    for (i, link) in robot.links.iter().enumerate() {
        if index.insert(&link.name, i).is_some() {
            problems.push(Problem::new(
                Some(link.range.clone()),
                format!(
                    "link `{}` is defined twice; link names must be unique",
                    link.name
                ),
            ));
        }
    }
    let mut joint_names: HashMap<&str, usize> = HashMap::new();
    let mut parent_joint: Vec<Option<usize>> = vec![None; robot.links.len()];
    let mut children = vec![Vec::new(); robot.links.len()];
    let mut child = vec![0; robot.joints.len()];
    let mut parent = vec![0; robot.joints.len()];
    for (j, joint) in robot.joints.iter().enumerate() {
        if joint_names.insert(&joint.name, j).is_some() {
            problems.push(Problem::new(
                Some(joint.range.clone()),
                format!(
                    "joint `{}` is defined twice; joint names must be unique",
                    joint.name
                ),
            ));
        }
        let mut resolve = |(name, range): &(String, std::ops::Range<usize>), role: &str| {
            let found = index.get(name.as_str()).copied();
            if found.is_none() {
                problems.push(Problem::new(
                    Some(range.clone()),
                    format!(
                        "joint `{}`: unknown {role} link `{name}`; expected the name of a `<link>` of the robot",
                        joint.name
                    ),
                ));
            }
            found
        };
        let (Some(p), Some(c)) = (
            resolve(&joint.parent, "parent"),
            resolve(&joint.child, "child"),
        ) else {
            continue;
        };
        if let Some(other) = parent_joint[c] {
            problems.push(Problem::new(
                Some(joint.child.1.clone()),
                format!(
                    "joint `{}`: link `{}` is already the child of joint `{}`; a link has one parent \
                     (closed loops are not supported)",
                    joint.name, joint.child.0, robot.joints[other].name
                ),
            ));
            continue;
        }
        parent_joint[c] = Some(j);
        children[p].push(j);
        child[j] = c;
        parent[j] = p;
    }
    if !problems.is_empty() {
        return Err(problems);
    }
    let roots: Vec<usize> = (0..robot.links.len())
        .filter(|&l| parent_joint[l].is_none())
        .collect();
    let Some(&root) = roots.first() else {
        return Err(vec![cycle(robot, &parent_joint, 0)]);
    };
    if let Some(&second) = roots.get(1) {
        let names: Vec<String> = roots
            .iter()
            .map(|&l| format!("`{}`", robot.links[l].name))
            .collect();
        return Err(vec![Problem::new(
            Some(robot.links[second].range.clone()),
            format!(
                "the robot has {} root links ({}): a URDF robot is one tree with one root; \
                 connect link `{}` to the others with a joint",
                roots.len(),
                names.join(", "),
                robot.links[second].name
            ),
        )]);
    }
    for joints in &mut children {
        joints.sort_by(|&a, &b| robot.joints[a].name.cmp(&robot.joints[b].name));
    }
    let tree = Tree {
        root,
        children,
        child,
        parent,
    };
    let mut reached = vec![false; robot.links.len()];
    reached[root] = true;
    for j in tree.depth_first() {
        reached[tree.child[j]] = true;
    }
    if let Some(lost) = reached.iter().position(|r| !r) {
        return Err(vec![cycle(robot, &parent_joint, lost)]);
    }
    Ok(tree)
}

/// The problem of the cycle above link `start` (a link the root does not
/// reach, so following parents from it loops): the joints of the loop in
/// order, reported at the joint of the loop that comes first in the file.
fn cycle(robot: &Robot, parent_joint: &[Option<usize>], start: usize) -> Problem {
    let link_index = |name: &str| robot.links.iter().position(|l| l.name == name);
    // Walk up the parents until a link repeats: that link is on the cycle.
    let mut seen = vec![false; robot.links.len()];
    let mut link = start;
    while !seen[link] {
        seen[link] = true;
        let Some(j) = parent_joint[link] else { break };
        link = link_index(&robot.joints[j].parent.0).unwrap_or(link);
    }
    let mut joints = Vec::new();
    let first = link;
    while let Some(j) = parent_joint[link] {
        joints.push(j);
        link = link_index(&robot.joints[j].parent.0).unwrap_or(first);
        if link == first {
            break;
        }
    }
    joints.reverse();
    let names: Vec<String> = joints
        .iter()
        .map(|&j| format!("`{}`", robot.joints[j].name))
        .collect();
    let closing = &robot.joints[joints.iter().copied().min().unwrap_or(0)];
    Problem::new(
        Some(closing.range.clone()),
        format!(
            "the joints {} form a cycle: a URDF robot is a tree (closed loops are not supported)",
            names.join(", ")
        ),
    )
}

/// Masses: zero or positive.
fn check_masses(robot: &Robot, problems: &mut Vec<Problem>) {
    for link in &robot.links {
        let Some(inertial) = &link.inertial else {
            continue;
        };
        if inertial.mass < 0.0 {
            problems.push(Problem::new(
                Some(inertial.mass_range.clone()),
                format!(
                    "link `{}`: negative mass {}; a mass must be zero or positive",
                    link.name, inertial.mass
                ),
            ));
        }
    }
}

/// Supported types, and an axis for the joints that move.
fn check_joints(robot: &Robot, problems: &mut Vec<Problem>) {
    for joint in &robot.joints {
        match joint.kind {
            JointType::Planar | JointType::Floating => {
                let why = if joint.kind == JointType::Floating {
                    "a floating joint is supported only at the root, with `--floating`"
                } else {
                    "expected `revolute`, `continuous`, `prismatic` or `fixed`"
                };
                problems.push(Problem::new(
                    Some(joint.kind_range.clone()),
                    format!(
                        "joint `{}`: joint type `{}` is not supported; {why}",
                        joint.name,
                        joint.kind.name()
                    ),
                ));
            }
            JointType::Fixed => {}
            JointType::Revolute | JointType::Continuous | JointType::Prismatic => {
                if joint.axis.iter().all(|&a| a == 0.0) {
                    problems.push(Problem::new(
                        Some(joint.axis_range.clone()),
                        format!(
                            "joint `{}`: the axis is zero; expected a direction, such as `xyz=\"0 0 1\"`",
                            joint.name
                        ),
                    ));
                }
            }
        }
    }
}
