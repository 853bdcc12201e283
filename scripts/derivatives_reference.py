#!/usr/bin/env python3
"""Pinocchio's analytical derivatives for the reference chains and two URDF robots.

At random states of the planar and spatial chains of tests/reference/README_chains.md
(n = 2, 6, 12; built here from that description, no torques: the chain models have no
inputs) and of the panda and ur5 robots of tests/reference/urdf/ (random torques), this
script records Pinocchio's `computeABADerivatives` (dq̈/dq, dq̈/dv, dq̈/dτ = M⁻¹) and
`computeRNEADerivatives` (dτ/dq, dτ/dv, dτ/da = M, at a random acceleration a) into
tests/reference/derivatives.json, every matrix row by row, in dalembert's coordinate
order (the robots' as in scripts/urdf_reference.py).

usage (in a Python environment with `pin` and `numpy`, e.g. the peers' venv):
    python scripts/derivatives_reference.py [--out tests/reference/derivatives.json]
"""
import argparse
import math
import os
import sys

import numpy as np
import pinocchio as pin

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from urdf_reference import ROBOTS, coordinate_order, write_document  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
STATES = 5
SEED = 20261124
LINKS = [2, 6, 12]


def chain(family, n):
    """The chain of README_chains.md: link i (1-based) a uniform rod of mass 1 + i/10 and
    length 1/2 + i/20, no inertia about its axis, joint i+1 at its far end."""
    model = pin.Model()
    parent, placement = 0, pin.SE3.Identity()
    for i in range(1, n + 1):
        mass, length = 1.0 + 0.1 * i, 0.5 + 0.05 * i
        if family == "planar":
            joint, rod = pin.JointModelRZ(), np.array([0.0, -1.0, 0.0])
        else:
            joint = pin.JointModelRZ() if i % 2 == 1 else pin.JointModelRY()
            rod = np.array([1.0, 0.0, 0.0])
        jid = model.addJoint(parent, joint, placement, f"q{i}")
        transverse = mass * length**2 / 12.0
        inertia = np.diag([transverse if r == 0.0 else 0.0 for r in rod])
        model.appendBodyToJoint(jid, pin.Inertia(mass, rod * length / 2.0, inertia), pin.SE3.Identity())
        parent, placement = jid, pin.SE3(np.eye(3), rod * length)
    model.gravity.linear = np.array([0.0, -9.81, 0.0] if family == "planar" else [0.0, 0.0, -9.81])
    return model


def derivatives(model, q, v, tau, a, perm):
    """Both derivative sets at one state, permuted into dalembert's order."""
    data = model.createData()
    pin.computeABADerivatives(model, data, q, v, tau)
    ddq_dq, ddq_dv = data.ddq_dq.copy(), data.ddq_dv.copy()
    minv = data.Minv.copy()
    minv = np.triu(minv) + np.triu(minv, 1).T
    qdd = pin.aba(model, model.createData(), q, v, tau)
    data = model.createData()
    pin.computeRNEADerivatives(model, data, q, v, a)
    dtau_dq, dtau_dv = data.dtau_dq.copy(), data.dtau_dv.copy()
    mass = data.M.copy()
    mass = np.triu(mass) + np.triu(mass, 1).T
    # Self-checks: M⁻¹ M = 1, and the two derivative sets agree (∂q̈/∂x = −M⁻¹ ∂τ/∂x at q̈).
    assert np.allclose(minv @ mass, np.eye(model.nv), atol=1e-9)
    data = model.createData()
    pin.computeRNEADerivatives(model, data, q, v, qdd)
    assert np.allclose(ddq_dq, -minv @ data.dtau_dq, atol=1e-8 * max(1.0, np.abs(ddq_dq).max()))
    rows = lambda m: [[float(x) for x in row] for row in m[np.ix_(perm, perm)]]
    floats = lambda x: [float(y) for y in x[perm]]
    return {
        "qdd": floats(qdd), "vdot": floats(a),
        "ddq_dq": rows(ddq_dq), "ddq_dv": rows(ddq_dv), "ddq_dtau": rows(minv),
        "dtau_dq": rows(dtau_dq), "dtau_dv": rows(dtau_dv), "dtau_da": rows(mass),
    }


def chain_entry(family, n, rng):
    model = chain(family, n)
    perm = np.arange(n)
    states = []
    for _ in range(STATES):
        q = rng.uniform(-math.pi, math.pi, n)
        v = rng.uniform(-2.0, 2.0, n)
        a = rng.uniform(-5.0, 5.0, n)
        entry = {"q": [float(x) for x in q], "qd": [float(x) for x in v], "tau": [0.0] * n}
        entry.update(derivatives(model, q, v, np.zeros(n), a, perm))
        states.append(entry)
    return {"model": f"{family}_chain_{n:02}", "nv": n, "states": states}


def robot_entry(file, rng):
    path = os.path.join(ROBOTS, file)
    model = pin.buildModelFromUrdf(path)
    order = coordinate_order(path)
    joints = [model.joints[model.getJointId(name)] for name in order]
    assert all(j.nq == 1 for j in joints), "one angle or slide per joint"
    perm = np.array([j.idx_v for j in joints])
    states = []
    for _ in range(STATES):
        q, v, tau, a = (rng.uniform(lo, hi, model.nv) for lo, hi in
                        [(-math.pi, math.pi), (-2.0, 2.0), (-10.0, 10.0), (-5.0, 5.0)])
        qp, vp, taup, ap = (np.zeros(model.nv) for _ in range(4))
        qp[perm], vp[perm], taup[perm], ap[perm] = q, v, tau, a
        entry = {"q": [float(x) for x in q], "qd": [float(x) for x in v], "tau": [float(x) for x in tau]}
        entry.update(derivatives(model, qp, vp, taup, ap, perm))
        states.append(entry)
    return {"model": os.path.splitext(file)[0], "nv": model.nv, "states": states}


def floating_entry(file, rng, folder=ROBOTS, count=STATES, extra=None):
    """The robot on Pinocchio's free flyer, as dalembert's `--floating` writes it: q is the
    base's position and unit quaternion (x, y, z, w) then the joints in Pinocchio's order; v the
    base's linear and angular velocity in its own axes then the joints'. The derivatives by
    q are Pinocchio's, in the tangent space (q ⊕ δ = q exp(δ)). `count` states of the robot
    `file` of `folder`; `extra(model, q, v, tau, perm, entry)`, if given, edits each state's
    entry (v and tau in Pinocchio's order)."""
    path = os.path.join(folder, file)
    model = pin.buildModelFromUrdf(path, pin.JointModelFreeFlyer())
    order = coordinate_order(path)
    joints = [model.joints[model.getJointId(name)] for name in order]
    assert all(j.nq == 1 for j in joints), "one angle or slide per joint"
    perm = np.array(list(range(6)) + [j.idx_v for j in joints])
    states = []
    for _ in range(count):
        q = pin.neutral(model)
        q[:3] = rng.uniform(-1.0, 1.0, 3)
        quaternion = rng.normal(size=4)
        q[3:7] = quaternion / np.linalg.norm(quaternion)
        angles = rng.uniform(-math.pi, math.pi, len(order))
        q[[j.idx_q for j in joints]] = angles
        v, a = rng.uniform(-2.0, 2.0, model.nv), rng.uniform(-5.0, 5.0, model.nv)
        tau = rng.uniform(-10.0, 10.0, len(order))
        vp, ap, taup = np.zeros(model.nv), np.zeros(model.nv), np.zeros(model.nv)
        vp[perm], ap[perm], taup[perm[6:]] = v, a, tau
        entry = {"q": [float(x) for x in list(q[:7]) + list(angles)],
                 "qd": [float(x) for x in v], "tau": [float(x) for x in tau]}
        entry.update(derivatives(model, q, vp, taup, ap, perm))
        if extra:
            extra(model, q, vp, taup, perm, entry)
        states.append(entry)
    return {"model": os.path.splitext(file)[0] + "_floating", "nv": model.nv, "states": states}


def brick_entry(rng):
    """generated/models/dzhanibekov.dal: a uniform 3 × 2 × 1 box of 12 kg on a spherical joint
    at its centre (q its unit quaternion (x, y, z, w), v its angular velocity in its axes), no
    torques; the derivatives by q in the tangent space."""
    model = pin.Model()
    joint = model.addJoint(0, pin.JointModelSpherical(), pin.SE3.Identity(), "ball")
    m, (a, b, c) = 12.0, (3.0, 2.0, 1.0)
    inertia = np.diag([m * (b * b + c * c), m * (a * a + c * c), m * (a * a + b * b)]) / 12.0
    model.appendBodyToJoint(joint, pin.Inertia(m, np.zeros(3), inertia), pin.SE3.Identity())
    states = []
    for _ in range(STATES):
        quaternion = rng.normal(size=4)
        q = quaternion / np.linalg.norm(quaternion)
        v, a_ = rng.uniform(-2.0, 2.0, 3), rng.uniform(-5.0, 5.0, 3)
        entry = {"q": [float(x) for x in q], "qd": [float(x) for x in v], "tau": [0.0] * 3}
        entry.update(derivatives(model, q, v, np.zeros(3), a_, np.arange(3)))
        states.append(entry)
    return {"model": "dzhanibekov", "nv": 3, "states": states}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=os.path.join(ROOT, "tests", "reference", "derivatives.json"))
    args = parser.parse_args()
    rng = np.random.default_rng(SEED)
    models = [chain_entry(f, n, rng) for f in ["planar", "spatial"] for n in LINKS]
    models += [robot_entry(f, rng) for f in ["panda.urdf", "ur5_robot.urdf"]]
    models += [floating_entry("solo12.urdf", rng), brick_entry(rng)]
    write_document(
        args.out,
        "derivatives/1",
        "scripts/derivatives_reference.py (Pinocchio Python bindings)",
        SEED,
        "Per state: q, qd, tau (zero for the chains), qdd = aba(q, qd, tau); "
        "ddq_dq, ddq_dv, ddq_dtau = M^-1 from computeABADerivatives at (q, qd, tau) "
        "(tau: the joints' torques; a floating base's q is position then quaternion (x, y, z, w), "
        "its derivatives by q in the tangent space); "
        "dtau_dq, dtau_dv, dtau_da = M from computeRNEADerivatives at (q, qd, vdot). "
        "Matrices row by row, entry [i][j] the derivative of component i by variable j, "
        "in dalembert's coordinate order.",
        models,
    )


if __name__ == "__main__":
    main()
