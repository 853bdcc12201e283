#!/usr/bin/env python3
"""Writes the IFToMM benchmark models in the dalembert language.

    scripts/iftomm_models.py rust > fixtures/src/iftomm.rs   # the fixtures module
    scripts/iftomm_models.py four-bar N > four_bar.dal       # A02 with N windows
    scripts/iftomm_models.py andrews > andrews.dal           # A03

Every loop is closed by a `closure` statement. For an independent check of
those statements, A02 (N = 2), A03 and A04 are also written with the same rows
as hand-written coordinate equations: for A04 the components, in N's axes,
of the chain's end point and of its last joint axis, multiplied out here
with SymPy from the chain of rotations.
"""

import sys

import sympy as sp


def four_bar(n, equations=False):
    """A02: n four-bar windows, 2n + 1 rods of length L and mass m.

    Crank k (k = 0..n) turns about the ground pivot A_k = (k L, 0) by the
    angle phi_k from N.x; its tip is B_k. Coupler j (j = 1..n) hangs from
    B_(j-1) at the angle psi_j from N.x; its far end E_j is closed on B_j,
    by a `closure` statement or, with `equations`, by the same two rows
    written as coordinate equations.
    """
    if equations:
        name = f"FourBarsEquations{n}"
        closed = "by its two rows written as\n/// coordinate equations (the check of the `closure` statement)."
    else:
        name = f"FourBars{n}"
        closed = "by a `closure` statement\n/// (two rows: the planar model drops the third)."
    lines = [
        f"/// IFToMM benchmark A02 with N = {n}: {n} four-bar windows, {2 * n + 1} uniform",
        "/// rods of length `L` and mass `m`. Crank `k` turns about `(k L, 0)` by",
        "/// `phi_k` from `N.x`; coupler `j` hangs from the tip `B_(j-1)` of crank",
        f"/// `j - 1` at `psi_j`, and its far end `E_j` is closed on the tip `B_j` {closed}",
        f"pub {name} {{",
        "    parameters m, L, g;",
        "    coordinates " + ", ".join([f"phi{k}" for k in range(n + 1)] + [f"psi{j}" for j in range(1, n + 1)]) + ";",
    ]
    for k in range(n + 1):
        pivot = "O" if k == 0 else f"O + {k} * L * N.x"
        lines += [
            f"    frame C{k} = N.rotate_z(phi{k});",
            f"    point B{k} = {pivot} + L * C{k}.x;",
            f"    point G{k} = {pivot} + L/2 * C{k}.x;",
            f"    body crank{k} {{ mass: m, center: G{k}, frame: C{k}, inertia: [0, 0, m*L^2/12] }};",
        ]
    for j in range(1, n + 1):
        lines += [
            f"    frame D{j} = N.rotate_z(psi{j});",
            f"    point H{j} = B{j - 1} + L/2 * D{j}.x;",
            f"    body coupler{j} {{ mass: m, center: H{j}, frame: D{j}, inertia: [0, 0, m*L^2/12] }};",
        ]
    lines.append("    gravity -g * N.y;")
    for j in range(1, n + 1):
        if equations:
            lines += [
                f"    constraint L*cos(phi{j - 1}) + L*cos(psi{j}) == L + L*cos(phi{j});",
                f"    constraint L*sin(phi{j - 1}) + L*sin(psi{j}) == L*sin(phi{j});",
            ]
        else:
            lines += [
                f"    point E{j} = B{j - 1} + L * D{j}.x;",
                f"    closure window{j} {{ at: E{j}, to: B{j} }};",
            ]
    lines.append("}")
    return "\n".join(lines)


def language(expr):
    """A SymPy expression in the language's syntax."""
    return sp.sstr(expr).replace("**", "^")


def bricard_closure():
    """The five closure rows of the Bricard chain, as language expressions."""
    q = sp.symbols("q1:6")
    L = sp.Symbol("L")

    def rot(axis, a):
        c, s = sp.cos(a), sp.sin(a)
        return {
            "x": sp.Matrix([[1, 0, 0], [0, c, -s], [0, s, c]]),
            "y": sp.Matrix([[c, 0, s], [0, 1, 0], [-s, 0, c]]),
            "z": sp.Matrix([[c, -s, 0], [s, c, 0], [0, 0, 1]]),
        }[axis]

    axes = ["y", "z", "x", "y", "z"]
    links = [(0, 1), (1, 1), (2, 1), (0, -1), (1, -1)]  # (axis index, sign) of each rod in its frame
    r = sp.eye(3)
    tip = sp.zeros(3, 1)
    for axis, a, (i, sign) in zip(axes, q, links):
        r = r * rot(axis, a)
        tip = tip + sign * L * r[:, i]
    last_axis = r[:, 0]
    rows = [
        (tip[0], "0"),
        (tip[1], "0"),
        (tip[2], "L"),
        (last_axis[1], "0"),
        (last_axis[2], "0"),
    ]
    return [f"    constraint {language(lhs)} == {rhs};" for lhs, rhs in rows]


def bricard(equations=False):
    name, closed = (
        ("BricardEquations", "as coordinate equations (the check of the `closure` statement)")
        if equations
        else ("Bricard", "by a revolute `closure`")
    )
    lines = [
        "/// IFToMM benchmark A04: Bricard's mechanism, five uniform slender rods of",
        "/// length `L` and mass `m` joined by revolute joints into a closed loop with",
        "/// the ground (six joints). Joint angles `q1..q5` from the configuration where",
        "/// the rods run along the edges of a cube: rod 1 from `O` along `N.x` (joint",
        "/// axis `N.y`), rod 2 along `y`, rod 3 along `z`, rod 4 along `-x`, rod 5 along",
        "/// `-y` to the ground joint at `(0, 0, L)` with axis `N.x`; consecutive joint",
        "/// axes are perpendicular. Five closure rows (the tip on the ground joint, the",
        "/// last axis along `N.x`) on five coordinates: Grübler counts 0 degrees of",
        "/// freedom; the rows have rank 4 and the mechanism moves with 1. The loop is",
        f"/// closed {closed}.",
        f"pub {name} {{",
        "    parameters m, L, g;",
        "    coordinates q1, q2, q3, q4, q5;",
        "    frame F1 = N.rotate_y(q1);",
        "    frame F2 = F1.rotate_z(q2);",
        "    frame F3 = F2.rotate_x(q3);",
        "    frame F4 = F3.rotate_y(q4);",
        "    frame F5 = F4.rotate_z(q5);",
        "    point P1 = O + L * F1.x;",
        "    point P2 = P1 + L * F2.y;",
        "    point P3 = P2 + L * F3.z;",
        "    point P4 = P3 - L * F4.x;",
        "    point G1 = O + L/2 * F1.x;",
        "    point G2 = P1 + L/2 * F2.y;",
        "    point G3 = P2 + L/2 * F3.z;",
        "    point G4 = P3 - L/2 * F4.x;",
        "    point G5 = P4 - L/2 * F5.y;",
        "    body rod1 { mass: m, center: G1, frame: F1, inertia: [0, m*L^2/12, m*L^2/12] };",
        "    body rod2 { mass: m, center: G2, frame: F2, inertia: [m*L^2/12, 0, m*L^2/12] };",
        "    body rod3 { mass: m, center: G3, frame: F3, inertia: [m*L^2/12, m*L^2/12, 0] };",
        "    body rod4 { mass: m, center: G4, frame: F4, inertia: [0, m*L^2/12, m*L^2/12] };",
        "    body rod5 { mass: m, center: G5, frame: F5, inertia: [m*L^2/12, 0, m*L^2/12] };",
        "    gravity -g * N.y;",
    ]
    if equations:
        lines += bricard_closure()
    else:
        lines += [
            "    point P5 = P4 - L * F5.y;",
            "    point J = O + L * N.z;",
            "    closure ground { at: P5, to: J, axis: F5.x, along: N.x };",
        ]
    lines.append("}")
    return "\n".join(lines)


def andrews(equations=False):
    """A03: Andrews' squeezing mechanism (Schiehlen; Hairer and Wanner,
    Solving ODEs II, section VII.7), seven bodies in the plane, seven angles,
    three loops closed on the point E of the crank's coupler (six rows)."""
    name, closed = (
        ("AndrewsEquations", "as coordinate equations (the check of the `closure` statements)")
        if equations
        else ("Andrews", "by three `closure` statements")
    )
    lines = [
        "/// IFToMM benchmark A03: Andrews' squeezing mechanism. Seven bodies in the",
        "/// plane driven by the torque `mom` on the crank `K1` (about `O`, angle `beta`);",
        "/// the coupler `K2` (`Theta` from the crank) carries the point `E`, joined to",
        "/// the rocker `K3` (about `B`, `gamma`, pulled by a spring of stiffness `c0` and",
        "/// rest length `l0` from its point `D` to `C`) and to the two dyads `K4, K5`",
        "/// (about `A`, `delta` and `Phi`) and `K6, K7` (about `A`, `epsilon` and",
        f"/// `Omega`). Its three loops are closed {closed}.",
        f"pub {name} {{",
        "    parameters m1, m2, m3, m4, m5, m6, m7, I1, I2, I3, I4, I5, I6, I7,",
        "        xa, ya, xb, yb, xc, yc, c0, d, da, e, ea, rr, ra, l0, ss, sa, sb, sc, sd,",
        "        ta, tb, u, ua, ub, zf, zt, fa, mom;",
        "    coordinates beta, Theta, gamma, Phi, delta, Omega, epsilon;",
        "    point A = O + xa * N.x + ya * N.y;",
        "    point B = O + xb * N.x + yb * N.y;",
        "    frame K1 = N.rotate_z(beta);",
        "    point F = O + rr * K1.x;",
        "    body crank { mass: m1, center: O + ra * K1.x, frame: K1, inertia: [0, 0, I1] };",
        "    frame K2 = K1.rotate_z(Theta);",
        "    point E = F - d * K2.x;",
        "    body coupler { mass: m2, center: F - da * K2.x, frame: K2, inertia: [0, 0, I2] };",
        "    frame K3 = N.rotate_z(gamma);",
        "    point E3 = B - ss * K3.y;",
        "    point D = B + sd * K3.x - sc * K3.y;",
        "    body rocker { mass: m3, center: B + sa * K3.x + sb * K3.y, frame: K3, inertia: [0, 0, I3] };",
        "    potential c0/2 * (sqrt((sd*cos(gamma) + sc*sin(gamma) + xb - xc)^2",
        "        + (sd*sin(gamma) - sc*cos(gamma) + yb - yc)^2) - l0)^2;",
        "    frame K5 = N.rotate_z(delta);",
        "    point H = A + zt * K5.x;",
        "    body link5 { mass: m5, center: A + ta * K5.x + tb * K5.y, frame: K5, inertia: [0, 0, I5] };",
        "    frame K4 = K5.rotate_z(Phi);",
        "    point E4 = H - e * K4.y;",
        "    body link4 { mass: m4, center: H - (e - ea) * K4.y, frame: K4, inertia: [0, 0, I4] };",
        "    frame K7 = N.rotate_z(epsilon);",
        "    point I = A - u * K7.y;",
        "    body link7 { mass: m7, center: A + ua * K7.x + ub * K7.y, frame: K7, inertia: [0, 0, I7] };",
        "    frame K6 = K7.rotate_z(Omega);",
        "    point E6 = I + zf * K6.x;",
        "    body link6 { mass: m6, center: I + (zf - fa) * K6.x, frame: K6, inertia: [0, 0, I6] };",
        "    torque mom * N.z on K1;",
    ]
    if equations:
        crank = "rr*cos(beta) - d*cos(beta + Theta)", "rr*sin(beta) - d*sin(beta + Theta)"
        lines += [
            f"    constraint {crank[0]} - ss*sin(gamma) - xb == 0;",
            f"    constraint {crank[1]} + ss*cos(gamma) - yb == 0;",
            f"    constraint {crank[0]} - e*sin(Phi + delta) - zt*cos(delta) - xa == 0;",
            f"    constraint {crank[1]} + e*cos(Phi + delta) - zt*sin(delta) - ya == 0;",
            f"    constraint {crank[0]} - zf*cos(Omega + epsilon) - u*sin(epsilon) - xa == 0;",
            f"    constraint {crank[1]} - zf*sin(Omega + epsilon) + u*cos(epsilon) - ya == 0;",
        ]
    else:
        lines += [
            "    closure rocker_joint { at: E, to: E3 };",
            "    closure upper_dyad { at: E, to: E4 };",
            "    closure lower_dyad { at: E, to: E6 };",
        ]
    lines.append("}")
    return "\n".join(lines)


PENDULUM = """/// IFToMM benchmark A01: a point mass `m` on a massless rod of length `l`, in
/// Cartesian coordinates held on the circle by one constraint row.
pub CartesianPendulum {
    parameters m, l, g;
    coordinates x, y;
    point P = O + x * N.x + y * N.y;
    particle bob { mass: m, at: P };
    gravity -g * N.y;
    constraint x^2 + y^2 == l^2;
}"""

ANGLE_PENDULUM = """/// The A01 pendulum in its angle from `N.x` (the independent reference).
pub AnglePendulum {
    parameters m, l, g;
    coordinates theta;
    frame B = N.rotate_z(theta);
    point P = O + l * B.x;
    particle bob { mass: m, at: P };
    gravity -g * N.y;
}"""

PARALLELOGRAM = """/// The A02 motion that keeps every crank parallel (`phi_k = phi`, couplers
/// level): `n + 1` cranks turning together and `n` couplers translating with
/// the crank tips, a one-coordinate system (the independent reference).
pub Parallelogram {
    parameters m, L, g, n;
    coordinates phi;
    frame C = N.rotate_z(phi);
    point G = O + L/2 * C.x;
    point B = O + L * C.x;
    body cranks { mass: (n + 1) * m, center: G, frame: C, inertia: [0, 0, (n + 1)*m*L^2/12] };
    particle couplers { mass: n * m, at: B };
    gravity -g * N.y;
}"""


FOUR_BAR_START = """/// The A02 start of a mechanism with `NQ = 2N + 1` coordinates and unit
/// rods: cranks upright, couplers level, the tip `B0` of the first crank
/// moving at 1 m/s along `N.x` (every crank turning at −1 rad/s).
pub fn four_bar_start<const NQ: usize>() -> dalembert::State<NQ, NQ> {
    let cranks = NQ.div_ceil(2);
    dalembert::State {
        t: 0.0,
        q: std::array::from_fn(|i| {
            if i < cranks {
                std::f64::consts::FRAC_PI_2
            } else {
                0.0
            }
        }),
        v: std::array::from_fn(|i| if i < cranks { -1.0 } else { 0.0 }),
    }
}
"""


ANDREWS_DATA = """/// Andrews' squeezer with the data of Hairer and Wanner (Solving ODEs II,
/// section VII.7) in SI units, as the struct `$system`.
macro_rules! andrews_data {
    ($system:ident) => {
        $system {
            m1: 0.04325, m2: 0.00365, m3: 0.02373, m4: 0.00706, m5: 0.07050, m6: 0.00706, m7: 0.05498,
            I1: 2.194e-6, I2: 4.410e-7, I3: 5.255e-6, I4: 5.667e-7, I5: 1.169e-5, I6: 5.667e-7, I7: 1.912e-5,
            xa: -0.06934, ya: -0.00227, xb: -0.03635, yb: 0.03273, xc: 0.014, yc: 0.072,
            c0: 4530.0, d: 28e-3, da: 115e-4, e: 2e-2, ea: 1421e-5, rr: 7e-3, ra: 92e-5,
            l0: 7785e-5, ss: 35e-3, sa: 1874e-5, sb: 1043e-5, sc: 18e-3, sd: 2e-2,
            ta: 2308e-5, tb: 916e-5, u: 4e-2, ua: 1228e-5, ub: 449e-5, zf: 2e-2, zt: 4e-2,
            fa: 1421e-5, mom: 33e-3,
        }
    };
}

/// A03 with the benchmark's data, its loops closed by `closure` statements.
pub const ANDREWS: Andrews = andrews_data!(Andrews);

/// A03 with the benchmark's data, its loops written as coordinate equations.
pub const ANDREWS_EQUATIONS: AndrewsEquations = andrews_data!(AndrewsEquations);

/// The consistent start of A03 at rest (Hairer and Wanner's initial values,
/// rounded to `f64`):
/// `beta, Theta, gamma, Phi, delta, Omega, epsilon`.
pub fn andrews_start() -> dalembert::State<7, 7> {
    dalembert::State {
        t: 0.0,
        q: [
            -0.06171389001427645,
            0.0,
            0.45527981916307037,
            0.22266839016588588,
            0.48736497954384256,
            -0.22266839016588588,
            1.2305474445498212,
        ],
        v: [0.0; 7],
    }
}
"""

def rust():
    models = [
        PENDULUM,
        ANGLE_PENDULUM,
        four_bar(2),
        four_bar(2, equations=True),
        four_bar(10),
        four_bar(40),
        PARALLELOGRAM,
        andrews(),
        andrews(equations=True),
        bricard(),
        bricard(equations=True),
    ]
    out = [
        "//! The IFToMM benchmark problems A01 to A04 (González, Dopico, Lugrís,",
        "//! Cuadrado, Multibody System Dynamics 15, 2006) written in the language,",
        "//! their loops closed by `closure` statements; the same loops written as",
        "//! coordinate equations, to check those statements; and the one-coordinate",
        "//! systems that serve as independent references.",
        "//!",
        "//! Written by `scripts/iftomm_models.py rust`; edit the script, not this file.",
        "",
        "#![allow(non_snake_case)]",
        "",
    ]
    for model in models:
        out.append("dalembert::dalembert! {")
        out += ["    " + line if line else line for line in model.splitlines()]
        out.append("}")
        out.append("")
    out.append(FOUR_BAR_START)
    out.append(ANDREWS_DATA)
    return "\n".join(out)


if __name__ == "__main__":
    if sys.argv[1:2] == ["rust"]:
        print(rust(), end="")
    elif sys.argv[1:2] == ["andrews"]:
        print(andrews())
    elif sys.argv[1:2] == ["four-bar"]:
        print(four_bar(int(sys.argv[2])))
    else:
        sys.exit(__doc__)
