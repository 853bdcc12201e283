#!/usr/bin/env bash
# Operation counts of the generated functions against Pinocchio's recursive
# algorithms on the floating humanoids and Solo-12 (and the UR5, fixed): prints
# one markdown section (BENCHMARKS.md, via scripts/benchmarks.sh; docs/humanoid.md
# reads it).
#
#   scripts/bench/op_counts.sh
#
# Ours: `dalembert urdf ROBOT.urdf [--floating] --outputs accelerations_jacobian`,
# then `dalembert generate`, counted by scripts/bench/op_counts.py (the straight-line
# code, the solve's row operations and, where the jacobian takes the runtime's loops
# over the tree (the floating robots), their operations counted from its table of links).
# Pinocchio's: scripts/bench/pinocchio_op_counts.cpp, its algorithms run once on a
# counting scalar, built against the headers under $PINOCCHIO_PREFIX (the `pin`
# wheel's cmeel.prefix, holding include/pinocchio and include/eigen3; default: the
# peers' Python environment's), the robot read by the peers' harness's urdf_model.py
# ($PINOCCHIO_HARNESS, set by scripts/benchmarks.sh --peers DIR) with $PYTHON (an
# environment with `pin`; default: the peers'). The counting build is kept under
# ${XDG_CACHE_HOME:-~/.cache}/dalembert-op-counts/ (one folder per source, compiler and
# Pinocchio; $PINOCCHIO_OP_COUNTER names another). Without the harness only our
# counts are printed.
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh"
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK" "$STAMP"' EXIT
COUNTER=""
if [ -n "${PINOCCHIO_HARNESS:-}" ]; then
  PINOCCHIO_PREFIX="${PINOCCHIO_PREFIX:-$(peers_site)/cmeel.prefix}"
  PYTHON="${PYTHON:-$(peers_python)}"
  # The counting build instantiates Pinocchio's algorithms for every joint kind on
  # a new scalar: half an hour of a loaded core. Its counts do not depend on
  # optimisation (every operation is a call that counts), so it is built at -O0 and
  # kept in a cache keyed by the source, the compiler and Pinocchio's headers; or
  # $PINOCCHIO_OP_COUNTER names one already built from the same source.
  flags=(-O0 -DNDEBUG -std=c++17 -w -DBOOST_MPL_LIMIT_LIST_SIZE=30 -DBOOST_MPL_LIMIT_VECTOR_SIZE=30
    -DBOOST_MPL_CFG_NO_PREPROCESSED_HEADERS -DBOOST_FUSION_INVOKE_MAX_ARITY=12
    -I"$PINOCCHIO_PREFIX/include" -I"$PINOCCHIO_PREFIX/include/eigen3")
  key=$({ cat scripts/bench/pinocchio_op_counts.cpp "$PINOCCHIO_PREFIX/include/pinocchio/config.hpp"
    g++ --version; echo "${flags[*]}"; } | sha256sum | cut -c1-16)
  COUNTER="${PINOCCHIO_OP_COUNTER:-${XDG_CACHE_HOME:-$HOME/.cache}/dalembert-op-counts/$key/pinocchio_op_counts}"
  if [ ! -x "$COUNTER" ]; then
    mkdir -p "$(dirname "$COUNTER")"
    g++ "${flags[@]}" scripts/bench/pinocchio_op_counts.cpp -o "$COUNTER.partial"
    mv "$COUNTER.partial" "$COUNTER"
  fi
fi
cargo build -q --release -p dalembert-codegen --bin dalembert
DALEMBERT="$CARGO_TARGET_DIR/release/dalembert"

# "function flops row_solve" of ours; "algo flops" of Pinocchio's.
flops() { awk -F, -v f="$2" '$1 == f { print $7 }' "$1"; }
solve() { awk -F, -v f="$2" '$1 == f { print $8 }' "$1"; }
pin() { [ -n "$COUNTER" ] && awk -F, -v a="$2" '$3 == a { print $10 }' "$1" || true; }
k() { [ -n "$1" ] && awk -v x="$1" 'BEGIN { printf "%.1f k", x / 1000 }' || printf -- "–"; }
ratio() { [ -n "$1" ] && [ -n "$2" ] && awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", a / b }' || printf -- "–"; }

echo "## Operation counts: generated functions against Pinocchio's algorithms"
echo
echo "Flops of one call (+, −, ×, ÷; not sin/cos). Ours: the generated code, each shared"
echo "subexpression once, with the solve's share in brackets and the runtime's loops where the"
echo "jacobian takes them (\`scripts/bench/op_counts.py\`); Pinocchio's: its algorithms run on a"
echo "counting scalar (\`scripts/bench/pinocchio_op_counts.cpp\`), structural zeros of its 6×6 blocks included."
echo
echo "| robot (speeds) | M + f | crba + nle | ratio | accelerations | aba | ratio | accelerations_jacobian (solve) | computeABADerivatives | ratio | jacobian / accelerations, ours |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for entry in "ur5_robot:urdf/ur5_robot.urdf:" "solo12:urdf/solo12.urdf:" \
  "solo12_floating:urdf/solo12.urdf:--floating" "g1_floating:humanoids/g1.urdf:--floating" \
  "talos_reduced_floating:humanoids/talos_reduced.urdf:--floating"; do
  IFS=: read -r name file floating <<< "$entry"
  # shellcheck disable=SC2086
  "$DALEMBERT" urdf "tests/reference/$file" $floating --name Robot \
    --outputs accelerations_jacobian > "$WORK/$name.dal"
  "$DALEMBERT" generate "$WORK/$name.dal" > "$WORK/$name.rs"
  python3 scripts/bench/op_counts.py "$WORK/$name.rs" > "$WORK/$name.csv"
  if [ -n "$COUNTER" ]; then
    # shellcheck disable=SC2086
    "${PYTHON:-python3}" "$PINOCCHIO_HARNESS/urdf_model.py" "tests/reference/$file" $floating \
      > "$WORK/$name.model"
    "$COUNTER" "$WORK/$name.model" > "$WORK/$name.pin.csv"
  fi
  nv=$(grep -o 'NV: usize = [0-9]*' "$WORK/$name.rs" | grep -o '[0-9]*$' | head -n1)
  mf=$(( $(flops "$WORK/$name.csv" mass_matrix) + $(flops "$WORK/$name.csv" forcing) ))
  acc=$(flops "$WORK/$name.csv" accelerations); jac=$(flops "$WORK/$name.csv" accelerations_jacobian)
  jsolve=$(solve "$WORK/$name.csv" accelerations_jacobian)
  crba=$(pin "$WORK/$name.pin.csv" crba); nle=$(pin "$WORK/$name.pin.csv" nonLinearEffects)
  pmf=""; [ -n "$crba" ] && pmf=$(( crba + nle ))
  aba=$(pin "$WORK/$name.pin.csv" aba); der=$(pin "$WORK/$name.pin.csv" computeABADerivatives)
  echo "| $name ($nv) | $(k "$mf") | $(k "$pmf") | $(ratio "$mf" "$pmf") | $(k "$acc") | $(k "$aba") | $(ratio "$acc" "$aba") | $(k "$jac") ($(k "$jsolve")) | $(k "$der") | $(ratio "$jac" "$der") | $(ratio "$jac" "$acc") |"
done
echo
printf 'Counted %s, commit `%s`.\n\n' "$(date -u '+%a %d %b %Y %H:%M UTC')" "$(git rev-parse --short HEAD)"
echo "    scripts/bench/op_counts.sh   # with PINOCCHIO_HARNESS=DIR, as scripts/benchmarks.sh --peers DIR sets it"
