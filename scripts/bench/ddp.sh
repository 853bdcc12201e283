#!/usr/bin/env bash
# Section "DDP": lab/examples/ddp.rs's problems solved by dalembert_lab::ddp
# and by Crocoddyl's FDDP (scripts/ddp_compare.sh, which leaves the solvers'
# JSON lines in target/ddp_compare/), CROCODDYL_PYTHON the Python with
# Crocoddyl (default ~/.cache/crocoddyl-venv/bin/python).
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh"

quietly scripts/ddp_compare.sh ${CROCODDYL_PYTHON:+"$CROCODDYL_PYTHON"}

cat <<'MD'
## DDP over the exact step jacobians against Crocoddyl

`lab/examples/ddp.rs` (`dalembert_lab::ddp` over `euler_step_jacobian`)
against Crocoddyl 3.2.1's `SolverFDDP`, one thread, same problems
(`scripts/ddp_crocoddyl.py`, `docs/control.md`): a UR5 to a joint pose and
its `tool0` to a pose (100 × 10 ms), a cart-pole swing-up (150 × 20 ms).
Best of 5 solves, thread CPU time; the cart-pole's actuation in Crocoddyl
is Python, so only the UR5's ratios are fair.

MD
python3 - target/ddp_compare/dalembert.jsonl target/ddp_compare/crocoddyl.jsonl <<'PY'
import json, sys
def solves(path):
    with open(path) as f:
        return {r["problem"]: r for r in map(json.loads, f) if "problem" in r}
ours, theirs = solves(sys.argv[1]), solves(sys.argv[2])
if not ours or set(ours) != set(theirs):
    sys.exit(f"the solvers' problems differ: {sorted(ours)} against {sorted(theirs)}")
print("| problem | cost, dalembert | cost, Crocoddyl | relative difference | iterations | µs per iteration, dalembert | Crocoddyl | ratio |")
print("|---|---|---|---|---|---|---|---|")
summaries = []
for name, a in ours.items():
    b = theirs[name]
    ratio = a["seconds_per_iteration"] / b["seconds_per_iteration"]
    print(f"| {name} | {a['cost']:.10g} | {b['cost']:.10g} | {abs(a['cost'] - b['cost']) / abs(b['cost']):.1e} "
          f"| {a['iterations']} / {b['iterations']} | {a['seconds_per_iteration'] * 1e6:.1f} "
          f"| {b['seconds_per_iteration'] * 1e6:.1f} | **{ratio:.2f}** |")
    if "ur5" in name:
        summaries.append(f"<!-- summary: DDP, time per iteration, {name} | Crocoddyl `SolverFDDP` | {ratio:.2f} -->")
with open(sys.argv[1]) as f:
    pose = {r["pose_error"]: r for r in map(json.loads, f) if "pose_error" in r}
if "ur5_pose" in pose:
    e = pose["ur5_pose"]
    print(f"\nThe tool ends {e['translation']:.1e} m and {e['rotation']:.1e} rad from its target pose.")
print()
print("\n".join(summaries))
PY
echo
measured "one run of each solver"
cat <<'MD'

    scripts/ddp_compare.sh [CROCODDYL_PYTHON]
MD
