#!/bin/sh
# The DDP problems of lab/examples/ddp.rs solved by dalembert and by
# Crocoddyl (scripts/ddp_crocoddyl.py) back to back, one thread each, and
# compared: relative difference of the final costs (the script fails when
# it is above 1e-6) and the ratio of the times per iteration (best of 5
# solves each, CPU time of the thread).
#
#   scripts/ddp_compare.sh [CROCODDYL_PYTHON]
#
# CROCODDYL_PYTHON defaults to ~/.cache/crocoddyl-venv/bin/python, a venv of
# its own with `pip install crocoddyl` (see scripts/ddp_crocoddyl.py).
set -eu
cd "$(dirname "$0")/.."
python=${1:-$HOME/.cache/crocoddyl-venv/bin/python}
out=target/ddp_compare
mkdir -p "$out"
cargo build --release -q -p dalembert-lab --example ddp
date -u +"run at %Y-%m-%d %H:%M:%S UTC"
target/release/examples/ddp --out target/charts > "$out/dalembert.jsonl"
OMP_NUM_THREADS=1 "$python" scripts/ddp_crocoddyl.py --inputs target/charts 2>/dev/null > "$out/crocoddyl.jsonl"
cat "$out/dalembert.jsonl" "$out/crocoddyl.jsonl"
python3 - "$out/dalembert.jsonl" "$out/crocoddyl.jsonl" <<'PY'
import json, sys
def solves(path):
    return {r["problem"]: r for r in map(json.loads, open(path)) if "problem" in r}
ours, theirs = solves(sys.argv[1]), solves(sys.argv[2])
costed = {r["costed"]: r["cost"] for r in map(json.loads, open(sys.argv[2])) if "costed" in r}
apart = []
for name in ours:
    if name in costed:
        c = costed[name]
        print(f"{name}: dalembert's optimal inputs cost {c:.15g} in Crocoddyl's problem, "
              f"{ours[name]['cost']:.15g} in ours: relative difference {abs(c - ours[name]['cost']) / abs(c):.2e}")
    a, b = ours[name], theirs[name]
    print(f"{name}: cost {a['cost']:.10g} (dalembert) vs {b['cost']:.10g} (Crocoddyl), "
          f"relative difference {abs(a['cost'] - b['cost']) / abs(b['cost']):.2e}; "
          f"iterations {a['iterations']} vs {b['iterations']}; "
          f"time per iteration {a['seconds_per_iteration'] * 1e6:.1f} us vs "
          f"{b['seconds_per_iteration'] * 1e6:.1f} us: ratio {a['seconds_per_iteration'] / b['seconds_per_iteration']:.3f}")
    if abs(a['cost'] - b['cost']) > 1e-6 * abs(b['cost']):
        apart.append(name)
for r in map(json.loads, open(sys.argv[1])):
    if "pose_error" in r:
        print(f"{r['pose_error']}: dalembert's tool ends {r['translation']:.1e} m and {r['rotation']:.1e} rad from the target")
if apart:
    sys.exit(f"the optimal costs differ by more than 1e-6 relative: {', '.join(apart)}")
PY
