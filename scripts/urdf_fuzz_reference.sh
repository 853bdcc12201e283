#!/usr/bin/env bash
# Regenerates tests/reference/urdf_fuzz/pinocchio.json: the sample of fuzzed
# URDF files that dalembert imports (written by the ignored test
# `write_the_sample_for_pinocchio` of codegen/tests/suite/urdf_fuzz.rs), read by
# Pinocchio (scripts/urdf_fuzz_reference.py).
#
#   bash scripts/urdf_fuzz_reference.sh
#
# PYTHON (default: python3) must have `pin`
# and `numpy`.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
python="${PYTHON:-python3}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cd "$root"
FUZZ_SAMPLE="$work" cargo test -q -p dalembert-codegen --test suite \
    urdf_fuzz::write_the_sample_for_pinocchio -- --ignored --exact >/dev/null
mkdir -p tests/reference/urdf_fuzz
"$python" scripts/urdf_fuzz_reference.py "$work" tests/reference/urdf_fuzz/pinocchio.json
