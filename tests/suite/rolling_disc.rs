//! The rolling disc, the classic of Kane's textbook and of SymPy's
//! `Linearizer`: a thin uniform disc (radius `r`, mass `m`,
//! `I_a = m r²/2` about its axle, `I_d = m r²/4` about a diameter) rolling
//! without slipping on a horizontal plane, linearised by `linearize` about
//! upright steady rolling at the spin rate `Ω`, against the closed form
//! derived here, and at a leaning, turning state against SymPy's own
//! `KanesMethod.linearize` (`scripts/rolling_disc_linearize_reference.py`).
//!
//! Coordinates: the contact point `(x, y, z)` (`z` its height, which the
//! `rolling` statement's contact row holds at zero), the heading `ψ` (frame
//! `A = N.rotate_z(ψ)`), the lean `θ` (`C = A.rotate_x(θ)`, the disc's
//! plane `C.x`, `C.z`, its axle `C.y`) and the spin `φ` about the axle. The
//! centre is `G = (x, y, z) + r C.z`; the disc's point at the contact,
//! `G − r C.z`, moves at `ẋ N.x + ẏ N.y + r ω_C × C.z − r ω × C.z =
//! ẋ N.x + ẏ N.y − r φ̇ C.x` (`ω = ω_C + φ̇ C.y`), so rolling is
//! `ẋ = r φ̇ cos ψ`, `ẏ = r φ̇ sin ψ`: the statement's two nonholonomic
//! rows, the speeds `ψ̇`, `θ̇`, `φ̇` independent (the contact row's
//! velocity form is `ż = 0`, so the numbers are those of the disc written
//! with the two rows by hand on `(x, y, ψ, θ, φ)`).
//!
//! About upright rolling (`θ = θ̇ = ψ̇ = 0`, `φ̇ = Ω`), to first order in
//! `C`'s axes: `ω_C = (θ̇, 0, ψ̇)`, the axial spin `s = φ̇ + ψ̇ sin θ`,
//! `H_G = (I_d θ̇, I_a s, I_d ψ̇)`, `v_G = ω × r C.z = r (s, −θ̇, 0)`, so
//! `dH_G/dt = (I_d θ̈ − I_a Ω ψ̇, I_a ṡ, I_d ψ̈ + I_a Ω θ̇)` and
//! `a_G = r (ṡ, −θ̈ + Ω ψ̇, 0)`. The contact force `F = m a_G − m g_N`
//! (`g_N ≈ −g (0, θ, 1)`) has the moment `−r C.z × F = (r F_y, −r F_x, 0)`
//! about `G`; equated:
//!
//! * `(I_d + m r²) θ̈ = m g r θ + (I_a + m r²) Ω ψ̇`,
//! * `(I_a + m r²) ṡ = 0`, hence `φ̈ = 0` to first order,
//! * `I_d ψ̈ = −I_a Ω θ̇`.
//!
//! With `ψ̇ = −(I_a Ω / I_d) θ` (the constant is a steady turn, an
//! eigenvalue zero) the lean obeys `(I_d + m r²) θ̈ = (m g r − (I_a + m r²)
//! I_a Ω² / I_d) θ`: `λ² = (m g r − (I_a + m r²) I_a Ω² / I_d) / (I_d + m r²)`,
//! and for the thin disc `λ² = 4/5 (g/r − 3 Ω²)`. Upright rolling is stable
//! (a purely imaginary pair) for `Ω² > g / 3r`, unstable (a positive real
//! root) below; every other eigenvalue is zero.

use dalembert::integrate::{Adaptive, AdaptiveOptions, ExplicitPair, Integration, State, Taylor};
use dalembert::{Constrained, Stabilisation, energy};
use dalembert_fixtures::reference::{assert_close, assert_near_all, flat};
use nalgebra::SMatrix;

dalembert::dalembert! {
    /// A thin uniform disc rolling without slipping on a horizontal plane.
    pub RollingDisc {
        parameters m, r, g;
        coordinates x, y, z, psi, theta, phi;
        frame A = N.rotate_z(psi);
        frame C = A.rotate_x(theta);
        frame B = C.rotate_y(phi);
        point G = O + x * N.x + y * N.y + z * N.z + r * C.z;
        body disc { mass: m, center: G, frame: B, inertia: [m*r^2/4, m*r^2/2, m*r^2/4] };
        gravity -g * N.z;
        rolling contact { wheel: B, axle: B.y, center: G, radius: r, plane: N.z };
        outputs taylor, linearize(x, y, psi, theta, phi; dt(psi), dt(theta), dt(phi));
    }
}

const DISC: RollingDisc = RollingDisc {
    m: 0.8,
    r: 0.3,
    g: 9.81,
};

/// The independent entries of `linearize`'s state `(q, v)`: every
/// coordinate but the contact's height `z`, and the speeds `ψ̇`, `θ̇`, `φ̇`.
const INDEPENDENT: [usize; 8] = [0, 1, 3, 4, 5, 9, 10, 11];

/// `A` of upright rolling at the spin rate `omega`, heading `psi`, reduced
/// to the independent rows and columns.
fn reduced_linearization(psi: f64, omega: f64) -> [[f64; 8]; 8] {
    let rolling = DISC.r * omega;
    let q = [0.4, -1.2, 0.0, psi, 0.0, 2.0];
    let v = [
        rolling * psi.cos(),
        rolling * psi.sin(),
        0.0,
        0.0,
        0.0,
        omega,
    ];
    let (a, _) = DISC.linearize(0.0, &q, &v, &[]).expect("linearisable");
    INDEPENDENT.map(|i| INDEPENDENT.map(|j| a[i][j]))
}

/// `λ² = 4/5 (g/r − 3 Ω²)` (module docs).
fn lean_exponent_squared(omega: f64) -> f64 {
    0.8 * (DISC.g / DISC.r - 3.0 * omega * omega)
}

/// The rows of `θ̈` and `ψ̈` are the closed form's:
/// `θ̈ = 4/5 (g/r) θ + 6/5 Ω ψ̇` and `ψ̈ = −2 Ω θ̇` for the thin disc
/// (`(I_a + m r²) / (I_d + m r²) = 6/5`, `I_a / I_d = 2`), `φ̈ = 0`.
#[test]
fn upright_rolling_has_the_closed_form_equations() {
    let (theta, psi_rate, theta_rate) = (3, 5, 6);
    for (psi, omega) in [(0.0, 5.0), (0.7, -2.0), (-2.5, 12.0)] {
        let a = reduced_linearization(psi, omega);
        let mut lean = [0.0; 8];
        lean[theta] = 0.8 * DISC.g / DISC.r;
        lean[psi_rate] = 1.2 * omega;
        let mut heading = [0.0; 8];
        heading[theta_rate] = -2.0 * omega;
        assert_close("θ̈ row", &a[theta_rate], &lean, 1e-12);
        assert_close("ψ̈ row", &a[psi_rate], &heading, 1e-12);
        assert_near_all("φ̈ row", &a[7], &[0.0; 8], 1e-12);
    }
}

/// On both sides of `Ω² = g / 3r` (3.3 rad/s here) the eigenvalues of the
/// reduced `A` are `±√λ²` and zeros (to 1e-7 of `|λ|`: a zero of a
/// Jordan block of two comes out of the eigensolver as `±√ε`).
#[test]
fn lean_is_stable_above_the_closed_form_spin_rate() {
    let threshold = (DISC.g / (3.0 * DISC.r)).sqrt();
    for factor in [0.0, 0.5, 0.9, 1.1, 2.0, 5.0] {
        let omega = factor * threshold;
        let a = reduced_linearization(0.3, omega);
        let mut eigenvalues = SMatrix::<f64, 8, 8>::from_fn(|i, j| a[i][j])
            .complex_eigenvalues()
            .as_slice()
            .to_vec();
        eigenvalues.sort_by(|p, q| q.norm().total_cmp(&p.norm()));
        let squared = lean_exponent_squared(omega);
        let root = squared.abs().sqrt();
        let pair = [eigenvalues[0], eigenvalues[1]];
        let (mut real, mut imaginary): (Vec<f64>, Vec<f64>) =
            pair.iter().map(|z| (z.re, z.im)).unzip();
        real.sort_by(f64::total_cmp);
        imaginary.sort_by(f64::total_cmp);
        let (expected_real, expected_imaginary) = match squared > 0.0 {
            true => ([-root, root], [0.0; 2]),
            false => ([0.0; 2], [-root, root]),
        };
        // One scale for both: the zero parts are compared at `|λ|`.
        assert_close(
            &format!("Ω = {omega}: the lean's pair"),
            &[real, imaginary].concat(),
            &[expected_real, expected_imaginary].concat(),
            1e-10,
        );
        for z in &eigenvalues[2..] {
            assert!(z.norm() < 1e-7 * root, "Ω = {omega}: {z} is not zero");
        }
    }
}

/// From [`leaning`], on the index-1 form for 3 s: `Taylor` at 1e-15 and DOP853 at 1e-14 reach
/// the same state to 1e-11, both rolling without slipping (the velocity
/// form of the rows) and keeping the energy (the rows do no work) to
/// 1e-12.
#[test]
fn a_leaning_disc_rolls_alike_by_taylor_and_dop853() {
    let (q, v) = leaning();
    let start = State { t: 0.0, q, v };
    let dynamics = Constrained::without_inputs(&DISC, Stabilisation::None);
    let initial = energy(&DISC, &start.q, &start.v);
    let options = Taylor::with_tolerance(1e-15);
    let by_taylor = Integration::new(&dynamics, start, 3.0, options)
        .run()
        .expect("integrates")
        .end;
    let options = AdaptiveOptions::with_tolerance(1e-14);
    let by_dop853 = Integration::new(
        &dynamics,
        start,
        3.0,
        Adaptive {
            pair: ExplicitPair::Dop853,
            options,
        },
    )
    .run()
    .expect("integrates")
    .end;
    let state = |s: &State<6, 6>| [s.q, s.v].concat();
    assert_close(
        "Taylor against DOP853",
        &state(&by_taylor),
        &state(&by_dop853),
        1e-11,
    );
    for end in [by_taylor, by_dop853] {
        let slip = DISC.constraint_velocity(end.t, &end.q, &end.v);
        assert_near_all("slip", &slip, &[0.0; 3], 1e-12);
        let change = energy(&DISC, &end.q, &end.v) / initial - 1.0;
        assert!(change.abs() < 1e-12, "energy {change:e}");
    }
}

/// SymPy's reduced `A` of `KanesMethod(...).linearize(A_and_B=True)` at
/// the state of [`leaning`], states
/// `(x, y, ψ, θ, φ, u_ψ, u_θ, u_φ)`: printed by
/// `scripts/rolling_disc_linearize_reference.py` (SymPy 1.14).
const SYMPYS_REDUCED_A: [[f64; 8]; 8] = [
    [
        0.0,
        0.0,
        -0.7009530161555708,
        0.0,
        0.0,
        0.0,
        0.0,
        0.2763182982008655,
    ],
    [
        0.0,
        0.0,
        1.657909789205193,
        0.0,
        0.0,
        0.0,
        0.0,
        0.11682550269259515,
    ],
    [0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0],
    [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0],
    [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0],
    [
        0.0,
        0.0,
        -3.2199171476717948e-15,
        -0.7771157152623784,
        0.0,
        2.1466114317811964e-15,
        -12.561019218457023,
        -0.41870064061523404,
    ],
    [
        0.0,
        0.0,
        0.0,
        23.689192682473887,
        0.0,
        7.443065195099398,
        7.709882115452476e-17,
        1.1464037869507269,
    ],
    [
        0.0,
        0.0,
        1.6071654057714212e-15,
        2.728160132327892,
        0.0,
        -0.3184454963752038,
        2.119807513439467,
        0.12373449984384916,
    ],
];

/// Leaning by 0.3 rad, heading 0.4 rad, turning at 1 rad/s, the lean
/// changing at 0.2 rad/s and spinning at 6 rad/s, rolling.
fn leaning() -> ([f64; 6], [f64; 6]) {
    let (psi, omega) = (0.4f64, 6.0);
    let rolling = DISC.r * omega;
    (
        [0.1, 0.2, 0.0, psi, 0.3, 0.5],
        [
            rolling * psi.cos(),
            rolling * psi.sin(),
            0.0,
            1.0,
            0.2,
            omega,
        ],
    )
}

/// Away from any equilibrium, where every term of `F` (the dependent
/// speeds' change with the heading) and of the gyroscopic coupling counts,
/// the reduced `A` is SymPy's own to 1e-12.
#[test]
fn leaning_and_turning_matches_sympys_linearizer() {
    let (q, v) = leaning();
    let (a, _) = DISC.linearize(0.0, &q, &v, &[]).expect("linearisable");
    let reduced = INDEPENDENT.map(|i| INDEPENDENT.map(|j| a[i][j]));
    assert_close("A", &flat(&reduced), &flat(&SYMPYS_REDUCED_A), 1e-12);
}
