#!/usr/bin/env bash
# Section "Work-precision": final-state error against CPU time for every
# integrator on seed examples 1 and 3 and the slider-crank, with SciPy's
# solve_ivp for comparison (examples/work_precision, scripts/scipy_baseline.sh,
# run in the peers' Python environment, which has SciPy and SymPy, unless
# $SCIPY_VENV says another). Redraws docs/charts/wp_*.svg.
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh"

export SCIPY_VENV="${SCIPY_VENV:-${PEERS_VENV:-$HOME/.cache/dalembert-peers-venv}}"
scipy_csv="$CARGO_TARGET_DIR/charts/scipy_dop853.csv"
quietly scripts/scipy_baseline.sh --out "$scipy_csv"
quietly cargo build --release --example work_precision
run() { "$CARGO_TARGET_DIR/release/examples/work_precision" --out docs/charts --scipy "$scipy_csv" "$@" | grep -v '^wrote '; }
summary=$(run)
taylor=$(run --taylor)

cat <<'MD'
## Work-precision: what each integrator buys

Final-state error against thread CPU time, every integrator of
`dalembert::integrate` and SciPy's `solve_ivp` over SymPy's `lambdify(cse=True)`.
Seed example 1 from θ₁ = θ₂ = 2 rad is chaotic (floor ≈ 3e-8); `--taylor`
adds the pendulum at 0.2 rad and seed example 3. Times to equal error:

MD
printf '%s\n%s\n' "$summary" "$taylor" | python3 -c '
import re, sys
text = sys.stdin.read()
scipy = re.search(r"at final-state error (\S+): our DOP853 (\S+) ms, SciPy.s (\S+) ms", text)
taylor = re.search(r"at final-state error (\S+) \(0.2 rad\): DOP853 (\S+) µs, Taylor (\S+) µs", text)
if not scipy or not taylor:
    sys.exit("work_precision printed no comparison at equal error:\n" + text)
error, ours, theirs = scipy.groups()
print("| run | final-state error | ours | theirs | ours / theirs |")
print("|---|---|---|---|---|")
print(f"| seed example 1 (chaotic), our DOP853 / SciPy `solve_ivp` DOP853 | {error} | {ours} ms | {theirs} ms "
      f"| **{float(ours) / float(theirs):.4f}** |")
error, dop853, ours = taylor.groups()
print(f"| seed example 1 at 0.2 rad, Taylor (`outputs taylor;`) / our DOP853 | {error} | {ours} µs | {dop853} µs "
      f"| **{float(ours) / float(dop853):.2f}** |")
print()
print(f"<!-- summary: DOP853 to equal final-state error, seed example 1 | SciPy `solve_ivp` DOP853 (SymPy `lambdify`) "
      f"| {float(scipy.group(2)) / float(scipy.group(3)):.4f} -->")
'
echo
measured "one run, thread CPU time"
cat <<'MD'

    scripts/scipy_baseline.sh --out target/charts/scipy_dop853.csv
    cargo run --release --example work_precision -- --out docs/charts --scipy target/charts/scipy_dop853.csv   # and --taylor

| seed example 1 | seed example 1 at 0.2 rad |
|---|---|
| ![work-precision, seed 1](docs/charts/wp_seed_1.svg) | ![work-precision, regular pendulum](docs/charts/wp_regular_pendulum.svg) |
MD
