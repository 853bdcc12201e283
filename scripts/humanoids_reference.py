#!/usr/bin/env python3
"""Pinocchio's dynamics and derivatives of the floating humanoids of
tests/reference/humanoids/ (Unitree G1, Talos), for generated/tests/suite/humanoids.rs.

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
import os
import sys

import numpy as np
import pinocchio as pin

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from derivatives_reference import floating_entry  # noqa: E402
from urdf_reference import write_document  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
HUMANOIDS = os.path.join(ROOT, "tests", "reference", "humanoids")
FILES = ["g1.urdf", "talos_reduced.urdf"]
STATES = 3
SEED = 20261128


def forcing_only(model, q, v, tau, perm, entry):
    """Adds f = tau - nle; drops dtau_dq and dtau_dv (the humanoids ask for no
    `inverse_dynamics_jacobian`), M kept."""
    nle = pin.nonLinearEffects(model, model.createData(), q, v)
    entry["f"] = [float(x) for x in (tau - nle)[perm]]
    del entry["dtau_dq"], entry["dtau_dv"]


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
        [floating_entry(f, rng, HUMANOIDS, STATES, forcing_only) for f in FILES],
    )


if __name__ == "__main__":
    main()
