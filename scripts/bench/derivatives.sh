#!/usr/bin/env bash
# Section "Exact derivatives": the generated accelerations_jacobian against
# accelerations and Pinocchio's computeABADerivatives
# (generated/benches/derivatives.rs and the peers' harness, same window).
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh"

out="$CARGO_TARGET_DIR/bench-peers/derivatives"
mkdir -p "$out"
quietly cargo bench -p dalembert-generated --features large --bench derivatives -- --warm-up-time 1 --measurement-time 3
peers --ns 2,6,12 --only derivatives > "$out/chains.csv"
peers --urdf tests/reference/urdf/panda.urdf --only derivatives > "$out/panda.csv"
peers --urdf tests/reference/urdf/ur5_robot.urdf --only derivatives > "$out/ur5.csv"

cat <<'MD'
## Exact derivatives against Pinocchio

`accelerations_jacobian` (∂v̇/∂q, ∂v̇/∂v, ∂v̇/∂u) against the system's
`accelerations` and Pinocchio's `computeABADerivatives`.

MD
table derivatives "$out"/{chains,panda,ur5}.csv
echo
measured "criterion medians, the peers' medians of thread CPU time"
cat <<'MD'

    cargo bench -p dalembert-generated --features large --bench derivatives -- --warm-up-time 1 --measurement-time 3
    bash $DALEMBERT_PEERS/run.sh --ns 2,6,12 --only derivatives
    bash $DALEMBERT_PEERS/run.sh --urdf tests/reference/urdf/panda.urdf --only derivatives   # and ur5_robot
MD
