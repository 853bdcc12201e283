#!/usr/bin/env bash
# Section "DDP": lab/examples/ddp.rs's UR5 reach and cart-pole swing-up
# solved by dalembert_lab::ddp and by Crocoddyl's FDDP (scripts/ddp_compare.sh).
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh"

compare=$(scripts/ddp_compare.sh ${CROCODDYL_PYTHON:+"$CROCODDYL_PYTHON"} | grep -E 'relative difference' )

cat <<'MD'
## DDP over the exact step jacobians against Crocoddyl

The same two problems (a UR5 reach, horizon 100 × 10 ms; a cart-pole
swing-up, 150 × 20 ms) solved by `dalembert_lab::ddp` over
`dalembert::control::euler_step_jacobian` and by Crocoddyl's `SolverFDDP`;
time per iteration is the best of 5 solves, CPU time of the solving thread
(`docs/control.md`).

```text
MD
echo "$compare"
echo '```'
echo
measured "one run of each solver"
cat <<'MD'

    scripts/ddp_compare.sh [CROCODDYL_PYTHON]

![DDP, UR5](docs/charts/ddp_ur5.svg)
![DDP convergence](docs/charts/ddp_convergence.svg)
MD
