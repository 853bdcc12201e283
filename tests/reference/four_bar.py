"""The crank-rocker four-bar of `tests/suite/loop_rows.rs` in its one independent
coordinate, integrated by SciPy: the reference `four_bar.json`.

Independent of dalembert: the position analysis is solved in closed form
(the rocker's tip where the coupler's and the rocker's circles meet, the
branch with the tip above the line from the crank's tip to the rocker's
pivot), the generalized mass J(phi) and potential V(phi) are differentiated
by SymPy, and phi'' = -(J'(phi) phi'^2 / 2 + V'(phi)) / J(phi) is integrated
by DOP853 at rtol = atol = 1e-13.

Run: python3 tests/reference/four_bar.py > tests/reference/four_bar.json
(needs sympy, scipy).
"""

import json

import numpy as np
import sympy as sp
from scipy.integrate import solve_ivp

# Parameters: crank a, coupler b, rocker c, ground d; rods of masses m1..m3;
# the coupler point P at p along the coupler and e across it.
PARAMETERS = dict(a=0.1, b=0.35, c=0.3, d=0.4, m1=0.5, m2=0.9, m3=0.7, p=0.2, e=0.08, g=9.81)
PHI0, PHI_DOT0 = 0.5, 12.0
TIMES = [0.25, 0.5, 0.75, 1.0]

phi = sp.symbols("phi")
a, b, c, d, m1, m2, m3, p, e, g = [sp.Float(PARAMETERS[k], 30) for k in
                                   ["a", "b", "c", "d", "m1", "m2", "m3", "p", "e", "g"]]
A = sp.Matrix([a * sp.cos(phi), a * sp.sin(phi)])
to_pivot = sp.Matrix([d, 0]) - A
r = sp.sqrt(to_pivot.dot(to_pivot))
delta = sp.atan2(to_pivot[1], to_pivot[0])
gamma = sp.acos((b**2 + r**2 - c**2) / (2 * b * r))
psi = delta + gamma
B = A + b * sp.Matrix([sp.cos(psi), sp.sin(psi)])
chi = sp.atan2(B[1], B[0] - d)
coupler_x = sp.Matrix([sp.cos(psi), sp.sin(psi)])
coupler_y = sp.Matrix([-sp.sin(psi), sp.cos(psi)])
P = A + p * coupler_x + e * coupler_y

centres = [A / 2, A + b / 2 * coupler_x, sp.Matrix([d, 0]) + c / 2 * sp.Matrix([sp.cos(chi), sp.sin(chi)])]
angles = [phi, psi, chi]
masses = [m1, m2, m3]
lengths = [a, b, c]
J = sum(m * centre.diff(phi).dot(centre.diff(phi)) + m * l**2 / 12 * angle.diff(phi) ** 2
        for m, centre, angle, l in zip(masses, centres, angles, lengths))
V = sum(m * g * centre[1] for m, centre in zip(masses, centres))

numeric = lambda expression: sp.lambdify(phi, expression, "math")
J_, dJ_, dV_ = numeric(J), numeric(J.diff(phi)), numeric(V.diff(phi))
psi_, chi_ = numeric(psi), numeric(chi)
Px_, Py_ = numeric(P[0]), numeric(P[1])
dpsi_, dchi_ = numeric(psi.diff(phi)), numeric(chi.diff(phi))


def rate(_t, y):
    x, v = y
    return [v, -(0.5 * dJ_(x) * v * v + dV_(x)) / J_(x)]


solution = solve_ivp(rate, (0.0, TIMES[-1]), [PHI0, PHI_DOT0], method="DOP853",
                     rtol=1e-13, atol=1e-13, t_eval=TIMES, dense_output=False)
assert solution.success
states = []
for t, x, v in zip(solution.t, solution.y[0], solution.y[1]):

    states.append(dict(t=float(t), phi=float(x), phi_dot=float(v),
                       coupler_point=[float(Px_(x)), float(Py_(x))]))
initial = dict(q=[PHI0, float(psi_(PHI0)), float(chi_(PHI0))],
               v=[PHI_DOT0, float(dpsi_(PHI0)) * PHI_DOT0, float(dchi_(PHI0)) * PHI_DOT0])
energy = lambda x, v: 0.5 * J_(x) * v * v + float(V.subs(phi, x))
print(json.dumps(dict(
    description="crank-rocker four-bar, closed-form position analysis, SciPy DOP853 at 1e-13",
    tools=dict(sympy=sp.__version__, scipy=__import__("scipy").__version__),
    parameters=PARAMETERS, initial=initial, states=states,
    energy=energy(PHI0, PHI_DOT0),
), indent=1))
