//! Writing the checked robot as a model in the language of the `dalembert!`
//! macro: one coordinate per moving joint in depth-first order, named after
//! the joint, one input `tau_<coordinate>` per coordinate acting along the
//! joint axis between the two bodies, one body per link welded by fixed
//! joints to the link a moving joint carries, every link's frame `L` and
//! origin point `L_origin` (welded links too, for outputs), and gravity
//! along `−N.z`.
//! Constant placements are written as URDF gives them (`rotate_z(yaw)`,
//! then `rotate_y(pitch)`, then `rotate_x(roll)`; offsets in the parent's
//! axes) so that the model reads like the file; only merged mass
//! properties are computed numbers.

use std::collections::HashSet;

use super::inertia::{
    InertiaFault, MassProperties, Placement, Vec3, check_inertia, without_rounding,
};
use super::tree::Tree;
use super::xml::{JointType, Robot};
use super::{Options, Problem};
use crate::model::{builtin_names, is_builtin, is_plain};

/// The gravity of the model: the acceleration along `−N.z`, the root
/// link's z axis (Pinocchio's default).
const GRAVITY: f64 = 9.81;

/// The free joint of a floating base (Pinocchio's name for it): its
/// coordinates are `root_joint_x … root_joint_qw`, its speeds
/// `root_joint_vx … root_joint_wz`.
const FREE_JOINT: &str = "root_joint";

/// The suffixes of the names a free joint makes.
const FREE_NAMES: [&str; 14] = [
    "x", "y", "z", "qx", "qy", "qz", "qw", "vx", "vy", "vz", "wx", "wy", "wz", "",
];

/// The model text of `robot`, its struct named `struct_name`, with the
/// warnings found, or the problems (at least one an error: names that
/// cannot be written, nothing that moves, a joint that moves no mass, a
/// body whose inertia no matrix of masses can have), after those already
/// found in `problems`.
pub(super) fn model_text(
    robot: &Robot,
    tree: &Tree,
    options: &Options,
    struct_name: &str,
    mut problems: Vec<Problem>,
) -> Result<(String, Vec<Problem>), Vec<Problem>> {
    let mut names = Names::default();
    let order = tree.depth_first();
    let moving: Vec<usize> = order
        .iter()
        .copied()
        .filter(|&j| robot.joints[j].kind != JointType::Fixed)
        .collect();
    if moving.is_empty() && !options.chosen.floating {
        problems.push(Problem::new(
            Some(robot.range.start..robot.range.start + 1),
            format!(
                "the {} has no revolute, continuous or prismatic joint: nothing moves, \
                 so there is no coordinate to write (with `--floating` the root link moves freely)",
                robot.called()
            ),
        ));
    }
    for &j in &moving {
        check_moves_mass(robot, tree, j, &mut problems);
    }
    if options.chosen.floating {
        for suffix in FREE_NAMES {
            let name = match suffix {
                "" => FREE_JOINT.to_owned(),
                _ => format!("{FREE_JOINT}_{suffix}"),
            };
            names.claim(&name);
        }
    }
    let mut coordinates = vec![String::new(); robot.joints.len()];
    for &j in &moving {
        let joint = &robot.joints[j];
        let name = sanitize(&joint.name);
        let input = format!("tau_{name}");
        if !names.claim(&name) {
            problems.push(Problem::new(
                Some(joint.range.clone()),
                format!(
                    "joint `{}`: its coordinate would be named `{name}`, which is not a free \
                     identifier here (it starts with a digit, is a keyword or a built-in name, \
                     or another joint's name gives the same); rename the joint",
                    joint.name
                ),
            ));
        } else if !names.claim(&input) {
            problems.push(Problem::new(
                Some(joint.range.clone()),
                format!(
                    "joint `{}`: its input `{input}` is already a name",
                    joint.name
                ),
            ));
        }
        coordinates[j] = name;
    }
    let places = link_places(robot, tree, &mut names);
    if problems.iter().any(Problem::is_error) {
        return Err(problems);
    }
    let mut writer = Writer {
        robot,
        tree,
        options,
        names,
        places,
        coordinates,
        lines: Vec::new(),
        problems,
    };
    writer.model(struct_name, &moving);
    if writer.problems.iter().any(Problem::is_error) {
        return Err(writer.problems);
    }
    Ok((writer.lines.join("\n") + "\n", writer.problems))
}

/// An error if the moving joint `j` carries no mass: no link beyond it has
/// a positive `<inertial>` mass, so its column of the mass matrix is zero.
fn check_moves_mass(robot: &Robot, tree: &Tree, j: usize, problems: &mut Vec<Problem>) {
    let mut links = vec![tree.child[j]];
    while let Some(link) = links.pop() {
        if robot.links[link]
            .inertial
            .as_ref()
            .is_some_and(|inertial| inertial.mass > 0.0)
        {
            return;
        }
        links.extend(tree.children[link].iter().map(|&k| tree.child[k]));
    }
    let joint = &robot.joints[j];
    problems.push(Problem::new(
        Some(joint.range.clone()),
        format!(
            "joint `{}` moves no mass: neither link `{}` nor any link beyond it has an \
             `<inertial>` with a positive mass, so the mass matrix would be singular; give \
             those links their masses, or make the joint `fixed`",
            joint.name, joint.child.0
        ),
    ));
}

/// The struct's name: `--name`, else the robot's name in UpperCamelCase,
/// prefixed with `Robot` (and a warning) where that is not an identifier.
pub(super) fn struct_name(robot: &Robot, options: &Options, problems: &mut Vec<Problem>) -> String {
    let at = Some(robot.range.start..robot.range.start + 1);
    if let Some(name) = &options.chosen.name {
        if !is_identifier(name) {
            problems.push(Problem::new(
                at,
                format!(
                    "the name given, `{name}`, cannot name the struct: expected a Rust identifier \
                     that is not a keyword nor a built-in name of the language ({})",
                    builtin_names()
                        .map(|r| format!("`{r}`"))
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            ));
        }
        return name.clone();
    }
    let Some(robot_name) = &robot.name else {
        problems.push(Problem::new(
            at,
            "`<robot>` has no attribute `name`: expected one, or the struct's name given \
             with `--name`"
                .to_owned(),
        ));
        return String::new();
    };
    let name = upper_camel_case(robot_name);
    if is_identifier(&name) {
        return name;
    }
    let prefixed = format!("Robot{name}");
    problems.push(Problem::warning(
        at,
        format!(
            "the robot's name `{robot_name}` gives `{name}`, which is not a Rust identifier; \
             the struct is named `{prefixed}` (choose another with `--name`)"
        ),
    ));
    prefixed
}

/// `ur5_robot` → `Ur5Robot`, `panda` → `Panda`.
pub(crate) fn upper_camel_case(name: &str) -> String {
    name.split(|c: char| !c.is_ascii_alphanumeric())
        .filter(|part| !part.is_empty())
        .map(|part| {
            let mut chars = part.chars();
            chars
                .next()
                .map(|first| first.to_ascii_uppercase().to_string() + chars.as_str())
                .unwrap_or_default()
        })
        .collect()
}

/// The name with every character outside `[A-Za-z0-9_]` replaced by `_`.
pub(crate) fn sanitize(name: &str) -> String {
    name.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// Whether `name` can name an item of the model: a plain Rust identifier
/// (not a keyword, raw, nor `Some`-like) that is not one of the language's built-in names,
/// as the model layer checks every name.
pub(crate) fn is_identifier(name: &str) -> bool {
    is_plain(name) && !is_builtin(name)
}

/// The names used so far in the model.
#[derive(Default)]
pub(crate) struct Names {
    taken: HashSet<String>,
}

impl Names {
    /// Takes `name` if it is a free identifier.
    pub(crate) fn claim(&mut self, name: &str) -> bool {
        is_identifier(name) && self.taken.insert(name.to_owned())
    }

    /// `base` sanitised, or with a suffix `_2`, `_3`, ... if it is taken.
    pub(crate) fn fresh(&mut self, base: &str) -> String {
        let mut base = sanitize(base);
        if base.starts_with(|c: char| c.is_ascii_digit()) {
            base.insert(0, '_');
        }
        if self.claim(&base) {
            return base;
        }
        (2..)
            .map(|i| format!("{base}_{i}"))
            .find(|name| self.claim(name))
            .unwrap_or_default()
    }
}

/// The names of every link's frame and origin point, root first, then in
/// the order of the joints (depth first): the link's name sanitized, and
/// that name with `_origin`. A name that is taken (a joint's coordinate, a
/// built-in, a keyword, another link's sanitized name) or not an
/// identifier gets a fresh one instead (`LF_HAA_2` for ANYmal's link named
/// as its joint), which a comment at the link states.
fn link_places(robot: &Robot, tree: &Tree, names: &mut Names) -> Vec<Place> {
    let mut places = vec![Place::default(); robot.links.len()];
    let links =
        std::iter::once(tree.root).chain(tree.depth_first().into_iter().map(|j| tree.child[j]));
    for link in links {
        let name = sanitize(&robot.links[link].name);
        let wanted = [name.clone(), format!("{name}_origin")];
        let [frame, origin] = wanted
            .clone()
            .map(|n| if names.claim(&n) { n } else { names.fresh(&n) });
        let renamed = [&frame, &origin] != [&wanted[0], &wanted[1]];
        places[link] = Place {
            frame,
            origin,
            renamed,
        };
    }
    places
}

/// Where a link is in the model: the frame with its axes and the point at
/// its origin.
#[derive(Clone, Debug, Default)]
struct Place {
    /// The frame whose axes are the link's.
    frame: String,
    /// The point at the link's origin.
    origin: String,
    /// Whether they are not named after the link, whose name is taken.
    renamed: bool,
}

impl Place {
    /// The sentence that says how the link's frame and origin are named,
    /// if not after the link: empty otherwise.
    fn naming(&self) -> String {
        match self.renamed {
            true => format!(
                " Its frame is `{}` and its origin `{}`, as the link's name is taken.",
                self.frame, self.origin
            ),
            false => String::new(),
        }
    }
}

struct Writer<'a> {
    robot: &'a Robot,
    tree: &'a Tree,
    options: &'a Options,
    names: Names,
    /// Per link, its frame and origin point.
    places: Vec<Place>,
    /// Per joint, its coordinate (empty for fixed joints).
    coordinates: Vec<String>,
    lines: Vec<String>,
    /// The bodies' inertias found wrong (errors) or not physical (warnings).
    problems: Vec<Problem>,
}

impl Writer<'_> {
    fn model(&mut self, struct_name: &str, moving: &[usize]) {
        let robot = self.robot;
        self.lines.push(format!(
            "/// The {} of {}, imported by `dalembert urdf`.",
            robot.called(),
            self.options.file_name
        ));
        self.lines.push(format!(
            "/// {} joint coordinates in depth-first order from the root link `{}`; \
             `tau_<coordinate>` is the joint's motor torque or force.",
            moving.len(),
            robot.links[self.tree.root].name
        ));
        self.lines.push(format!("pub {struct_name} {{"));
        let root = self.tree.root;
        let floating = self.options.chosen.floating;
        if floating {
            let place = self.places[root].clone();
            let Place { frame, origin, .. } = &place;
            self.comment(format!(
                "Root link `{}`, floating: a free joint from the ground, first in q and v \
                 (position in N and unit quaternion; velocity and angular velocity in the \
                 link's axes).{}",
                self.robot.links[root].name,
                place.naming()
            ));
            self.statement(format!(
                "joint free {FREE_JOINT} {{ parent: N, child: {frame}, at: O }};"
            ));
            self.statement(format!("point {origin} = {FREE_JOINT};"));
        }
        let coordinates: Vec<String> = moving
            .iter()
            .map(|&j| self.coordinates[j].clone())
            .collect();
        if !coordinates.is_empty() {
            self.statement(format!("coordinates {};", coordinates.join(", ")));
            let inputs: Vec<String> = coordinates.iter().map(|c| format!("tau_{c}")).collect();
            self.statement(format!("inputs {};", inputs.join(", ")));
        }
        if floating {
            self.body(root);
        } else {
            self.base();
        }
        self.below(root);
        self.statement(format!("gravity -{GRAVITY} * N.z;"));
        if self.options.chosen.damping {
            self.dissipation(moving);
        }
        self.lines.push("}".to_owned());
    }

    fn statement(&mut self, text: String) {
        self.lines.push(format!("    {text}"));
    }

    fn comment(&mut self, text: String) {
        self.lines.push(String::new());
        self.lines.push(format!("    // {text}"));
    }

    /// The root link fixed to the ground: its frame has `N`'s axes, its
    /// origin is `O`. The masses welded to it do not move and are left
    /// out; a floating base instead makes the root's frame with a free
    /// joint and its masses a body (see [`Writer::model`]).
    fn base(&mut self) {
        let root = self.tree.root;
        let place = self.places[root].clone();
        let Place { frame, origin, .. } = &place;
        self.comment(format!(
            "Root link `{}`, fixed to the ground: its frame has N's axes, its origin is O. \
             Masses welded to it do not move and are left out.{}",
            self.robot.links[root].name,
            place.naming()
        ));
        self.statement(format!("frame {frame} = N.rotate_z(0);"));
        self.statement(format!("point {origin} = O;"));
    }

    /// The joints below `link`, depth first, children by joint name.
    fn below(&mut self, link: usize) {
        for j in self.tree.children[link].clone() {
            if self.robot.joints[j].kind == JointType::Fixed {
                self.fixed(j);
            } else {
                self.moving(j);
            }
            self.below(self.tree.child[j]);
        }
    }

    /// A fixed joint: the child's mass joins the parent's body, and the
    /// child gets its frame and origin (for outputs, and for the joints
    /// below it).
    fn fixed(&mut self, j: usize) {
        let joint = &self.robot.joints[j];
        let parent = self.places[self.tree.parent[j]].clone();
        let place = self.places[self.tree.child[j]].clone();
        let Place { frame, origin, .. } = &place;
        self.comment(format!(
            "Fixed joint `{}`: link `{}` is welded to link `{}`.{}",
            joint.name,
            joint.child.0,
            joint.parent.0,
            place.naming()
        ));
        self.rotated_frames(&parent.frame, joint.origin.rpy, frame, Some(frame));
        let at = offset(&parent.origin, joint.origin.xyz, &parent.frame);
        self.statement(format!("point {origin} = {at};"));
    }

    /// A revolute, continuous or prismatic joint: its placement frames,
    /// the joint, the child's body (with the links welded to it), and the
    /// input acting along the axis.
    fn moving(&mut self, j: usize) {
        let joint = &self.robot.joints[j];
        let child = self.tree.child[j];
        let child_name = &joint.child.0;
        let parent = self.places[self.tree.parent[j]].clone();
        self.comment(format!(
            "Joint `{}` ({}): link `{}` carries link `{child_name}`.{}",
            joint.name,
            joint.kind.name(),
            joint.parent.0,
            self.places[child].naming()
        ));
        if let Some(mimicked) = &joint.mimic {
            self.statement(format!(
                "// It mimics `{mimicked}` in the URDF; here it is an independent coordinate, \
                 as in Pinocchio by default."
            ));
        }
        let joint_frame = self.rotated_frames(
            &parent.frame,
            joint.origin.rpy,
            &format!("{}_frame", joint.name),
            None,
        );
        let at = offset(&parent.origin, joint.origin.xyz, &parent.frame);
        let Place {
            frame,
            origin: point,
            ..
        } = self.places[child].clone();
        let coordinate = self.coordinates[j].clone();
        let length = norm(joint.axis);
        let axis = joint.axis.map(|a| a / length);
        let axis_field = axis_field(axis);
        let kind = if joint.kind == JointType::Prismatic {
            "prismatic"
        } else {
            "revolute"
        };
        self.statement(format!(
            "joint {kind} {point} {{ parent: {joint_frame}, child: {frame}, {axis_field}, \
             coordinate: {coordinate}, at: {at} }};"
        ));
        self.body(child);
        let input = format!("tau_{coordinate}");
        let push = scaled(&input, axis, &joint_frame);
        if joint.kind == JointType::Prismatic {
            let pull = scaled(&input, axis.map(|a| -a), &joint_frame);
            self.statement(format!("force {push} at {point};"));
            self.statement(format!("force {pull} at {at};"));
        } else {
            self.statement(format!("torque {push} on {frame} reacting {joint_frame};"));
        }
    }

    /// Frames turning `parent` by URDF's `rpy` (`rotate_z(yaw)`, then
    /// `rotate_y(pitch)`, then `rotate_x(roll)`, the non-zero ones), those
    /// before the last named after `name` and the turn: the last is
    /// `last` if given (and is then written even for a zero `rpy`, as
    /// `parent.rotate_z(0)`), else a fresh name from `name`; without
    /// `last`, a zero `rpy` gives `parent` itself.
    fn rotated_frames(
        &mut self,
        parent: &str,
        [roll, pitch, yaw]: Vec3,
        name: &str,
        last: Option<&str>,
    ) -> String {
        let turns: Vec<(&str, f64, &str)> = [
            ("z", yaw, "yaw"),
            ("y", pitch, "pitch"),
            ("x", roll, "roll"),
        ]
        .into_iter()
        .filter(|&(_, angle, _)| angle != 0.0)
        .collect();
        if turns.is_empty()
            && let Some(last) = last
        {
            self.statement(format!("frame {last} = {parent}.rotate_z(0);"));
            return last.to_owned();
        }
        let mut frame = parent.to_owned();
        for (i, (axis, angle, turn)) in turns.iter().enumerate() {
            let new = match last {
                Some(last) if i + 1 == turns.len() => last.to_owned(),
                _ if i + 1 == turns.len() => self.names.fresh(name),
                _ => self.names.fresh(&format!("{name}_{turn}")),
            };
            self.statement(format!(
                "frame {new} = {frame}.rotate_{axis}({});",
                number(*angle)
            ));
            frame = new;
        }
        frame
    }

    /// The body of the link `link` and the links welded to it, in its
    /// frame with its origin; nothing if it is massless.
    fn body(&mut self, link: usize) {
        let Place { frame, origin, .. } = self.places[link].clone();
        let mut total = MassProperties::NONE;
        let mut welded = Vec::new();
        for (l, place) in self.links_of_body(link) {
            let Some(inertial) = &self.robot.links[l].inertial else {
                continue;
            };
            let own = MassProperties::from_inertial(
                &Placement::from_xyz_rpy(inertial.origin.xyz, inertial.origin.rpy),
                inertial.mass,
                &inertial.inertia,
            );
            if own.is_empty() {
                continue;
            }
            if l != link {
                welded.push(format!("`{}`", self.robot.links[l].name));
            }
            total = total.merged(&own.placed(&place));
        }
        if total.is_empty() {
            return;
        }
        total.inertia = without_rounding(&total.inertia);
        self.check_body_inertia(link, &welded, &total);
        if !welded.is_empty() {
            self.statement(format!("// With the welded link(s) {}.", welded.join(", ")));
        }
        let name = self
            .names
            .fresh(&format!("{}_body", self.robot.links[link].name));
        let center = offset(&origin, total.center, &frame);
        self.statement(body_statement(&name, &total, &center, &frame));
    }

    /// The inertia of the body of `link` (with the links `welded` to it),
    /// about its center: an error if it is not positive semi-definite (the
    /// mass matrix could lose its definiteness), a warning if it breaks the
    /// triangle inequality (no mass distribution has it, but the dynamics
    /// are well defined: imported as written, as Pinocchio does).
    fn check_body_inertia(&mut self, link: usize, welded: &[String], total: &MassProperties) {
        let Err(fault) = check_inertia(&total.inertia) else {
            return;
        };
        let name = &self.robot.links[link].name;
        let whose = if welded.is_empty() {
            format!("link `{name}`")
        } else {
            format!(
                "link `{name}` with its welded link(s) {}",
                welded.join(", ")
            )
        };
        let range = self.robot.links[link].inertial.as_ref().map_or_else(
            || self.robot.links[link].range.clone(),
            |i| i.inertia_range.clone(),
        );
        self.problems.push(match fault {
            InertiaFault::NotPositiveSemiDefinite { moments: [a, b, c] } => Problem::new(
                Some(range),
                format!(
                    "{whose}: the inertia is not positive semi-definite (principal moments \
                     {a}, {b}, {c}): every principal moment must be zero or positive"
                ),
            ),
            InertiaFault::TriangleInequality { moments: [a, b, c] } => Problem::warning(
                Some(range),
                format!(
                    "{whose}: the inertia breaks the triangle inequality (principal moments \
                     {a}, {b}, {c}): no mass distribution has it, since each principal moment \
                     is at most the sum of the other two; imported as written, as Pinocchio does"
                ),
            ),
        });
    }

    /// `link` and the links welded to it by fixed joints, with their
    /// placements in `link`'s frame.
    fn links_of_body(&self, link: usize) -> Vec<(usize, Placement)> {
        let mut found = vec![(link, Placement::IDENTITY)];
        let mut i = 0;
        while i < found.len() {
            let (l, place) = found[i];
            for &j in &self.tree.children[l] {
                let joint = &self.robot.joints[j];
                if joint.kind == JointType::Fixed {
                    let inner = Placement::from_xyz_rpy(joint.origin.xyz, joint.origin.rpy);
                    found.push((self.tree.child[j], place.then(&inner)));
                }
            }
            i += 1;
        }
        found
    }

    /// `dissipation ½ Σ d q̇²` over the joints with a `<dynamics damping>`.
    fn dissipation(&mut self, moving: &[usize]) {
        let terms: Vec<String> = moving
            .iter()
            .filter(|&&j| self.robot.joints[j].damping != 0.0)
            .map(|&j| {
                format!(
                    "{} * dt({})^2",
                    number(self.robot.joints[j].damping),
                    self.coordinates[j]
                )
            })
            .collect();
        if !terms.is_empty() {
            self.comment("Viscous joint damping from `<dynamics damping>`.".to_owned());
            self.statement(format!("dissipation 1/2 * ({});", terms.join(" + ")));
        }
    }
}

/// The joint's `axis:` field for the unit axis `axis`: a positive axis of
/// the frame by name, any other direction by its components.
pub(crate) fn axis_field(axis: Vec3) -> String {
    let named = ["x", "y", "z"].into_iter().enumerate().find(|&(k, _)| {
        let mut unit = [0.0; 3];
        unit[k] = 1.0;
        axis == unit
    });
    match named {
        Some((_, name)) => format!("axis: {name}"),
        None => {
            let components: Vec<String> = axis.into_iter().map(number).collect();
            format!("axis: [{}]", components.join(", "))
        }
    }
}

/// The length of `v`, without overflow for components near `f64::MAX` (an
/// axis `1e308 1e308 1e308` has a direction, which squaring first would
/// lose to an infinite length and a zero axis).
pub(crate) fn norm(v: Vec3) -> f64 {
    let scale = v.iter().fold(0.0_f64, |m, a| m.max(a.abs()));
    if scale == 0.0 {
        return 0.0;
    }
    let [x, y, z] = v.map(|a| a / scale);
    scale * (x * x + y * y + z * z).sqrt()
}

/// The signed terms `c * F.x` of the vector `v` in `frame`'s axes.
fn terms(v: Vec3, frame: &str) -> Vec<(bool, String)> {
    ["x", "y", "z"]
        .into_iter()
        .zip(v)
        .filter(|&(_, c)| c != 0.0)
        .map(|(axis, c)| {
            let unit = format!("{frame}.{axis}");
            let text = if c.abs() == 1.0 {
                unit
            } else {
                format!("{} * {unit}", number(c.abs()))
            };
            (c < 0.0, text)
        })
        .collect()
}

/// The point `base` moved by `v` in `frame`'s axes: `P + 0.1 * F.x - F.z`.
/// The `body` statement of `name` with the mass and central inertia of
/// `body` (in `frame`'s axes), its center written `center`: the three
/// principal entries, and the products of inertia where one is not zero.
pub(crate) fn body_statement(
    name: &str,
    body: &MassProperties,
    center: &str,
    frame: &str,
) -> String {
    let i = body.inertia;
    let mut entries = vec![i[0][0], i[1][1], i[2][2]];
    if [i[0][1], i[1][2], i[2][0]] != [0.0; 3] {
        entries.extend([i[0][1], i[1][2], i[2][0]]);
    }
    let entries: Vec<String> = entries.into_iter().map(number).collect();
    format!(
        "body {name} {{ mass: {}, center: {center}, frame: {frame}, inertia: [{}] }};",
        number(body.mass),
        entries.join(", ")
    )
}

pub(crate) fn offset(base: &str, v: Vec3, frame: &str) -> String {
    let mut text = base.to_owned();
    for (negative, term) in terms(v, frame) {
        text += if negative { " - " } else { " + " };
        text += &term;
    }
    text
}

/// The vector `v` in `frame`'s axes scaled by `scalar`: `u * F.z`,
/// `-u * F.y`, `u * (0.6 * F.y - 0.8 * F.z)`.
pub(crate) fn scaled(scalar: &str, v: Vec3, frame: &str) -> String {
    let terms = terms(v, frame);
    if let [(negative, term)] = &terms[..] {
        let sign = if *negative { "-" } else { "" };
        return format!("{sign}{scalar} * {term}");
    }
    let mut text = String::new();
    for (i, (negative, term)) in terms.into_iter().enumerate() {
        text += match (i, negative) {
            (0, false) => "",
            (0, true) => "-",
            (_, false) => " + ",
            (_, true) => " - ",
        };
        text += &term;
    }
    format!("{scalar} * ({text})")
}

/// A literal that reads back as exactly `x`: the shortest decimal that
/// round-trips, as an integer when it is one.
pub(crate) fn number(x: f64) -> String {
    if x == x.trunc() && x.abs() < 1e15 {
        format!("{}", x as i64)
    } else {
        format!("{x:?}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_follow_the_contract() {
        assert_eq!(upper_camel_case("ur5_robot"), "Ur5Robot");
        assert_eq!(upper_camel_case("my-robot v2"), "MyRobotV2");
        assert_eq!(
            sanitize("base_link-base_fixed_joint"),
            "base_link_base_fixed_joint"
        );
        assert!(!is_identifier("1st") && !is_identifier("type") && !is_identifier("N"));
        let mut names = Names::default();
        assert_eq!(names.fresh("a-b"), "a_b");
        assert_eq!(names.fresh("a_b"), "a_b_2");
        assert_eq!(names.fresh("2nd"), "_2nd");
    }

    #[test]
    fn an_axis_near_the_largest_number_keeps_its_direction() {
        assert_eq!(norm([0.0, 3.0, 4.0]), 5.0);
        let length = norm([1e308; 3]);
        assert!(length.is_finite());
        assert!((length / 1e308 - 3.0_f64.sqrt()).abs() < 1e-15);
    }

    #[test]
    fn numbers_and_vectors_read_back_exactly() {
        assert_eq!(number(4.0), "4");
        assert_eq!(number(-0.0), "0");
        assert_eq!(number(0.333), "0.333");
        assert_eq!(number(2.3749999999999997e-06), "2.3749999999999997e-6");
        assert_eq!(offset("P", [0.5, 0.0, -1.0], "F"), "P + 0.5 * F.x - F.z");
        assert_eq!(scaled("u", [0.0, -1.0, 0.0], "F"), "-u * F.y");
        assert_eq!(
            scaled("u", [0.6, 0.0, -0.8], "F"),
            "u * (0.6 * F.x - 0.8 * F.z)"
        );
        assert_eq!(axis_field([0.0, 0.0, 1.0]), "axis: z");
        assert_eq!(axis_field([0.0, 0.0, -1.0]), "axis: [0, 0, -1]");
    }
}
