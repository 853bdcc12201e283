"""Taylor coefficients of the motion of `generated/models/taylor_functions.dal`
through one state, from SymPy: Lagrange's equations of the particle written
here apart from the engine, x'' solved, and its derivatives along the flow
(d/dt = ∂t + ẋ ∂x + ẍ ∂ẋ) evaluated at 30 digits. Prints the coefficients
that `tests/suite/taylor.rs` expects: q_k = x⁽ᵏ⁾/k!, v_k = x⁽ᵏ⁺¹⁾/k!.

    python3 scripts/taylor_functions_reference.py
"""
import sympy as sp

t, x, xd, xdd = sp.symbols("t x xd xdd")
m, k, c, F = sp.Rational(3, 2), sp.Rational(7, 10), sp.Rational(3, 10), sp.Rational(2, 5)
state = {t: sp.Rational(1, 5), x: sp.Rational(4, 5), xd: sp.Rational(-3, 10)}
ORDER = 6

# The particle at (x, sin x) in the plane.
T = m / 2 * xd**2 * (1 + sp.cos(x) ** 2)
V = k * (sp.sqrt(1 + x**2) + sp.exp(x / 4) + sp.log(2 + x**2) + sp.tan(x / 3)
         + (5 - x) + 1 / (3 + x) ** 2)  # |x - 5| = 5 - x near the state
D = c * xd**2 / 2
Q = F + sp.cos(t)
L = T - V


def along(e, acceleration):
    """d/dt of e(t, x, ẋ) along the flow."""
    return sp.diff(e, t) + xd * sp.diff(e, x) + acceleration * sp.diff(e, xd)


p = sp.diff(L, xd)
lagrange = along(p, xdd) - sp.diff(L, x) + sp.diff(D, xd) - Q
acceleration = sp.solve(lagrange, xdd)[0]

derivatives = [x, xd, acceleration]
while len(derivatives) < ORDER + 2:
    derivatives.append(along(derivatives[-1], acceleration))
values = [sp.N(d.subs(state), 30) for d in derivatives]
q = [values[j] / sp.factorial(j) for j in range(ORDER + 1)]
v = [values[j + 1] / sp.factorial(j) for j in range(ORDER + 1)]
print("q:", ", ".join(f"{sp.N(e, 20)}" for e in q))
print("v:", ", ".join(f"{sp.N(e, 20)}" for e in v))
