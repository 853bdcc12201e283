//! A wheel's radii are sizes: a numeric `radius` must be positive and a
//! numeric `tire` zero or positive, each an error at the number otherwise
//! (a negative radius was taken, with the contact point above the centre).
//! Radii of parameters are taken as they are: their values come at run time.

use dalembert_codegen::generate;

/// A disc rolling on `N.z` with the given `radius` field (and any
/// optional ones after it).
fn disc(radius: &str) -> String {
    format!(
        "Disc {{
            parameters m, r, g;
            coordinates x, y, z, psi, theta, phi;
            frame A = N.rotate_z(psi);
            frame L = A.rotate_x(theta);
            frame B = L.rotate_y(phi);
            point G = O + x * N.x + y * N.y + z * N.z;
            body disc {{ mass: m, center: G, frame: B, inertia: [1, 2, 1] }};
            gravity -g * N.z;
            rolling contact {{ wheel: B, axle: B.y, center: G, radius: {radius}, plane: N.z }};
        }}"
    )
}

#[test]
fn a_size_that_is_not_one_is_an_error_at_the_number() {
    for (radius, at, expected) in [
        (
            "-0.5",
            "-0.5",
            "a wheel's radius must be positive; found -0.5",
        ),
        ("0", "0", "a wheel's radius must be positive; found 0"),
        (
            "r - r",
            "r - r",
            "a wheel's radius must be positive; found 0",
        ),
        (
            "0.3, tire: -0.1",
            "-0.1",
            "a tire's radius must be zero or positive; found -0.1",
        ),
    ] {
        let source = disc(radius);
        let error = generate(&source).expect_err(radius);
        assert_eq!(error.to_string(), expected, "radius: {radius}");
        // The number is the last field's but `plane`.
        let position = source.find(&format!("{at}, plane")).unwrap();
        let column = position - source[..position].rfind('\n').unwrap() - 1;
        assert_eq!(error.span().start().column, column, "radius: {radius}");
    }
}

#[test]
fn sizes_of_parameters_and_a_flat_tire_are_taken() {
    for radius in ["r", "0.3", "r, tire: 0", "r, tire: r / 4"] {
        generate(&disc(radius)).unwrap_or_else(|e| panic!("radius: {radius}: {e}"));
    }
}
