"""Independent SymPy references for tests/suite/rolling_wheels.rs: wheels rolling
without slipping, a Chaplygin sleigh, a differential-drive robot and a
two-wheeled self-balancing robot, each built with sympy.physics.mechanics
(`KanesMethod`, speeds u = qdot) from the textbook's contact point, not
from the language's formula:

* a disc whose lean frame `C` (yaw, then roll) has the axle `C.y`: the
  contact point is `G - r C.z` (for a torus `G - r C.z - rt N.z`);
* a wheel on a level axle (the robots): the contact point is `G - r N.z`.

For every model and every stored state (random q, u, inputs; t = 0) it
writes M and f of the unconstrained equations (`M u' = f`), the
constraint rows' A (holonomic rows: dh/dq; nonholonomic: the
coefficients of u), b = -(dA/dt) u and the residual (h for holonomic
rows, 0 for the others), evaluated at 30 digits; and at states on the
constraint manifold, the constrained accelerations of `KanesMethod` with
the rows as configuration and velocity constraints (its `u_dependent`).
For the self-balancing robot it adds `KanesMethod.linearize` (SymPy's
`Linearizer`) about upright motion at a forward speed: the reduced A and
its eigenvalues.

Run: python3 scripts/rolling_wheels_reference.py  (SymPy and mpmath installed)
It writes tests/reference/rolling_wheels.json (SymPy 1.14, mpmath 30 digits).
"""

import json
import random
from pathlib import Path

import mpmath
import sympy as sp
from sympy.physics.mechanics import (
    KanesMethod, Point, ReferenceFrame, RigidBody, dynamicsymbols, inertia,
)

mpmath.mp.dps = 30
DIGITS = 30
random.seed(37)


class Model:
    """A system: coordinates q (speeds u = qdot), bodies, loads, inputs,
    parameters with values, holonomic rows h(q), nonholonomic rows c(q, qdot)."""

    def __init__(self, name, q, bodies, loads, inputs, values, holonomic, nonholonomic, frame):
        self.name, self.q, self.bodies, self.loads = name, q, bodies, loads
        self.inputs, self.values, self.frame = inputs, values, frame
        self.u = [dynamicsymbols(f"u_{qi.name}") for qi in q]
        self.qd = {qi.diff(): ui for qi, ui in zip(q, self.u)}
        self.holonomic = [sp.expand(h) for h in holonomic]
        self.nonholonomic = [c.subs(self.qd) for c in nonholonomic]

    def kd(self):
        return [qi.diff() - ui for qi, ui in zip(self.q, self.u)]

    def unconstrained(self):
        kane = KanesMethod(self.frame, q_ind=self.q, u_ind=self.u, kd_eqs=self.kd())
        kane.kanes_equations(self.bodies, self.loads)
        return kane.mass_matrix, kane.forcing.subs(self.qd)

    def rows(self):
        """A and b of all rows, holonomic first as in the models' order."""
        a = [[sp.diff(h, qi) for qi in self.q] for h in self.holonomic]
        a += [[sp.diff(c, ui) for ui in self.u] for c in self.nonholonomic]
        b = []
        for row in a:
            velocity = sum(ak * uk for ak, uk in zip(row, self.u))
            b.append(-sum(sp.diff(velocity, qj) * uj for qj, uj in zip(self.q, self.u)))
        return sp.Matrix(a), sp.Matrix(b)

    def plain(self):
        """Plain symbols for q, u and inputs (for evaluation)."""
        names = [qi.name for qi in self.q]
        qs = sp.symbols(names)
        us = sp.symbols([f"u_{n}" for n in names])
        ins = sp.symbols([i.name for i in self.inputs]) if self.inputs else []
        swap = dict(zip(self.q, qs)) | dict(zip(self.u, us)) | dict(zip(self.inputs, ins))
        return qs, us, ins, swap

    def evaluate(self, exprs, q, u, inputs):
        qs, us, ins, swap = self.plain()
        at = dict(zip(qs, q)) | dict(zip(us, u)) | dict(zip(ins, inputs))
        at |= {k: v for k, v in self.values.items()}
        out = []
        for e in exprs:
            e = sp.sympify(e).xreplace(swap)
            out.append(float(sp.N(e.xreplace({k: sp.Float(v, DIGITS) for k, v in at.items()}), DIGITS)))
        return out


def random_state(model):
    q = [random.uniform(-1.0, 1.0) for _ in model.q]
    u = [random.uniform(-2.0, 2.0) for _ in model.u]
    inputs = [random.uniform(-1.0, 1.0) for _ in model.inputs]
    return q, u, inputs


def matrix_values(model, matrix, q, u, inputs):
    rows, cols = matrix.shape
    flat = model.evaluate(list(matrix), q, u, inputs)
    return [flat[i * cols:(i + 1) * cols] for i in range(rows)]


def equations(model, count):
    mass, forcing = model.unconstrained()
    a, b = model.rows()
    states = []
    for _ in range(count):
        q, u, inputs = random_state(model)
        states.append({
            "q": q, "v": u, "u": inputs,
            "M": matrix_values(model, mass, q, u, inputs),
            "f": model.evaluate(list(forcing), q, u, inputs),
            "A": matrix_values(model, a, q, u, inputs),
            "b": model.evaluate(list(b), q, u, inputs),
            "residual": model.evaluate(model.holonomic, q, u, inputs) + [0.0] * len(model.nonholonomic),
        })
    return states


def consistent(model, q, u, q_dep, u_dep, inputs):
    """q and u moved onto the manifold: the dependent coordinates solve the
    holonomic rows, the dependent speeds all rows' velocity form."""
    qs, us, ins, swap = model.plain()
    values = {k: sp.Float(v, DIGITS) for k, v in model.values.items()}
    q = list(q)
    dep_q = [model.q.index(d) for d in q_dep]
    if dep_q:
        known = {qs[i]: sp.Float(q[i], DIGITS) for i in range(len(q)) if i not in dep_q}
        eqs = [h.xreplace(swap).xreplace(known | values) for h in model.holonomic]
        unknowns = [qs[i] for i in dep_q]
        root = sp.nsolve(eqs, unknowns, [q[i] for i in dep_q], prec=DIGITS)
        for k, i in enumerate(dep_q):
            q[i] = float(root[k])
    a, _ = model.rows()
    a = a.xreplace(swap).xreplace({qs[i]: sp.Float(q[i], DIGITS) for i in range(len(q))} | values)
    u = list(u)
    dep_u = [model.u.index(d) for d in u_dep]
    ind_u = [i for i in range(len(u)) if i not in dep_u]
    rows = independent_rows(a, len(dep_u))
    a_dep = sp.Matrix([[a[r, i] for i in dep_u] for r in rows])
    rhs = sp.Matrix([-sum(a[r, i] * sp.Float(u[i], DIGITS) for i in ind_u) for r in rows])
    solved = a_dep.LUsolve(rhs)
    for k, i in enumerate(dep_u):
        u[i] = float(solved[k])
    return q, u


def independent_rows(a, count):
    """The first `count` rows of `a` that are independent (a robot's two
    wheels on one axle share their sideways row)."""
    chosen = []
    for r in range(a.rows):
        trial = sp.Matrix([list(a.row(k)) for k in chosen + [r]])
        if trial.rank(iszerofunc=lambda x: abs(x) < 1e-20) == len(chosen) + 1:
            chosen.append(r)
        if len(chosen) == count:
            break
    return chosen


def constrained_kane(model, q_dep, u_dep, rows):
    """KanesMethod with the model's rows (those of `rows`, by index, for the
    velocity constraints) as constraints."""
    q_ind = [qi for qi in model.q if qi not in q_dep]
    u_ind = [ui for ui in model.u if ui not in u_dep]
    velocity = []
    for h in model.holonomic:
        velocity.append(sp.diff(h, dynamicsymbols._t).subs(model.qd))
    velocity += model.nonholonomic
    velocity = [velocity[r] for r in rows]
    kane = KanesMethod(
        model.frame, q_ind=q_ind, u_ind=u_ind, kd_eqs=model.kd(),
        q_dependent=list(q_dep), configuration_constraints=model.holonomic,
        u_dependent=list(u_dep), velocity_constraints=velocity,
    )
    kane.kanes_equations(model.bodies, model.loads)
    return kane, u_ind + list(u_dep)


def constrained_accelerations(model, q_dep, u_dep, count, rows=None):
    rows = rows if rows is not None else list(range(len(model.holonomic) + len(model.nonholonomic)))
    kane, order = constrained_kane(model, q_dep, u_dep, rows)
    mass = kane.mass_matrix_full.subs(model.qd)
    forcing = kane.forcing_full.subs(model.qd)
    n = len(model.q)
    states = []
    for _ in range(count):
        q, u, inputs = random_state(model)
        q, u = consistent(model, q, u, q_dep, u_dep, inputs)
        full = sp.Matrix(matrix_values(model, mass, q, u, inputs))
        rhs = sp.Matrix(model.evaluate(list(forcing), q, u, inputs))
        mpm = mpmath.matrix(full.tolist())
        rates = mpmath.lu_solve(mpm, mpmath.matrix(list(rhs)))
        udot = [0.0] * n
        for k, ui in enumerate(order):
            udot[model.u.index(ui)] = float(rates[n + k])
        states.append({"q": q, "v": u, "u": inputs, "vdot": udot})
    return states


N = ReferenceFrame("N")
O = Point("O")
O.set_vel(N, 0)


def disc_or_torus(torus):
    """A disc (or a torus) with its centre's coordinates, rolling on
    z = 0 (the torus on z = h); a torque T about the axle, drag on the
    torus' centre."""
    x, y, z, psi, th, phi = dynamicsymbols("x y z psi theta phi")
    T = dynamicsymbols("T")
    m, r, g = sp.symbols("m r g")
    A = N.orientnew("A", "Axis", [psi, N.z])
    C = A.orientnew("C", "Axis", [th, A.x])
    B = C.orientnew("B", "Axis", [phi, C.y])
    G = O.locatenew("G", x * N.x + y * N.y + z * N.z)
    values = {m: 0.8, r: 0.3, g: 9.81}
    if torus:
        rt, h, c, Ia, Id = sp.symbols("rt h c Ia Id")
        values |= {rt: 0.05, h: 0.2, c: 0.15, Ia: 0.04, Id: 0.025}
        contact = G.locatenew("Ct", -r * C.z - rt * N.z)
        plane_height = h
        body = RigidBody("torus", G, B, m, (inertia(B, Id, Ia, Id), G))
        loads = [(G, -m * g * N.z - c * G.vel(N)), (B, T * C.y)]
    else:
        contact = G.locatenew("Ct", -r * C.z)
        plane_height = 0
        body = RigidBody("disc", G, B, m, (inertia(B, m * r**2 / 4, m * r**2 / 2, m * r**2 / 4), G))
        loads = [(G, -m * g * N.z), (B, T * C.y)]
    slip = G.vel(N) + B.ang_vel_in(N).cross(contact.pos_from(G))
    model = Model(
        "torus" if torus else "disc", [x, y, z, psi, th, phi], [body], loads, [T], values,
        [contact.pos_from(O).dot(N.z) - plane_height],
        [slip.dot(N.x), slip.dot(N.y)], N,
    )
    return model, [z], [model.u[2], model.u[0], model.u[1]]


def sleigh():
    """A Chaplygin sleigh: the blade at P = (x, y) slips not sideways, the
    centre of mass a ahead of it, a spring k to O, a push F and a turn T."""
    x, y, th = dynamicsymbols("x y theta")
    F, T = dynamicsymbols("F T")
    m, I, a, k = sp.symbols("m I a k")
    B = N.orientnew("B", "Axis", [th, N.z])
    P = O.locatenew("P", x * N.x + y * N.y)
    G = P.locatenew("G", a * B.x)
    body = RigidBody("sleigh", G, B, m, (inertia(B, 0, 0, I), G))
    # The spring's potential k/2 |G - O|^2 as its force.
    loads = [(G, -k * G.pos_from(O)), (P, F * B.x), (B, T * N.z)]
    model = Model(
        "sleigh", [x, y, th], [body], loads, [F, T],
        {m: 2.5, I: 0.3, a: 0.4, k: 1.7},
        [], [P.vel(N).dot(B.y)], N,
    )
    return model, [], [model.u[1]]


def robot(balancing):
    """Two wheels (radius r, half-track d) on a level axle whose midpoint
    G0 is at height r, driven by torques TL, TR from the body: the chassis
    (level, centre b ahead) of a differential drive, or the pendulum (pitch
    theta, centre l above the axle) of a self-balancing robot."""
    names = "x y psi theta phiL phiR" if balancing else "x y psi phiL phiR"
    q = dynamicsymbols(names)
    x, y, psi = q[:3]
    phiL, phiR = q[-2:]
    TL, TR = dynamicsymbols("TL TR")
    mb, mw, Iwa, Iwd, r, d, g = sp.symbols("mb mw Iwa Iwd r d g")
    values = {mb: 12.0, mw: 1.1, Iwa: 0.012, Iwd: 0.007, r: 0.15, d: 0.25, g: 9.81}
    A = N.orientnew("A", "Axis", [psi, N.z])
    WL = A.orientnew("WL", "Axis", [phiL, A.y])
    WR = A.orientnew("WR", "Axis", [phiR, A.y])
    G0 = O.locatenew("G0", x * N.x + y * N.y + r * N.z)
    PL = G0.locatenew("PL", d * A.y)
    PR = G0.locatenew("PR", -d * A.y)
    if balancing:
        th = q[3]
        l, Ibx, Iby, Ibz = sp.symbols("l Ibx Iby Ibz")
        values |= {l: 0.45, Ibx: 0.9, Iby: 0.8, Ibz: 0.35}
        Bd = A.orientnew("Bd", "Axis", [th, A.y])
        GB = G0.locatenew("GB", l * Bd.z)
        chassis = RigidBody("pendulum", GB, Bd, mb, (inertia(Bd, Ibx, Iby, Ibz), GB))
        reacting = Bd
    else:
        b, Ib = sp.symbols("b Ib")
        values |= {b: 0.12, Ib: 0.6}
        GB = G0.locatenew("GB", b * A.x)
        chassis = RigidBody("chassis", GB, A, mb, (inertia(A, Ib / 2, Ib / 2, Ib), GB))
        reacting = A
    left = RigidBody("left", PL, WL, mw, (inertia(WL, Iwd, Iwa, Iwd), PL))
    right = RigidBody("right", PR, WR, mw, (inertia(WR, Iwd, Iwa, Iwd), PR))
    loads = [
        (GB, -mb * g * N.z), (PL, -mw * g * N.z), (PR, -mw * g * N.z),
        (WL, TL * A.y), (WR, TR * A.y), (reacting, -(TL + TR) * A.y),
    ]
    slip_left = PL.vel(N) + WL.ang_vel_in(N).cross(-r * N.z)
    slip_right = PR.vel(N) + WR.ang_vel_in(N).cross(-r * N.z)
    if balancing:
        rows = [slip_left.dot(N.x), slip_left.dot(N.y), slip_right.dot(A.x)]
    else:
        rows = [slip_left.dot(N.x), slip_left.dot(N.y), slip_right.dot(N.x), slip_right.dot(N.y)]
    model = Model(
        "balancing_robot" if balancing else "differential_drive", list(q),
        [chassis, left, right], loads, [TL, TR], values, [], rows, N,
    )
    u = model.u
    return model, [], [u[0], u[1], u[2]]


def balancing_linearization(model, speed):
    """KanesMethod.linearize about upright motion along N.x at `speed`:
    the reduced A (states q, then u_theta, u_phiL, u_phiR) and its eigenvalues."""
    u = model.u
    kane, order = constrained_kane(model, [], [u[0], u[1], u[2]], [0, 1, 2])
    r = [k for k in model.values if k.name == "r"][0]
    spin = speed / model.values[r]
    op = {qi: 0.0 for qi in model.q}
    op |= {u[0]: speed, u[1]: 0.0, u[2]: 0.0, u[3]: 0.0, u[4]: spin, u[5]: spin}
    op |= {i: 0.0 for i in model.inputs}
    qd_op = {qi.diff(): op[ui] for qi, ui in zip(model.q, u)}
    ud_op = {ui.diff(): 0.0 for ui in u}
    a, _, _ = kane.linearize(op_point=[op, qd_op, ud_op, model.values], A_and_B=True)
    a = sp.Matrix(a).evalf(DIGITS)
    eigen = mpmath.eig(mpmath.matrix(a.tolist()), left=False, right=False)
    return {
        "speed": speed,
        "q": [0.0] * len(model.q),
        "v": [speed, 0.0, 0.0, 0.0, spin, spin],
        "reduced_A": [[float(v) for v in row] for row in a.tolist()],
        "eigenvalues": [[float(mpmath.re(e)), float(mpmath.im(e))] for e in eigen],
    }


def main():
    out = {"tools": f"SymPy {sp.__version__}, mpmath {mpmath.__version__}, {DIGITS} digits", "systems": {}}
    for build, extra in [
        (lambda: disc_or_torus(False), None),
        (lambda: disc_or_torus(True), None),
        (sleigh, None),
        (lambda: robot(False), [0, 1, 2]),
        (lambda: robot(True), None),
    ]:
        model, q_dep, u_dep = build()
        entry = {
            "coordinates": [qi.name for qi in model.q],
            "inputs": [i.name for i in model.inputs],
            "parameters": {k.name: v for k, v in model.values.items()},
            "states": equations(model, 4),
            "constrained": constrained_accelerations(model, q_dep, u_dep, 3, extra),
        }
        if model.name == "balancing_robot":
            entry["linearization"] = [balancing_linearization(model, s) for s in (0.8, 2.0)]
        out["systems"][model.name] = entry
        print(model.name, "done", flush=True)
    path = Path(__file__).resolve().parent.parent / "tests/reference/rolling_wheels.json"
    path.write_text(json.dumps(out, indent=1) + "\n")


if __name__ == "__main__":
    main()
