#!/usr/bin/env python3
"""MuJoCo's numbers for the sample of fuzzed MJCF files that dalembert imports
(codegen/tests/mjcf_fuzz.rs, `sample()`): the reference half of
scripts/mjcf_fuzz_reference.sh.

For each file of FOLDER (case_NNN.xml, sorted; the folder also holds the files
they include), MuJoCo's own compiler loads the model and mjcf_reference.py's
entry records M, f, qdd and the energies at STATES random states (contacts,
constraints and actuation disabled), in dalembert's conventions, with the
largest condition number of M ("cond"). A file MuJoCo refuses, or whose M is
singular, gets its error instead. Each case records the 64-bit FNV-1a hash of
the file, which the test compares with the mutant it regenerates.

usage (in a Python environment with `mujoco` and `numpy`):
    python scripts/mjcf_fuzz_reference.py FOLDER OUT.json
"""
import argparse
import json
import os
import sys

import mujoco
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mjcf_reference  # noqa: E402
from urdf_fuzz_reference import fnv1a  # noqa: E402

SEED = 20261128
STATES = 3


def case(folder, file, rng):
    path = os.path.join(folder, file)
    with open(path, "rb") as f:
        data = f.read()
    result = {"name": os.path.splitext(file)[0], "fnv1a": fnv1a(data)}
    try:
        entry = mjcf_reference.entry(path, rng)
        cond = max(np.linalg.cond(np.array(s["M"])) for s in entry["states"])
        if not np.isfinite(cond) or cond > 1e14:
            raise ValueError(f"M is singular (condition number {cond:.1e})")
        entry["file"] = file
        result["cond"] = cond
        result["entry"] = entry
    except Exception as error:  # MuJoCo's refusals and the singular M alike
        # Without this machine's folder, so the reference reads the same anywhere.
        message = str(error).replace(os.path.join(folder, ""), "")
        result["error"] = f"{type(error).__name__}: {message}".strip()
    return result


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("folder", help="the sample's case_NNN.xml files")
    parser.add_argument("out", help="the JSON file to write")
    args = parser.parse_args()
    mjcf_reference.STATES = STATES
    files = sorted(f for f in os.listdir(args.folder) if f.startswith("case_"))
    rng = np.random.default_rng(SEED)
    document = {
        "generator": "scripts/mjcf_fuzz_reference.py",
        "mujoco_version": mujoco.__version__,
        "seed": SEED,
        "states": STATES,
        "cases": [case(args.folder, file, rng) for file in files],
    }
    with open(args.out, "w") as out:
        json.dump(document, out)
        out.write("\n")
    refused = sum("error" in c for c in document["cases"])
    print(f"wrote {args.out}: {len(files)} cases, {refused} refused by MuJoCo", file=sys.stderr)


if __name__ == "__main__":
    main()
