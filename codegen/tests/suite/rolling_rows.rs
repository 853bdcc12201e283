//! A `rolling` statement adds exactly three rows, those that vanish
//! identically kept as zero rows and listed in the generated
//! `ConstrainedSystem::VANISHING_ROWS`, which systems without such a row
//! do not emit.

use dalembert_codegen::generate;

/// A thin disc on `z = 0` whose centre is placed as `centre`.
fn disc(coordinates: &str, centre: &str) -> String {
    format!(
        "Disc {{
            parameters m, r, g;
            coordinates {coordinates};
            frame A = N.rotate_z(psi);
            frame C = A.rotate_x(theta);
            frame B = C.rotate_y(phi);
            point G = {centre};
            body disc {{ mass: m, center: G, frame: B, inertia: [m*r^2/4, m*r^2/2, m*r^2/4] }};
            gravity -g * N.z;
            rolling contact {{ wheel: B, axle: B.y, center: G, radius: r, plane: N.z }};
            outputs linearize(x, y, psi, theta, phi; dt(psi), dt(theta), dt(phi));
        }}"
    )
}

#[test]
fn a_contact_placed_from_the_contact_point_is_a_zero_first_row() {
    let code = generate(&disc(
        "x, y, psi, theta, phi",
        "O + x * N.x + y * N.y + r * C.z",
    ))
    .expect("generates");
    assert!(code.contains("pub const NC: usize = 3;"), "{code}");
    assert!(
        code.contains("const VANISHING_ROWS: [bool; 3] = [true, false, false];"),
        "{code}"
    );
}

#[test]
fn a_live_contact_row_emits_no_vanishing_rows() {
    let code = generate(&disc(
        "x, y, z, psi, theta, phi",
        "O + x * N.x + y * N.y + z * N.z + r * C.z",
    ))
    .expect("generates");
    assert!(code.contains("pub const NC: usize = 3;"), "{code}");
    assert!(!code.contains("VANISHING_ROWS"), "{code}");
}

#[test]
fn a_planar_wheel_keeps_its_zero_contact_and_sideways_rows() {
    // A wheel on a level axle at height r, rolling along N.x only: its
    // contact and its sideways (N.y) rows vanish.
    let code = generate(
        "Wheel {
            parameters m, r, g;
            coordinates x, phi;
            frame B = N.rotate_y(phi);
            point G = O + x * N.x + r * N.z;
            body wheel { mass: m, center: G, frame: B, inertia: [m*r^2/4, m*r^2/2, m*r^2/4] };
            gravity -g * N.z;
            rolling contact { wheel: B, axle: B.y, center: G, radius: r, plane: N.z };
            outputs linearize(x, phi; dt(phi));
        }",
    )
    .expect("generates");
    assert!(code.contains("pub const NC: usize = 3;"), "{code}");
    assert!(
        code.contains("const VANISHING_ROWS: [bool; 3] = [true, false, true];"),
        "{code}"
    );
}
