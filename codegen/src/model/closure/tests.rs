//! The rows of each kind of closure against their closed forms, and the
//! rows that vanish identically dropped.

use crate::interpret::{Interpreter, Route, Sample};

/// The residuals of `source`'s constraints at `seeds` random samples, with
/// the closed forms `expected(parameters, q)` they must equal.
fn assert_rows(source: &str, expected: impl Fn(&[f64], &[f64]) -> Vec<f64>) {
    let interpreter = Interpreter::new(source, Route::Dalembert).expect("derives");
    for seed in 0..5 {
        let sample = Sample::random(&interpreter, seed);
        let found = interpreter.constraint_residual(&sample.values());
        let wanted = expected(&sample.parameters, &sample.q);
        assert_eq!(found.len(), wanted.len(), "number of rows");
        for (f, w) in found.iter().zip(&wanted) {
            assert!((f - w).abs() < 1e-12, "{found:?} != {wanted:?}");
        }
    }
}

/// One window of the IFToMM four-bar (A02): crank `a` about `O`, coupler
/// `c` from its tip, closed on the tip of crank `b` about `(L, 0)`.
const FOUR_BAR: &str = "FourBar {
    parameters L;
    coordinates a, b, c;
    frame A = N.rotate_z(a);
    frame B = N.rotate_z(b);
    frame C = N.rotate_z(c);
    point TA = O + L * A.x;
    point TB = O + L * N.x + L * B.x;
    point TC = TA + L * C.x;
    CLOSURE
}";

#[test]
fn a_planar_point_closure_gives_two_rows() {
    let source = FOUR_BAR.replace("CLOSURE", "closure window { at: TC, to: TB };");
    assert_rows(&source, |p, q| {
        let (l, [a, b, c]) = (p[0], [q[0], q[1], q[2]]);
        vec![
            l * a.cos() + l * c.cos() - l - l * b.cos(),
            l * a.sin() + l * c.sin() - l * b.sin(),
        ]
    });
}

#[test]
fn a_planar_revolute_closure_adds_no_row_and_a_weld_adds_one() {
    let hinge = FOUR_BAR.replace(
        "CLOSURE",
        "closure window { at: TC, to: TB, axis: C.z, along: B.z };",
    );
    let planar_point = |p: &[f64], q: &[f64]| {
        let (l, [a, b, c]) = (p[0], [q[0], q[1], q[2]]);
        vec![
            l * a.cos() + l * c.cos() - l - l * b.cos(),
            l * a.sin() + l * c.sin() - l * b.sin(),
        ]
    };
    assert_rows(&hinge, planar_point);
    let weld = FOUR_BAR.replace(
        "CLOSURE",
        "closure window { at: TC, to: TB, frame: C, welded: B };",
    );
    // C.x · B.y = −cos c sin b + sin c cos b = sin(c − b).
    assert_rows(&weld, |p, q| {
        let mut rows = planar_point(p, q);
        rows.push((q[2] - q[1]).sin());
        rows
    });
}

/// A rod turned about `N.x` by `a` and then about its own y by `b`, its
/// tip `L` along its z axis; `extra` closes it.
fn spatial_rod(extra: &str) -> String {
    format!(
        "Rod {{
    parameters L, h;
    coordinates a, b;
    frame F = N.rotate_x(a);
    frame G = F.rotate_y(b);
    point T = O + L * G.z;
    point H = O + h * N.y;
    {extra}
}}"
    )
}

/// The tip: `L Rx(a) Ry(b) ẑ = L (sin b, −sin a cos b, cos a cos b)`.
fn tip(l: f64, a: f64, b: f64) -> [f64; 3] {
    [l * b.sin(), -l * a.sin() * b.cos(), l * a.cos() * b.cos()]
}

#[test]
fn a_spatial_point_closure_gives_three_rows_in_newtonian_axes() {
    let source = spatial_rod("closure tip { at: T, to: H };");
    assert_rows(&source, |p, q| {
        let (l, h) = (p[0], p[1]);
        let r = tip(l, q[0], q[1]);
        vec![r[0], r[1] - h, r[2]]
    });
}

#[test]
fn a_spatial_revolute_closure_keeps_the_axis_components_off_the_hinge() {
    let source = spatial_rod("closure hinge { at: T, to: H, axis: G.z, along: N.z };");
    assert_rows(&source, |p, q| {
        let (l, h) = (p[0], p[1]);
        let r = tip(l, q[0], q[1]);
        // G.z in N's axes is the tip direction: its x and y components.
        let axis = tip(1.0, q[0], q[1]);
        vec![r[0], r[1] - h, r[2], axis[0], axis[1]]
    });
}

#[test]
fn a_spatial_weld_gives_the_three_small_rotations() {
    let source = spatial_rod("closure weld { at: T, to: H, frame: N, welded: G };");
    assert_rows(&source, |p, q| {
        let (l, h) = (p[0], p[1]);
        let (a, b) = (q[0], q[1]);
        let r = tip(l, a, b);
        // G = Rx(a) Ry(b); N.i · G.j is the entry (i, j) of that matrix,
        // and N.x · G.y vanishes identically (no rotation about z): its row
        // is dropped.
        let (sa, ca, sb, cb) = (a.sin(), a.cos(), b.sin(), b.cos());
        let g = [
            [cb, 0.0, sb],
            [sa * sb, ca, -sa * cb],
            [-ca * sb, sa, ca * cb],
        ];
        assert_eq!(g[0][1], 0.0);
        vec![r[0], r[1] - h, r[2], g[1][2], g[2][0]]
    });
}
