//! Reading an MJCF model into its bodies as MuJoCo compiles them: the
//! `<compiler>` settings, `<default>` classes (nested classes inherit
//! their parent's attributes; an element takes its `class`, else the
//! nearest `childclass` of its body or an ancestor, else `main`), every
//! body's placement as a unit quaternion, its joints in file order, and
//! its mass properties from `<inertial>` or from its geoms by MuJoCo's
//! rules (`inertiafromgeom`, `inertiagrouprange`, `mass` or `density`,
//! `settotalmass`). Numbers are read strictly; what the import leaves out
//! is listed as notes for the model's documentation, and what would make
//! the dynamics differ from MuJoCo's is an error.

use std::collections::HashMap;

use super::files::{Element, Files};
use super::pose::{self, EPS, IDENTITY, Quat, Shape};
use super::{Loc, Problem};
use crate::urdf::inertia::{MassProperties, Placement, Vec3};

/// The model as MuJoCo compiles it, bodies in MuJoCo's order (depth
/// first, in file order; `bodies[0]` is the world).
pub(super) struct Model {
    /// `<mujoco model="...">`.
    pub name: Option<String>,
    /// The `<mujoco>` tag.
    pub loc: Loc,
    /// `<option gravity>`, zero when the gravity flag is disabled.
    pub gravity: Vec3,
    pub bodies: Vec<Body>,
    /// What the import leaves out, for the model's documentation.
    pub notes: Vec<String>,
}

/// A `<body>` (or the world).
pub(super) struct Body {
    /// The `name` attribute, if any.
    pub name: Option<String>,
    /// The parent body (the world's is itself).
    pub parent: usize,
    /// The body frame in the parent's at rest.
    pub pos: Vec3,
    pub quat: Quat,
    /// Its joints, in file order.
    pub joints: Vec<Joint>,
    /// Mass, centre and central inertia in the body frame.
    pub mass: MassProperties,
    /// `gravcomp`: the fraction of the body's weight a passive force at
    /// its centre of mass holds up.
    pub gravcomp: f64,
}

/// The joint types of MJCF.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum JointKind {
    Hinge,
    Slide,
    Ball,
    Free,
}

impl JointKind {
    /// The type as MJCF writes it.
    pub fn name(self) -> &'static str {
        match self {
            JointKind::Hinge => "hinge",
            JointKind::Slide => "slide",
            JointKind::Ball => "ball",
            JointKind::Free => "free",
        }
    }
}

/// A `<joint>` or `<freejoint>`.
pub(super) struct Joint {
    pub name: Option<String>,
    pub loc: Loc,
    pub kind: JointKind,
    /// The anchor in the body frame.
    pub pos: Vec3,
    /// The unit axis in the body frame (hinge and slide).
    pub axis: Vec3,
    /// `ref` (hinge and slide) in radians or metres: the value of the
    /// coordinate at which the body is where the file places it.
    pub reference: f64,
    /// `springref` in radians or metres.
    pub springref: f64,
    pub stiffness: f64,
    pub damping: f64,
    pub armature: f64,
}

/// `<compiler>`'s settings that change the dynamics.
struct Compiler {
    /// `angle="degree"` (MJCF's default).
    degree: bool,
    eulerseq: [u8; 3],
    /// `inertiafromgeom`: `Some(true)` always, `Some(false)` never, `None`
    /// (auto) for bodies without `<inertial>`.
    from_geoms: Option<bool>,
    group_range: [i64; 2],
    total_mass: Option<f64>,
}

impl Default for Compiler {
    fn default() -> Self {
        Compiler {
            degree: true,
            eulerseq: *b"xyz",
            from_geoms: None,
            group_range: [0, 5],
            total_mass: None,
        }
    }
}

/// An attribute's value and where it is written.
#[derive(Clone)]
struct Attribute<'a> {
    value: &'a str,
    loc: Loc,
}

/// A `<default>` class: its parent and, per element tag, its attributes.
#[derive(Default)]
struct Class<'a> {
    parent: Option<String>,
    attributes: HashMap<String, HashMap<String, Attribute<'a>>>,
}

/// Reads the model of `files`, or every problem found.
pub(super) fn read(files: &Files<'_>) -> Result<Model, Vec<Problem>> {
    let root = files.root();
    let mut reader = Reader {
        files,
        compiler: Compiler::default(),
        classes: HashMap::new(),
        problems: Vec::new(),
        notes: Vec::new(),
        bodies: Vec::new(),
        actuator_gravcomp: Vec::new(),
    };
    if root.tag() != "mujoco" {
        reader.problem(
            root.loc(),
            format!(
                "expected the root element `<mujoco>`, found `<{}>`",
                root.tag()
            ),
        );
        return Err(reader.problems);
    }
    let top = files.children(root);
    // Settings and classes first: MuJoCo applies them wherever they are
    // written.
    for element in &top {
        match element.tag() {
            "compiler" => reader.compiler(*element),
            "default" => reader.default_class(*element, None),
            _ => {}
        }
    }
    let mut gravity = [0.0, 0.0, -9.81];
    reader.bodies.push(Body {
        name: Some("world".to_owned()),
        parent: 0,
        pos: [0.0; 3],
        quat: IDENTITY,
        joints: Vec::new(),
        mass: MassProperties::NONE,
        gravcomp: 0.0,
    });
    for element in &top {
        match element.tag() {
            "option" => gravity = reader.option(*element, gravity),
            "worldbody" => reader.world(*element),
            tag => reader.top_level(*element, tag),
        }
    }
    reader.total_mass();
    reader.check_actuator_gravcomp();
    if !reader.problems.is_empty() {
        return Err(reader.problems);
    }
    Ok(Model {
        name: root.node.attribute("model").map(str::to_owned),
        loc: root.loc(),
        gravity,
        bodies: reader.bodies,
        notes: reader.notes,
    })
}

struct Reader<'a> {
    files: &'a Files<'a>,
    compiler: Compiler,
    classes: HashMap<String, Class<'a>>,
    problems: Vec<Problem>,
    notes: Vec<String>,
    bodies: Vec<Body>,
    /// The joints' `actuatorgravcomp="true"` attributes.
    actuator_gravcomp: Vec<Loc>,
}

impl<'a> Reader<'a> {
    /// Records a problem once (an unknown class is met at every attribute
    /// looked up through it).
    fn problem(&mut self, loc: Loc, message: String) {
        let seen = self
            .problems
            .iter()
            .any(|p| p.loc.range == loc.range && p.loc.file == loc.file && p.message == message);
        if !seen {
            self.problems.push(Problem::new(loc, message));
        }
    }

    fn note(&mut self, note: &str) {
        if !self.notes.iter().any(|n| n == note) {
            self.notes.push(note.to_owned());
        }
    }

    /// The elements outside `<worldbody>` that change the dynamics:
    /// refused, or noted as left out.
    fn top_level(&mut self, element: Element<'a>, tag: &str) {
        match tag {
            "equality" if !self.files.children(element).is_empty() => self.problem(
                element.loc(),
                "equality constraints are not imported: they close loops or weld bodies, \
                 which changes the motion; write them as `constraint` or `closure` \
                 statements in the model instead"
                    .to_owned(),
            ),
            "tendon" => self.tendons(element),
            "actuator" => {
                self.note("Actuators are left out (their gears and activation dynamics).")
            }
            "contact" => self.note(
                "Contacts are left out (`<contact>` pairs and exclusions, and the geoms' \
                 collision properties).",
            ),
            _ => {}
        }
    }

    /// Tendons with stiffness or damping add passive forces, with
    /// armature inertia (`M += Jᵀ a J`, off the diagonal too): refused;
    /// others only serve actuators and limits: noted.
    fn tendons(&mut self, element: Element<'a>) {
        for tendon in self.files.children(element) {
            for (name, adds) in [
                ("stiffness", "a passive force"),
                ("damping", "a passive force"),
                ("armature", "inertia"),
            ] {
                let value = self.attribute(tendon, None, name);
                if let Some(value) = value {
                    if value.value.trim().parse::<f64>().is_ok_and(|x| x != 0.0) {
                        self.problem(
                            value.loc,
                            format!(
                                "a tendon with `{name}` is not imported: it adds {adds} \
                                 along the tendon's length, which the import does not model"
                            ),
                        );
                    }
                }
            }
        }
        self.note("Tendons are left out (used by actuators and limits only).");
    }

    fn compiler(&mut self, element: Element<'a>) {
        if let Some(angle) = self.own(element, "angle") {
            match angle.value {
                "degree" => self.compiler.degree = true,
                "radian" => self.compiler.degree = false,
                other => self.problem(
                    angle.loc,
                    format!("`angle=\"{other}\"`: expected `degree` or `radian`"),
                ),
            }
        }
        if let Some(sequence) = self.own(element, "eulerseq") {
            match <[u8; 3]>::try_from(sequence.value.as_bytes()) {
                Ok(seq) if seq.iter().all(|c| b"xyzXYZ".contains(c)) => {
                    self.compiler.eulerseq = seq;
                }
                _ => self.problem(
                    sequence.loc,
                    format!(
                        "`eulerseq=\"{}\"`: expected three of `x y z X Y Z` (lower case: \
                         moving axes, upper case: fixed axes)",
                        sequence.value
                    ),
                ),
            }
        }
        if let Some(mode) = self.own(element, "inertiafromgeom") {
            match mode.value {
                "true" => self.compiler.from_geoms = Some(true),
                "false" => self.compiler.from_geoms = Some(false),
                "auto" => self.compiler.from_geoms = None,
                other => self.problem(
                    mode.loc,
                    format!("`inertiafromgeom=\"{other}\"`: expected `true`, `false` or `auto`"),
                ),
            }
        }
        if let Some([low, high]) = self.numbers::<2>(element, None, "inertiagrouprange") {
            self.compiler.group_range = [low as i64, high as i64];
        }
        if let Some([mass]) = self.numbers::<1>(element, None, "settotalmass") {
            self.compiler.total_mass = (mass > 0.0).then_some(mass);
        }
        for refused in ["boundmass", "boundinertia"] {
            if let Some([x]) = self.numbers::<1>(element, None, refused) {
                if x > 0.0 {
                    let loc = self.own(element, refused).map(|a| a.loc);
                    self.problem(
                        loc.unwrap_or(element.loc()),
                        format!("`{refused}` is not supported; give the masses and inertias"),
                    );
                }
            }
        }
        for refused in ["balanceinertia", "alignfree"] {
            if let Some(flag) = self.own(element, refused).filter(|a| a.value == "true") {
                self.problem(flag.loc, format!("`{refused}=\"true\"` is not supported"));
            }
        }
        if let Some(coordinate) = self
            .own(element, "coordinate")
            .filter(|a| a.value != "local")
        {
            self.problem(
                coordinate.loc,
                "`coordinate=\"global\"` is not supported (MuJoCo 3 removed it)".to_owned(),
            );
        }
    }

    /// A `<default>` class and the classes nested in it.
    fn default_class(&mut self, element: Element<'a>, parent: Option<String>) {
        let name = match (self.own(element, "class"), &parent) {
            (Some(class), None) if class.value != "main" => {
                self.problem(
                    class.loc,
                    format!(
                        "a top-level `<default>` is the class `main`, which cannot be renamed \
                         (found `class=\"{}\"`): expected no `class` (or `class=\"main\"`), and the named classes nested in it",
                        class.value
                    ),
                );
                return;
            }
            (Some(class), _) => class.value.to_owned(),
            (None, None) => "main".to_owned(),
            (None, Some(_)) => {
                self.problem(
                    element.loc(),
                    "a nested `<default>` needs the attribute `class`".to_owned(),
                );
                return;
            }
        };
        let mut class = Class {
            parent,
            attributes: HashMap::new(),
        };
        let mut nested = Vec::new();
        for child in self.files.children(element) {
            if child.tag() == "default" {
                nested.push(child);
                continue;
            }
            if class.attributes.contains_key(child.tag()) {
                // Else the second's attributes would silently override the
                // first's, where MuJoCo refuses the file.
                self.problem(
                    child.loc(),
                    format!(
                        "a second `<{}>` in this `<default>`: a class has at most one of each \
                         element",
                        child.tag()
                    ),
                );
                continue;
            }
            let attributes = class.attributes.entry(child.tag().to_owned()).or_default();
            for attribute in child.node.attributes() {
                attributes.insert(
                    attribute.name().to_owned(),
                    Attribute {
                        value: attribute.value(),
                        loc: Loc {
                            file: child.file,
                            range: attribute.range(),
                        },
                    },
                );
            }
        }
        match self.classes.get_mut(&name) {
            // Several top-level `<default>`s (one per included file, say)
            // are one class `main`, merged attribute by attribute, the
            // later winning, as MuJoCo reads them.
            Some(_) if class.parent.is_none() => self.merge_into_main(&name, class),
            Some(_) => {
                self.problem(
                    element.loc(),
                    format!("the default class `{name}` is defined twice"),
                );
                self.classes.insert(name.clone(), class);
            }
            None => {
                self.classes.insert(name.clone(), class);
            }
        }
        for child in nested {
            self.default_class(child, Some(name.clone()));
        }
    }

    /// Merges a second top-level `<default>`'s attributes into the class
    /// `main`. The classes made before keep `main`'s attributes as they
    /// were: MuJoCo copies a parent class into a child when it makes it,
    /// so they no longer look up to `main`.
    fn merge_into_main(&mut self, main: &str, later: Class<'a>) {
        let Some(earlier) = self.classes.get(main).map(|c| c.attributes.clone()) else {
            return;
        };
        for class in self.classes.values_mut() {
            if class.parent.as_deref() != Some(main) {
                continue;
            }
            class.parent = None;
            for (tag, attributes) in &earlier {
                let own = class.attributes.entry(tag.clone()).or_default();
                for (name, attribute) in attributes {
                    own.entry(name.clone()).or_insert_with(|| attribute.clone());
                }
            }
        }
        if let Some(class) = self.classes.get_mut(main) {
            for (tag, attributes) in later.attributes {
                class.attributes.entry(tag).or_default().extend(attributes);
            }
        }
    }

    /// A joint with `actuatorgravcomp="true"` takes the gravity
    /// compensation of the bodies beyond it through its actuator, not as
    /// a passive force: refused where some body has `gravcomp` (the
    /// import leaves actuators out).
    fn check_actuator_gravcomp(&mut self) {
        if self.bodies.iter().all(|b| b.gravcomp == 0.0) {
            return;
        }
        for loc in std::mem::take(&mut self.actuator_gravcomp) {
            self.problem(
                loc,
                "`actuatorgravcomp=\"true\"` is not supported: it sends the bodies' gravity \
                 compensation (`gravcomp`) through the actuators, which the import leaves out"
                    .to_owned(),
            );
        }
    }

    /// The attribute `name` written on `element` itself.
    fn own(&self, element: Element<'a>, name: &str) -> Option<Attribute<'a>> {
        element.node.attribute_node(name).map(|a| Attribute {
            value: a.value(),
            loc: Loc {
                file: element.file,
                range: a.range(),
            },
        })
    }

    /// The attribute `name` of `element`: its own, else its class's
    /// (`class`, else `childclass`, else `main`) or an ancestor class's.
    fn attribute(
        &mut self,
        element: Element<'a>,
        childclass: Option<&str>,
        name: &str,
    ) -> Option<Attribute<'a>> {
        if let Some(own) = self.own(element, name) {
            return Some(own);
        }
        let own_class = self.own(element, "class");
        let mut class = own_class
            .as_ref()
            .map(|c| c.value)
            .or(childclass)
            .unwrap_or("main");
        loop {
            let Some(found) = self.classes.get(class) else {
                if let Some(written) = own_class.as_ref().filter(|c| c.value == class) {
                    self.problem(
                        written.loc.clone(),
                        format!("unknown default class `{class}`"),
                    );
                }
                return None;
            };
            if let Some(attribute) = found
                .attributes
                .get(element.tag())
                .and_then(|a| a.get(name))
            {
                return Some(attribute.clone());
            }
            class = found.parent.as_deref()?;
        }
    }

    /// `N` finite numbers in the attribute `name` of `element` (with its
    /// classes), or `None` if absent or wrong (then a problem).
    fn numbers<const N: usize>(
        &mut self,
        element: Element<'a>,
        childclass: Option<&str>,
        name: &str,
    ) -> Option<[f64; N]> {
        let attribute = self.attribute(element, childclass, name)?;
        let parsed: Vec<f64> = attribute
            .value
            .split_whitespace()
            .filter_map(|w| w.parse::<f64>().ok().filter(|x| x.is_finite()))
            .collect();
        let words = attribute.value.split_whitespace().count();
        if words == N && parsed.len() == N {
            let mut out = [0.0; N];
            out.copy_from_slice(&parsed);
            return Some(out);
        }
        let expected = if N == 1 {
            "a finite number".to_owned()
        } else {
            format!("{N} finite numbers separated by spaces")
        };
        self.problem(
            attribute.loc,
            format!(
                "`<{}>`: `{name}=\"{}\"` is not {expected}",
                element.tag(),
                attribute.value
            ),
        );
        None
    }

    /// Up to three finite numbers (`size`), the rest zero.
    fn sizes(&mut self, element: Element<'a>, childclass: Option<&str>) -> Option<Vec3> {
        let attribute = self.attribute(element, childclass, "size")?;
        let parsed: Vec<Option<f64>> = attribute
            .value
            .split_whitespace()
            .map(|w| w.parse::<f64>().ok().filter(|x| x.is_finite()))
            .collect();
        if parsed.is_empty() || parsed.len() > 3 || parsed.iter().any(Option::is_none) {
            self.problem(
                attribute.loc,
                format!(
                    "`<{}>`: `size=\"{}\"` is not one to three finite numbers",
                    element.tag(),
                    attribute.value
                ),
            );
            return None;
        }
        let mut size = [0.0; 3];
        for (s, x) in size.iter_mut().zip(parsed) {
            *s = x.unwrap_or_default();
        }
        Some(size)
    }

    /// An angle in the compiler's unit, in radians.
    fn radians(&self, angle: f64) -> f64 {
        if self.compiler.degree {
            angle / 180.0 * std::f64::consts::PI
        } else {
            angle
        }
    }

    /// The orientation of `element` from whichever of `quat`, `axisangle`,
    /// `euler`, `xyaxes`, `zaxis` it has (at most one).
    fn orientation(&mut self, element: Element<'a>, childclass: Option<&str>) -> Option<Quat> {
        let given: Vec<&str> = ["quat", "axisangle", "euler", "xyaxes", "zaxis"]
            .into_iter()
            .filter(|n| self.own(element, n).is_some())
            .collect();
        if given.len() > 1 {
            self.problem(
                element.loc(),
                format!(
                    "`<{}>` gives its orientation twice ({}); expected one of `quat`, \
                     `axisangle`, `euler`, `xyaxes`, `zaxis`",
                    element.tag(),
                    given.join(", ")
                ),
            );
            return None;
        }
        let too_small = |reader: &mut Self, what: &str| {
            let loc = reader.own(element, what).map_or(element.loc(), |a| a.loc);
            reader.problem(loc, format!("`<{}>`: the `{what}` is zero", element.tag()));
        };
        match given.first().copied() {
            None => {
                let quat = self.numbers::<4>(element, childclass, "quat");
                Some(quat.map_or(IDENTITY, |q| pose::normalized(q).0))
            }
            Some("quat") => {
                let (q, norm) = pose::normalized(self.numbers::<4>(element, None, "quat")?);
                if norm < EPS {
                    too_small(self, "quat");
                    return None;
                }
                Some(q)
            }
            Some("axisangle") => {
                let [x, y, z, a] = self.numbers::<4>(element, None, "axisangle")?;
                let q = pose::from_axis_angle([x, y, z], self.radians(a));
                if q.is_none() {
                    too_small(self, "axisangle");
                }
                q
            }
            Some("euler") => {
                let angles = self.numbers::<3>(element, None, "euler")?;
                Some(pose::from_euler(
                    angles.map(|a| self.radians(a)),
                    &self.compiler.eulerseq,
                ))
            }
            Some("xyaxes") => {
                let q = pose::from_xy_axes(self.numbers::<6>(element, None, "xyaxes")?);
                if q.is_none() {
                    too_small(self, "xyaxes");
                }
                q
            }
            _ => {
                let q = pose::from_z_axis(self.numbers::<3>(element, None, "zaxis")?);
                if q.is_none() {
                    too_small(self, "zaxis");
                }
                q
            }
        }
    }

    fn option(&mut self, element: Element<'a>, mut gravity: Vec3) -> Vec3 {
        if let Some(g) = self.numbers::<3>(element, None, "gravity") {
            gravity = g;
        }
        for name in ["density", "viscosity"] {
            if self
                .numbers::<1>(element, None, name)
                .is_some_and(|[x]| x != 0.0)
            {
                let loc = self.own(element, name).map_or(element.loc(), |a| a.loc);
                self.problem(
                    loc,
                    format!(
                        "`{name}` adds fluid forces, which the import does not model; remove \
                         it to import the model without them"
                    ),
                );
            }
        }
        for flag in self.files.children(element) {
            if flag.tag() != "flag" {
                continue;
            }
            for name in ["gravity", "passive", "spring", "damper"] {
                if let Some(off) = self.own(flag, name).filter(|a| a.value == "disable") {
                    if name == "gravity" {
                        gravity = [0.0; 3];
                        self.note("Gravity is disabled (`<flag gravity=\"disable\">`).");
                    } else {
                        self.problem(
                            off.loc,
                            format!(
                                "`{name}=\"disable\"` is not supported: the import writes \
                                 every spring and damper"
                            ),
                        );
                    }
                }
            }
        }
        gravity
    }

    fn world(&mut self, element: Element<'a>) {
        for child in self.files.children(element) {
            match child.tag() {
                "body" => self.body(child, 0, None),
                "frame" => self.frame_element(child),
                "joint" | "freejoint" => self.problem(
                    child.loc(),
                    "a joint in `<worldbody>` moves nothing; put it in a `<body>`".to_owned(),
                ),
                _ => {}
            }
        }
    }

    fn frame_element(&mut self, element: Element<'a>) {
        self.problem(
            element.loc(),
            "`<frame>` is not supported; place its bodies with their own `pos` and `quat`"
                .to_owned(),
        );
    }

    /// A `<body>` below `parent`, then its children.
    fn body(&mut self, element: Element<'a>, parent: usize, inherited: Option<&str>) {
        let own_childclass = self.own(element, "childclass");
        if let Some(written) = own_childclass
            .as_ref()
            .filter(|c| !self.classes.contains_key(c.value))
        {
            // Else every lookup through it would miss, the `main` class's
            // defaults included, where MuJoCo refuses the file.
            self.problem(
                written.loc.clone(),
                format!("unknown default class `{}`", written.value),
            );
        }
        let childclass = own_childclass.map(|c| c.value).or(inherited);
        let pos = self.numbers::<3>(element, None, "pos").unwrap_or([0.0; 3]);
        let quat = self.orientation(element, None).unwrap_or(IDENTITY);
        let gravcomp = self
            .numbers::<1>(element, None, "gravcomp")
            .map_or(0.0, |[c]| c);
        let index = self.bodies.len();
        self.bodies.push(Body {
            name: self.own(element, "name").map(|n| n.value.to_owned()),
            parent,
            pos,
            quat,
            joints: Vec::new(),
            mass: MassProperties::NONE,
            gravcomp,
        });
        let children = self.files.children(element);
        let mut inertial = None;
        let mut geoms = Vec::new();
        for child in &children {
            match child.tag() {
                "joint" => {
                    if let Some(joint) = self.joint(*child, childclass) {
                        self.bodies[index].joints.push(joint);
                    }
                }
                "freejoint" => {
                    let joint = self.free_joint(*child);
                    self.bodies[index].joints.extend(joint);
                }
                "inertial" if inertial.is_some() => self.problem(
                    child.loc(),
                    "a second `<inertial>`: a body has at most one".to_owned(),
                ),
                "inertial" => inertial = Some(*child),
                "geom" => geoms.push(*child),
                "frame" => self.frame_element(*child),
                "composite" | "flexcomp" | "replicate" | "attach" => {
                    self.problem(child.loc(), format!("`<{}>` is not supported", child.tag()))
                }
                _ => {}
            }
        }
        self.check_joints(index);
        self.check_planes(index, &geoms, childclass);
        self.bodies[index].mass = self.mass(inertial, &geoms, childclass);
        let mut leaf = true;
        for child in children {
            if child.tag() == "body" {
                leaf = false;
                self.body(child, index, childclass);
            }
        }
        if leaf && inertial.is_none() && geoms.is_empty() && self.moves(index) {
            self.problem(
                element.loc(),
                format!(
                    "body{}: it moves but has neither `<inertial>` nor geoms, nor bodies \
                     beyond it, so its joints move no mass (MuJoCo refuses it too); expected \
                     an `<inertial>` or a geom",
                    self.bodies[index]
                        .name
                        .as_ref()
                        .map_or(String::new(), |n| format!(" `{n}`"))
                ),
            );
        }
    }

    /// Whether body `index` or one of its ancestors has a joint.
    fn moves(&self, mut index: usize) -> bool {
        while index != 0 {
            if !self.bodies[index].joints.is_empty() {
                return true;
            }
            index = self.bodies[index].parent;
        }
        false
    }

    /// MuJoCo allows plane geoms only in bodies that do not move.
    fn check_planes(&mut self, index: usize, geoms: &[Element<'a>], childclass: Option<&str>) {
        if !self.moves(index) {
            return;
        }
        for geom in geoms {
            if let Some(kind) = self
                .attribute(*geom, childclass, "type")
                .filter(|t| t.value == "plane")
            {
                self.problem(
                    kind.loc,
                    "a plane geom in a moving body (MuJoCo allows planes only in static \
                     bodies); expected a box, or the plane in a body that does not move"
                        .to_owned(),
                );
            }
        }
    }

    /// MuJoCo's rules on a body's joints: a free joint alone, in a body
    /// of the world; no rotation after a ball joint.
    fn check_joints(&mut self, index: usize) {
        let body = &self.bodies[index];
        let mut faults = Vec::new();
        let mut ball = false;
        for joint in &body.joints {
            match joint.kind {
                JointKind::Free if body.joints.len() > 1 || body.parent != 0 => faults.push((
                    joint.loc.clone(),
                    "a free joint must be the only joint of a body of `<worldbody>`",
                )),
                JointKind::Ball | JointKind::Hinge if ball => faults.push((
                    joint.loc.clone(),
                    "a rotation after a ball joint in the same body (MuJoCo refuses it)",
                )),
                _ => {}
            }
            ball |= joint.kind == JointKind::Ball;
        }
        for (loc, message) in faults {
            self.problem(loc, message.to_owned());
        }
    }

    fn joint(&mut self, element: Element<'a>, childclass: Option<&str>) -> Option<Joint> {
        let kind = match self.attribute(element, childclass, "type") {
            None => JointKind::Hinge,
            Some(kind) => match kind.value {
                "hinge" => JointKind::Hinge,
                "slide" => JointKind::Slide,
                "ball" => JointKind::Ball,
                "free" => JointKind::Free,
                other => {
                    self.problem(
                        kind.loc,
                        format!(
                            "unknown joint type `{other}`; expected `hinge`, `slide`, `ball` \
                             or `free`"
                        ),
                    );
                    return None;
                }
            },
        };
        let scalar = |reader: &mut Self, name| {
            reader
                .numbers::<1>(element, childclass, name)
                .map_or(0.0, |[x]| x)
        };
        let pos = self
            .numbers::<3>(element, childclass, "pos")
            .unwrap_or([0.0; 3]);
        let axis = self
            .numbers::<3>(element, childclass, "axis")
            .unwrap_or([0.0, 0.0, 1.0]);
        let mut springref = scalar(self, "springref");
        if kind == JointKind::Hinge {
            springref = self.radians(springref);
        }
        let mut reference = scalar(self, "ref");
        if kind == JointKind::Hinge {
            reference = self.radians(reference);
        }
        let (unit, norm) = pose::normalized(axis);
        if matches!(kind, JointKind::Hinge | JointKind::Slide) && norm < EPS {
            let loc = self.attribute(element, childclass, "axis").map(|a| a.loc);
            self.problem(
                loc.unwrap_or(element.loc()),
                format!(
                    "joint{}: the axis is zero; expected a direction, such as `axis=\"0 0 1\"`",
                    self.own(element, "name")
                        .map_or(String::new(), |n| format!(" `{}`", n.value))
                ),
            );
        }
        let joint = Joint {
            name: self.own(element, "name").map(|n| n.value.to_owned()),
            loc: element.loc(),
            kind,
            pos,
            axis: unit,
            reference,
            springref,
            stiffness: scalar(self, "stiffness"),
            damping: scalar(self, "damping"),
            armature: scalar(self, "armature"),
        };
        if let Some(attribute) = self
            .attribute(element, childclass, "springdamper")
            .filter(|a| a.value.split_whitespace().any(|w| w.parse() != Ok(0.0)))
        {
            self.problem(
                attribute.loc,
                "`springdamper` is not supported: MuJoCo derives the stiffness and damping \
                 from the joint's inertia at `qpos0`; expected `stiffness` and `damping`"
                    .to_owned(),
            );
        }
        if let Some(attribute) = self
            .attribute(element, childclass, "actuatorgravcomp")
            .filter(|a| a.value == "true")
        {
            self.actuator_gravcomp.push(attribute.loc);
        }
        if matches!(kind, JointKind::Ball | JointKind::Free) && joint.stiffness != 0.0 {
            let loc = self
                .attribute(element, childclass, "stiffness")
                .map(|a| a.loc);
            self.problem(
                loc.unwrap_or(element.loc()),
                format!(
                    "the stiffness of a {} joint is not supported (its potential is a \
                     function of the rotation angle, which the language cannot write)",
                    kind.name()
                ),
            );
        }
        Some(joint)
    }

    /// `<freejoint>`: a free joint that takes no defaults.
    fn free_joint(&mut self, element: Element<'a>) -> Option<Joint> {
        if self
            .own(element, "align")
            .is_some_and(|a| a.value == "true")
        {
            let loc = self.own(element, "align").map(|a| a.loc)?;
            self.problem(loc, "`align=\"true\"` is not supported".to_owned());
        }
        Some(Joint {
            name: self.own(element, "name").map(|n| n.value.to_owned()),
            loc: element.loc(),
            kind: JointKind::Free,
            pos: [0.0; 3],
            axis: [0.0, 0.0, 1.0],
            reference: 0.0,
            springref: 0.0,
            stiffness: 0.0,
            damping: 0.0,
            armature: 0.0,
        })
    }

    /// The body's mass properties: from `<inertial>`, or from its geoms
    /// where MuJoCo computes them.
    fn mass(
        &mut self,
        inertial: Option<Element<'a>>,
        geoms: &[Element<'a>],
        childclass: Option<&str>,
    ) -> MassProperties {
        let from_geoms = self.compiler.from_geoms.unwrap_or(inertial.is_none());
        if from_geoms {
            let selected: Vec<Element<'a>> = geoms
                .iter()
                .copied()
                .filter(|g| {
                    let group = self
                        .numbers::<1>(*g, childclass, "group")
                        .map_or(0, |[x]| x as i64);
                    (self.compiler.group_range[0]..=self.compiler.group_range[1]).contains(&group)
                })
                .collect();
            if !selected.is_empty() || inertial.is_none() {
                let mut total = MassProperties::NONE;
                for geom in selected {
                    if let Some(part) = self.geom_mass(geom, childclass) {
                        total = total.merged(&part);
                    }
                }
                return total;
            }
        }
        match inertial {
            Some(inertial) => self.inertial(inertial).unwrap_or(MassProperties::NONE),
            None => MassProperties::NONE,
        }
    }

    fn inertial(&mut self, element: Element<'a>) -> Option<MassProperties> {
        let pos = self.numbers::<3>(element, None, "pos").unwrap_or([0.0; 3]);
        let [mass] = self.numbers::<1>(element, None, "mass").or_else(|| {
            self.problem(
                element.loc(),
                "`<inertial>` needs the attribute `mass`".to_owned(),
            );
            None
        })?;
        if mass < 0.0 {
            let loc = self.own(element, "mass").map_or(element.loc(), |a| a.loc);
            self.problem(
                loc,
                format!("`<inertial>`: negative mass {mass}; a mass must be zero or positive"),
            );
            return None;
        }
        let quat = self.orientation(element, None)?;
        let tensor = if self.own(element, "fullinertia").is_some() {
            let [xx, yy, zz, xy, xz, yz] = self.numbers::<6>(element, None, "fullinertia")?;
            [[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]]
        } else {
            let Some([a, b, c]) = self.numbers::<3>(element, None, "diaginertia") else {
                if self.own(element, "diaginertia").is_none() {
                    self.problem(
                        element.loc(),
                        "`<inertial>` needs `diaginertia` or `fullinertia`".to_owned(),
                    );
                }
                return None;
            };
            [[a, 0.0, 0.0], [0.0, b, 0.0], [0.0, 0.0, c]]
        };
        Some(placed(mass, tensor, pos, quat))
    }

    /// The mass properties of one geom, in the body frame.
    fn geom_mass(
        &mut self,
        element: Element<'a>,
        childclass: Option<&str>,
    ) -> Option<MassProperties> {
        let kind = self.attribute(element, childclass, "type");
        let shape = match kind.map_or("sphere", |k| k.value) {
            "sphere" => Shape::Sphere,
            "capsule" => Shape::Capsule,
            "cylinder" => Shape::Cylinder,
            "ellipsoid" => Shape::Ellipsoid,
            "box" => Shape::Box,
            "plane" => return None,
            other => {
                let name = self
                    .own(element, "name")
                    .map_or(String::new(), |n| format!(" `{}`", n.value));
                self.problem(
                    element.loc(),
                    format!(
                        "geom{name}: MuJoCo computes the inertia of a `{other}` geom from its \
                         asset, which the import does not read; give the body an \
                         `<inertial>`, or put the geom in a group outside `inertiagrouprange`"
                    ),
                );
                return None;
            }
        };
        if self
            .attribute(element, childclass, "shellinertia")
            .is_some_and(|a| a.value == "true")
        {
            self.problem(
                element.loc(),
                "`shellinertia=\"true\"` is not supported".to_owned(),
            );
            return None;
        }
        let mut size = self.sizes(element, childclass).unwrap_or([0.0; 3]);
        let (pos, quat) = match self.numbers::<6>(element, childclass, "fromto") {
            // MuJoCo's rule, also for a `fromto` a sphere inherits from a
            // default class: it has no axis to lay along the segment.
            Some(_) if matches!(shape, Shape::Sphere) => {
                self.problem(
                    element.loc(),
                    "geom: `fromto` places a capsule, cylinder, box or ellipsoid; found a \
                     sphere (set `pos` for a sphere, or give the geom its own `type`)"
                        .to_owned(),
                );
                return None;
            }
            Some(ends) => {
                let Some((center, quat, half)) = pose::from_to(ends) else {
                    self.problem(
                        element.loc(),
                        "`fromto`: the two points are too close".to_owned(),
                    );
                    return None;
                };
                if matches!(shape, Shape::Ellipsoid | Shape::Box) {
                    size = [size[0], size[0], half];
                } else {
                    size[1] = half;
                }
                (center, quat)
            }
            None => (
                self.numbers::<3>(element, childclass, "pos")
                    .unwrap_or([0.0; 3]),
                self.orientation(element, childclass)?,
            ),
        };
        let volume = shape.volume(size);
        let mass = match self.numbers::<1>(element, childclass, "mass") {
            Some([mass]) => {
                if mass < 0.0 {
                    let loc = self
                        .attribute(element, childclass, "mass")
                        .map_or(element.loc(), |a| a.loc);
                    self.problem(
                        loc,
                        format!("geom: negative mass {mass}; a mass must be zero or positive"),
                    );
                    return None;
                }
                if mass == 0.0 || volume <= EPS {
                    return None;
                }
                mass
            }
            None => {
                let density = self
                    .numbers::<1>(element, childclass, "density")
                    .map_or(1000.0, |[d]| d);
                if density < 0.0 {
                    self.problem(element.loc(), "geom: negative density".to_owned());
                    return None;
                }
                density * volume
            }
        };
        if mass == 0.0 {
            return None;
        }
        let [a, b, c] = shape.inertia(mass, size);
        Some(placed(
            mass,
            [[a, 0.0, 0.0], [0.0, b, 0.0], [0.0, 0.0, c]],
            pos,
            quat,
        ))
    }

    /// `settotalmass`: every body's mass and inertia scaled so that they
    /// add up to it.
    fn total_mass(&mut self) {
        let Some(target) = self.compiler.total_mass else {
            return;
        };
        let total: f64 = self.bodies.iter().map(|b| b.mass.mass).sum();
        if total <= 0.0 {
            return;
        }
        let scale = target / total;
        for body in &mut self.bodies[1..] {
            body.mass.mass *= scale;
            body.mass.inertia = body.mass.inertia.map(|row| row.map(|x| x * scale));
        }
    }
}

/// Mass `mass` with central `tensor` in the frame at `pos` turned by
/// `quat`, expressed in the body frame.
fn placed(mass: f64, tensor: [[f64; 3]; 3], pos: Vec3, quat: Quat) -> MassProperties {
    MassProperties {
        mass,
        center: [0.0; 3],
        inertia: tensor,
    }
    .placed(&Placement {
        rotation: pose::matrix(quat),
        translation: pos,
    })
}
