#!/usr/bin/env python3
"""Pinocchio's numbers for every URDF file under a folder, fixed and floating
base: the reference half of scripts/urdf_numeric_sweep.sh.

For each file (sorted by path) and base, the entry urdf_reference.py would
write for it (robot_entry, or floating_entry on Pinocchio's free flyer): M,
nle, f = tau - nle and aba's qdd at random states, in dalembert's coordinate
order (continuous joints as one angle, the free flyer's quaternion
(qx, qy, qz, qw), its speeds in the base's axes). A file Pinocchio refuses,
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

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import urdf_reference  # noqa: E402

SEED = 20261125


def case(path, file, base, rng):
    """One file on one base: Pinocchio's entry, or why there is none."""
    entry_of = urdf_reference.floating_entry if base == "floating" else urdf_reference.robot_entry
    try:
        entry = entry_of(path, rng)
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
