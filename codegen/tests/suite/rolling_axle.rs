//! A wheel turns about its axle, so the axle of a `rolling` statement is a
//! unit vector fixed in the wheel's frame: the frame's own (`B.y`), or one
//! of a frame it turns about (`L.y` for `B = L.rotate_y(phi)`). An axle
//! that turns in the wheel's frame (`N.y`, `L.x`) was taken silently, with
//! a contact point the disc does not have; it is an error at the axle.

use dalembert_codegen::generate;

/// A disc turning with `B` about `L`'s y axis, rolling on `N.z` with the
/// given `axle`.
fn disc(axle: &str) -> String {
    format!(
        "Disc {{
            parameters m, r, g;
            coordinates x, y, psi, theta, phi;
            frame A = N.rotate_z(psi);
            frame L = A.rotate_x(theta);
            frame B = L.rotate_y(phi);
            point G = O + x * N.x + y * N.y + r * L.z;
            body disc {{ mass: m, center: G, frame: B, inertia: [m*r^2/4, m*r^2/2, m*r^2/4] }};
            gravity -g * N.z;
            rolling contact {{ wheel: B, axle: {axle}, center: G, radius: r, plane: N.z }};
        }}"
    )
}

#[test]
fn an_axle_fixed_in_the_wheel_is_taken() {
    for axle in ["B.y", "L.y"] {
        generate(&disc(axle)).unwrap_or_else(|e| panic!("axle {axle}: {e}"));
    }
}

#[test]
fn an_axle_turning_in_the_wheel_is_an_error_at_the_axle() {
    for axle in ["N.y", "L.x", "A.y"] {
        let source = disc(axle);
        let error = generate(&source).expect_err(axle);
        let message = error.to_string();
        assert!(
            message.starts_with("the wheel turns about its axle: expected a unit vector of"),
            "axle {axle}: {message}"
        );
        let at = source.find(&format!("axle: {axle}")).unwrap() + "axle: ".len();
        let span = error.span();
        let line = source[..at].matches('\n').count() + 1;
        let column = at - source[..at].rfind('\n').map_or(0, |n| n + 1);
        assert_eq!(
            (span.start().line, span.start().column),
            (line, column),
            "axle {axle}"
        );
    }
}
