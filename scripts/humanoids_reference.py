#!/usr/bin/env python3
"""Pinocchio's dynamics and derivatives of the floating humanoids of
tests/reference/humanoids/ (Unitree G1, Talos), for generated/tests/humanoids.rs.

At random states of each robot on Pinocchio's free flyer (built by its own URDF
parser), this script records crba (M, symmetric), f = tau - nle (the forcing,
tau the joints' torques), aba (qdd), and computeABADerivatives (ddq_dq, ddq_dv,
ddq_dtau = M^-1) and computeRNEADerivatives' dtau_da = M (the
schema and conventions of scripts/derivatives_reference.py: q is the base's
position and unit quaternion (x, y, z, w) then the joints in dalembert's order;
v the base's linear and angular velocity in its own axes then the joints'; the
derivatives by q in the tangent space) into tests/reference/humanoids/pinocchio.json.

usage (in a Python environment with `pin` and `numpy`, e.g. the peers' venv):
    python scripts/humanoids_reference.py [--out tests/reference/humanoids/pinocchio.json]
"""
import argparse
import math
import os
import sys

import numpy as np
import pinocchio as pin

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from derivatives_reference import derivatives  # noqa: E402
from urdf_reference import coordinate_order, write_document  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
HUMANOIDS = os.path.join(ROOT, "tests", "reference", "humanoids")
FILES = ["g1.urdf", "talos_reduced.urdf"]
STATES = 3
SEED = 20261128


def floating_entry(file, rng):
    """The robot on the free flyer at STATES random states."""
    path = os.path.join(HUMANOIDS, file)
    model = pin.buildModelFromUrdf(path, pin.JointModelFreeFlyer())
    order = coordinate_order(path)
    joints = [model.joints[model.getJointId(name)] for name in order]
    assert all(j.nq == 1 for j in joints), "one angle or slide per joint"
    perm = np.array(list(range(6)) + [j.idx_v for j in joints])
    states = []
    for _ in range(STATES):
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
        # The humanoids ask for no `inverse_dynamics_jacobian`: M is kept.
        del entry["dtau_dq"], entry["dtau_dv"]
        nle = pin.nonLinearEffects(model, model.createData(), q, vp)
        entry["f"] = [float(x) for x in (taup - nle)[perm]]
        states.append(entry)
    return {"model": os.path.splitext(file)[0] + "_floating", "nv": model.nv, "states": states}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=os.path.join(HUMANOIDS, "pinocchio.json"))
    args = parser.parse_args()
    rng = np.random.default_rng(SEED)
    write_document(
        args.out,
        "humanoids/1",
        "scripts/humanoids_reference.py (Pinocchio Python bindings)",
        SEED,
        "Per state: q, qd, tau (the joints' torques), f = tau - nle, qdd = aba(q, qd, tau); "
        "ddq_dq, ddq_dv, ddq_dtau = M^-1 from computeABADerivatives at (q, qd, tau); "
        "dtau_da = M from computeRNEADerivatives. "
        "q is the base's position and quaternion (x, y, z, w), then the joints; derivatives by "
        "q in the tangent space. Matrices row by row, entry [i][j] the derivative of component "
        "i by variable j, in dalembert's coordinate order.",
        [floating_entry(f, rng) for f in FILES],
    )


if __name__ == "__main__":
    main()
