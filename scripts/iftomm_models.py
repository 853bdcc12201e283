#!/usr/bin/env python3
"""Writes the IFToMM benchmark models in the dalembert language.

    scripts/iftomm_models.py rust > fixtures/src/iftomm.rs   # the fixtures module
    scripts/iftomm_models.py four-bar N > four_bar.dal       # A02 with N windows

Every loop is closed by a `closure` statement. For an independent check of
those statements, A02 (N = 2) and A04 are also written with the same rows
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


def rust():
    models = [
        PENDULUM,
        ANGLE_PENDULUM,
        four_bar(2),
        four_bar(2, equations=True),
        four_bar(10),
        PARALLELOGRAM,
        bricard(),
        bricard(equations=True),
    ]
    out = [
        "//! The IFToMM benchmark problems A01, A02 and A04 (González, Dopico, Lugrís,",
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
    return "\n".join(out)


if __name__ == "__main__":
    if sys.argv[1:2] == ["rust"]:
        print(rust(), end="")
    elif sys.argv[1:2] == ["four-bar"]:
        print(four_bar(int(sys.argv[2])))
    else:
        sys.exit(__doc__)
