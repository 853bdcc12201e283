#!/usr/bin/env bash
# Regenerates tests/reference/mjcf_fuzz/mujoco.json: the sample of fuzzed MJCF
# files that dalembert imports (written by the ignored test
# `write_the_sample_for_mujoco` of codegen/tests/suite/mjcf_fuzz.rs), beside the
# files they include, read by MuJoCo (scripts/mjcf_fuzz_reference.py).
#
#   bash scripts/mjcf_fuzz_reference.sh
#
# PYTHON (default: python3) must have
# `mujoco`, `pin` (the script shares urdf_fuzz_reference.py's command line) and `numpy`.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
python="${PYTHON:-python3}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cd "$root"
FUZZ_SAMPLE="$work" cargo test -q -p dalembert-codegen --test suite \
    mjcf_fuzz::write_the_sample_for_mujoco -- --ignored --exact >/dev/null
mkdir -p "$work/common" tests/reference/mjcf_fuzz
cp tests/reference/mjcf/dm_control/common/*.xml "$work/common/"
cp tests/reference/mjcf/features/features_defaults.xml "$work/"
"$python" scripts/mjcf_fuzz_reference.py "$work" tests/reference/mjcf_fuzz/mujoco.json
