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

Every integration of `Constrained` dynamics checks, after each accepted
step, the residual and velocity form of every constraint row
(`DriftLimits::default()`), and, for the runs that do not project, the
rows' conditioning (a factorisation of the mass matrix and the Schur
complement). RK4, 1000 steps (of 1 ms; of 0.5 ms for the four-bars, whose cranks fall flat at 0.72 s), time per step (criterion's median),
watched and with `DriftLimits::UNWATCHED`:

MD
python3 - "$CRITERION_DIR" "$STAMP" <<'PY'
import glob, json, os, sys
root, stamp = sys.argv[1], os.path.getmtime(sys.argv[2])
STEPS = 1000
medians = {}
for path in glob.glob(os.path.join(root, "**", "new", "benchmark.json"), recursive=True):
    estimates = path.replace("benchmark.json", "estimates.json")
    if os.path.getmtime(estimates) < stamp:
        continue  # an earlier run's
    with open(path) as f:
        name = json.load(f)["full_id"]
    with open(estimates) as f:
        medians[name] = json.load(f)["median"]["point_estimate"] / STEPS / 1e3
systems = [("seed_3", "seed example 3 (3 coordinates, 2 rows)"),
           ("four_bars_10", "IFToMM A02, ten four-bars (21 coordinates, 20 rows)")]
print("| system | stabilisation | watched (µs/step) | unwatched (µs/step) | watch's share |")
print("|---|---|---|---|---|")
for system, label in systems:
    for stabilisation in ("unstabilised", "projected"):
        w = medians[f"drift_watch/{system}/{stabilisation}/watched"]
        u = medians[f"drift_watch/{system}/{stabilisation}/unwatched"]
        print(f"| {label} | {stabilisation} | {w:.2f} | {u:.2f} | {(w - u) / w:.0%} |")
PY
echo
measured "criterion medians"
cat <<'MD'

    cargo bench -p dalembert --bench drift_watch -- --warm-up-time 1 --measurement-time 3
MD
