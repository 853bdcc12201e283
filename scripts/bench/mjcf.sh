#!/usr/bin/env bash
# Section "MJCF": dm_control's cheetah and humanoid imported by Builder::mjcf
# against MuJoCo's mj_forward through its C API (generated/benches/robots.rs
# and scripts/bench/mj_forward.c, same window).
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh"

out="$CARGO_TARGET_DIR/bench-peers/mjcf"
mkdir -p "$out"
quietly cargo bench -p dalembert-generated --features large --bench robots -- 'robots/(cheetah|humanoid)/'
build_mj_forward "$out/mj_forward"
for model in cheetah humanoid; do
    "$out/mj_forward" "tests/reference/mjcf/dm_control/$model.xml" > "$out/$model.csv"
done

cat <<'MD'
## MJCF models against MuJoCo

dm_control's cheetah (9 speeds, fixed base) and humanoid (27 speeds, free
joint) imported by `Builder::mjcf`, against MuJoCo's `mj_forward` through
its C API with contacts, constraints and actuation disabled (positions, M
and its factorisation, bias forces, accelerations): ours / theirs.

MD
table mjcf "$out"/{cheetah,humanoid}.csv
echo
measured "criterion medians, MuJoCo's median of thread CPU time"
cat <<'MD'

    cargo bench -p dalembert-generated --features large --bench robots -- 'robots/(cheetah|humanoid)/'
    cc -O2 scripts/bench/mj_forward.c -I$MUJOCO/include $MUJOCO/libmujoco.so* -lm -o mj_forward
    ./mj_forward tests/reference/mjcf/dm_control/humanoid.xml   # and cheetah.xml
MD
