#!/usr/bin/env bash
# Section "DDP": lab/examples/ddp.rs's UR5 joint-space reach, UR5 tool-pose
# reach and cart-pole swing-up solved by dalembert_lab::ddp and by
# Crocoddyl's FDDP in one run of scripts/ddp_compare.sh, as a table.
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh"

quietly scripts/ddp_compare.sh ${CROCODDYL_PYTHON:+"$CROCODDYL_PYTHON"}
rows=$(python3 - target/ddp_compare/dalembert.jsonl target/ddp_compare/crocoddyl.jsonl <<'PY'
import json, sys
def lines(path):
    return list(map(json.loads, open(path)))
ours = {r["problem"]: r for r in lines(sys.argv[1]) if "problem" in r}
theirs = {r["problem"]: r for r in lines(sys.argv[2]) if "problem" in r}
pose = {r["pose_error"]: r for r in lines(sys.argv[1]) if "pose_error" in r}
names = {"ur5": "UR5, joint-space reach", "ur5_pose": "UR5, tool pose reach", "cart_pole": "cart-pole swing-up"}
for name, label in names.items():
    a, b = ours[name], theirs[name]
    ratio = a["seconds_per_iteration"] / b["seconds_per_iteration"]
    bold = "**" if name != "cart_pole" else ""
    print(f"| {label} | {a['cost']:.10g} | {abs(a['cost'] - b['cost']) / abs(b['cost']):.1e} | "
          f"{a['iterations']} / {b['iterations']} | {a['seconds_per_iteration'] * 1e6:.0f} µs | "
          f"{b['seconds_per_iteration'] * 1e6:.0f} µs | {bold}{ratio:.2f}{bold} |")
e = pose["ur5_pose"]
print(f"\nThe tool ends {e['translation']:.1e} m and {e['rotation']:.1e} rad from its target pose.")
PY
)

cat <<'MD'
## DDP over the exact step jacobians against Crocoddyl

The same three problems solved by `dalembert_lab::ddp` over
`dalembert::control::euler_step_jacobian` and by Crocoddyl 3.2.1's
`SolverFDDP` (one thread): a UR5 reaching a joint-space pose and the UR5's
tool flange reaching a pose (translation and `log₃` rotation errors of
`tool0`, Crocoddyl's `ResidualModelFrameTranslation` and
`ResidualModelFrameRotation`), both 100 × 10 ms, and a cart-pole swing-up,
150 × 20 ms (`docs/control.md`). Time per iteration is the best of 5
solves, CPU time of the solving thread; the cart-pole's Crocoddyl actuation
is a Python model, so its ratio is not a fair one.

| problem | optimal cost | relative difference (≤ 1e-6) | iterations (dalembert / Crocoddyl) | dalembert per iteration | Crocoddyl | ratio (≤ 1/3) |
|---|---|---|---|---|---|---|
MD
echo "$rows"
echo
measured "one run of each solver"
cat <<'MD'

    scripts/ddp_compare.sh [CROCODDYL_PYTHON]

![DDP, UR5's tool pose](docs/charts/ddp_ur5_pose_tool.svg)
![DDP convergence](docs/charts/ddp_convergence.svg)
MD
