//! Reading a URDF file: the XML parsed with `roxmltree` into the robot's
//! links and joints as written, each with the byte range it came from so
//! that an error can name its line. Numbers are read strictly: a value that
//! is not exactly the expected count of finite numbers is an error, never
//! guessed. Geometry, limits, transmissions and simulator tags are ignored.

use std::ops::Range;

use roxmltree::Node;

use super::Problem;

/// A robot as its URDF file describes it, in file order.
#[derive(Debug)]
pub(super) struct Robot {
    /// The `name` attribute of `<robot>`, which a struct named by the
    /// user (`--name`) does without.
    pub name: Option<String>,
    /// Where `<robot>` starts.
    pub range: Range<usize>,
    pub links: Vec<Link>,
    pub joints: Vec<Joint>,
}

impl Robot {
    /// How messages and docs call the robot, after an article: the word
    /// robot and, where it has one, its name in backticks.
    pub fn called(&self) -> String {
        match &self.name {
            Some(name) => format!("robot `{name}`"),
            None => "robot".to_owned(),
        }
    }
}

/// A `<link>`.
#[derive(Debug)]
pub(super) struct Link {
    pub name: String,
    /// The `<link>` tag.
    pub range: Range<usize>,
    /// `None` without `<inertial>`: a massless link.
    pub inertial: Option<Inertial>,
}

/// A `<link>`'s `<inertial>`: mass and central inertia in the frame of its
/// `<origin>`, relative to the link frame.
#[derive(Debug)]
pub(super) struct Inertial {
    pub origin: Pose,
    pub mass: f64,
    /// The `<mass>` value.
    pub mass_range: Range<usize>,
    /// The tensor from `ixx ixy ixz iyy iyz izz`.
    pub inertia: [[f64; 3]; 3],
    /// The `<inertia>` tag.
    pub inertia_range: Range<usize>,
}

/// An `<origin>`: translation `xyz` and fixed-axis roll, pitch, yaw `rpy`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(super) struct Pose {
    pub xyz: [f64; 3],
    pub rpy: [f64; 3],
}

/// The joint types of URDF.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum JointType {
    Revolute,
    Continuous,
    Prismatic,
    Fixed,
    Floating,
    Planar,
}

impl JointType {
    fn from_name(name: &str) -> Option<Self> {
        Some(match name {
            "revolute" => JointType::Revolute,
            "continuous" => JointType::Continuous,
            "prismatic" => JointType::Prismatic,
            "fixed" => JointType::Fixed,
            "floating" => JointType::Floating,
            "planar" => JointType::Planar,
            _ => return None,
        })
    }

    /// The type as URDF writes it.
    pub fn name(self) -> &'static str {
        match self {
            JointType::Revolute => "revolute",
            JointType::Continuous => "continuous",
            JointType::Prismatic => "prismatic",
            JointType::Fixed => "fixed",
            JointType::Floating => "floating",
            JointType::Planar => "planar",
        }
    }
}

/// A `<joint>`.
#[derive(Debug)]
pub(super) struct Joint {
    pub name: String,
    /// The `<joint>` tag.
    pub range: Range<usize>,
    pub kind: JointType,
    /// The `type` attribute's value.
    pub kind_range: Range<usize>,
    /// The parent link's name and where it is written.
    pub parent: (String, Range<usize>),
    /// The child link's name and where it is written.
    pub child: (String, Range<usize>),
    /// The child frame's placement in the parent frame at rest.
    pub origin: Pose,
    /// The axis in the joint frame, as written (URDF's default is x).
    pub axis: [f64; 3],
    /// The `<axis>` tag (the joint's when it has none).
    pub axis_range: Range<usize>,
    /// `<dynamics damping>`, 0 if absent.
    pub damping: f64,
    /// The joint named by `<mimic joint>`, if any.
    pub mimic: Option<String>,
}

/// Reads the robot in `source`, or every problem found.
pub(super) fn read(source: &str) -> Result<Robot, Vec<Problem>> {
    let document = roxmltree::Document::parse(source).map_err(|e| {
        let pos = e.pos();
        let offset = offset_of(source, pos.row, pos.col);
        vec![Problem::new(
            Some(offset..offset + 1),
            format!("malformed XML: {e}"),
        )]
    })?;
    let root = document.root_element();
    let mut reader = Reader::default();
    if root.tag_name().name() != "robot" {
        reader.problem(
            root,
            format!(
                "expected the root element `<robot>`, found `<{}>`",
                root.tag_name().name()
            ),
        );
        return Err(reader.problems);
    }
    let name = root.attribute("name").map(str::to_owned);
    let mut links = Vec::new();
    let mut joints = Vec::new();
    for node in root.children().filter(Node::is_element) {
        match node.tag_name().name() {
            "link" => links.extend(reader.link(node)),
            "joint" => joints.extend(reader.joint(node)),
            _ => {}
        }
    }
    if reader.problems.is_empty() {
        Ok(Robot {
            name,
            range: root.range(),
            links,
            joints,
        })
    } else {
        Err(reader.problems)
    }
}

/// The byte offset of 1-based `row` and `col` (in characters) in `source`.
pub(crate) fn offset_of(source: &str, row: u32, col: u32) -> usize {
    let line_start: usize = source
        .split_inclusive('\n')
        .take(row.saturating_sub(1) as usize)
        .map(str::len)
        .sum();
    let line = &source[line_start.min(source.len())..];
    let column = line
        .char_indices()
        .nth(col.saturating_sub(1) as usize)
        .map_or(line.len(), |(i, _)| i);
    (line_start + column).min(source.len().saturating_sub(1))
}

/// Collects the problems met while reading elements.
#[derive(Default)]
struct Reader {
    problems: Vec<Problem>,
}

impl Reader {
    fn problem(&mut self, node: Node<'_, '_>, message: String) {
        self.problems
            .push(Problem::new(Some(tag_range(node)), message));
    }

    /// The attribute `name` of `node`, which `owner` requires.
    fn attribute<'a>(&mut self, node: Node<'a, '_>, name: &str, owner: &str) -> Option<&'a str> {
        let value = node.attribute(name);
        if value.is_none() {
            self.problem(
                node,
                format!(
                    "{owner}: `<{}>` needs the attribute `{name}`",
                    node.tag_name().name()
                ),
            );
        }
        value
    }

    /// The first child element of `node` named `tag`.
    fn child<'a, 'i>(&mut self, node: Node<'a, 'i>, tag: &str) -> Option<Node<'a, 'i>> {
        node.children()
            .find(|c| c.is_element() && c.tag_name().name() == tag)
    }

    /// The child element `tag` of `node`, which `owner` requires.
    fn required_child<'a, 'i>(
        &mut self,
        node: Node<'a, 'i>,
        tag: &str,
        owner: &str,
    ) -> Option<Node<'a, 'i>> {
        let child = self.child(node, tag);
        if child.is_none() {
            self.problem(
                node,
                format!(
                    "{owner}: `<{}>` needs a `<{tag}>` element",
                    node.tag_name().name()
                ),
            );
        }
        child
    }

    /// `N` finite numbers separated by white space in attribute `name` of
    /// `node`; `default` if the attribute is absent and a default is given.
    fn numbers<const N: usize>(
        &mut self,
        node: Node<'_, '_>,
        name: &str,
        owner: &str,
        default: Option<[f64; N]>,
    ) -> Option<[f64; N]> {
        let Some(attribute) = node.attribute_node(name) else {
            if default.is_none() {
                self.attribute(node, name, owner);
            }
            return default;
        };
        let parsed: Vec<Option<f64>> = attribute
            .value()
            .split_whitespace()
            .map(|word| word.parse::<f64>().ok().filter(|x| x.is_finite()))
            .collect();
        if parsed.len() == N && parsed.iter().all(Option::is_some) {
            let mut values = [0.0; N];
            for (value, x) in values.iter_mut().zip(parsed) {
                *value = x.unwrap_or_default();
            }
            return Some(values);
        }
        let expected = if N == 1 {
            "a finite number".to_owned()
        } else {
            format!("{N} finite numbers separated by spaces")
        };
        self.problems.push(Problem::new(
            Some(attribute.range_value()),
            format!(
                "{owner}: `{name}=\"{}\"` is not {expected}",
                attribute.value()
            ),
        ));
        None
    }

    /// An optional `<origin>` child of `node`.
    fn origin(&mut self, node: Node<'_, '_>, owner: &str) -> Option<Pose> {
        let Some(origin) = self.child(node, "origin") else {
            return Some(Pose::default());
        };
        if let Some(quaternion) = origin.attribute_node("quat_xyzw") {
            self.problems.push(Problem::new(
                Some(quaternion.range()),
                format!("{owner}: `quat_xyzw` orientations are not supported; give `rpy`"),
            ));
            return None;
        }
        let xyz = self.numbers(origin, "xyz", owner, Some([0.0; 3]));
        let rpy = self.numbers(origin, "rpy", owner, Some([0.0; 3]));
        Some(Pose {
            xyz: xyz?,
            rpy: rpy?,
        })
    }

    fn link(&mut self, node: Node<'_, '_>) -> Option<Link> {
        let name = self.attribute(node, "name", "a link")?.to_owned();
        let inertial = match self.child(node, "inertial") {
            Some(inertial) => Some(self.inertial(inertial, &format!("link `{name}`"))?),
            None => None,
        };
        Some(Link {
            name,
            range: tag_range(node),
            inertial,
        })
    }

    fn inertial(&mut self, node: Node<'_, '_>, owner: &str) -> Option<Inertial> {
        let origin = self.origin(node, owner);
        let mass_node = self.required_child(node, "mass", owner);
        let inertia_node = self.required_child(node, "inertia", owner);
        let mass = mass_node.and_then(|m| self.numbers::<1>(m, "value", owner, None));
        let mut entries = [0.0; 6];
        let mut complete = inertia_node.is_some();
        for (entry, name) in entries
            .iter_mut()
            .zip(["ixx", "iyy", "izz", "ixy", "iyz", "ixz"])
        {
            match inertia_node.and_then(|n| self.numbers::<1>(n, name, owner, None)) {
                Some([x]) => *entry = x,
                None => complete = false,
            }
        }
        let [xx, yy, zz, xy, yz, xz] = entries;
        let (Some(origin), Some([mass]), true) = (origin, mass, complete) else {
            return None;
        };
        Some(Inertial {
            origin,
            mass,
            mass_range: mass_node.map(tag_range).unwrap_or_default(),
            inertia: [[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]],
            inertia_range: inertia_node.map(tag_range).unwrap_or_default(),
        })
    }

    fn joint(&mut self, node: Node<'_, '_>) -> Option<Joint> {
        let name = self.attribute(node, "name", "a joint")?.to_owned();
        let owner = format!("joint `{name}`");
        let kind = self.joint_type(node, &owner);
        let parent = self.link_reference(node, "parent", &owner);
        let child = self.link_reference(node, "child", &owner);
        let origin = self.origin(node, &owner);
        let axis_node = self.child(node, "axis");
        let axis = match axis_node {
            Some(axis) => self.numbers(axis, "xyz", &owner, None),
            None => Some([1.0, 0.0, 0.0]),
        };
        let damping = match self.child(node, "dynamics") {
            Some(dynamics) => self.numbers(dynamics, "damping", &owner, Some([0.0])),
            None => Some([0.0]),
        };
        let mimic = self
            .child(node, "mimic")
            .and_then(|m| self.attribute(m, "joint", &owner))
            .map(str::to_owned);
        let ((kind, kind_range), parent, child, origin, axis, [damping]) =
            (kind?, parent?, child?, origin?, axis?, damping?);
        Some(Joint {
            name,
            range: tag_range(node),
            kind,
            kind_range,
            parent,
            child,
            origin,
            axis,
            axis_range: tag_range(axis_node.unwrap_or(node)),
            damping,
            mimic,
        })
    }

    fn joint_type(&mut self, node: Node<'_, '_>, owner: &str) -> Option<(JointType, Range<usize>)> {
        let attribute = node.attribute_node("type");
        let Some(attribute) = attribute else {
            self.attribute(node, "type", owner);
            return None;
        };
        let kind = JointType::from_name(attribute.value());
        if kind.is_none() {
            self.problems.push(Problem::new(
                Some(attribute.range_value()),
                format!(
                    "{owner}: unknown joint type `{}`; expected `revolute`, `continuous`, \
                     `prismatic` or `fixed`",
                    attribute.value()
                ),
            ));
        }
        Some((kind?, attribute.range_value()))
    }

    /// `<parent link="..."/>` or `<child link="..."/>`.
    fn link_reference(
        &mut self,
        node: Node<'_, '_>,
        tag: &str,
        owner: &str,
    ) -> Option<(String, Range<usize>)> {
        let element = self.required_child(node, tag, owner)?;
        self.attribute(element, "link", owner)?;
        let attribute = element.attribute_node("link")?;
        Some((attribute.value().to_owned(), attribute.range_value()))
    }
}

/// The byte range of `node`'s start tag (`<joint name="..." type="...">`),
/// or the whole element when it has no children.
pub(crate) fn tag_range(node: Node<'_, '_>) -> Range<usize> {
    let range = node.range();
    let end = node
        .first_child()
        .map_or(range.end, |child| child.range().start);
    range.start..end.max(range.start + 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_links_joints_and_defaults() {
        let robot = read(
            r#"<robot name="r">
                 <link name="a"/>
                 <link name="b"><inertial><origin xyz="1 2 3"/><mass value="2"/>
                   <inertia ixx="1" iyy="2" izz="3" ixy="0.1" iyz="0.2" ixz="0.3"/></inertial></link>
                 <joint name="j" type="continuous"><parent link="a"/><child link="b"/>
                   <dynamics damping="0.5"/><mimic joint="k"/></joint>
               </robot>"#,
        )
        .unwrap();
        assert_eq!(robot.name.as_deref(), Some("r"));
        assert!(robot.links[0].inertial.is_none());
        let inertial = robot.links[1].inertial.as_ref().unwrap();
        assert_eq!(inertial.origin.xyz, [1.0, 2.0, 3.0]);
        assert_eq!(inertial.inertia[0], [1.0, 0.1, 0.3]);
        assert_eq!(inertial.inertia[1], [0.1, 2.0, 0.2]);
        let joint = &robot.joints[0];
        assert_eq!(joint.kind, JointType::Continuous);
        assert_eq!(joint.axis, [1.0, 0.0, 0.0]);
        assert_eq!(joint.origin, Pose::default());
        assert_eq!(joint.damping, 0.5);
        assert_eq!(joint.mimic.as_deref(), Some("k"));
    }

    #[test]
    fn numbers_are_read_strictly() {
        let problems = read(
            r#"<robot name="r"><link name="a"/><link name="b"/>
               <joint name="j" type="fixed"><parent link="a"/><child link="b"/>
               <origin xyz="1 oops 2 3"/></joint></robot>"#,
        )
        .unwrap_err();
        assert_eq!(problems.len(), 1);
        assert!(
            problems[0]
                .message
                .contains("`xyz=\"1 oops 2 3\"` is not 3 finite numbers")
        );
    }

    #[test]
    fn offsets_follow_rows_and_columns() {
        assert_eq!(offset_of("ab\ncd\n", 2, 2), 4);
        assert_eq!(offset_of("ab", 1, 1), 0);
    }
}
