#!/usr/bin/env python3
"""Pinocchio's numbers for the sample of fuzzed URDF files that dalembert
imports (codegen/tests/urdf_fuzz.rs, `sample()`): the reference half of
scripts/urdf_fuzz_reference.sh.

For each file of FOLDER (case_NNN.urdf, sorted), Pinocchio's own URDF parser
builds the model on a fixed base and urdf_reference.py's robot_entry records M,
f = tau - nle, aba's qdd and the energies at STATES random states, in
dalembert's coordinate order, with the largest condition number of M ("cond").
A file Pinocchio refuses, or whose numbers fail the self-checks (a singular M),
gets its error instead. Each case records the 64-bit FNV-1a hash of the file,
which the test compares with the mutant it regenerates.

usage (in a Python environment with `pin` and `numpy`):
    python scripts/urdf_fuzz_reference.py FOLDER OUT.json
"""
import argparse
import json
import os
import sys

import numpy as np
import pinocchio as pin

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import urdf_reference  # noqa: E402

SEED = 20261128
STATES = 3


def fnv1a(data):
    """The 64-bit FNV-1a hash of `data` (bytes), as 16 hex digits."""
    h = 0xcbf29ce484222325
    for byte in data:
        h = ((h ^ byte) * 0x100000001b3) % (1 << 64)
    return f"{h:016x}"


def case(folder, file, rng):
    path = os.path.join(folder, file)
    with open(path, "rb") as f:
        data = f.read()
    result = {"name": os.path.splitext(file)[0], "fnv1a": fnv1a(data)}
    try:
        entry = urdf_reference.robot_entry(path, rng)
        result["cond"] = max(np.linalg.cond(np.array(s["M"])) for s in entry["states"])
        entry["urdf"] = entry["robot"] = file
        result["entry"] = entry
    except Exception as error:  # Pinocchio's refusals and the self-checks alike
        # Without this machine's folder, so the reference reads the same anywhere.
        message = str(error).replace(os.path.join(folder, ""), "")
        result["error"] = f"{type(error).__name__}: {message}".strip()
    return result


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("folder", help="the sample's case_NNN.urdf files")
    parser.add_argument("out", help="the JSON file to write")
    args = parser.parse_args()
    urdf_reference.STATES = STATES
    files = sorted(f for f in os.listdir(args.folder) if f.endswith(".urdf"))
    rng = np.random.default_rng(SEED)
    document = {
        "generator": "scripts/urdf_fuzz_reference.py",
        "pinocchio_version": pin.__version__,
        "units": "SI: kg, m, s, rad, N m",
        "seed": SEED,
        "states": STATES,
        "cases": [case(args.folder, file, rng) for file in files],
    }
    with open(args.out, "w") as out:
        json.dump(document, out, indent=None)
        out.write("\n")
    refused = sum("error" in c for c in document["cases"])
    print(f"wrote {args.out}: {len(files)} cases, {refused} refused by Pinocchio", file=sys.stderr)


if __name__ == "__main__":
    main()
