#!/usr/bin/env bash
# Section "The drift watch's cost": benches/drift_watch.rs, RK4 runs of
# constrained systems with the default DriftLimits against the same runs
# with DriftLimits::UNWATCHED; prints one markdown section on stdout
# (cargo's and criterion's output on stderr).
#
#   bash scripts/bench/reliability.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh"

quietly cargo bench -p dalembert --bench drift_watch -- --warm-up-time 1 --measurement-time 3

cat <<'MD'
## The drift watch's cost

`Constrained` dynamics check every constraint row's residual after each
step (and, unprojected, the rows' conditioning). RK4, 1000 steps of 1 ms
(0.5 ms for the four-bars), watched and with `DriftLimits::UNWATCHED`:

MD
table drift_watch
echo
measured "criterion medians of thread CPU time"
cat <<'MD'

    cargo bench -p dalembert --bench drift_watch -- --warm-up-time 1 --measurement-time 3
MD
