#!/usr/bin/env bash
# Every URDF file of the example-robot-data wheel (PyPI), on a fixed and on a
# floating base, against Pinocchio's numbers: one line a file and base (the
# worst relative errors of M, f, T, V and q̈ on d'Alembert's route, and on
# Lagrange's on a fixed base, and of RNEA and its derivatives in q and v; or
# who refuses the file and why), the counts at the end. Not in CI: it needs
# the network and Pinocchio. About 2 minutes once built.
#
#   bash scripts/urdf_numeric_sweep.sh [VERSION]   # default 6.0.0
#
# PYTHON (default: the peers' environment, ~/.cache/dalembert-peers-venv) must
# have `pin` and `numpy`. scripts/urdf_numeric_sweep.py writes Pinocchio's
# side (urdf_reference.py's entries: 10 random states a case, in dalembert's
# coordinate order), codegen/examples/urdf_numeric_sweep.rs imports each file
# as `dalembert urdf [--floating]` does, evaluates it with the interpreter and
# compares. A case matches when M, f, T, V, RNEA and its partials agree to
# 1e-12 of their largest entry and q̈ to 1e-12 times the condition number of M.
set -euo pipefail
version="${1:-6.0.0}"
root="$(cd "$(dirname "$0")/.." && pwd)"
python="${PYTHON:-$HOME/.cache/dalembert-peers-venv/bin/python}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
python3 -m pip download --quiet --no-deps --dest "$work" "example-robot-data==$version"
python3 -m zipfile -e "$work"/example_robot_data-*.whl "$work/wheel"
# Pinocchio's URDF parser prints its refusals on stderr; the sweep reports them.
"$python" "$root/scripts/urdf_numeric_sweep.py" \
    "$work/wheel/cmeel.prefix/share/example-robot-data/robots" "$work/reference.json" 2>/dev/null
cargo run --quiet --release --manifest-path "$root/Cargo.toml" -p dalembert-codegen \
    --example urdf_numeric_sweep -- "$work/reference.json"
