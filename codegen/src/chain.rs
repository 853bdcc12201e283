//! The benchmark chains as `.dal` text: the two families of
//! `tests/reference/README_chains.md` (and of the Pinocchio peer harness),
//! for any number of links, in three spellings ([`Spelling`]).
//!
//! Link `i = 1..n` is a uniform slender rod of mass `mᵢ = 1 + i/10` and
//! length `Lᵢ = 1/2 + i/20`, hinged at its near end; joint `i + 1` sits at
//! the far end of rod `i`.

use std::fmt::Write;

/// One of the two chain families of the reference data.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Family {
    /// Revolute joints about `z`, rods along the link's `−y` (hanging at
    /// `q = 0`), gravity `−9.81` along `N.y`.
    Planar,
    /// Joint axes `z, y, z, y, …`, rods along the link's `+x` (horizontal at
    /// `q = 0`), gravity `−9.81` along `N.z`.
    Spatial,
}

impl Family {
    /// The family's name as in the reference data (`planar`, `spatial`).
    pub fn name(self) -> &'static str {
        match self {
            Family::Planar => "planar",
            Family::Spatial => "spatial",
        }
    }

    /// The family named `name` (`planar` or `spatial`).
    pub fn from_name(name: &str) -> Option<Family> {
        [Family::Planar, Family::Spatial]
            .into_iter()
            .find(|f| f.name() == name)
    }

    /// The name of the system of `n` links: `PlanarChain6`, `SpatialChain12`.
    pub fn system_name(self, n: usize) -> String {
        match self {
            Family::Planar => format!("PlanarChain{n}"),
            Family::Spatial => format!("SpatialChain{n}"),
        }
    }

    /// The axis of joint `i` (1-based).
    fn joint_axis(self, i: usize) -> char {
        match self {
            Family::Spatial if i % 2 == 0 => 'y',
            _ => 'z',
        }
    }

    /// The rod direction in the link frame, as a signed unit-vector suffix.
    fn rod(self) -> (char, char) {
        match self {
            Family::Planar => ('-', 'y'),
            Family::Spatial => ('+', 'x'),
        }
    }

    /// The central inertia `[Ixx, Iyy, Izz]` of a rod with transverse
    /// moment `transverse` (zero about the rod's own axis).
    fn inertia(self, transverse: &str) -> String {
        match self {
            Family::Planar => format!("[{transverse}, 0, {transverse}]"),
            Family::Spatial => format!("[0, {transverse}, {transverse}]"),
        }
    }

    /// The gravity statement's vector.
    fn gravity(self) -> &'static str {
        match self {
            Family::Planar => "-9.81 * N.y",
            Family::Spatial => "-9.81 * N.z",
        }
    }
}

/// How a chain is written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Spelling {
    /// `joint` statements, masses and lengths as numeric literals (which
    /// the engine folds exactly).
    Joints,
    /// `joint` statements, masses `m1..mn`, lengths `L1..Ln` and gravity `g`
    /// as parameters.
    SymbolicJoints,
    /// The seed document's spelling: `frame Bi = B{i-1}.rotate_z(qi)`,
    /// points relative to the previous joint, parameters as in
    /// [`Spelling::SymbolicJoints`], and joint torques `tau1..taun` as
    /// inputs (`torque taui * B{i-1}.z on Bi reacting B{i-1}`).
    FramesAndPoints,
}

impl Spelling {
    /// Every spelling.
    pub const ALL: [Spelling; 3] = [
        Spelling::Joints,
        Spelling::SymbolicJoints,
        Spelling::FramesAndPoints,
    ];

    /// The spelling's name on the command line (`joints`, `symbolic`, `seed`).
    pub fn name(self) -> &'static str {
        match self {
            Spelling::Joints => "joints",
            Spelling::SymbolicJoints => "symbolic",
            Spelling::FramesAndPoints => "seed",
        }
    }

    /// The spelling named `name`.
    pub fn from_name(name: &str) -> Option<Spelling> {
        Spelling::ALL.into_iter().find(|s| s.name() == name)
    }

    /// The prefix of the system's name: empty, `Symbolic` or `Seed`.
    fn prefix(self) -> &'static str {
        match self {
            Spelling::Joints => "",
            Spelling::SymbolicJoints => "Symbolic",
            Spelling::FramesAndPoints => "Seed",
        }
    }
}

/// The parameters of a chain of `n` links in a symbolic spelling, with the
/// reference values: `m1..mn`, `L1..Ln`, `g`.
pub fn chain_parameters(n: usize) -> Vec<(String, f64)> {
    let n = n.max(1);
    // The nearest doubles of the decimals, as the literal spelling has them.
    let value = |text: String| text.parse::<f64>().unwrap_or(f64::NAN);
    let masses = (1..=n).map(|i| (format!("m{i}"), value(decimal(10 + i as u64, 1))));
    let lengths = (1..=n).map(|i| (format!("L{i}"), value(decimal(50 + 5 * i as u64, 2))));
    masses
        .chain(lengths)
        .chain(std::iter::once(("g".to_owned(), 9.81)))
        .collect()
}

/// The `.dal` text of the `family` chain of `n` links (`n ≥ 1`) written with
/// literal `joint`s ([`Spelling::Joints`]).
pub fn chain(family: Family, n: usize) -> String {
    chain_spelled(family, n, Spelling::Joints)
}

/// The `.dal` text of the `family` chain of `n` links (`n ≥ 1`) in
/// `spelling`, exactly the geometry of the reference data: coordinates
/// `q1..qn` are relative joint angles, link frames `B1..Bn`.
pub fn chain_spelled(family: Family, n: usize, spelling: Spelling) -> String {
    match spelling {
        Spelling::Joints => joints(family, n),
        _ => symbolic(family, n, spelling),
    }
}

/// [`Spelling::SymbolicJoints`] and [`Spelling::FramesAndPoints`].
fn symbolic(family: Family, n: usize, spelling: Spelling) -> String {
    let n = n.max(1);
    let (sign, axis) = family.rod();
    let list = |name: &str| {
        (1..=n)
            .map(|i| format!("{name}{i}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let mut text = String::new();
    let _ = writeln!(
        text,
        "/// The {} chain of {n} links of `tests/reference/README_chains.md`, spelled\n\
         /// `{}` (masses, lengths and gravity are parameters), generated by\n\
         /// `dalembert_codegen::testing::chain_spelled`.\n\
         pub {}{} {{\n    parameters {}, {}, g;\n    coordinates {};",
        family.name(),
        spelling.name(),
        spelling.prefix(),
        family.system_name(n),
        list("m"),
        list("L"),
        list("q"),
    );
    if spelling == Spelling::FramesAndPoints {
        let _ = writeln!(text, "    inputs {};", list("tau"));
    }
    for i in 1..=n {
        let joint_axis = family.joint_axis(i);
        let parent = if i == 1 {
            "N".to_owned()
        } else {
            format!("B{}", i - 1)
        };
        let inertia = family.inertia(&format!("m{i} * L{i}^2/12"));
        match spelling {
            Spelling::SymbolicJoints => {
                let at = match i {
                    1 => "O".to_owned(),
                    _ => format!("J{} {sign} L{} * B{}.{axis}", i - 1, i - 1, i - 1),
                };
                let _ = writeln!(
                    text,
                    "    joint revolute J{i} {{ parent: {parent}, child: B{i}, axis: {joint_axis}, coordinate: q{i}, at: {at} }};\n    \
                     body link{i} {{ mass: m{i}, center: J{i} {sign} L{i}/2 * B{i}.{axis}, frame: B{i}, inertia: {inertia} }};",
                );
            }
            _ => {
                let base = if i == 1 {
                    "O".to_owned()
                } else {
                    format!("P{}", i - 1)
                };
                let _ = writeln!(
                    text,
                    "    frame B{i} = {parent}.rotate_{joint_axis}(q{i});\n    \
                     point P{i} = {base} {sign} L{i} * B{i}.{axis};\n    \
                     body link{i} {{ mass: m{i}, center: {base} {sign} L{i}/2 * B{i}.{axis}, frame: B{i}, inertia: {inertia} }};\n    \
                     torque tau{i} * {parent}.{joint_axis} on B{i} reacting {parent};",
                );
            }
        }
    }
    let gravity = family.gravity().replace("9.81", "g");
    let _ = writeln!(text, "    gravity {gravity};\n}}");
    text
}

/// [`Spelling::Joints`].
fn joints(family: Family, n: usize) -> String {
    let n = n.max(1);
    let mut text = String::new();
    let coordinates: Vec<String> = (1..=n).map(|i| format!("q{i}")).collect();
    // `write!` into a `String` cannot fail.
    let _ = writeln!(
        text,
        "/// The {} chain of {n} links of `tests/reference/README_chains.md`\n\
         /// (m_i = 1 + i/10, L_i = 1/2 + i/20), generated by `dalembert_codegen::testing::chain`.\n\
         pub {} {{\n    coordinates {};",
        family.name(),
        family.system_name(n),
        coordinates.join(", ")
    );
    let (sign, axis) = family.rod();
    for i in 1..=n {
        let (mass, length) = (decimal(10 + i as u64, 1), decimal(50 + 5 * i as u64, 2));
        let (parent, at) = match i {
            1 => ("N".to_owned(), "O".to_owned()),
            _ => {
                let previous = decimal(50 + 5 * (i as u64 - 1), 2);
                (
                    format!("B{}", i - 1),
                    format!("J{} {sign} {previous} * B{}.{axis}", i - 1, i - 1),
                )
            }
        };
        let _ = writeln!(
            text,
            "    joint revolute J{i} {{ parent: {parent}, child: B{i}, axis: {}, coordinate: q{i}, at: {at} }};\n    \
             body link{i} {{ mass: {mass}, center: J{i} {sign} {length}/2 * B{i}.{axis}, frame: B{i}, inertia: {} }};",
            family.joint_axis(i),
            family.inertia(&format!("{mass} * {length}^2/12")),
        );
    }
    let _ = writeln!(text, "    gravity {};\n}}", family.gravity());
    text
}

/// `value / 10^places` as a decimal literal (`decimal(55, 2)` is `0.55`).
fn decimal(value: u64, places: u32) -> String {
    let scale = 10u64.pow(places);
    let fraction = format!("{:0width$}", value % scale, width = places as usize);
    format!("{}.{fraction}", value / scale)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decimals_are_exact() {
        assert_eq!(decimal(11, 1), "1.1");
        assert_eq!(decimal(55, 2), "0.55");
        assert_eq!(decimal(200, 2), "2.00");
    }

    #[test]
    fn planar_chain_of_two_links() {
        let text = chain(Family::Planar, 2);
        assert!(text.contains("pub PlanarChain2 {"), "{text}");
        assert!(text.contains(
            "joint revolute J2 { parent: B1, child: B2, axis: z, coordinate: q2, at: J1 - 0.55 * B1.y };"
        ));
        assert!(text.contains(
            "body link2 { mass: 1.2, center: J2 - 0.60/2 * B2.y, frame: B2, inertia: [1.2 * 0.60^2/12, 0, 1.2 * 0.60^2/12] };"
        ));
        assert!(text.contains("gravity -9.81 * N.y;"));
    }

    #[test]
    fn spatial_axes_alternate_z_y() {
        let text = chain(Family::Spatial, 3);
        for (i, axis) in [(1, 'z'), (2, 'y'), (3, 'z')] {
            assert!(
                text.contains(&format!("child: B{i}, axis: {axis},")),
                "{text}"
            );
        }
        assert!(text.contains("inertia: [0, "));
        assert!(text.contains("gravity -9.81 * N.z;"));
    }

    #[test]
    fn every_chain_checks() {
        for family in [Family::Planar, Family::Spatial] {
            assert_eq!(Family::from_name(family.name()), Some(family));
            for spelling in Spelling::ALL {
                assert_eq!(Spelling::from_name(spelling.name()), Some(spelling));
                for n in [1, 2, 7] {
                    let text = chain_spelled(family, n, spelling);
                    crate::check(&text).unwrap_or_else(|e| panic!("{text}\n{e}"));
                }
            }
        }
    }

    #[test]
    fn the_seed_spelling_writes_frames_points_and_torques() {
        let text = chain_spelled(Family::Spatial, 2, Spelling::FramesAndPoints);
        for line in [
            "pub SeedSpatialChain2 {",
            "parameters m1, m2, L1, L2, g;",
            "inputs tau1, tau2;",
            "frame B2 = B1.rotate_y(q2);",
            "point P2 = P1 + L2 * B2.x;",
            "body link2 { mass: m2, center: P1 + L2/2 * B2.x, frame: B2, inertia: [0, m2 * L2^2/12, m2 * L2^2/12] };",
            "torque tau1 * N.z on B1 reacting N;",
            "torque tau2 * B1.y on B2 reacting B1;",
            "gravity -g * N.z;",
        ] {
            assert!(text.contains(line), "{line} missing from\n{text}");
        }
        assert_eq!(chain_parameters(2).len(), 5);
    }
}
