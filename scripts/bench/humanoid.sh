#!/usr/bin/env bash
# Floating humanoids and MuJoCo's humanoid against the peers, in one run: prints
# one markdown section (BENCHMARKS.md, via scripts/benchmarks.sh).
#
#   scripts/bench/humanoid.sh
#
# Times, in the same window:
# * ours: scripts/bench/humanoid_timing.rs (thread CPU time, the peers' method):
#   `mass_matrix` + `forcing`, `dalembert::accelerations` and
#   `accelerations_jacobian` of the floating Unitree G1 and Talos
#   (tests/reference/humanoids/) and Solo-12, imported with `--floating` and
#   `accelerations_jacobian, linearize` (as generated/build.rs does under its
#   `humanoids` feature), and the first two of dm_control's humanoid and cheetah
#   (imported from MJCF); built in release in a temporary crate that depends on
#   this repository (sharing its target directory), which also gives the build time;
# * Pinocchio (header-only, -O3 -march=native): the peers' harness
#   `run.sh --urdf ROBOT.urdf --floating` (pin_crba_sym + pin_nle, pin_aba,
#   pin_aba_derivatives), from $PINOCCHIO_HARNESS (the folder of run.sh; set by
#   scripts/benchmarks.sh --peers DIR);
# * MuJoCo's mj_forward through its C API (scripts/bench/mj_forward.c, contacts,
#   constraints and actuation disabled), built against $MUJOCO_DIR (the folder
#   holding include/mujoco/mujoco.h and libmujoco.so*; default: the `mujoco`
#   wheel's package folder in the peers' Python environment).
# Without either peer the script fails.
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh"
ROOT="$(pwd)"
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK" "$STAMP"' EXIT
mkdir -p "$CARGO_TARGET_DIR"
TARGET="$(cd "$CARGO_TARGET_DIR" && pwd)"
[ -f "${PINOCCHIO_HARNESS:-}/run.sh" ] || { echo "set PINOCCHIO_HARNESS (or --peers DIR) to the peers' harness" >&2; exit 1; }

# Ours: the models' code, then the harness, as "robot function ns".
cargo build -q --release -p dalembert-codegen --bin dalembert
DALEMBERT="$TARGET/release/dalembert"
mkdir -p "$WORK/models" "$WORK/crate"
# Named as humanoid_timing.rs names them.
for entry in g1:humanoids/g1.urdf:G1 talos_reduced:humanoids/talos_reduced.urdf:Talos \
  solo12:urdf/solo12.urdf:FloatingSolo12; do
  IFS=: read -r model file name <<< "$entry"
  "$DALEMBERT" urdf "tests/reference/$file" --floating --name "$name" \
    --outputs "accelerations_jacobian, linearize" > "$WORK/models/$model.dal"
done
for model in humanoid cheetah; do
  "$DALEMBERT" mjcf "tests/reference/mjcf/dm_control/$model.xml" > "$WORK/models/$model.dal"
done
for model in g1 talos_reduced solo12 humanoid cheetah; do
  "$DALEMBERT" generate "$WORK/models/$model.dal" > "$WORK/models/$model.rs"
done
{
  echo '[package]'
  echo 'name = "humanoid-timing"'
  echo 'version = "0.0.0"'
  echo 'edition = "2024"'
  echo 'publish = false'
  echo '[[bin]]'
  echo 'name = "humanoid-timing"'
  echo "path = \"$ROOT/scripts/bench/humanoid_timing.rs\""
  echo '[dependencies]'
  echo "dalembert = { path = \"$ROOT\", default-features = false }"
  echo '[workspace]'
} > "$WORK/crate/Cargo.toml"
# The runtime first, so that the timed build is the models' code alone.
CARGO_TARGET_DIR="$TARGET" cargo build -q --release -p dalembert
start=$(date +%s.%N)
HUMANOID_MODELS="$WORK/models" CARGO_TARGET_DIR="$TARGET" \
  cargo build -q --release --manifest-path "$WORK/crate/Cargo.toml"
build_s=$(echo "$(date +%s.%N) - $start" | bc -l | xargs printf '%.0f')
"$TARGET/release/humanoid-timing" > "$WORK/ours.txt"
ours() { awk -v r="$1" -v f="$2" '$1 == r && $2 == f { print $3 }' "$WORK/ours.txt"; }

# Pinocchio: median ns per algorithm, as "robot algo ns".
: > "$WORK/pinocchio.txt"
for robot in humanoids/g1 humanoids/talos_reduced urdf/solo12; do
  bash "$PINOCCHIO_HARNESS/run.sh" --urdf "tests/reference/$robot.urdf" --floating \
    --only pin_ | awk -F, -v r="$(basename "$robot")" \
    'NR > 1 { print r, $4, $5 }' >> "$WORK/pinocchio.txt"
done
pin() { awk -v r="$1" -v a="$2" '$1 == r && $2 == a { print $3 }' "$WORK/pinocchio.txt"; }

# MuJoCo: median ns of mj_forward, as "model ns".
: > "$WORK/mujoco.txt"
build_mj_forward "$WORK/mj_forward"
for model in humanoid cheetah; do
  "$WORK/mj_forward" "tests/reference/mjcf/dm_control/$model.xml" |
    awk -F, -v m="$model" 'NR > 1 { print m, $5 }' >> "$WORK/mujoco.txt"
done
[ "$(wc -l < "$WORK/pinocchio.txt")" -ge 18 ] && [ "$(wc -l < "$WORK/mujoco.txt")" -eq 2 ] &&
  [ "$(wc -l < "$WORK/ours.txt")" -ge 13 ] || { echo "ours or the peers' figures are incomplete" >&2; exit 1; }
mj() { awk -v m="$1" '$1 == m { print $2 }' "$WORK/mujoco.txt"; }

us() { [ -n "$1" ] && awk -v x="$1" 'BEGIN { printf "%.2f", x / 1000 }' || printf -- "–"; }
ratio() { [ -n "$1" ] && [ -n "$2" ] && awk -v a="$1" -v b="$2" 'BEGIN { printf "**%.2f**", a / b }' || { echo "missing figures" >&2; exit 1; }; }
sum() { [ -n "$1" ] && [ -n "$2" ] && awk -v a="$1" -v b="$2" 'BEGIN { print a + b }' || true; }

echo "## Floating humanoids against Pinocchio and MuJoCo"
echo
echo "Ours (\`scripts/bench/humanoid_timing.rs\`, default release build), Pinocchio (header-only,"
echo "\`-O3 -march=native\`) and MuJoCo's \`mj_forward\` (C API; contacts, constraints, actuation"
echo "off) in one run, thread CPU time over 1000 random states: µs per call and ours / theirs."
echo "Targets: M + f and accelerations ≤ 0.20 of Pinocchio's, the jacobian ≤ 0.33; ≤ 0.25 of"
echo "\`mj_forward\`. Operation counts explain the gaps (docs/humanoid.md)."
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
echo
echo "The five models' code (the humanoids and Solo-12 with \`accelerations_jacobian\` and \`linearize\`) built in release in ${build_s} s wall."
g1_mf=$(ours g1 "mass_matrix+forcing"); g1_pmf=$(sum "$(pin g1 pin_crba_sym)" "$(pin g1 pin_nle)")
echo
summary "\`mass_matrix\` + \`forcing\`, G1 floating (35 speeds)" "Pinocchio \`crba\` + \`nonLinearEffects\`" "$(ratio "$g1_mf" "$g1_pmf" | tr -d '*')"
summary "\`accelerations\`, G1 floating" "Pinocchio \`aba\`" "$(ratio "$(ours g1 accelerations)" "$(pin g1 pin_aba)" | tr -d '*')"
summary "\`accelerations_jacobian\`, G1 floating" "Pinocchio \`computeABADerivatives\`" "$(ratio "$(ours g1 accelerations_jacobian)" "$(pin g1 pin_aba_derivatives)" | tr -d '*')"
summary "\`accelerations\`, dm_control humanoid (27 speeds)" "MuJoCo \`mj_forward\`" "$(ratio "$(ours humanoid accelerations)" "$(mj humanoid)" | tr -d '*')"
echo
measured "ours and the peers' medians of thread CPU time"
cat <<'MD'

    scripts/bench/humanoid.sh   # with PINOCCHIO_HARNESS=DIR, as scripts/benchmarks.sh --peers DIR sets it
MD
