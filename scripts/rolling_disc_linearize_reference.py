"""SymPy's own linearisation of the rolling disc of tests/suite/rolling_disc.rs
(`RollingDisc`), a thin uniform disc rolling without slipping on a
horizontal plane (two nonholonomic rows), about a leaning, turning state on
its constraint manifold: `KanesMethod(...).linearize(A_and_B=True)` with
every coordinate (x, y, psi, theta, phi) independent, the speeds of psi,
theta and phi independent and those of x and y dependent.

Run: ~/.cache/dal-venv/bin/python scripts/rolling_disc_linearize_reference.py
It prints the reduced A (states x, y, psi, theta, phi, u_psi, u_theta,
u_phi) that the test copies (SymPy 1.14).
"""

import sympy as sp
from sympy.physics.mechanics import (
    KanesMethod, Point, ReferenceFrame, RigidBody, dynamicsymbols, inertia,
)

m, r, g = sp.symbols("m r g")
x, y, psi, th, phi = dynamicsymbols("x y psi theta phi")
ux, uy, upsi, uth, uphi = dynamicsymbols("u_x u_y u_psi u_theta u_phi")

N = ReferenceFrame("N")
A = N.orientnew("A", "Axis", [psi, N.z])
C = A.orientnew("C", "Axis", [th, A.x])
B = C.orientnew("B", "Axis", [phi, C.y])
A.set_ang_vel(N, upsi * N.z)
C.set_ang_vel(A, uth * A.x)
B.set_ang_vel(C, uphi * C.y)
O = Point("O")
O.set_vel(N, 0)
contact = O.locatenew("contact", x * N.x + y * N.y)
contact.set_vel(N, ux * N.x + uy * N.y)
G = contact.locatenew("G", r * C.z)
G.v2pt_theory(contact, N, C)

disc = RigidBody(
    "disc", G, B, m, (inertia(C, m * r**2 / 4, m * r**2 / 2, m * r**2 / 4), G)
)
kane = KanesMethod(
    N,
    q_ind=[x, y, psi, th, phi],
    u_ind=[upsi, uth, uphi],
    u_dependent=[ux, uy],
    kd_eqs=[
        x.diff() - ux, y.diff() - uy, psi.diff() - upsi,
        th.diff() - uth, phi.diff() - uphi,
    ],
    velocity_constraints=[
        ux - r * sp.cos(psi) * uphi,
        uy - r * sp.sin(psi) * uphi,
    ],
)
kane.kanes_equations([disc], [(G, -m * g * N.z)])

# The state of the test: leaning, turning and spinning, rolling.
values = {m: 0.8, r: 0.3, g: 9.81}
heading, spin = 0.4, 6.0
rolling = 0.3 * spin
op = {
    x: 0.1, y: 0.2, psi: heading, th: 0.3, phi: 0.5,
    upsi: 1.0, uth: 0.2, uphi: spin,
    ux: rolling * sp.cos(heading), uy: rolling * sp.sin(heading),
}
qd_op = {q.diff(): op[u] for q, u in [(x, ux), (y, uy), (psi, upsi), (th, uth), (phi, uphi)]}
# The linearisation holds the accelerations at their values at the state:
# those of the full equations (kinematic, dynamic and the rows' derivative).
at = {**op, **qd_op, **values}
rates = kane.mass_matrix_full.subs(at).LUsolve(kane.forcing_full.subs(at))
ud_op = {u.diff(): rates[5 + k] for k, u in enumerate([upsi, uth, uphi, ux, uy])}
op_point = [op, qd_op, ud_op, values]
A_, B_, inputs = kane.linearize(op_point=op_point, A_and_B=True)
A_ = sp.Matrix(A_).evalf(17)
print("states", [x, y, psi, th, phi, upsi, uth, uphi])
print("A =")
for row in A_.tolist():
    print("    [" + ", ".join(repr(float(v)) for v in row) + "],")
