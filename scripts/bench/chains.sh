#!/usr/bin/env bash
# Section "Chains": the planar and spatial n-link chains in their three
# spellings against Pinocchio's crba + nonLinearEffects and aba and MuJoCo's
# M + bias and mj_forward (generated/benches/spellings.rs and the peers'
# harness, same window).
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh"

peers_csv="$CARGO_TARGET_DIR/bench-peers/chains.csv"
mkdir -p "$(dirname "$peers_csv")"
quietly cargo bench -p dalembert-generated --features large --bench spellings -- --warm-up-time 1 --measurement-time 3
peers --ns 2,6,12,30 > "$peers_csv"
quietly cargo bench -p dalembert-generated --features large --bench chains -- '^(planar|spatial)/60/'
peers --ns 60 > "${peers_csv%.csv}_60.csv"

cat <<'MD'
## Chains against Pinocchio and MuJoCo

The chains of `tests/reference/` (planar: revolute z; spatial: axes z, y,
z, …) in three spellings, each cell joints / symbolic / seed's frames:
M + f against `crba` + `nonLinearEffects` and MuJoCo's M + bias,
`accelerations` against `aba` and `mj_forward`.

MD
python3 benches/spellings_table.py "$peers_csv" "$CARGO_TARGET_DIR" --since "$STAMP"
cat <<'MD'

At n = 60 (the `joint` spelling, generated with the `large` feature):

MD
table chains60 "${peers_csv%.csv}_60.csv"
echo
measured "criterion medians, the peers' medians of thread CPU time"
cat <<'MD'

    cargo bench -p dalembert-generated --features large --bench spellings -- --warm-up-time 1 --measurement-time 3
    bash $DALEMBERT_PEERS/run.sh --ns 2,6,12,30
    python3 benches/spellings_table.py PEERS.csv
    cargo bench -p dalembert-generated --features large --bench chains -- '^(planar|spatial)/60/'
    bash $DALEMBERT_PEERS/run.sh --ns 60
MD
