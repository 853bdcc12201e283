#!/usr/bin/env bash
# Section "Integrators": each integrator's cost per evaluation over the bare
# `accelerations` loop, and fixed-step RK4's time per step against MuJoCo's
# own RK4 (generated/benches/integrators.rs and the peers' harness).
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh"

out="$CARGO_TARGET_DIR/bench-peers/integrators"
mkdir -p "$out"
quietly cargo bench -p dalembert-generated --features large --bench integrators
peers --ns 2,6,12,30 --only mj_step > "$out/chains.csv"

cat <<'MD'
## Integrators: cost per evaluation, and throughput against MuJoCo

Each integrator's cost per evaluation beside a bare loop of `accelerations`:

MD
table integrators
cat <<'MD'

Fixed-step RK4 at h = 1 ms, per step, against one step of MuJoCo's own RK4
(`mj_step` with `mjINT_RK4`) on the same chains:

MD
table throughput "$out/chains.csv"
echo
measured "criterion medians, the peers' medians of thread CPU time"
cat <<'MD'

    cargo bench -p dalembert-generated --features large --bench integrators
    bash $DALEMBERT_PEERS/run.sh --ns 2,6,12,30 --only mj_step
MD
