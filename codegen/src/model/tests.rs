//! Every rule of the model layer: the message of each violation and the
//! token (line, column) it points at, and that all violations are reported.

use crate::language::parse_system;

/// The errors of `source` as `(message, line, column)`, in order.
fn errors(source: &str) -> Vec<(String, usize, usize)> {
    let system = parse_system(source.parse().expect("tokens")).expect("parses");
    match super::resolve(&system) {
        Ok(_) => Vec::new(),
        Err(error) => error
            .into_iter()
            .map(|e| {
                let start = e.span().start();
                (e.to_string(), start.line, start.column)
            })
            .collect(),
    }
}

/// Asserts that `source` gives exactly one error, containing `message`, at
/// `line`:`column` (1-based line, 0-based column, as proc-macro2 reports).
fn assert_error(source: &str, message: &str, line: usize, column: usize) {
    let found = errors(source);
    assert_eq!(found.len(), 1, "expected one error, found {found:?}");
    let (text, l, c) = &found[0];
    assert!(text.contains(message), "message {text:?} lacks {message:?}");
    assert_eq!((*l, *c), (line, column), "position of {text:?}");
}

/// A valid pendulum, with `EXTRA` replaced by the statement under test.
fn pendulum(extra: &str) -> String {
    format!(
        "P {{
    parameters m, l, g;
    coordinates theta;
    inputs u;
    frame B = N.rotate_z(theta);
    point G = O - l * B.y;
    {extra}
}}"
    )
}

#[test]
fn the_seed_examples_resolve() {
    let ok = pendulum(
        "body bar { mass: m, center: G, frame: B, inertia: [0, 0, m*l^2/12] };
         gravity -g * N.y;
         torque u * N.z on B;",
    );
    assert!(errors(&ok).is_empty());
}

#[test]
fn unknown_names_point_at_the_name() {
    assert_error(&pendulum("gravity -k * N.y;"), "unknown name `k`", 7, 13);
}

#[test]
fn use_before_definition_says_so() {
    assert_error(
        &pendulum("point Q = R + l * B.x;\n    point R = O;"),
        "`R` is used before its definition",
        7,
        14,
    );
}

#[test]
fn duplicate_names_point_at_the_second() {
    assert_error(
        &pendulum("point G = O;"),
        "`G` is already defined as a point",
        7,
        10,
    );
}

#[test]
fn built_in_names_cannot_be_defined() {
    assert_error(
        &pendulum("frame N = B.rotate_x(theta);"),
        "`N` is a built-in name",
        7,
        10,
    );
    assert_error(&pendulum("point t = O;"), "`t` is a built-in name", 7, 10);
}

#[test]
fn a_vector_where_a_scalar_is_expected() {
    assert_error(
        &pendulum("potential m * B.x;"),
        "expected a scalar, found a vector",
        7,
        14,
    );
}

#[test]
fn a_scalar_where_a_vector_is_expected() {
    assert_error(
        &pendulum("gravity g;"),
        "expected a vector, found a scalar",
        7,
        12,
    );
}

#[test]
fn adding_a_scalar_to_a_vector_points_at_the_operator() {
    assert_error(
        &pendulum("gravity g * N.y + g;"),
        "cannot add a vector and a scalar",
        7,
        20,
    );
}

#[test]
fn bodies_need_every_field() {
    assert_error(
        &pendulum("body bar { center: G, frame: B, inertia: [0, 0, 1] };"),
        "body `bar` is missing the field `mass`",
        7,
        9,
    );
    assert_error(
        &pendulum("body bar { mass: m, center: G, frame: B, inertia: [0, 0, 1], colour: m };"),
        "unknown field `colour`",
        7,
        65,
    );
}

#[test]
fn masses_and_moments_are_checked() {
    assert_error(
        &pendulum("body bar { mass: 0, center: G, frame: B, inertia: [0, 0, 1] };"),
        "a mass must be positive",
        7,
        21,
    );
    assert_error(
        &pendulum("body bar { mass: m, center: G, frame: B, inertia: [1, -2, 1] };"),
        "cannot be negative",
        7,
        58,
    );
    assert_error(
        &pendulum("body bar { mass: m * theta, center: G, frame: B, inertia: [1, 1, 1] };"),
        "coordinate `theta` cannot be used in mass and inertia",
        7,
        25,
    );
}

#[test]
fn exponents_must_be_constant_integers() {
    assert_error(
        &pendulum("potential theta^0.5;"),
        "must be a constant integer",
        7,
        20,
    );
    assert_error(
        &pendulum("potential theta^g;"),
        "cannot be used in an exponent",
        7,
        20,
    );
    assert!(errors(&pendulum("potential theta^(1+1) + l^-2;")).is_empty());
}

#[test]
fn inputs_cannot_move_geometry() {
    assert_error(
        &pendulum("point Q = G + u * B.x;"),
        "input `u` cannot be used in geometry",
        7,
        18,
    );
}

#[test]
fn speeds_cannot_be_used_in_potentials() {
    assert_error(
        &pendulum("potential dt(theta)^2;"),
        "speeds `dt(..)` cannot be used in a potential",
        7,
        14,
    );
}

#[test]
fn nonholonomic_constraints_must_be_linear_in_speeds() {
    assert_error(
        &pendulum("constraint dt(theta)^2 == 1;"),
        "must be linear in the speeds",
        7,
        4,
    );
    assert_error(
        &pendulum("constraint theta == u;"),
        "input `u` cannot be used in a constraint",
        7,
        24,
    );
    assert!(errors(&pendulum("constraint l * cos(theta) * dt(theta) == t;")).is_empty());
}

#[test]
fn unknown_functions_and_members() {
    assert_error(
        &pendulum("potential sinh(theta);"),
        "unknown function `sinh`",
        7,
        14,
    );
    assert_error(&pendulum("gravity g * B.w;"), "found `.w`", 7, 18);
    assert_error(
        &pendulum("frame C = B.turn_z(theta);"),
        "unknown method `turn_z`",
        7,
        16,
    );
}

#[test]
fn points_and_frames_are_not_values() {
    assert_error(
        &pendulum("point Q = G + O;"),
        "cannot add a point and a point",
        7,
        16,
    );
    assert_error(
        &pendulum("torque u * N.z on G;"),
        "expected a frame, found a point",
        7,
        22,
    );
}

#[test]
fn a_system_needs_coordinates() {
    assert_error(
        "S { parameters m; }",
        "at least one generalized coordinate",
        1,
        0,
    );
}

#[test]
fn every_error_is_reported() {
    let found = errors(&pendulum(
        "gravity -k * N.y;\n    potential dt(theta);\n    body b { mass: m };",
    ));
    assert_eq!(found.len(), 3, "{found:?}");
}

#[test]
fn joints_define_a_frame_and_a_point() {
    let source = "Arm {
        parameters L;
        coordinates q1, q2;
        joint revolute J1 { parent: N, child: A, axis: z, coordinate: q1, at: O };
        joint prismatic J2 { parent: A, child: S, axis: x, coordinate: q2, at: J1 + L * A.y };
        particle p { mass: 1, at: J2 + L * S.z };
    }";
    assert!(errors(source).is_empty(), "{:?}", errors(source));
    let bad = "Arm {
        coordinates q1;
        joint hinge J1 { parent: N, child: A, axis: z, coordinate: q1, at: O };
        joint revolute J2 { parent: N, child: C, axis: w, coordinate: q1, at: O };
    }";
    let found = errors(bad);
    assert_eq!(found.len(), 2, "{found:?}");
    assert!(found[0].0.contains("unknown joint kind `hinge`"));
    assert!(found[1].0.contains("expected a joint axis"));
}

#[test]
fn a_broken_definition_is_reported_once() {
    let found = errors(&pendulum(
        "frame C = B.rotate_x(k);\n    point Q = O + l * C.x;\n    torque u * C.z on C;",
    ));
    assert_eq!(found.len(), 1, "{found:?}");
    assert!(found[0].0.contains("unknown name `k`"));
}

/// The first and last position of the single error of `source`, as
/// `(line, column)` pairs: the whole range a diagnostic underlines.
fn error_range(source: &str) -> ((usize, usize), (usize, usize)) {
    let system = parse_system(source.parse().expect("tokens")).expect("parses");
    let error = super::resolve(&system).err().expect("an error");
    assert_eq!(error.clone().into_iter().count(), 1, "{error:?}");
    let (start, end) = (error.span().start(), error.span().end());
    ((start.line, start.column), (end.line, end.column))
}

#[test]
fn errors_about_an_expression_underline_all_of_it() {
    // `potential m * B.x;` on line 7 from column 14: the vector is `B.x`,
    // so underlining only `m` would point at the wrong token.
    assert_eq!(
        error_range(&pendulum("potential m * B.x;")),
        ((7, 14), (7, 21))
    );
    assert_eq!(
        error_range(&pendulum("potential m * sin(theta, l);")),
        ((7, 18), (7, 31))
    );
    assert_eq!(
        error_range(&pendulum("constraint dt(theta)^2 == l;")),
        ((7, 4), (7, 31))
    );
    assert_eq!(
        error_range(&pendulum("gravity -g * theta * N.y + N.x * 2;")),
        ((7, 17), (7, 22))
    );
}

#[test]
fn an_exponent_out_of_range_says_so() {
    assert_error(
        &pendulum("potential theta^4294967296;"),
        "the exponent of `^` must be an integer from -2147483648 to 2147483647; found 4294967296",
        7,
        20,
    );
    assert!(errors(&pendulum("potential theta^2147483647 + theta^-2147483648;")).is_empty());
}

/// The errors of the whole derivation (as `crate::check` reports them),
/// as `(message, line, column)`.
fn derivation_errors(source: &str) -> Vec<(String, usize, usize)> {
    match crate::check(source) {
        Ok(()) => Vec::new(),
        Err(error) => error
            .into_iter()
            .map(|e| {
                (
                    e.to_string(),
                    e.span().start().line,
                    e.span().start().column,
                )
            })
            .collect(),
    }
}

#[test]
fn a_mass_may_move_with_time_and_then_its_functions_take_t() {
    // A bead carried round by a turning platform: `t` cancels from
    // `T = ½ m l²`, so the time-free `mass_matrix(q)` and energies hold.
    let platform = "frame R = N.rotate_z(t);\n    particle p { mass: m, at: O + l * R.x };\n    particle bob { mass: m, at: G };";
    assert!(errors(&pendulum(platform)).is_empty());
    assert!(derivation_errors(&pendulum(platform)).is_empty());
    let generated = |source: &str| crate::generate(source).expect("derives");
    let code = generated(&pendulum(platform));
    assert!(code.contains("pub fn mass_matrix(") && !code.contains("TIME_DEPENDENT"));
    // With gravity in the plane, `V = m g l sin t` keeps `t`: the
    // energies and the mass matrix are the `_at` functions.
    let turning = pendulum(&format!("{platform}\n    gravity -g * N.y;"));
    assert!(derivation_errors(&turning).is_empty());
    let code = generated(&turning);
    for function in ["mass_matrix_at", "kinetic_energy_at", "potential_energy_at"] {
        assert!(code.contains(&format!("pub fn {function}(")), "{function}");
    }
    assert!(code.contains("pub const TIME_DEPENDENT: bool = true;"));
    assert!(!code.contains("pub fn mass_matrix("));
    // A shaken body.
    let shaken = "point C = G + sin(t) * N.x;\n    body b { mass: m, center: C, frame: B, inertia: [1, 1, 1] };";
    assert!(derivation_errors(&pendulum(shaken)).is_empty());
    assert!(generated(&pendulum(shaken)).contains("pub fn kinetic_energy_at("));
}

#[test]
fn a_constraint_jacobian_may_depend_on_time() {
    for row in [
        "constraint sin(theta * t) == 0;",
        "constraint t * dt(theta) == 0;",
    ] {
        let source = pendulum(row);
        assert!(errors(&source).is_empty(), "{row}");
        let code = crate::generate(&source).expect("derives");
        assert!(code.contains("pub fn constraint_jacobian_at("), "{row}");
    }
    assert!(errors(&pendulum("constraint l * sin(theta) == sin(t);")).is_empty());
}

#[test]
fn a_coordinate_that_moves_no_mass_is_reported_at_its_declaration() {
    let found = derivation_errors(
        "P {
    parameters m, l, k;
    coordinates theta, idle;
    frame B = N.rotate_z(theta);
    particle bob { mass: m, at: O - l * B.y };
    potential k * idle^2;
}",
    );
    assert_eq!(found.len(), 1, "{found:?}");
    assert!(
        found[0].0.contains("the coordinate `idle` moves no mass"),
        "{found:?}"
    );
    assert_eq!((found[0].1, found[0].2), (3, 23));
}

#[test]
fn closures_report_bad_fields_at_the_token() {
    assert_error(
        &pendulum("closure c { at: G, to: O, axis: B.z, welded: N };"),
        "mixes the fields of a revolute closure",
        7,
        12,
    );
    assert_error(
        &pendulum("closure c { at: G, to: O, axis: z, along: N.z };"),
        "expected a unit vector of a frame",
        7,
        36,
    );
    assert_error(
        &pendulum("closure c { at: G, to: O, axis: B.z };"),
        "revolute closure `c` is missing the field `along`",
        7,
        12,
    );
    assert_error(
        &pendulum("closure c { at: G, to: B };"),
        "expected a point, found a frame",
        7,
        27,
    );
}

#[test]
fn closures_that_cannot_hold_or_constrain_nothing_say_so() {
    assert_error(
        &pendulum("closure c { at: G, to: G };"),
        "closure `c` constrains nothing",
        7,
        12,
    );
    assert_error(
        &pendulum("point H = O + l * N.x; closure c { at: O, to: H };"),
        "closure `c` can never hold: the x-component of `at − to` involves no coordinate",
        7,
        35,
    );
}

#[test]
fn a_torque_may_react_on_another_frame_fixed_to_its_own() {
    // Legal physics: `F` and `B` are distinct frames (welded by a constant
    // angle), so the torque and its reaction do not cancel by statement.
    let source = pendulum("frame F = B.rotate_x(l);\n    torque u * N.z on B reacting F;");
    assert!(errors(&source).is_empty(), "{:?}", errors(&source));
    let itself = errors(&pendulum("torque u * N.z on B reacting B;"));
    assert_eq!(itself.len(), 1, "{itself:?}");
    assert!(itself[0].0.contains("cannot react on the frame it acts on"));
    // `torque u * N.z on B reacting B;` on line 7: the second `B`
    // starts at column 33 (proc-macro columns count from 0).
    assert_eq!((itself[0].1, itself[0].2), (7, 33));
}

#[test]
fn a_coordinate_moved_by_a_joint_may_also_turn_a_frame_statement() {
    // Only two joints sharing a coordinate are refused: a `frame`
    // statement is how a coupled motion is spelled out.
    let source = pendulum(
        "joint revolute J { parent: B, child: C, axis: z, coordinate: theta, at: G };\n    \
         frame D = C.rotate_z(theta);\n    particle p { mass: m, at: J + l * D.x };",
    );
    assert!(errors(&source).is_empty(), "{:?}", errors(&source));
}

#[test]
fn a_moment_that_is_zero_but_for_rounding_is_not_negative() {
    // sin(1.6)² + cos(1.6)² − 1 is zero; in floating point it is −1.1e-16,
    // which a principal moment of 1 beside it puts within rounding.
    let rounded = "body bar { mass: m, center: G, frame: B, \
                   inertia: [1, 1, sin(1.6)^2 + cos(1.6)^2 - 1] };";
    assert!(
        errors(&pendulum(rounded)).is_empty(),
        "{:?}",
        errors(&pendulum(rounded))
    );
    // Beyond rounding, an evaluated moment is negative; an exact one at any size.
    assert_error(
        &pendulum("body bar { mass: m, center: G, frame: B, inertia: [1, 1, 1 - sqrt(2)] };"),
        "cannot be negative",
        7,
        61,
    );
    assert_error(
        &pendulum("body bar { mass: m, center: G, frame: B, inertia: [1, 1, -1/10^30] };"),
        "cannot be negative",
        7,
        61,
    );
}
