#!/usr/bin/env bash
# The SciPy side of the DOP853 comparison in BENCHMARKS.md: creates a virtual
# environment (default `target/scipy-venv`, or $SCIPY_VENV), installs SciPy,
# SymPy and NumPy from PyPI into it, and runs `scipy_baseline.py`, which times
# `solve_ivp(method="DOP853")` on seed example 1 over a tolerance sweep.
#
#     scripts/scipy_baseline.sh [--out target/charts/scipy_dop853.csv]
#
# Our side: `cargo run --release --example work_precision`.
set -euo pipefail

root="$(cd "$(dirname "$0")/.." && pwd)"
venv="${SCIPY_VENV:-$root/target/scipy-venv}"

if [ ! -x "$venv/bin/python" ]; then
    python3 -m venv "$venv"
fi
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check \
    "scipy>=1.11" "sympy>=1.12" "numpy>=1.26"
exec "$venv/bin/python" "$root/scripts/scipy_baseline.py" "$@"
