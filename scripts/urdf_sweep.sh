#!/usr/bin/env bash
# Imports every URDF file of the example-robot-data wheel (PyPI) with
# `dalembert urdf`, on a fixed and on a floating base, and checks each model
# with `dalembert check`: one line a file and base, then the counts.
#
#   bash scripts/urdf_sweep.sh [VERSION]      # default 6.0.0; needs pip and network
set -euo pipefail
version="${1:-6.0.0}"
root="$(cd "$(dirname "$0")/.." && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
python3 -m pip download --quiet --no-deps --dest "$work" "example-robot-data==$version"
python3 -m zipfile -e "$work"/example_robot_data-*.whl "$work/wheel"
cargo build --quiet --release --manifest-path "$root/Cargo.toml" -p dalembert-codegen --bin dalembert
dalembert="$root/target/release/dalembert"
passed=0
total=0
while IFS= read -r urdf; do
    name="${urdf#"$work"/wheel/cmeel.prefix/share/example-robot-data/robots/}"
    for base in fixed floating; do
        flag=()
        [ "$base" = floating ] && flag=(--floating)
        total=$((total + 1))
        if ! "$dalembert" urdf "$urdf" "${flag[@]}" >"$work/model.dal" 2>"$work/stderr"; then
            echo "$name ($base): import error: $(grep -m1 '^error' "$work/stderr")"
        elif ! "$dalembert" check "$work/model.dal" >/dev/null 2>"$work/check"; then
            echo "$name ($base): model error: $(grep -m1 '^error' "$work/check")"
        else
            passed=$((passed + 1))
            echo "$name ($base): ok, $(grep -c '^warning' "$work/stderr" || true) warning(s)"
        fi
    done
done < <(find "$work/wheel" -name '*.urdf' | sort)
echo "$passed of $total imports (files × bases) give a model that checks"
