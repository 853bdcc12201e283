#!/usr/bin/env python3
"""Pinocchio's numbers for the sample of fuzzed URDF files that dalembert
imports (codegen/tests/suite/urdf_fuzz.rs, `sample()`): the reference half of
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


def peer_case(folder, file, entry_of):
    """One file of a sample: its name, its hash, and the peer's entry
    (`entry_of(path, file)`) with the largest condition number of M, or why
    there is none."""
    path = os.path.join(folder, file)
    with open(path, "rb") as f:
        data = f.read()
    result = {"name": os.path.splitext(file)[0], "fnv1a": fnv1a(data)}
    try:
        entry = entry_of(path, file)
        result["cond"] = max(np.linalg.cond(np.array(s["M"])) for s in entry["states"])
        result["entry"] = entry
    except Exception as error:  # the peer's refusals and the self-checks alike
        # Without this machine's folder, so the reference reads the same anywhere.
        message = str(error).replace(os.path.join(folder, ""), "")
        result["error"] = f"{type(error).__name__}: {message}".strip()
    return result


def write_sample(description, extension, header, entry_of):
    """The command line of a sample's script: reads FOLDER's case_NNN files
    ending in `extension`, writes OUT.json with `header` and each case of
    `entry_of(path, file, rng)`."""
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("folder", help=f"the sample's case_NNN{extension} files")
    parser.add_argument("out", help="the JSON file to write")
    args = parser.parse_args()
    files = sorted(f for f in os.listdir(args.folder)
                   if f.startswith("case_") and f.endswith(extension))
    rng = np.random.default_rng(SEED)
    cases = [peer_case(args.folder, file, lambda path, file: entry_of(path, file, rng))
             for file in files]
    document = dict(header, seed=SEED, states=STATES, cases=cases)
    with open(args.out, "w") as out:
        json.dump(document, out)
        out.write("\n")
    refused = sum("error" in c for c in cases)
    print(f"wrote {args.out}: {len(files)} cases, {refused} without the peer's numbers",
          file=sys.stderr)


def pinocchio_entry(path, file, rng):
    """urdf_reference.py's entry of the file, named after it."""
    entry = urdf_reference.robot_entry(path, rng)
    entry["urdf"] = entry["robot"] = file
    return entry


def main():
    urdf_reference.STATES = STATES
    header = {
        "generator": "scripts/urdf_fuzz_reference.py",
        "pinocchio_version": pin.__version__,
        "units": "SI: kg, m, s, rad, N m",
    }
    write_sample(__doc__.splitlines()[0], ".urdf", header, pinocchio_entry)


if __name__ == "__main__":
    main()
