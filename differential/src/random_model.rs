//! Random valid models: kinematic trees of one to six links as `.dal` text.
//!
//! Also compiled into `build.rs` (by `#[path]`), which writes the code of
//! [`EMITTED_MODELS`] of them: this file uses proptest and std only.
//!
//! Every coordinate carries inertia, so `M` is positive definite: link `i`
//! turns with its own coordinates (about distinct successive axes, so the
//! rates give independent angular velocities) only if it is a body with a
//! positive definite inertia tensor (moments at least 0.1 and products at
//! most 0.04: diagonally dominant), and slides along a fixed axis of its
//! parent with positive mass. Angles may add earlier coordinates;
//! by induction over the links, `q̇ᵀ M q̇ = 2T = 0` forces every rate to 0.

use std::fmt::Write;

use proptest::prelude::*;

/// How many fixed-seed random models `build.rs` generates and compiles.
pub const EMITTED_MODELS: usize = 24;

/// The axis names of a frame.
const AXES: [&str; 3] = ["x", "y", "z"];

/// A random kinematic tree with its loads.
#[derive(Clone, Debug)]
pub struct RandomModel {
    /// The links, each attached to the ground or to an earlier link.
    pub links: Vec<Link>,
    /// Gravity along `-N.axis`, if any.
    pub gravity: Option<usize>,
    /// Forces and torques.
    pub loads: Vec<Load>,
    /// Potential terms, as pairs of raw coordinate indices.
    pub potentials: Vec<(usize, usize)>,
    /// Dissipation terms, as pairs of raw coordinate indices.
    pub dissipations: Vec<(usize, usize)>,
}

/// One link of the tree.
#[derive(Clone, Debug)]
pub struct Link {
    /// The parent, modulo the link's index + 1: 0 is the ground.
    pub parent: usize,
    /// A constant rotation relative to the parent's frame before the
    /// link's own rotations (bodies only), as a joint's placement has.
    pub tilt: Option<Tilt>,
    /// Up to two rotations relative to the parent's frame (bodies only).
    pub rotations: Vec<Rotation>,
    /// A slide along this axis of the parent's frame, if any.
    pub slide: Option<usize>,
    /// The center's offset from the parent's point, in tenths, along the
    /// link's own axes.
    pub offset: [i8; 3],
    /// What the link carries.
    pub mass: Mass,
}

/// A rotation by `scale · q + coupling` about `axis`. (Never with time: a
/// mass may not move with `t`, see the checker.)
#[derive(Clone, Debug)]
pub struct Rotation {
    /// The axis of the frame rotated.
    pub axis: usize,
    /// The factor of the rotation's own coordinate (non-zero).
    pub scale: i8,
    /// An earlier coordinate (raw index) and its factor; `sin` of it if
    /// the flag is set.
    pub coupling: Option<(usize, i8, bool)>,
}

/// A rotation by a constant angle, in tenths of a radian (either sign),
/// about a coordinate axis or about a constant direction.
#[derive(Clone, Debug)]
pub struct Tilt {
    /// The coordinate axis, used when `direction` is `None` or zero.
    pub axis: usize,
    /// A direction `[ax, ay, az]` in the parent's axes, if any.
    pub direction: Option<[i8; 3]>,
    /// The angle in tenths of a radian.
    pub tenths: i8,
}

/// The mass a link carries.
#[derive(Clone, Debug)]
pub enum Mass {
    /// A rigid body: principal moments in tenths of its mass, and products
    /// of inertia in hundredths, if any.
    Body {
        /// `Ixx, Iyy, Izz` in tenths of the mass (1 to 20).
        moments: [u8; 3],
        /// `Ixy, Iyz, Izx` in hundredths of the mass (−4 to 4).
        products: Option<[i8; 3]>,
    },
    /// A point mass.
    Particle,
}

/// A force or torque on a link.
#[derive(Clone, Debug)]
pub struct Load {
    /// The link (raw index).
    pub link: usize,
    /// Along this axis of the frame of link `frame` (raw index; ground too).
    pub axis: usize,
    /// The frame whose axis gives the direction (raw index).
    pub frame: usize,
    /// What the magnitude depends on.
    pub magnitude: Magnitude,
    /// A torque (reacting on the parent if the flag is set) or a force.
    pub torque: Option<bool>,
}

/// The magnitude of a load.
#[derive(Clone, Debug)]
pub enum Magnitude {
    /// `k`.
    Constant,
    /// `-c · q̇ⱼ` (raw index).
    Damping(usize),
    /// `k · sin(qⱼ)` (raw index).
    Position(usize),
    /// The input `u0`.
    Input,
    /// `k · cos(t)`.
    Time,
}

/// The strategy for random models.
pub fn random_model() -> impl Strategy<Value = RandomModel> {
    (
        proptest::collection::vec(link(), 1..=6),
        proptest::option::of(0..3usize),
        proptest::collection::vec(load(), 0..4),
        proptest::collection::vec((0..64usize, 0..64usize), 0..3),
        proptest::collection::vec((0..64usize, 0..64usize), 0..3),
    )
        .prop_map(
            |(links, gravity, loads, potentials, dissipations)| RandomModel {
                links,
                gravity,
                loads,
                potentials,
                dissipations,
            },
        )
        .prop_filter("a model needs a coordinate", |model| {
            model.coordinate_count() > 0
        })
}

fn link() -> impl Strategy<Value = Link> {
    let body = (
        [1..=20u8, 1..=20u8, 1..=20u8],
        proptest::option::of([-4..=4i8, -4..=4i8, -4..=4i8]),
    )
        .prop_map(|(moments, products)| Mass::Body { moments, products });
    let tilt = (
        0..3usize,
        proptest::option::of([-3..=3i8, -3..=3i8, -3..=3i8]),
        prop_oneof![-20..=-1i8, 1..=20i8],
    )
        .prop_map(|(axis, direction, tenths)| Tilt {
            axis,
            direction,
            tenths,
        });
    (
        0..6usize,
        proptest::option::weighted(0.4, tilt),
        proptest::collection::vec(rotation(), 0..=2),
        proptest::option::weighted(0.3, 0..3usize),
        [-10..=10i8, -10..=10i8, -10..=10i8],
        prop_oneof![3 => body, 1 => Just(Mass::Particle)],
    )
        .prop_map(|(parent, tilt, rotations, slide, offset, mass)| Link {
            parent,
            tilt,
            rotations,
            slide,
            offset,
            mass,
        })
}

fn rotation() -> impl Strategy<Value = Rotation> {
    (
        0..3usize,
        prop_oneof![-3..=-1i8, 1..=3i8],
        proptest::option::weighted(0.3, (0..64usize, -3..=3i8, any::<bool>())),
    )
        .prop_map(|(axis, scale, coupling)| Rotation {
            axis,
            scale,
            coupling,
        })
}

fn load() -> impl Strategy<Value = Load> {
    let magnitude = prop_oneof![
        Just(Magnitude::Constant),
        (0..64usize).prop_map(Magnitude::Damping),
        (0..64usize).prop_map(Magnitude::Position),
        Just(Magnitude::Input),
        Just(Magnitude::Time),
    ];
    (
        0..6usize,
        0..3usize,
        0..7usize,
        magnitude,
        proptest::option::of(any::<bool>()),
    )
        .prop_map(|(link, axis, frame, magnitude, torque)| Load {
            link,
            axis,
            frame,
            magnitude,
            torque,
        })
}

/// A number in tenths or hundredths as a decimal literal: `-0.3`, `1.2`.
fn decimal(value: i32, scale: u32) -> String {
    let sign = if value < 0 { "-" } else { "" };
    let magnitude = value.unsigned_abs();
    let unit = 10u32.pow(scale);
    let width = scale as usize;
    format!("{sign}{}.{:0width$}", magnitude / unit, magnitude % unit)
}

impl RandomModel {
    /// The rotations link `i` really makes: none for a particle (it has
    /// no rotational inertia to carry them).
    fn rotations(link: &Link) -> &[Rotation] {
        match link.mass {
            Mass::Body { .. } => &link.rotations,
            Mass::Particle => &[],
        }
    }

    /// The number of generalized coordinates.
    pub fn coordinate_count(&self) -> usize {
        self.links
            .iter()
            .map(|link| Self::rotations(link).len().min(2) + usize::from(link.slide.is_some()))
            .sum()
    }

    /// The parameters, in declaration order: `g, k, c, m0, m1, ...`.
    pub fn parameter_names(&self) -> Vec<String> {
        let mut names: Vec<String> = ["g", "k", "c"].map(String::from).to_vec();
        names.extend((0..self.links.len()).map(|i| format!("m{i}")));
        names
    }

    /// The model as `.dal` text, the system named `name`.
    pub fn source(&self, name: &str) -> String {
        let nq = self.coordinate_count();
        let coordinate = |raw: usize| format!("q{}", raw % nq);
        let mut statements = Vec::new();
        // The frame and point of the ground, then of each link.
        let mut frames = vec!["N".to_owned()];
        let mut points = vec!["O".to_owned()];
        let mut next = 0;
        for (i, link) in self.links.iter().enumerate() {
            let parent = link.parent % (i + 1);
            let mut frame = frames[parent].clone();
            if let (Some(tilt), Mass::Body { .. }) = (&link.tilt, &link.mass) {
                let angle = decimal(i32::from(tilt.tenths), 1);
                let rotation = match tilt.direction {
                    Some(d) if d != [0; 3] => {
                        format!("rotate([{}, {}, {}], {angle})", d[0], d[1], d[2])
                    }
                    _ => format!("rotate_{}({angle})", AXES[tilt.axis]),
                };
                let name = format!("T{i}");
                statements.push(format!("frame {name} = {frame}.{rotation};"));
                frame = name;
            }
            let mut previous_axis = None;
            for (r, rotation) in Self::rotations(link).iter().take(2).enumerate() {
                // Successive rotations about one axis would add up to one.
                let axis = match previous_axis {
                    Some(p) if p == rotation.axis => (rotation.axis + 1) % 3,
                    _ => rotation.axis,
                };
                previous_axis = Some(axis);
                let mut angle = format!("{} * q{next}", rotation.scale);
                if let Some((other, factor, sine)) = rotation.coupling {
                    if next > 0 {
                        let other = format!("q{}", other % next);
                        let term = if sine { format!("sin({other})") } else { other };
                        write!(angle, " + {} * {term}", decimal(i32::from(factor), 1))
                            .expect("writing to a String");
                    }
                }
                next += 1;
                let name = format!("F{i}_{r}");
                statements.push(format!(
                    "frame {name} = {frame}.rotate_{}({angle});",
                    AXES[axis]
                ));
                frame = name;
            }
            let mut center = points[parent].clone();
            for (axis, &tenths) in link.offset.iter().enumerate() {
                if tenths != 0 {
                    write!(
                        center,
                        " + {} * {frame}.{}",
                        decimal(i32::from(tenths), 1),
                        AXES[axis]
                    )
                    .expect("writing to a String");
                }
            }
            if let Some(axis) = link.slide {
                write!(center, " + q{next} * {}.{}", frames[parent], AXES[axis])
                    .expect("writing to a String");
                next += 1;
            }
            let point = format!("C{i}");
            statements.push(format!("point {point} = {center};"));
            statements.push(match &link.mass {
                Mass::Body { moments, products } => {
                    let mut entries: Vec<String> = moments
                        .iter()
                        .map(|&m| format!("{} * m{i}", decimal(i32::from(m), 1)))
                        .collect();
                    if let Some(products) = products {
                        entries.extend(
                            products
                                .iter()
                                .map(|&p| format!("{} * m{i}", decimal(i32::from(p), 2))),
                        );
                    }
                    format!(
                        "body b{i} {{ mass: m{i}, center: {point}, frame: {frame}, inertia: [{}] }};",
                        entries.join(", ")
                    )
                }
                Mass::Particle => format!("particle p{i} {{ mass: m{i}, at: {point} }};"),
            });
            frames.push(frame);
            points.push(point);
        }
        if let Some(axis) = self.gravity {
            statements.push(format!("gravity -g * N.{};", AXES[axis]));
        }
        for load in &self.loads {
            let link = load.link % self.links.len() + 1;
            let magnitude = match load.magnitude {
                Magnitude::Constant => "0.7 * k".to_owned(),
                Magnitude::Damping(j) => format!("-c * dt({})", coordinate(j)),
                Magnitude::Position(j) => format!("k * sin({})", coordinate(j)),
                Magnitude::Input => "u0".to_owned(),
                Magnitude::Time => "k * cos(t)".to_owned(),
            };
            let direction = format!("{}.{}", frames[load.frame % frames.len()], AXES[load.axis]);
            // A link whose frame is also its parent's (`N`, say) cannot
            // take a reaction on it (the language refuses a torque that
            // reacts on its own frame): it takes the torque alone.
            let parent = &frames[self.links[link - 1].parent % link];
            statements.push(match load.torque {
                None => format!("force {magnitude} * {direction} at {};", points[link]),
                Some(true) if *parent != frames[link] => format!(
                    "torque {magnitude} * {direction} on {} reacting {parent};",
                    frames[link]
                ),
                Some(_) => format!("torque {magnitude} * {direction} on {};", frames[link]),
            });
        }
        for &(i, j) in &self.potentials {
            let (a, b) = (coordinate(i), coordinate(j));
            statements.push(format!(
                "potential k * ({a} - 0.5 * {b})^2 / 2 + k * cos({b});"
            ));
        }
        for &(i, j) in &self.dissipations {
            let (a, b) = (coordinate(i), coordinate(j));
            statements.push(format!(
                "dissipation c * (dt({a}) + 0.5 * dt({b}))^2 / 2 + c * cos({a})^2 * dt({b})^2;"
            ));
        }
        let coordinates: Vec<String> = (0..nq).map(|i| format!("q{i}")).collect();
        format!(
            "/// A random model.\npub {name} {{\n    parameters {};\n    coordinates {};\n    inputs u0;\n    {}\n}}\n",
            self.parameter_names().join(", "),
            coordinates.join(", "),
            statements.join("\n    ")
        )
    }
}
