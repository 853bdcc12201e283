//! `outputs accelerations_x4;`: generated only where it is asked for, over
//! the lanes of the runtime (no `unsafe`, nothing for `#![no_std]` crates),
//! and refused on a system with constraints at the output's token.

use dalembert_codegen::chain::{Family, chain};
use dalembert_codegen::{Target, generate, generate_for};

const PENDULUM: &str = "pub P {
    parameters m, l, g;
    coordinates theta;
    frame B = N.rotate_z(theta);
    body bob { mass: m, center: O - l * B.y, frame: B, inertia: [0, 0, 0] };
    gravity -g * N.y;
    OUTPUTS
}";

fn pendulum(outputs: &str) -> String {
    PENDULUM.replace("OUTPUTS", outputs)
}

#[test]
fn generated_where_asked_over_the_runtimes_lanes() {
    let code = generate(&pendulum("outputs accelerations_x4;")).expect("generates");
    assert!(code.contains("pub fn accelerations_x4("), "{code}");
    assert!(
        code.contains("::dalembert::__private::lanes::per_state"),
        "{code}"
    );
    assert!(code.contains("fn accelerations_x4(") && code.contains("P::accelerations_x4(self"));
    assert!(!code.contains("unsafe"));
    let plain = generate(&pendulum("")).expect("generates");
    // (The struct's docs list what each output would add.)
    assert!(!plain.contains("fn accelerations_x4"), "only where asked");
    let no_std =
        generate_for(&pendulum("outputs accelerations_x4;"), Target::NoStd).expect("generates");
    assert!(!no_std.contains("fn accelerations_x4"), "needs the runtime");
}

#[test]
fn refused_with_constraints() {
    let source = "pub C {
        parameters m;
        coordinates x, y;
        particle p { mass: m, at: O + x * N.x + y * N.y };
        constraint x - y == 0;
        outputs accelerations_x4;
    }";
    let error = generate(source).expect_err("refused").to_string();
    assert!(
        error.contains("`accelerations_x4` is for systems without constraints"),
        "{error}"
    );
}

/// The routes of `accelerations` and `accelerations_x4` in the code
/// generated for the spatial chain of `n`: whether each takes the
/// articulated-body recursion.
fn recursion_taken(n: usize) -> (bool, bool) {
    let source = chain(Family::Spatial, n);
    let end = source.rfind('}').expect("a closing brace");
    let code = generate(&format!(
        "{}    outputs accelerations_x4;\n}}",
        &source[..end]
    ))
    .expect("generates");
    let scalar = code.contains(" by the articulated-body recursion over the kinematic tree");
    let factorised = code.contains(" square-root-free Cholesky factorisation `L D Lᵀ` unrolled");
    assert_ne!(scalar, factorised, "one route for `accelerations`");
    let lanes = code.contains("::dalembert::__private::lanes::articulated_pivots_hold");
    let lanes_factorised = code.contains("::dalembert::__private::lanes::factorised_pivots_hold");
    assert_ne!(lanes, lanes_factorised, "one route for `accelerations_x4`");
    (scalar, lanes)
}

/// Over lanes the recursion is taken sooner than by the scalar call (the
/// factorisation gains less there): the chain of 12 factorises one state
/// at a time and takes the recursion four at a time; the chain of 6
/// factorises both ways, the chain of 30 takes the recursion both ways.
#[test]
fn lanes_take_the_recursion_sooner() {
    assert_eq!(recursion_taken(6), (false, false));
    assert_eq!(recursion_taken(12), (false, true));
    assert_eq!(recursion_taken(30), (true, true));
}
