#!/usr/bin/env python3
"""MuJoCo's numbers for the sample of fuzzed MJCF files that dalembert imports
(codegen/tests/suite/mjcf_fuzz.rs, `sample()`): the reference half of
scripts/mjcf_fuzz_reference.sh.

For each file of FOLDER (case_NNN.xml, sorted; the folder also holds the files
they include), MuJoCo's own compiler loads the model and mjcf_reference.py's
entry records M, f, qdd and the energies at 3 random states (contacts,
constraints and actuation disabled), in dalembert's conventions, with the
largest condition number of M ("cond"). A file MuJoCo refuses, or whose M is
singular, gets its error instead. Each case records the 64-bit FNV-1a hash of
the file, which the test compares with the mutant it regenerates.

The command line, the seed and the document's form are
urdf_fuzz_reference.py's (which imports Pinocchio).

usage (in a Python environment with `mujoco`, `pin` and `numpy`):
    python scripts/mjcf_fuzz_reference.py FOLDER OUT.json
"""
import os
import sys

import mujoco
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mjcf_reference  # noqa: E402
import urdf_fuzz_reference  # noqa: E402
from urdf_fuzz_reference import write_sample  # noqa: E402


def mujoco_entry(path, file, rng):
    """mjcf_reference.py's entry of the file, named after it; a singular M
    is an error."""
    entry = mjcf_reference.entry(path, rng)
    cond = max(np.linalg.cond(np.array(s["M"])) for s in entry["states"])
    if not np.isfinite(cond) or cond > 1e14:
        raise ValueError(f"M is singular (condition number {cond:.1e})")
    entry["file"] = file
    return entry


def main():
    mjcf_reference.STATES = urdf_fuzz_reference.STATES
    header = {
        "generator": "scripts/mjcf_fuzz_reference.py",
        "mujoco_version": mujoco.__version__,
    }
    write_sample(__doc__.splitlines()[0], ".xml", header, mujoco_entry)


if __name__ == "__main__":
    main()
