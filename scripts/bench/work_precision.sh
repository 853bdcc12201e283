#!/usr/bin/env bash
# Section "Work-precision": final-state error against CPU time for every
# integrator on seed examples 1 and 3 and the slider-crank, with SciPy's
# solve_ivp for comparison (examples/work_precision, scripts/scipy_baseline.sh).
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh"

quietly scripts/scipy_baseline.sh
quietly cargo build --release --example work_precision
summary=$("$CARGO_TARGET_DIR/release/examples/work_precision" --out docs/charts --scipy target/charts/scipy_dop853.csv | grep -v '^wrote ')
taylor=$("$CARGO_TARGET_DIR/release/examples/work_precision" --out docs/charts --scipy target/charts/scipy_dop853.csv --taylor | grep -v '^wrote ')

cat <<'MD'
## Work-precision: what each integrator buys

Final-state error against CPU time, every integrator of `dalembert::integrate`
on the generated code, SciPy's `solve_ivp` over a SymPy `lambdify(cse=True)`
right-hand side beside them. Seed example 1 from θ₁ = θ₂ = 2 rad is chaotic
(no double-precision method gets much below 3e-8); `--taylor` redraws the
regular pendulum at 0.2 rad and seed example 3.

```text
MD
echo "$summary"
echo "$taylor"
echo '```'
echo
measured "one run"
cat <<'MD'

    scripts/scipy_baseline.sh
    cargo run --release --example work_precision -- --out docs/charts --scipy target/charts/scipy_dop853.csv   # and --taylor

| seed example 1 | seed example 1 at 0.2 rad |
|---|---|
| ![work-precision, seed 1](docs/charts/wp_seed_1.svg) | ![work-precision, regular pendulum](docs/charts/wp_regular_pendulum.svg) |
MD
