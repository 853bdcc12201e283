# Sourced by every scripts/bench/*.sh: the repository root as the working
# directory, cargo's noise on stderr, and the few helpers each section uses.
# A section script prints one markdown section on stdout and nothing else.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../../.."

# Absolute: cargo runs each bench in its package's folder, and criterion
# writes its results under $CARGO_TARGET_DIR/criterion from there.
CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-target}"
case "$CARGO_TARGET_DIR" in /*) ;; *) CARGO_TARGET_DIR="$(pwd)/$CARGO_TARGET_DIR" ;; esac
export CARGO_TARGET_DIR
CRITERION_DIR="$CARGO_TARGET_DIR/criterion"
BENCH_LIB="scripts/bench/lib"

# A stamp older than this run's criterion results: the tables read only the
# estimates written after it, never a stale one from an earlier run.
STAMP="$(mktemp)"
trap 'rm -f "$STAMP"' EXIT

# Runs cargo with its output (criterion's console lines too) on stderr.
quietly() {
    "$@" >&2
}

# The peers' timing harness (Pinocchio and MuJoCo), kept outside this
# repository: its directory is DALEMBERT_PEERS (scripts/benchmarks.sh --peers DIR,
# which also sets PINOCCHIO_HARNESS, the name other section scripts read).
peers() {
    if [ -z "${DALEMBERT_PEERS:-}" ] || [ ! -f "$DALEMBERT_PEERS/run.sh" ]; then
        echo "set DALEMBERT_PEERS to the peers' harness directory (the one holding run.sh)" >&2
        return 1
    fi
    bash "$DALEMBERT_PEERS/run.sh" "$@"
}

# The Python with Pinocchio and MuJoCo the peers' harness installs.
peers_python() {
    echo "${PEERS_VENV:-$HOME/.cache/dalembert-peers-venv}/bin/python"
}

# That environment's site-packages: Pinocchio's and Eigen's headers under
# cmeel.prefix/, MuJoCo's C API (headers and library) under mujoco/.
peers_site() {
    "$(peers_python)" -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])'
}

# Builds scripts/bench/mj_forward.c (MuJoCo's mj_forward timed through its C
# API) as $1, against $MUJOCO_DIR (headers and libmujoco.so*; default: the
# `mujoco` wheel in the peers' Python environment).
build_mj_forward() {
    local mujoco="${MUJOCO_DIR:-$(peers_site)/mujoco}"
    cc -O2 scripts/bench/mj_forward.c -I"$mujoco/include" "$(ls "$mujoco"/libmujoco.so* | head -n1)" \
        -Wl,-rpath,"$mujoco" -lm -o "$1"
}

# One row of BENCHMARKS.md's opening summary (scripts/benchmarks.sh gathers
# them from every section): measure, against, ours / theirs.
summary() {
    printf '<!-- summary: %s | %s | %s -->\n' "$1" "$2" "$3"
}

# The measurement line under a table: when, on which commit, how loaded.
measured() {
    local load
    load=$(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || echo "unknown")
    local cpu
    cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo 2>/dev/null | head -1)
    printf 'Measured %s on %s (%s cores), commit `%s`, load average %s; %s.\n' \
        "$(date -u '+%a %d %b %Y %H:%M UTC')" "${cpu:-an unknown CPU}" "$(nproc)" \
        "$(git rev-parse --short HEAD)" "$load" "$1"
}

# Criterion medians written since this script started, as a table built by
# scripts/bench/lib/criterion_table.py TABLE [ARGS].
table() {
    python3 "$BENCH_LIB/criterion_table.py" --target "$CARGO_TARGET_DIR" --since "$STAMP" "$@"
}
