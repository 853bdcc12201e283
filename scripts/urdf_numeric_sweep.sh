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
# PYTHON (default: python3) must have `pin` (Pinocchio 4.1) and `numpy`. scripts/urdf_numeric_sweep.py writes Pinocchio's
# side (urdf_reference.py's entries: 10 random states a case, in dalembert's
# coordinate order), codegen/examples/urdf_numeric_sweep.rs imports each file
# as `dalembert urdf [--floating]` does, evaluates it with the interpreter and
# compares. A case matches when M, f, T, V, RNEA and its partials agree to
# 1e-12 of their largest entry and q̈ to 1e-12 times the condition number of M.
#
# COMPILED="FILE:BASE ..." (paths under robots/, BASE fixed or floating) also
# generates those models' code (`dalembert generate`) into a scratch crate in
# target/urdf_compiled_check and compares the compiled M, f, T and the q̈ of
# the emitted solver (scripts/urdf_compiled_check.rs), e.g.
#   COMPILED="pr2_description/urdf/pr2.urdf:floating z1_description/urdf/z1.urdf:fixed"
set -euo pipefail
version="${1:-6.0.0}"
root="$(cd "$(dirname "$0")/.." && pwd)"
python="${PYTHON:-python3}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
python3 -m pip download --quiet --no-deps --dest "$work" "example-robot-data==$version"
python3 -m zipfile -e "$work"/example_robot_data-*.whl "$work/wheel"
# Pinocchio's URDF parser prints its refusals on stderr; the sweep reports them.
"$python" "$root/scripts/urdf_numeric_sweep.py" \
    "$work/wheel/cmeel.prefix/share/example-robot-data/robots" "$work/reference.json" 2>/dev/null
cargo run --quiet --release --manifest-path "$root/Cargo.toml" -p dalembert-codegen \
    --example urdf_numeric_sweep -- "$work/reference.json"
[ -z "${COMPILED:-}" ] && exit 0
robots="$work/wheel/cmeel.prefix/share/example-robot-data/robots"
crate="$root/target/urdf_compiled_check"
cargo build --quiet --release --manifest-path "$root/Cargo.toml" -p dalembert-codegen --bin dalembert
mkdir -p "$crate/src"
printf '%s\n' '[package]' 'name = "urdf_compiled_check"' 'edition = "2024"' '[dependencies]' \
    'dalembert = { path = "../.." }' 'dalembert-codegen = { path = "../../codegen" }' \
    'serde_json = "1"' '[workspace]' >"$crate/Cargo.toml"
modules=""
calls=""
i=0
for chosen in $COMPILED; do
    file="${chosen%:*}"
    base="${chosen##*:}"
    flag=()
    [ "$base" = floating ] && flag=(--floating)
    "$root/target/release/dalembert" urdf "$robots/$file" "${flag[@]}" >"$work/case.dal" 2>/dev/null
    "$root/target/release/dalembert" generate "$work/case.dal" >"$crate/src/case_$i.rs"
    system="case_$i::$(grep -m1 -oP 'pub struct \K\w+' "$crate/src/case_$i.rs")"
    modules+="mod case_$i;"$'\n'
    calls+="    compare::<_, { $system::NQ }, { $system::NV }, { $system::NU }>(&$system {}, (\"$file\", \"$base\"), cases);"$'\n'
    i=$((i + 1))
done
cases="${modules}fn compare_all(cases: &[Value]) {"$'\n'"${calls}}"
python3 -c 'import sys; print(open(sys.argv[1]).read().replace("\n// CASES\n", "\n" + sys.argv[2] + "\n"), end="")' \
    "$root/scripts/urdf_compiled_check.rs" "$cases" >"$crate/src/main.rs"
CARGO_TARGET_DIR="$crate/target" cargo run --quiet --release --manifest-path "$crate/Cargo.toml" -- \
    "$work/reference.json"
