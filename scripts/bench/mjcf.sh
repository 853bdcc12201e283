#!/usr/bin/env bash
# Section "MJCF": dm_control's cheetah and humanoid imported by Builder::mjcf
# against MuJoCo's mj_forward through its Python bindings
# (generated/benches/robots.rs and scripts/mjcf_timing.py, same window).
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh"

quietly cargo bench -p dalembert-generated --bench robots -- 'robots/(cheetah|humanoid)/'
mujoco=$("$(peers_python)" scripts/mjcf_timing.py)

cat <<'MD'
## MJCF models against MuJoCo

dm_control's cheetah (9 speeds, fixed base) and humanoid (27 speeds, free
joint) imported by `Builder::mjcf`, against MuJoCo's `mj_forward` with
contacts, constraints and actuation disabled. MuJoCo is timed through its
Python bindings, the binding's call left in: its figure is an upper bound,
loose for the small cheetah.

MD
BENCH_PREFIX=robots/ table list | grep -E '^\|(---| benchmark)|cheetah|humanoid'
echo
echo '```text'
echo "$mujoco"
echo '```'
echo
measured "criterion medians; MuJoCo's best of seven rounds"
cat <<'MD'

    cargo bench -p dalembert-generated --bench robots -- 'robots/(cheetah|humanoid)/'
    python scripts/mjcf_timing.py   # in the peers' Python environment (mujoco)
MD
