#!/usr/bin/env bash
# Section "Robots": the URDF robots imported by Builder::urdf against
# Pinocchio on the same files (generated/benches/robots.rs and the peers'
# harness's --urdf mode, same window).
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh"

out="$CARGO_TARGET_DIR/bench-peers/robots"
mkdir -p "$out"
quietly cargo bench -p dalembert-generated --features large --bench robots -- 'robots/(panda|ur5|solo12|floating_solo12)/'
peers --urdf tests/reference/urdf/panda.urdf > "$out/panda.csv"
peers --urdf tests/reference/urdf/ur5_robot.urdf > "$out/ur5.csv"
peers --urdf tests/reference/urdf/solo12.urdf > "$out/solo12.csv"
peers --urdf tests/reference/urdf/solo12.urdf --floating > "$out/floating_solo12.csv"

cat <<'MD'
## Robots from URDF against Pinocchio

`tests/reference/urdf/` by `Builder::urdf` against Pinocchio reading the
same files: M + f against `crba` + `nonLinearEffects`, `accelerations` against `aba`.

MD
python3 benches/robots_table.py "$out"/{panda,ur5,solo12,floating_solo12}.csv --target "$CARGO_TARGET_DIR" --since "$STAMP"
echo
measured "criterion medians, the peers' medians of thread CPU time"
cat <<'MD'

    cargo bench -p dalembert-generated --features large --bench robots -- 'robots/(panda|ur5|solo12|floating_solo12)/'
    bash $DALEMBERT_PEERS/run.sh --urdf tests/reference/urdf/panda.urdf   # ur5_robot, solo12, solo12 --floating
    python3 benches/robots_table.py panda.csv ur5.csv solo12.csv floating_solo12.csv
MD
