#!/usr/bin/env bash
# Section "MJCF": dm_control's cheetah and humanoid imported by Builder::mjcf
# against MuJoCo's mj_forward through its C API (generated/benches/robots.rs
# and scripts/bench/mj_forward.c, same window).
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh"

out="$CARGO_TARGET_DIR/bench-peers/mjcf"
mkdir -p "$out"
quietly cargo bench -p dalembert-generated --bench robots -- 'robots/(cheetah|humanoid)/'
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
python3 - "$CRITERION_DIR" "$STAMP" "$out" <<'PY'
import csv, glob, json, os, sys
root, stamp, out = sys.argv[1], os.path.getmtime(sys.argv[2]), sys.argv[3]
ours = {}
for path in glob.glob(os.path.join(root, "**", "new", "benchmark.json"), recursive=True):
    estimates = path.replace("benchmark.json", "estimates.json")
    if os.path.getmtime(estimates) < stamp:
        continue  # an earlier run's
    with open(path) as f:
        name = json.load(f)["full_id"]
    with open(estimates) as f:
        ours[name] = json.load(f)["median"]["point_estimate"]
print("| model | `mass_matrix` + `forcing` (ns) | `accelerations` (ns) | MuJoCo `mj_forward` (ns) | M + f / `mj_forward` | accelerations / `mj_forward` |")
print("|---|---|---|---|---|---|")
for model in ("cheetah", "humanoid"):
    mf = ours.get(f"robots/{model}/mass_matrix+forcing")
    acc = ours.get(f"robots/{model}/accelerations")
    with open(os.path.join(out, model + ".csv")) as f:
        forward = next(float(r["median_ns"]) for r in csv.DictReader(f) if r["algo"] == "mj_forward")
    if mf is None or acc is None:
        sys.exit(f"no fresh result of robots/{model}: did the bench run?")
    print(f"| {model} | {mf:.0f} | {acc:.0f} | {forward:.0f} | {mf / forward:.2f} | **{acc / forward:.2f}** |")
    if model == "humanoid":
        summary = acc / forward
print()
print(f"<!-- summary: `accelerations`, dm_control humanoid (27 speeds) | MuJoCo `mj_forward` | {summary:.2f} -->")
PY
echo
measured "criterion medians, MuJoCo's median of thread CPU time"
cat <<'MD'

    cargo bench -p dalembert-generated --bench robots -- 'robots/(cheetah|humanoid)/'
    cc -O2 scripts/bench/mj_forward.c -I$MUJOCO/include $MUJOCO/libmujoco.so* -lm -o mj_forward
    ./mj_forward tests/reference/mjcf/dm_control/humanoid.xml   # and cheetah.xml
MD
