//! The outputs a model asks for (`outputs ...;`), evaluated by the
//! interpreter on the expressions the generator emits:
//!
//! * `inverse_dynamics` against Pinocchio's `rnea` (through the reference
//!   data's `aba`, `nonLinearEffects` and `computeGeneralizedGravity`) on the
//!   chains and the URDF robots, and against `M v̇ − f` on both derivations
//!   (d'Alembert's and Lagrange's) of every spelling of the chains and the
//!   seed examples;
//! * `regressor`: `Y π = M v̇ − f` at zero inputs, with `π` from
//!   `base_parameters`, and `Y`'s columns independent over random motions;
//! * the kinematic outputs against central differences of each other
//!   (velocity of position, acceleration of velocity, angular velocity of
//!   the rotation) and `J v` against the velocities.

use dalembert_codegen::chain::{Family, Spelling, chain_spelled};
use dalembert_codegen::testing::{Interpreter, Random, Route, Sample, Values};
use dalembert_codegen::{Urdf, check};
use dalembert_fixtures::reference::{reference, reference_path};
use serde_json::Value;

/// A JSON array of numbers.
fn vector(v: &Value) -> Vec<f64> {
    let numbers = v.as_array().unwrap().iter();
    numbers.map(|x| x.as_f64().unwrap()).collect()
}

/// The largest |a − b| over the largest |b| (over 1 if all |b| < 1).
fn relative_error(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    let scale = b.iter().fold(1.0_f64, |m, x| m.max(x.abs()));
    a.iter()
        .zip(b)
        .fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()))
        / scale
}

/// `source` with `outputs` statements added before its closing brace.
fn asking(source: &str, outputs: &str) -> String {
    let end = source.rfind('}').unwrap();
    format!("{}    {outputs}\n}}\n", &source[..end])
}

/// The generated models' source, by file name.
fn model(name: &str) -> String {
    let models = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../generated/models");
    let path = models.join(format!("{name}.dal"));
    std::fs::read_to_string(path).unwrap()
}

fn interpreter(source: &str, route: Route) -> Interpreter {
    Interpreter::new(source, route).unwrap_or_else(|e| panic!("{e}\n{source}"))
}

fn values<'a>(parameters: &'a [f64], q: &'a [f64], qd: &'a [f64], u: &'a [f64]) -> Values<'a> {
    Values {
        parameters,
        t: 0.0,
        q,
        qd,
        u,
    }
}

/// The worst relative errors of `inverse_dynamics` against Pinocchio's
/// `rnea` over `entry`'s states: `rnea(q, v, aba(q, v, τ)) = τ`,
/// `rnea(q, v, 0) = nle`, `rnea(q, 0, 0) = g(q)`.
fn rnea_errors(interpreter: &Interpreter, entry: &Value) -> [f64; 3] {
    let n = interpreter.nq();
    let (zeros, no_inputs) = (vec![0.0; n], vec![0.0; interpreter.nu()]);
    let mut worst = [0.0_f64; 3];
    for state in dalembert_fixtures::reference::states(entry) {
        let (q, qd, tau, qdd) = (
            vector(&state["q"]),
            vector(&state["qd"]),
            vector(&state["tau"]),
            vector(&state["qdd"]),
        );
        let moving = values(&[], &q, &qd, &no_inputs);
        let resting = values(&[], &q, &zeros, &no_inputs);
        let id = |at: &Values<'_>, rates: &[f64]| {
            interpreter.output("inverse_dynamics", at, rates).unwrap()
        };
        let errors = [
            relative_error(&id(&moving, &qdd), &tau),
            relative_error(&id(&moving, &zeros), &vector(&state["nle"])),
            relative_error(&id(&resting, &zeros), &vector(&state["gravity_torque"])),
        ];
        for (w, e) in worst.iter_mut().zip(errors) {
            *w = w.max(e);
        }
    }
    worst
}

/// Relative agreement with `rnea` (the worst measured: 1.1e-14 for `τ` on
/// the panda, whose `q̈` comes from ABA; 1e-15 for `nle` and `g`).
const RNEA_TOLERANCES: [f64; 3] = [1e-12, 1e-13, 1e-13];

fn assert_rnea(what: &str, worst: [f64; 3]) {
    eprintln!(
        "{what}: inverse dynamics vs rnea: τ {:.1e}, nle {:.1e}, g {:.1e}",
        worst[0], worst[1], worst[2]
    );
    for ((error, tolerance), quantity) in worst.iter().zip(RNEA_TOLERANCES).zip(["τ", "nle", "g"])
    {
        assert!(error <= &tolerance, "{what}: {quantity} off by {error:e}");
    }
}

#[test]
fn inverse_dynamics_is_pinocchios_rnea_on_the_chains() {
    let chains = reference("chains.json");
    for entry in chains["models"].as_array().unwrap() {
        let family = Family::from_name(entry["family"].as_str().unwrap()).unwrap();
        let n = entry["n"].as_u64().unwrap() as usize;
        let source = asking(
            &chain_spelled(family, n, Spelling::Joints),
            "outputs inverse_dynamics;",
        );
        let worst = rnea_errors(&interpreter(&source, Route::Dalembert), entry);
        assert_rnea(&format!("{} chain of {n}", family.name()), worst);
    }
}

#[test]
fn inverse_dynamics_is_pinocchios_rnea_on_the_robots() {
    let robots = reference("urdf/pinocchio.json");
    // The free-flyer entries hold the joints' torques only (the base has
    // none) and no gravity torque: their `M` and `f` are checked against
    // Pinocchio's in generated/tests/suite/urdf.rs.
    let fixed = |entry: &&Value| entry["nq"] == entry["nv"];
    for entry in robots["models"].as_array().unwrap().iter().filter(fixed) {
        let path = reference_path(&format!("urdf/{}", entry["urdf"].as_str().unwrap()));
        let source = asking(
            &Urdf::read(path).unwrap().model().unwrap(),
            "outputs inverse_dynamics;",
        );
        let worst = rnea_errors(&interpreter(&source, Route::Dalembert), entry);
        assert_rnea(entry["robot"].as_str().unwrap(), worst);
    }
}

/// Every spelling of the chains up to four links, and the seed examples.
fn test_systems() -> Vec<String> {
    let mut systems = Vec::new();
    for family in [Family::Planar, Family::Spatial] {
        for n in 1..=4 {
            for spelling in [
                Spelling::Joints,
                Spelling::SymbolicJoints,
                Spelling::FramesAndPoints,
            ] {
                systems.push(chain_spelled(family, n, spelling));
            }
        }
    }
    for name in [
        "double_pendulum",
        "rotating_bar",
        "constrained_pendulum",
        "two_link_arm",
    ] {
        systems.push(model(name));
    }
    systems
}

/// `M v̇ − f` of `interpreter` at `at`.
fn m_vdot_minus_f(interpreter: &Interpreter, at: &Values<'_>, rates: &[f64]) -> Vec<f64> {
    let m = interpreter.mass_matrix(at);
    let f = interpreter.forcing(at);
    m.iter()
        .zip(&f)
        .map(|(row, fk)| row.iter().zip(rates).map(|(a, b)| a * b).sum::<f64>() - fk)
        .collect()
}

/// A random `v̇` for `interpreter`'s system.
fn random_rates(interpreter: &Interpreter, seed: u64) -> Vec<f64> {
    let mut random = Random::new(seed);
    (0..interpreter.nq())
        .map(|_| random.uniform(-3.0, 3.0))
        .collect()
}

#[test]
fn inverse_dynamics_is_m_vdot_minus_f_on_both_routes() {
    for source in test_systems() {
        let source = source.replace("    outputs inverse_dynamics, regressor;\n", "");
        let source = asking(&source, "outputs inverse_dynamics;");
        for route in [Route::Dalembert, Route::Lagrange] {
            let interpreter = interpreter(&source, route);
            for seed in 0..5 {
                let sample = Sample::random(&interpreter, seed);
                let rates = random_rates(&interpreter, seed + 100);
                let at = sample.values();
                let id = interpreter.output("inverse_dynamics", &at, &rates).unwrap();
                let error = relative_error(&id, &m_vdot_minus_f(&interpreter, &at, &rates));
                assert!(
                    error < 1e-12,
                    "{} ({route:?}): inverse dynamics off by {error:e}",
                    interpreter.name()
                );
            }
        }
    }
}

/// `Y π` at `at` (inputs set to zero).
fn regressor_times_base_parameters(
    interpreter: &Interpreter,
    at: &Values<'_>,
    rates: &[f64],
) -> Vec<f64> {
    let y = interpreter.output("regressor", at, rates).unwrap();
    let pi = interpreter.output("base_parameters", at, rates).unwrap();
    y.chunks(pi.len().max(1))
        .map(|row| row.iter().zip(&pi).map(|(a, b)| a * b).sum())
        .collect()
}

/// The numerical rank of `rows` (Gram–Schmidt on the columns, relative
/// tolerance 1e-9).
fn column_rank(rows: &[Vec<f64>]) -> usize {
    let width = rows.first().map_or(0, Vec::len);
    let mut basis: Vec<Vec<f64>> = Vec::new();
    for j in 0..width {
        let mut column: Vec<f64> = rows.iter().map(|row| row[j]).collect();
        let norm = column.iter().map(|x| x * x).sum::<f64>().sqrt();
        for b in &basis {
            let dot: f64 = column.iter().zip(b).map(|(x, y)| x * y).sum();
            column.iter_mut().zip(b).for_each(|(x, y)| *x -= dot * y);
        }
        let rest = column.iter().map(|x| x * x).sum::<f64>().sqrt();
        if rest > 1e-9 * norm.max(1e-300) {
            basis.push(column.iter().map(|x| x / rest).collect());
        }
    }
    basis.len()
}

#[test]
fn regressor_times_base_parameters_is_the_inverse_dynamics() {
    let mut systems = test_systems();
    for family in [Family::Planar, Family::Spatial] {
        for n in [5, 6] {
            systems.push(chain_spelled(family, n, Spelling::SymbolicJoints));
        }
    }
    for source in systems {
        let source = source.replace("    outputs inverse_dynamics, regressor;\n", "");
        let source = asking(&source, "outputs inverse_dynamics, regressor;");
        let interpreter = interpreter(&source, Route::Dalembert);
        let mut stacked = Vec::new();
        let mut nb = 0;
        for seed in 0..16 {
            let mut sample = Sample::random(&interpreter, seed);
            sample.u.iter_mut().for_each(|u| *u = 0.0);
            let rates = random_rates(&interpreter, seed + 100);
            let at = sample.values();
            let id = interpreter.output("inverse_dynamics", &at, &rates).unwrap();
            let y_pi = regressor_times_base_parameters(&interpreter, &at, &rates);
            let error = relative_error(&y_pi, &id);
            assert!(
                error < 1e-12,
                "{}: Y π off the inverse dynamics by {error:e}",
                interpreter.name()
            );
            let y = interpreter.output("regressor", &at, &rates).unwrap();
            nb = y.len() / interpreter.nq();
            stacked.extend(y.chunks(nb.max(1)).map(<[f64]>::to_vec));
        }
        assert_eq!(
            column_rank(&stacked),
            nb,
            "{}: the base parameters are not independent",
            interpreter.name()
        );
    }
}

#[test]
fn the_arm_has_the_five_textbook_base_parameters() {
    // Two links in a vertical plane: I₁ + m₁c₁² + m₂l₁², I₂ + m₂c₂², m₂l₁c₂,
    // and the gravity moments g(m₁c₁ + m₂l₁), g m₂c₂ (Khalil & Dombre's
    // regrouping): five columns, whatever the nine parameters' values.
    let interpreter = interpreter(&model("two_link_arm"), Route::Dalembert);
    let sample = Sample::random(&interpreter, 7);
    let at = sample.values();
    let pi = interpreter
        .output("base_parameters", &at, &[0.0; 2])
        .unwrap();
    let [m1, m2, l1, _l2, c1, c2, i1, i2, g] = sample.parameters[..] else {
        panic!("nine parameters")
    };
    let mut expected = [
        g * (m1 * c1 + m2 * l1),
        m2 * l1 * c2,
        m2 * c2 * g,
        i1 + m1 * c1 * c1 + m2 * l1 * l1,
        i2 + m2 * c2 * c2,
    ];
    let mut found = pi.clone();
    found.sort_by(f64::total_cmp);
    expected.sort_by(f64::total_cmp);
    assert!(
        relative_error(&found, &expected) < 1e-14,
        "{found:?} vs {expected:?}"
    );
}

/// `x` moved by `h` along `direction`.
fn step(x: &[f64], direction: &[f64], h: f64) -> Vec<f64> {
    x.iter().zip(direction).map(|(a, d)| a + h * d).collect()
}

/// The central difference of `f` along the motion `(q + h v, v + h v̇)`.
fn rate_along(
    f: impl Fn(&[f64], &[f64]) -> Vec<f64>,
    q: &[f64],
    v: &[f64],
    rates: &[f64],
) -> Vec<f64> {
    let h = 1e-6;
    let ahead = f(&step(q, v, h), &step(v, rates, h));
    let behind = f(&step(q, v, -h), &step(v, rates, -h));
    ahead
        .iter()
        .zip(&behind)
        .map(|(a, b)| (a - b) / (2.0 * h))
        .collect()
}

/// `J v` for a `3 × n` matrix `J` given row by row.
fn times(j: &[f64], v: &[f64]) -> Vec<f64> {
    j.chunks(v.len())
        .map(|row| row.iter().zip(v).map(|(a, b)| a * b).sum())
        .collect()
}

#[test]
fn kinematic_outputs_agree_with_differences_of_each_other() {
    for family in [Family::Planar, Family::Spatial] {
        let n = 3;
        let source = asking(
            &chain_spelled(family, n, Spelling::SymbolicJoints),
            "outputs position(J3), velocity(J3), acceleration(J3), jacobian(J3);
    outputs rotation(B3), angular_velocity(B3), angular_jacobian(B3);
    outputs velocity(J3 in B2), rotation(B3 in B1), position(J3 in B3);",
        );
        let interpreter = interpreter(&source, Route::Dalembert);
        for seed in 0..5 {
            let sample = Sample::random(&interpreter, seed);
            let rates = random_rates(&interpreter, seed + 100);
            let (p, q, v) = (&sample.parameters, &sample.q, &sample.qd);
            let eval = |name: &str, q: &[f64], v: &[f64]| {
                let at = values(p, q, v, &sample.u);
                interpreter.output(name, &at, &rates).unwrap()
            };
            let close = |what: &str, a: &[f64], b: &[f64], tolerance: f64| {
                let error = relative_error(a, b);
                assert!(
                    error < tolerance,
                    "{family:?} seed {seed}: {what} off by {error:e}"
                );
            };
            let velocity = eval("velocity_J3", q, v);
            let differenced = rate_along(|q, v| eval("position_J3", q, v), q, v, &rates);
            close("velocity vs ṙ", &velocity, &differenced, 1e-8);
            let jacobian = eval("jacobian_J3", q, v);
            close("J v vs velocity", &times(&jacobian, v), &velocity, 1e-13);
            let acceleration = eval("acceleration_J3", q, v);
            let differenced = rate_along(|q, v| eval("velocity_J3", q, v), q, v, &rates);
            close("acceleration vs v̇", &acceleration, &differenced, 1e-8);
            // Ṙ Rᵀ = [ω]×, ω in N's axes.
            let r = eval("rotation_B3", q, v);
            let r_dot = rate_along(|q, v| eval("rotation_B3", q, v), q, v, &rates);
            let spin = |i: usize, j: usize| (0..3).map(|k| r_dot[3 * i + k] * r[3 * j + k]).sum();
            let omega: Vec<f64> = vec![spin(2, 1), spin(0, 2), spin(1, 0)];
            let angular = eval("angular_velocity_B3", q, v);
            close("ω vs Ṙ Rᵀ", &angular, &omega, 1e-8);
            let angular_jacobian = eval("angular_jacobian_B3", q, v);
            close("J_ω v vs ω", &times(&angular_jacobian, v), &angular, 1e-13);
            // Components in other axes: Rᵀ times the components in N's, with
            // the closed-form rotations of the first links (about z, then z
            // or y).
            let position = eval("position_J3", q, v);
            close(
                "position in B3 vs R_B3ᵀ r",
                &eval("position_J3_in_B3", q, v),
                &transposed_times(&r, &position),
                1e-13,
            );
            let r_b1 = about(2, q[0]);
            let r_b2 = product(&r_b1, &about(family_axis(family), q[1]));
            close(
                "velocity in B2 vs R_B2ᵀ v",
                &eval("velocity_J3_in_B2", q, v),
                &transposed_times(&r_b2, &velocity),
                1e-13,
            );
            close(
                "R_B3 vs R_B1 R_B3/B1",
                &r,
                &product(&r_b1, &eval("rotation_B3_in_B1", q, v)),
                1e-13,
            );
        }
    }
}

/// The second joint's axis: `z` in the planar chains, `y` in the spatial.
fn family_axis(family: Family) -> usize {
    match family {
        Family::Planar => 2,
        Family::Spatial => 1,
    }
}

/// The rotation by `angle` about the `axis`-th coordinate axis, row by row.
fn about(axis: usize, angle: f64) -> Vec<f64> {
    let (s, c) = angle.sin_cos();
    let (i, j) = ((axis + 1) % 3, (axis + 2) % 3);
    let mut r = vec![0.0; 9];
    r[3 * axis + axis] = 1.0;
    r[3 * i + i] = c;
    r[3 * j + j] = c;
    r[3 * i + j] = -s;
    r[3 * j + i] = s;
    r
}

/// `a b` for 3 × 3 matrices given row by row.
fn product(a: &[f64], b: &[f64]) -> Vec<f64> {
    (0..9)
        .map(|e| (0..3).map(|k| a[3 * (e / 3) + k] * b[3 * k + e % 3]).sum())
        .collect()
}

/// `rᵀ x` for a 3 × 3 matrix given row by row.
fn transposed_times(r: &[f64], x: &[f64]) -> Vec<f64> {
    (0..3)
        .map(|j| (0..3).map(|i| r[3 * i + j] * x[i]).sum())
        .collect()
}

#[test]
fn bad_outputs_are_reported_together_at_their_tokens() {
    let source = "S {
    parameters m, l;
    coordinates q;
    frame B = N.rotate_z(q);
    point P = O + l * B.x;
    particle p { mass: m, at: P };
    outputs position(P), velocity(B), rotation(P), jacobian(Q), speed(P);
    outputs position(P), inverse_dynamics(P), angular_velocity(B in P), rotation;
}";
    let messages: Vec<(String, usize)> = check(source)
        .unwrap_err()
        .into_iter()
        .map(|e| (e.to_string(), e.span().start().line))
        .collect();
    let expected = [
        ("`B` is a frame; `velocity` expects a point", 7),
        ("`P` is a point; expected a frame", 7),
        ("unknown name `Q`", 7),
        ("unknown output `speed`", 7),
        ("this output is already asked for, as `position_P`", 8),
        ("`inverse_dynamics` takes no point or frame", 8),
        ("`P` is a point; expected a frame", 8),
        ("`rotation` needs a frame", 8),
    ];
    assert_eq!(messages.len(), expected.len(), "{messages:#?}");
    for ((message, line), (start, expected_line)) in messages.iter().zip(expected) {
        assert!(
            message.starts_with(start) && *line == expected_line,
            "{message} (line {line}) should start with {start} (line {expected_line})"
        );
    }
}
