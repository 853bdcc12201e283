#!/usr/bin/env python3
"""Pinocchio's numbers for every URDF file under a folder, fixed and floating
base: the reference half of scripts/urdf_numeric_sweep.sh.

For each file (sorted by path) and base, the entry urdf_reference.py would
write for it (robot_entry, or floating_entry on Pinocchio's free flyer): M,
nle, f = tau - nle and aba's qdd at random states, in dalembert's coordinate
order (continuous joints as one angle, the free flyer's quaternion
(qx, qy, qz, qw), its speeds in the base's axes); and at each state random
accelerations a with rnea(q, v, a) and computeRNEADerivatives' dtau/dq (in
the tangent space for the free flyer, as dalembert's) and dtau/dv. A file Pinocchio refuses,
or whose numbers fail the script's self-checks (T = 1/2 v^T M v,
M qdd = f: a singular M fails the second), gets its error instead.

usage (in a Python environment with `pin` and `numpy`):
    python scripts/urdf_numeric_sweep.py ROBOTS_DIR OUT.json [--states N]
writes OUT.json: {"seed", "states", "cases": [{"file", "path", "base",
"cond" (the largest condition number of M) and "entry", or "error"}]}
"""
import argparse
import json
import os
import sys

import numpy as np
import pinocchio as pin

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import urdf_reference  # noqa: E402

SEED = 20261125


def add_inverse_dynamics(path, base, entry, rng):
    """Adds to each state of `entry` random accelerations `a`, Pinocchio's
    `rnea` (M a + nle) and its derivatives `rnea_dq` (in the tangent space
    for the free flyer) and `rnea_dv`, in dalembert's order."""
    floating = base == "floating"
    model = (pin.buildModelFromUrdf(path, pin.JointModelFreeFlyer()) if floating
             else pin.buildModelFromUrdf(path))
    data = model.createData()
    order = entry["coordinates"][len(urdf_reference.FREE):] if floating else entry["coordinates"]
    for state in entry["states"]:
        q = pin.neutral(model)
        base_q = state["q"][:len(urdf_reference.FREE)] if floating else []
        q[:len(base_q)] = base_q
        idx_v = urdf_reference.set_angles(model, q, order, state["q"][len(base_q):])
        perm = np.array(list(range(6)) * floating + idx_v, dtype=int)
        a = rng.uniform(-3.0, 3.0, model.nv)
        v_pin, a_pin = np.zeros(model.nv), np.zeros(model.nv)
        v_pin[perm], a_pin[perm] = state["qd"], a
        rnea = pin.rnea(model, data, q, v_pin, a_pin)[perm]
        dq, dv, _ = pin.computeRNEADerivatives(model, data, q, v_pin, a_pin)
        expected = np.array(state["M"]) @ a + np.array(state["nle"])
        if not np.abs(rnea - expected).max() <= 1e-9 * max(1.0, np.abs(expected).max()):
            raise ValueError("rnea differs from M a + nle")
        state["a"] = [float(x) for x in a]
        state["rnea"] = [float(x) for x in rnea]
        state["rnea_dq"] = [[float(x) for x in row] for row in dq[np.ix_(perm, perm)]]
        state["rnea_dv"] = [[float(x) for x in row] for row in dv[np.ix_(perm, perm)]]


def case(path, file, base, rng):
    """One file on one base: Pinocchio's entry, or why there is none."""
    entry_of = urdf_reference.floating_entry if base == "floating" else urdf_reference.robot_entry
    try:
        entry = entry_of(path, rng)
        add_inverse_dynamics(path, base, entry, rng)
        cond = max(np.linalg.cond(np.array(state["M"])) for state in entry["states"])
        return {"file": file, "path": path, "base": base, "cond": cond, "entry": entry}
    except Exception as error:  # Pinocchio's refusals and the self-checks alike
        return {"file": file, "path": path, "base": base,
                "error": f"{type(error).__name__}: {error}".strip()}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("robots", help="folder searched for *.urdf")
    parser.add_argument("out", help="the JSON file to write")
    parser.add_argument("--states", type=int, default=urdf_reference.STATES)
    args = parser.parse_args()
    urdf_reference.STATES = args.states
    files = sorted(
        os.path.relpath(os.path.join(folder, name), args.robots)
        for folder, _, names in os.walk(args.robots)
        for name in names
        if name.endswith(".urdf")
    )
    rng = np.random.default_rng(SEED)
    cases = [
        case(os.path.abspath(os.path.join(args.robots, file)), file, base, rng)
        for file in files
        for base in ("fixed", "floating")
    ]
    with open(args.out, "w") as out:
        json.dump({"seed": SEED, "states": args.states, "cases": cases}, out)
    print(f"wrote {args.out}: {len(cases)} cases", file=sys.stderr)


if __name__ == "__main__":
    main()
