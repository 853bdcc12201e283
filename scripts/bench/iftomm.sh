#!/usr/bin/env bash
# Section "IFToMM": thread CPU time of whole 20 s simulations of the IFToMM
# N-four-bar mechanism (A02, N = 10 and 40) by the integrators and
# constraint solvers that reach 1e-3 m on the reference point (benches/iftomm.rs).
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh"

log="$CARGO_TARGET_DIR/bench-peers/iftomm.log"
mkdir -p "$(dirname "$log")"
cargo bench -p dalembert --bench iftomm 2> "$log" >&2

cat <<'MD'
## IFToMM A02: whole simulations through singular positions

Thread CPU time of one 20 s simulation of the N-four-bar mechanism (A02) per
method; only the runs checked to reach 1e-3 m on the reference point B0 are
timed (`benches/iftomm.rs`; `docs/iftomm.md` has the benchmarks and their
references).

MD
BENCH_PREFIX=a02_ table list
cat <<'MD'

The errors on B0 at N = 40 and how they move under perturbed starts (the
timed runs are those whose error "as set" is below 1e-3 m):

```text
MD
grep -E '\|' "$log"
echo '```'
echo
measured "criterion medians of thread CPU time"
cat <<'MD'

    cargo bench -p dalembert --bench iftomm
MD
