#!/usr/bin/env bash
# Section "IFToMM": thread CPU time of whole 20 s simulations of the IFToMM
# N-four-bar mechanism (A02, N = 10 and 40) by the integrators and
# constraint solvers that reach 1e-3 m on the reference point (benches/iftomm.rs).
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh"

quietly cargo bench -p dalembert --bench iftomm

cat <<'MD'
## IFToMM A02: whole simulations through singular positions

Thread CPU time of one 20 s simulation of the N-four-bar mechanism per
method, for the runs that reach 1e-3 m on point B0 (`docs/iftomm.md`).

MD
BENCH_PREFIX=a02_ table list
cat <<'MD'
MD
echo
measured "criterion medians of thread CPU time"
cat <<'MD'

    cargo bench -p dalembert --bench iftomm
MD
