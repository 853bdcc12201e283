#!/usr/bin/env bash
# Floating humanoids and MuJoCo's humanoid against the peers, in one run: prints
# one markdown section (BENCHMARKS.md, via scripts/benchmarks.sh).
#
#   scripts/bench/humanoid.sh
#
# Times, in the same window:
# * ours: `cargo bench -p dalembert-generated --bench robots --features humanoids`
#   (criterion, the fixtures' 1000 states): `mass_matrix` + `forcing`,
#   `dalembert::accelerations` and `accelerations_jacobian` of the floating
#   Unitree G1 and Talos (tests/reference/humanoids/) and Solo-12, and the first two
#   of dm_control's humanoid and cheetah (imported from MJCF);
# * Pinocchio (header-only, -O3 -march=native): the peers' harness
#   `run.sh --urdf ROBOT.urdf --floating` (pin_crba_sym + pin_nle, pin_aba,
#   pin_aba_derivatives), from $PINOCCHIO_HARNESS (the folder of run.sh);
# * MuJoCo's mj_forward through its C API (scripts/bench/mj_forward.c, contacts,
#   constraints and actuation disabled), built against $MUJOCO_DIR (the folder
#   holding include/mujoco/mujoco.h and libmujoco.so*, e.g. the `mujoco` wheel's
#   package folder).
# A peer whose variable is unset is left out of the table.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
cd "$ROOT"

# Ours: criterion's middle estimate per function, in ns, as "robot function ns".
cargo bench -q -p dalembert-generated --bench robots --features humanoids -- \
  'robots/(floating_solo12|g1|talos_reduced|humanoid|cheetah)/(mass_matrix\+forcing|accelerations)' \
  2>/dev/null | awk '
    /^robots\// { name = $1 }
    /time:/ {
      gsub(/[\[\]]/, "");
      for (i = 1; i <= NF; i++) if ($i == "time:") { v = $(i + 3); u = $(i + 4) }
      f = (u == "ns") ? 1 : (u == "µs" || u == "us") ? 1e3 : (u == "ms") ? 1e6 : 1e9;
      split(name, p, "/"); printf "%s %s %.1f\n", p[2], p[3], v * f
    }' > "$WORK/ours.txt"

ours() { awk -v r="$1" -v f="$2" '$1 == r && $2 == f { print $3 }' "$WORK/ours.txt"; }

# Pinocchio: median ns per algorithm, as "robot algo ns".
: > "$WORK/pinocchio.txt"
if [ -n "${PINOCCHIO_HARNESS:-}" ]; then
  for robot in humanoids/g1 humanoids/talos_reduced urdf/solo12; do
    bash "$PINOCCHIO_HARNESS/run.sh" --urdf "tests/reference/$robot.urdf" --floating \
      --only pin_ 2>/dev/null | awk -F, -v r="$(basename "$robot")" \
      'NR > 1 { print r, $4, $5 }' >> "$WORK/pinocchio.txt"
  done
fi
pin() { awk -v r="$1" -v a="$2" '$1 == r && $2 == a { print $3 }' "$WORK/pinocchio.txt"; }

# MuJoCo: median ns of mj_forward, as "model ns".
: > "$WORK/mujoco.txt"
if [ -n "${MUJOCO_DIR:-}" ]; then
  cc -O2 scripts/bench/mj_forward.c -I"$MUJOCO_DIR/include" "$(ls "$MUJOCO_DIR"/libmujoco.so* | head -n1)" \
    -Wl,-rpath,"$MUJOCO_DIR" -lm -o "$WORK/mj_forward"
  for model in humanoid cheetah; do
    "$WORK/mj_forward" "tests/reference/mjcf/dm_control/$model.xml" 2>/dev/null |
      awk -F, -v m="$model" 'NR > 1 { print m, $5 }' >> "$WORK/mujoco.txt"
  done
fi
mj() { awk -v m="$1" '$1 == m { print $2 }' "$WORK/mujoco.txt"; }

us() { [ -n "$1" ] && awk -v x="$1" 'BEGIN { printf "%.2f", x / 1000 }' || printf -- "–"; }
ratio() { [ -n "$1" ] && [ -n "$2" ] && awk -v a="$1" -v b="$2" 'BEGIN { printf "**%.2f**", a / b }' || printf -- "–"; }
sum() { [ -n "$1" ] && [ -n "$2" ] && awk -v a="$1" -v b="$2" 'BEGIN { print a + b }' || true; }

echo "## Floating humanoids against Pinocchio and MuJoCo"
echo
echo "Measured $(date -u +%Y-%m-%d) with \`scripts/bench/humanoid.sh\` (ours: criterion, default"
echo "build; Pinocchio: the peers' harness, header-only, \`-O3 -march=native\`, thread CPU time;"
echo "MuJoCo: \`mj_forward\` through its C API, contacts, constraints and actuation disabled), in one"
echo "run; µs per call, and ours / theirs. Targets (issue #40): M + f ≤ 0.20 of \`crba\` +"
echo "\`nonLinearEffects\`, accelerations ≤ 0.20 of \`aba\`, \`accelerations_jacobian\` ≤ 0.33 of"
echo "\`computeABADerivatives\`; ≤ 0.25 of \`mj_forward\` (issue #35). The operation counts that"
echo "explain the gaps: docs/humanoid.md."
echo
echo "| robot (speeds) | M + f | crba + nle | ratio | accelerations | aba | ratio | accelerations_jacobian | computeABADerivatives | ratio |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for robot in g1:35 talos_reduced:38 solo12:18; do
  name=${robot%%:*}; nv=${robot##*:}
  mine=$name; [ "$name" = solo12 ] && mine=floating_solo12
  mf=$(ours "$mine" "mass_matrix+forcing"); acc=$(ours "$mine" accelerations)
  jac=$(ours "$mine" accelerations_jacobian)
  pmf=$(sum "$(pin "$name" pin_crba_sym)" "$(pin "$name" pin_nle)")
  paba=$(pin "$name" pin_aba); pder=$(pin "$name" pin_aba_derivatives)
  echo "| $name, floating ($nv) | $(us "$mf") | $(us "$pmf") | $(ratio "$mf" "$pmf") | $(us "$acc") | $(us "$paba") | $(ratio "$acc" "$paba") | $(us "$jac") | $(us "$pder") | $(ratio "$jac" "$pder") |"
done
echo
echo "| MJCF model (speeds) | M + f | accelerations | mj_forward | M + f / mj_forward | accelerations / mj_forward |"
echo "|---|---|---|---|---|---|"
for model in humanoid:27 cheetah:9; do
  name=${model%%:*}; nv=${model##*:}
  mf=$(ours "$name" "mass_matrix+forcing"); acc=$(ours "$name" accelerations); fwd=$(mj "$name")
  echo "| dm_control $name ($nv) | $(us "$mf") | $(us "$acc") | $(us "$fwd") | $(ratio "$mf" "$fwd") | $(ratio "$acc" "$fwd") |"
done
