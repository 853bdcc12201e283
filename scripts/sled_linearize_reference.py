"""SymPy's own linearisation of the knife-edge sled of
tests/suite/constrained_linearize.rs (`Sled`), a nonholonomic system, about a
state on its constraint manifold: `KanesMethod(...).linearize(A_and_B=True)`
with `x`, `y`, `theta` independent coordinates, the speeds of `x` and
`theta` independent and that of `y` dependent (fixed by the no-slip row).

Run: ~/.cache/dal-venv/bin/python scripts/sled_linearize_reference.py
It prints the reduced A (states x, y, theta, u_x, u_theta) and B (inputs
push, turn) that the test copies; see tests/reference/README_derivatives.md.
"""

import sympy as sp
from sympy.physics.mechanics import (
    KanesMethod, Point, ReferenceFrame, RigidBody, dynamicsymbols, inertia,
)

m, I, c, g = sp.symbols("m I c g")
x, y, th = dynamicsymbols("x y theta")
ux, uy, uth = dynamicsymbols("u_x u_y u_theta")
push, turn = dynamicsymbols("push turn")

N = ReferenceFrame("N")
B = N.orientnew("B", "Axis", [th, N.z])
B.set_ang_vel(N, uth * N.z)
O = Point("O")
O.set_vel(N, 0)
blade = O.locatenew("blade", x * N.x + y * N.y)
blade.set_vel(N, ux * N.x + uy * N.y)
G = blade.locatenew("G", c * B.x)
G.v2pt_theory(blade, N, B)

sled = RigidBody("sled", G, B, m, (inertia(B, 0, 0, I), G))
loads = [
    (G, -m * g * N.y + push * B.x),
    (B, turn * N.z),
]
kane = KanesMethod(
    N,
    q_ind=[x, y, th],
    u_ind=[ux, uth],
    u_dependent=[uy],
    kd_eqs=[x.diff() - ux, y.diff() - uy, th.diff() - uth],
    velocity_constraints=[-sp.sin(th) * ux + sp.cos(th) * uy],
)
kane.kanes_equations([sled], loads)

# The state of the test: on the manifold, moving along the blade.
values = {m: 2.5, I: 0.3, c: 0.4, g: 9.81}
theta, speed, rate = 0.6, 1.5, 0.8
op = {
    x: 0.2, y: -0.1, th: theta,
    ux: speed * sp.cos(theta), uy: speed * sp.sin(theta), uth: rate,
    push: 0.7, turn: -0.2,
}
qd_op = {x.diff(): op[ux], y.diff(): op[uy], th.diff(): op[uth]}
# The linearisation holds the accelerations at their values at the state:
# those of the full equations (kinematic, dynamic and the rows' derivative).
at = {**op, **qd_op, **values}
rates = kane.mass_matrix_full.subs(at).LUsolve(kane.forcing_full.subs(at))
ud_op = {u.diff(): rates[3 + k] for k, u in enumerate([ux, uth, uy])}
op_point = [op, qd_op, ud_op, values]
A, B_, r = kane.linearize(op_point=op_point, A_and_B=True)
A = sp.Matrix(A).evalf(17)
B_ = sp.Matrix(B_).evalf(17)
print("states", [x, y, th, ux, uth], "inputs", r)
print("A =")
for row in A.tolist():
    print("    [" + ", ".join(f"{float(v):.17e}" for v in row) + "],")
print("B =")
for row in B_.tolist():
    print("    [" + ", ".join(f"{float(v):.17e}" for v in row) + "],")
