//! A bicycle: the Whipple model of the benchmark of Meijaard, Papadopoulos,
//! Ruina and Schwab (2007, "Linearized dynamics equations for the balance
//! and steer of a bicycle: a benchmark and review", Proc. R. Soc. A 463),
//! written with two `rolling` statements: a rear frame with its rider, a
//! steering fork with its handlebar, two knife-edge wheels. Each wheel adds
//! a holonomic contact row (the front one ties the pitch to the lean and
//! the steer) and two no-slip rows: six rows on nine coordinates, three
//! degrees of freedom of speed (lean, steer, forward speed).
//!
//! `linearize` at upright straight running (independent coordinates all
//! but the height `z` and the pitch `theta`; independent speeds the lean,
//! steer and rear wheel rates) is checked against the benchmark's
//! published linearised equations `M q̈ + v C1 q̇ + (g K0 + v² K2) q = 0`
//! for `q = (φ, δ)`, whose matrices the paper prints to 14 digits (Table 2,
//! "benchmark values"): the reduced `A`'s nonzero eigenvalues are those of
//! the benchmark's at every speed, to 1e-10 (the benchmark's own digits
//! reproduce its weave and capsize speeds, 4.29238253634111 and
//! 6.02426201538837 m/s, to 1e-13); and at those two speeds the weave pair
//! and the capsize root cross the imaginary axis.
//!
//! Axes: the benchmark's x forward, y right, z down; ours x forward, y
//! left, z up (`N.z` up). So its heights `zB`, `zH` are negative numbers
//! taken with a minus sign, its products of inertia `I_xz` change sign,
//! and its steer angle is ours with the opposite sign (eigenvalues do not
//! depend on that).

use dalembert_fixtures::reference::assert_close;
use nalgebra::{Complex, SMatrix};

dalembert::dalembert! {
    /// The benchmark bicycle: rear wheel centre `PR` at `(x, y, z)`, yaw
    /// `psi`, lean `phi`, pitch `theta` of the rear frame, steer `delta`
    /// about the steer axis (tilted back by `lambda`), wheel angles `phiR`,
    /// `phiF`.
    pub Bicycle {
        parameters w, c, lambda, g, rR, mR, IRxx, IRyy, xB, zB, mB, IBxx, IByy, IBzz, IBxz,
            xH, zH, mH, IHxx, IHyy, IHzz, IHxz, rF, mF, IFxx, IFyy;
        coordinates x, y, z, psi, phi, theta, delta, phiR, phiF;
        frame A = N.rotate_z(psi);
        frame L = A.rotate_x(phi);
        frame R = L.rotate_y(theta);
        frame WR = R.rotate_y(phiR);
        // The steer axis, tilted back by lambda from R.z; the fork turns
        // about it, and H is the fork's frame parallel to R when delta = 0.
        frame S = R.rotate_y(-lambda);
        frame Fk = S.rotate_z(delta);
        frame H = Fk.rotate_y(lambda);
        frame WF = H.rotate_y(phiF);
        point PR = O + x * N.x + y * N.y + z * N.z;
        // The steer axis meets the ground a trail c ahead of the front contact.
        point S0 = PR + (w + c) * R.x - rR * R.z;
        point PF = S0 - c * H.x + rF * H.z;
        body rear_wheel { mass: mR, center: PR, frame: WR, inertia: [IRxx, IRyy, IRxx] };
        body rear_frame { mass: mB, center: PR + xB * R.x - (zB + rR) * R.z, frame: R,
            inertia: [IBxx, IByy, IBzz, 0, 0, -IBxz] };
        body fork { mass: mH, center: S0 + (xH - w - c) * H.x - zH * H.z, frame: H,
            inertia: [IHxx, IHyy, IHzz, 0, 0, -IHxz] };
        body front_wheel { mass: mF, center: PF, frame: WF, inertia: [IFxx, IFyy, IFxx] };
        gravity -g * N.z;
        rolling rear { wheel: WR, axle: WR.y, center: PR, radius: rR, plane: N.z };
        rolling front { wheel: WF, axle: WF.y, center: PF, radius: rF, plane: N.z };
        outputs linearize(x, y, psi, phi, delta, phiR, phiF; dt(phi), dt(delta), dt(phiR));
    }
}

/// The benchmark's parameters (Meijaard et al. 2007, Table 1).
const BENCHMARK: Bicycle = Bicycle {
    w: 1.02,
    c: 0.08,
    lambda: std::f64::consts::PI / 10.0,
    g: 9.81,
    rR: 0.3,
    mR: 2.0,
    IRxx: 0.0603,
    IRyy: 0.12,
    xB: 0.3,
    zB: -0.9,
    mB: 85.0,
    IBxx: 9.2,
    IByy: 11.0,
    IBzz: 2.8,
    IBxz: 2.4,
    xH: 0.9,
    zH: -0.7,
    mH: 4.0,
    IHxx: 0.05892,
    IHyy: 0.06,
    IHzz: 0.00708,
    IHxz: -0.00756,
    rF: 0.35,
    mF: 3.0,
    IFxx: 0.1405,
    IFyy: 0.28,
};

/// The benchmark's `M`, `C1`, `K0`, `K2` (Meijaard et al. 2007, Table 2,
/// rows and columns `(φ, δ)`).
const MASS: [[f64; 2]; 2] = [
    [80.81722, 2.31941332208709],
    [2.31941332208709, 0.29784188199686],
];
const DAMPING: [[f64; 2]; 2] = [
    [0.0, 33.86641391492494],
    [-0.85035641456978, 1.68540397397560],
];
const STIFFNESS_0: [[f64; 2]; 2] = [
    [-80.95, -2.59951685249872],
    [-2.59951685249872, -0.80329488458618],
];
const STIFFNESS_2: [[f64; 2]; 2] = [[0.0, 76.59734589573222], [0.0, 2.65431523794604]];

/// The benchmark's weave and capsize speeds (m/s).
const WEAVE_SPEED: f64 = 4.29238253634111;
const CAPSIZE_SPEED: f64 = 6.02426201538837;

/// The independent entries of `linearize`'s state: every coordinate but
/// `z` and `theta`, and the speeds of `phi`, `delta`, `phiR`.
const INDEPENDENT: [usize; 10] = [0, 1, 3, 4, 6, 7, 8, 13, 15, 16];

/// Upright straight running along `N.x` at `speed`: the rear wheel centre
/// at height `rR`, the wheels turning at `speed / r`.
fn upright(speed: f64) -> ([f64; 9], [f64; 9]) {
    let b = BENCHMARK;
    let mut q = [0.0; 9];
    q[2] = b.rR;
    let mut v = [0.0; 9];
    v[0] = speed;
    v[7] = speed / b.rR;
    v[8] = speed / b.rF;
    (q, v)
}

/// Eigenvalues sorted by real, then imaginary part, those below 1e-6 in
/// magnitude dropped (the zeros of the cyclic coordinates, which the
/// eigensolver returns as `±√ε`).
fn sorted_nonzero(eigenvalues: impl Iterator<Item = Complex<f64>>) -> Vec<Complex<f64>> {
    let mut kept: Vec<Complex<f64>> = eigenvalues.filter(|z| z.norm() > 1e-6).collect();
    kept.sort_by(|p, q| p.re.total_cmp(&q.re).then(p.im.total_cmp(&q.im)));
    kept
}

/// Ours: the nonzero eigenvalues of the reduced `A` at `speed`.
fn our_eigenvalues(speed: f64) -> Vec<Complex<f64>> {
    let (q, v) = upright(speed);
    let (a, _) = BENCHMARK.linearize(0.0, &q, &v, &[]).expect("linearisable");
    let reduced = SMatrix::<f64, 10, 10>::from_fn(|i, j| a[INDEPENDENT[i]][INDEPENDENT[j]]);
    sorted_nonzero(reduced.complex_eigenvalues().iter().copied())
}

/// The benchmark's: the eigenvalues of `[[0, 1], [−M⁻¹ (g K0 + v² K2), −M⁻¹ v C1]]`.
fn benchmark_eigenvalues(speed: f64) -> Vec<Complex<f64>> {
    let m = SMatrix::<f64, 2, 2>::from_fn(|i, j| MASS[i][j]);
    let inverse = m.try_inverse().expect("invertible");
    let stiffness = SMatrix::<f64, 2, 2>::from_fn(|i, j| {
        BENCHMARK.g * STIFFNESS_0[i][j] + speed * speed * STIFFNESS_2[i][j]
    });
    let damping = SMatrix::<f64, 2, 2>::from_fn(|i, j| speed * DAMPING[i][j]);
    let (k, d) = (-inverse * stiffness, -inverse * damping);
    let a = SMatrix::<f64, 4, 4>::from_fn(|i, j| match (i, j) {
        (0, 2) | (1, 3) => 1.0,
        (2..=3, 0..=1) => k[(i - 2, j)],
        (2..=3, 2..=3) => d[(i - 2, j - 2)],
        _ => 0.0,
    });
    sorted_nonzero(a.complex_eigenvalues().iter().copied())
}

fn parts(z: &[Complex<f64>]) -> Vec<f64> {
    z.iter().flat_map(|z| [z.re, z.im]).collect()
}

#[test]
fn the_rows_are_two_contacts_and_four_no_slip_rows() {
    assert_eq!((Bicycle::NQ, Bicycle::NC), (9, 6));
    // Three rows per wheel, none vanishing: each wheel leans and steers.
    assert_eq!(
        <Bicycle as dalembert::ConstrainedSystem<9, 9, 0, 6>>::VANISHING_ROWS,
        [false; 6]
    );
    let (q, v) = upright(4.0);
    let residual = BENCHMARK.constraint_residual(0.0, &q);
    let slip = BENCHMARK.constraint_velocity(0.0, &q, &v);
    assert!(residual.iter().chain(&slip).all(|r| r.abs() < 1e-14));
}

#[test]
fn eigenvalues_are_the_benchmarks() {
    for speed in [0.5, 2.0, 4.0, WEAVE_SPEED, 5.0, 6.0, 8.0, 10.0] {
        let (ours, theirs) = (our_eigenvalues(speed), benchmark_eigenvalues(speed));
        assert_eq!(ours.len(), 4, "at {speed} m/s: {ours:?}");
        assert_close(
            &format!("eigenvalues at {speed} m/s"),
            &parts(&ours),
            &parts(&theirs),
            1e-10,
        );
    }
}

/// The weave pair's real part and the capsize root change sign at the
/// benchmark's speeds: unstable below the weave speed, stable between, the
/// capsize root unstable above its speed.
#[test]
fn weave_and_capsize_cross_at_the_benchmarks_speeds() {
    let weave_real = |speed: f64| {
        let pair: Vec<f64> = our_eigenvalues(speed)
            .iter()
            .filter(|z| z.im.abs() > 1e-3)
            .map(|z| z.re)
            .collect();
        assert_eq!(pair.len(), 2, "at {speed} m/s");
        pair[0]
    };
    let capsize = |speed: f64| {
        our_eigenvalues(speed)
            .iter()
            .filter(|z| z.im.abs() < 1e-9)
            .map(|z| z.re)
            .fold(f64::NEG_INFINITY, f64::max)
    };
    assert!(weave_real(WEAVE_SPEED - 1e-3) > 0.0 && weave_real(WEAVE_SPEED + 1e-3) < 0.0);
    assert!(capsize(CAPSIZE_SPEED - 1e-3) < 0.0 && capsize(CAPSIZE_SPEED + 1e-3) > 0.0);
    assert!(weave_real(WEAVE_SPEED).abs() < 1e-9);
}
