//! Writing the compiled MJCF bodies as a model in the language of the
//! `dalembert!` macro, in MuJoCo's order: per body, its placement in its
//! parent (a constant rotation and offset), then its joints in file order
//! (each joint's anchor and axis in the frame the joints before it left,
//! as `mj_kinematics` composes them), the frame `B` and point `B_origin`
//! it ends at, and its mass. Coordinates and inputs are declared at their
//! joint, so that `q`, `v` and `u` follow `qpos` and `qvel`; springs,
//! dampers and armatures come last.

use super::pose::{self, IDENTITY, Quat};
use super::read::{Body, Joint, JointKind, Model};
use super::{Options, Problem};
use crate::model::{is_builtin, is_plain};
use crate::urdf::inertia::without_rounding;
use crate::urdf::write::{
    Names, axis_field, body_statement, number, offset, sanitize, scaled, upper_camel_case,
};

/// The suffixes of the names a free joint makes (its point is the bare
/// name).
const FREE_NAMES: [&str; 13] = [
    "x", "y", "z", "qx", "qy", "qz", "qw", "vx", "vy", "vz", "wx", "wy", "wz",
];

/// The suffixes of the names a ball joint makes.
const BALL_NAMES: [&str; 7] = ["qx", "qy", "qz", "qw", "wx", "wy", "wz"];

/// The model text of `model`, or the problems.
pub(super) fn model_text(model: &Model, options: &Options) -> Result<String, Vec<Problem>> {
    let mut problems = Vec::new();
    let struct_name = struct_name(model, options, &mut problems);
    let mut names = Names::default();
    let joints = joint_names(model, &mut names, &mut problems);
    if model.bodies.iter().all(|b| b.joints.is_empty()) {
        problems.push(Problem::new(
            model.loc.clone(),
            "the model has no joint: nothing moves, so there is no coordinate to write".to_owned(),
        ));
    }
    if !problems.is_empty() {
        return Err(problems);
    }
    let body_names: Vec<String> = (0..model.bodies.len())
        .map(|b| body_name(&model.bodies[b], b))
        .collect();
    let mut frames = vec!["N".to_owned()];
    let mut origins = vec!["O".to_owned()];
    for name in &body_names[1..] {
        frames.push(if names.claim(name) {
            name.clone()
        } else {
            names.fresh(&format!("{name}_frame"))
        });
        origins.push(names.fresh(&format!("{name}_origin")));
    }
    let mut writer = Writer {
        model,
        names,
        joints,
        frames,
        origins,
        body_names,
        lines: Vec::new(),
    };
    writer.model(&struct_name, options);
    Ok(writer.lines.join("\n") + "\n")
}

/// The struct's name: `--name`, else the model's name in UpperCamelCase.
fn struct_name(model: &Model, options: &Options, problems: &mut Vec<Problem>) -> String {
    let (name, whence) = match options.chosen.name.as_deref() {
        Some(name) => (name.to_owned(), "the name given"),
        None => (
            upper_camel_case(model.name.as_deref().unwrap_or("MuJoCo Model")),
            "the model's name in UpperCamelCase",
        ),
    };
    if !is_plain(&name) || is_builtin(&name) {
        problems.push(Problem::new(
            model.loc.clone(),
            format!(
                "{whence}, `{name}`, cannot name the struct: expected a Rust identifier that is \
                 not a keyword nor a built-in name of the language (choose one with `--name`)"
            ),
        ));
    }
    name
}

/// A body's name for the model: its own, sanitized, or `body<id>`.
fn body_name(body: &Body, id: usize) -> String {
    match &body.name {
        Some(name) => sanitize(name),
        None if id == 0 => "world".to_owned(),
        None => format!("body{id}"),
    }
}

/// Per body, per joint, the joint's name in the model (a hinge's or
/// slide's coordinate, a ball's or free joint's prefix), each claimed with
/// the names it makes; an unnamed joint is named `<body>_<type>`.
fn joint_names(model: &Model, names: &mut Names, problems: &mut Vec<Problem>) -> Vec<Vec<String>> {
    let mut out = Vec::new();
    for (b, body) in model.bodies.iter().enumerate() {
        let mut own = Vec::new();
        for joint in &body.joints {
            let name = match &joint.name {
                Some(name) => sanitize(name),
                None => format!("{}_{}", body_name(body, b), joint.kind.name()),
            };
            let made: Vec<String> = match joint.kind {
                JointKind::Hinge | JointKind::Slide => vec![name.clone(), format!("tau_{name}")],
                JointKind::Ball => std::iter::once(name.clone())
                    .chain(BALL_NAMES.iter().map(|s| format!("{name}_{s}")))
                    .chain(["wx", "wy", "wz"].map(|s| format!("tau_{name}_{s}")))
                    .collect(),
                JointKind::Free => std::iter::once(name.clone())
                    .chain(FREE_NAMES.iter().map(|s| format!("{name}_{s}")))
                    .collect(),
            };
            if let Some(taken) = made.iter().find(|n| !names.claim(n)) {
                problems.push(joint_name_problem(joint, &name, taken));
            }
            own.push(name);
        }
        out.push(own);
    }
    out
}

fn joint_name_problem(joint: &Joint, name: &str, taken: &str) -> Problem {
    let what = match &joint.name {
        Some(written) => format!("joint `{written}`"),
        None => "an unnamed joint".to_owned(),
    };
    Problem::new(
        joint.loc.clone(),
        format!(
            "{what}: the model would name it `{name}`, and `{taken}` is not a free identifier \
             there (a keyword, a built-in name, or the name of another joint); rename the joint"
        ),
    )
}

struct Writer<'a> {
    model: &'a Model,
    names: Names,
    /// Per body, per joint, its name in the model.
    joints: Vec<Vec<String>>,
    /// Per body, its frame (`N` for the world).
    frames: Vec<String>,
    /// Per body, the point at its origin (`O` for the world).
    origins: Vec<String>,
    /// Per body, its sanitized name.
    body_names: Vec<String>,
    lines: Vec<String>,
}

impl Writer<'_> {
    fn model(&mut self, struct_name: &str, options: &Options) {
        let model = self.model;
        let called = model
            .name
            .as_ref()
            .map_or("MuJoCo model".to_owned(), |n| format!("MuJoCo model `{n}`"));
        self.lines.push(format!(
            "/// The {called} of {}, imported by `dalembert mjcf`.",
            options.file_name
        ));
        self.lines.push(
            "/// Coordinates and speeds in MuJoCo's order (`qpos`, `qvel`); a free joint's \
             position and quaternion `(x, y, z, qx, qy, qz, qw)`, its velocity and angular \
             velocity in the body's axes; `tau_<coordinate>` is the force on each other speed \
             (MuJoCo's `qfrc_applied`)."
                .to_owned(),
        );
        self.lines.push(
            "/// Left out: contacts and the geoms' collision properties, joint limits and \
             friction loss (constraints)."
                .to_owned(),
        );
        for note in &model.notes {
            self.lines.push(format!("/// {note}"));
        }
        self.lines.push(format!("pub {struct_name} {{"));
        for b in 1..model.bodies.len() {
            self.body(b);
        }
        if model.gravity != [0.0; 3] {
            self.comment("Gravity from `<option gravity>`.".to_owned());
            self.statement(format!("gravity {};", in_n(model.gravity)));
        }
        self.passive();
        self.lines.push("}".to_owned());
    }

    fn statement(&mut self, text: String) {
        self.lines.push(format!("    {text}"));
    }

    fn comment(&mut self, text: String) {
        self.lines.push(String::new());
        self.lines.push(format!("    // {text}"));
    }

    /// Body `b`: its placement, its joints, its frame and origin, its mass.
    fn body(&mut self, b: usize) {
        let body = &self.model.bodies[b];
        let parent = body.parent;
        self.comment(format!(
            "Body `{}` in `{}`.",
            self.body_names[b], self.body_names[parent]
        ));
        let own_frame = self.frames[b].clone();
        let is_free = body
            .joints
            .first()
            .is_some_and(|j| j.kind == JointKind::Free);
        let (mut frame, mut origin) = if is_free {
            ("N".to_owned(), "O".to_owned())
        } else {
            let parent_frame = self.frames[parent].clone();
            let origin = offset(&self.origins[parent], body.pos, &parent_frame);
            let frame = if body.quat == IDENTITY {
                parent_frame
            } else {
                let name = if body.joints.is_empty() {
                    own_frame.clone()
                } else {
                    self.names.fresh(&format!("{}_mount", self.body_names[b]))
                };
                self.rotated(&name, &parent_frame, body.quat);
                name
            };
            (frame, origin)
        };
        for (k, joint) in body.joints.iter().enumerate() {
            let child = if k + 1 == body.joints.len() {
                own_frame.clone()
            } else {
                self.names.fresh(&format!("{}_frame", self.joints[b][k]))
            };
            origin = self.joint(joint, &self.joints[b][k].clone(), &frame, &child, &origin);
            frame = child;
        }
        if frame != own_frame {
            self.statement(format!("frame {own_frame} = {frame}.rotate_z(0);"));
        }
        let point = self.origins[b].clone();
        self.statement(format!("point {point} = {origin};"));
        self.mass(b, &own_frame, &point);
    }

    /// `frame name = parent.rotate(..)` turning `parent` by `quat`.
    fn rotated(&mut self, name: &str, parent: &str, quat: Quat) {
        let (axis, angle) = pose::axis_angle(quat);
        let turn = match axis_field(axis).strip_prefix("axis: ") {
            Some(unit) if unit.len() == 1 => format!("rotate_{unit}({})", number(angle)),
            _ => {
                let components: Vec<String> = axis.into_iter().map(number).collect();
                format!("rotate([{}], {})", components.join(", "), number(angle))
            }
        };
        self.statement(format!("frame {name} = {parent}.{turn};"));
    }

    /// One joint from `frame` (the body's frame as the joints before it
    /// left it, with origin `origin`) to `child`; the new origin.
    fn joint(
        &mut self,
        joint: &Joint,
        name: &str,
        frame: &str,
        child: &str,
        origin: &str,
    ) -> String {
        let anchor = offset(origin, joint.pos, frame);
        let from_anchor = |point: &str| offset(point, joint.pos.map(|x| -x), child);
        match joint.kind {
            JointKind::Hinge | JointKind::Slide => {
                let axis = axis_field(joint.axis);
                let input = format!("tau_{name}");
                self.statement(format!("coordinates {name};"));
                self.statement(format!("inputs {input};"));
                // MuJoCo turns or slides by `q − ref` from the placement
                // written: back by `ref` (a turn about the axis, which
                // keeps the axis and the anchor), then by `q`.
                let back = -joint.reference;
                let parent = if joint.kind == JointKind::Hinge && back != 0.0 {
                    let turned = self.names.fresh(&format!("{name}_ref"));
                    let turn = pose::from_axis_angle(joint.axis, back).unwrap_or(IDENTITY);
                    self.rotated(&turned, frame, turn);
                    turned
                } else {
                    frame.to_owned()
                };
                let point = self.names.fresh(&format!("{name}_anchor"));
                let push = scaled(&input, joint.axis, &parent);
                if joint.kind == JointKind::Hinge {
                    self.statement(format!(
                        "joint revolute {point} {{ parent: {parent}, child: {child}, {axis}, \
                         coordinate: {name}, at: {anchor} }};"
                    ));
                    self.statement(format!("torque {push} on {child} reacting {parent};"));
                    from_anchor(&point)
                } else {
                    let at = offset(origin, joint.axis.map(|a| a * back), frame);
                    self.statement(format!(
                        "joint prismatic {point} {{ parent: {frame}, child: {child}, {axis}, \
                         coordinate: {name}, at: {at} }};"
                    ));
                    let pull = scaled(&input, joint.axis.map(|a| -a), frame);
                    self.statement(format!("force {push} at {point};"));
                    self.statement(format!("force {pull} at {at};"));
                    point
                }
            }
            JointKind::Ball => {
                self.statement(format!(
                    "joint spherical {name} {{ parent: {frame}, child: {child}, at: {anchor} }};"
                ));
                let inputs = ["wx", "wy", "wz"].map(|s| format!("tau_{name}_{s}"));
                self.statement(format!("inputs {};", inputs.join(", ")));
                let [x, y, z] = inputs;
                self.statement(format!(
                    "torque {x} * {child}.x + {y} * {child}.y + {z} * {child}.z on {child} \
                     reacting {frame};"
                ));
                from_anchor(name)
            }
            JointKind::Free => {
                self.statement(format!(
                    "joint free {name} {{ parent: N, child: {child}, at: O }};"
                ));
                name.to_owned()
            }
        }
    }

    /// The body of `b`, if it has mass, fixed in `frame` about `origin`.
    fn mass(&mut self, b: usize, frame: &str, origin: &str) {
        let mut body = self.model.bodies[b].mass;
        body.inertia = without_rounding(&body.inertia);
        if body.mass == 0.0 && body.inertia.iter().flatten().all(|&x| x == 0.0) {
            return;
        }
        let name = self.names.fresh(&format!("{}_mass", self.body_names[b]));
        let center = offset(origin, body.center, frame);
        self.statement(body_statement(&name, &body, &center, frame));
        let gravcomp = self.model.bodies[b].gravcomp;
        if gravcomp != 0.0 && self.model.gravity != [0.0; 3] {
            // MuJoCo's `qfrc_gravcomp`, part of its passive force (not of
            // its potential energy).
            let lift = self.model.gravity.map(|g| -gravcomp * body.mass * g);
            self.lines.push(format!(
                "    // Gravity compensation, `gravcomp=\"{gravcomp}\"`: that part of the weight held up."
            ));
            self.statement(format!("force {} at {center};", in_n(lift)));
        }
    }

    /// MuJoCo puts a free joint's armature `a` on its linear speeds in
    /// world axes, `½ a |v|²` of the origin's velocity `v` in `N`; on the
    /// speeds in the body's axes that inertia also turns with the body:
    /// `a (v̇ + ω × v)`, whose second term (no part of `M`) is written
    /// as the force `−a ω × v` at the origin.
    fn free_armature_turning(&self, b: usize, armature: f64) -> String {
        let (frame, origin) = (&self.frames[b], &self.origins[b]);
        format!(
            "force {} * cross(angular_velocity({frame}), velocity({origin})) at {origin};",
            number(-armature)
        )
    }

    /// The joints' springs (`½ k (q − springref)²`), dampers (`½ d v²`
    /// per speed) and armatures (on `M`'s diagonal), as MuJoCo's passive
    /// forces and `dof_armature`.
    fn passive(&mut self) {
        let mut springs = Vec::new();
        let mut dampers = Vec::new();
        let mut armatures = Vec::new();
        for (b, body) in self.model.bodies.iter().enumerate() {
            for (joint, name) in body.joints.iter().zip(&self.joints[b]) {
                let speeds = speeds(joint.kind, name);
                if joint.stiffness != 0.0 {
                    let displacement = match joint.springref {
                        0.0 => name.clone(),
                        r if r < 0.0 => format!("({name} + {})", number(-r)),
                        r => format!("({name} - {})", number(r)),
                    };
                    springs.push(format!("{} * {displacement}^2", number(joint.stiffness)));
                }
                if joint.damping != 0.0 {
                    let squares: Vec<String> = speeds.iter().map(|v| format!("{v}^2")).collect();
                    let sum = match &squares[..] {
                        [one] => one.clone(),
                        _ => format!("({})", squares.join(" + ")),
                    };
                    dampers.push(format!("{} * {sum}", number(joint.damping)));
                }
                if joint.armature != 0.0 {
                    for speed in &speeds {
                        armatures.push(format!("armature {} on {speed};", number(joint.armature)));
                    }
                    if joint.kind == JointKind::Free {
                        armatures.push(format!(
                            "// `{name}`'s linear armature is in world axes, as MuJoCo's: it \
                             turns with the body."
                        ));
                        armatures.push(self.free_armature_turning(b, joint.armature));
                    }
                }
            }
        }
        if !springs.is_empty() {
            self.comment("Joint springs: `stiffness` and `springref`.".to_owned());
            self.statement(format!("potential 1/2 * ({});", springs.join(" + ")));
        }
        if !dampers.is_empty() {
            self.comment("Joint damping.".to_owned());
            self.statement(format!("dissipation 1/2 * ({});", dampers.join(" + ")));
        }
        if !armatures.is_empty() {
            self.comment("Joint armature, added to the diagonal of M.".to_owned());
            for armature in armatures {
                self.statement(armature);
            }
        }
    }
}

/// The vector `v` in `N`'s axes, its zero components left out.
fn in_n(v: [f64; 3]) -> String {
    let terms: Vec<String> = v
        .iter()
        .zip(["x", "y", "z"])
        .filter(|(c, _)| **c != 0.0)
        .map(|(c, axis)| format!("{} * N.{axis}", number(*c)))
        .collect();
    terms.join(" + ").replace("+ -", "- ")
}

/// The speeds of a joint named `name`, as the language writes them.
fn speeds(kind: JointKind, name: &str) -> Vec<String> {
    let suffixes: &[&str] = match kind {
        JointKind::Hinge | JointKind::Slide => return vec![format!("dt({name})")],
        JointKind::Ball => &["wx", "wy", "wz"],
        JointKind::Free => &["vx", "vy", "vz", "wx", "wy", "wz"],
    };
    suffixes.iter().map(|s| format!("{name}_{s}")).collect()
}
