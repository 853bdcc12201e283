#!/usr/bin/env bash
# Section "Four states at once": the generated accelerations_x4 (one state in
# each lane of a wide::f64x4) against the scalar accelerations, per state, on
# the default target and on x86-64-v3 (generated/benches/lanes.rs, built a
# second time in a target directory of its own; LANES_V3=0 leaves it out),
# and the batched RK4 step against MuJoCo's in the same window when the
# peers' harness is given (DALEMBERT_PEERS).
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh"

out="$CARGO_TARGET_DIR/bench-peers/lanes"
mkdir -p "$out"
v3="$CARGO_TARGET_DIR/x86-64-v3"
quietly cargo bench -p dalembert-generated --features large --bench lanes -- --warm-up-time 1 --measurement-time 3
# LANES_V3=0 leaves the x86-64-v3 run out (it is a release build of its own),
# and so does a machine without AVX2 (x86-64-v3's binaries would not run).
if [ "${LANES_V3:-1}" = 0 ]; then
    v3="" v3_missing="left out of this run (\`LANES_V3=0\`)"
elif ! grep -qw avx2 /proc/cpuinfo 2>/dev/null; then
    v3="" v3_missing="left out: this machine has no AVX2"
else
    RUSTFLAGS="-C target-cpu=x86-64-v3" CARGO_TARGET_DIR="$v3" \
        quietly cargo bench -p dalembert-generated --bench lanes -- --warm-up-time 1 --measurement-time 3
fi
peers_csv=()
if [ -n "${DALEMBERT_PEERS:-}" ]; then
    peers --ns 12 --families spatial --only mj_step > "$out/chains.csv"
    peers_csv=("$out/chains.csv")
fi

cat <<'MD'
## Four states at once

`accelerations_x4` (`outputs accelerations_x4;`) solves four states a call,
one in each lane of a `wide::f64x4`: its time over four against the scalar
`accelerations` (the recursion on the chain of 30, over the lanes on the
chains of 12 and 30; the unrolled `L D Lᵀ` elsewhere). Then one RK4 step of
the chain of 12, `Rk4::step` and `control::rk4_group_step_x4`, against
MuJoCo's `mj_step` with its RK4.

MD
python3 - "$CARGO_TARGET_DIR" "$v3" "${v3_missing:-}" "$STAMP" "${peers_csv[@]}" <<'PY'
import sys
sys.path.insert(0, "scripts/bench/lib")
from criterion_table import medians, ns, peer_rows, quotient, ratio, summary

target, v3, v3_missing, since, *csvs = sys.argv[1:]
default, avx = medians(target, since), (medians(v3, since) if v3 else {})
peers = peer_rows(csvs)
systems = [("spatial_chain_06", 6), ("spatial_chain_12", 12), ("spatial_chain_30", 30),
           ("panda", 9), ("floating_solo12", 18)]
print("| system | n | scalar (ns) | x4, per state (ns) | ratio | v3 scalar (ns) | v3 x4, per state (ns) | v3 ratio |")
print("|---|---|---|---|---|---|---|---|")
for name, n in systems:
    row = []
    for found in (default, avx):
        one = found.get(f"lanes/{name}/accelerations")
        four = found.get(f"lanes/{name}/accelerations_x4 per state")
        row += [ns(one), ns(four), ratio(four, one)]
    print(f"| {name} | {n} | " + " | ".join(row) + " |")
if not v3:
    print()
    print(f"The x86-64-v3 build was {v3_missing}.")
print()
print("| RK4 step, h = 1 ms, spatial chain of 12 | default (ns) | MuJoCo `mj_step` RK4 / ours | v3 (ns) | MuJoCo / ours |")
print("|---|---|---|---|---|")
mujoco = peers.get(("spatial_12", "mj_step_rk4"))
for label, bench in [("one state a call", "rk4 step"), ("four a call, per state", "rk4 step x4 per state")]:
    ours, fast = default.get(f"lanes/spatial_chain_12/{bench}"), avx.get(f"lanes/spatial_chain_12/{bench}")
    print(f"| {label} | {ns(ours)} | {ratio(mujoco, ours)} | {ns(fast)} | {ratio(mujoco, fast)} |")
print()
summary("`accelerations_x4` per state, spatial chains 6–30, panda, Solo-12", "our scalar `accelerations`",
        [quotient(default.get(f"lanes/{name}/accelerations_x4 per state"), default.get(f"lanes/{name}/accelerations"))
         for name, _ in systems])
if mujoco:
    summary("one RK4 step, four states a call, per state, spatial chain of 12", "MuJoCo's RK4 step (`mj_step`)",
            [quotient(default.get("lanes/spatial_chain_12/rk4 step x4 per state"), mujoco)])
PY
echo
measured "criterion medians of thread CPU time; the peers' medians in the same window where given"
cat <<'MD'

    cargo bench -p dalembert-generated --features large --bench lanes -- --warm-up-time 1 --measurement-time 3
    RUSTFLAGS="-C target-cpu=x86-64-v3" cargo bench -p dalembert-generated --bench lanes -- --warm-up-time 1 --measurement-time 3
    bash $DALEMBERT_PEERS/run.sh --ns 12 --families spatial --only mj_step
MD
