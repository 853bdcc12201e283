//! `outputs accelerations_x4;`: generated only where it is asked for, over
//! the lanes of the runtime (no `unsafe`, nothing for `#![no_std]` crates),
//! and refused on a system with constraints at the output's token.

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
