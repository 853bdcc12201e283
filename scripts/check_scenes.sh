#!/usr/bin/env bash
# Opens each animated scene (an HTML page written by dalembert_lab::Scene) in
# headless Chromium at two instants (the start and 37 % of the run) and checks that the page ran without a
# script error and that the canvas changed where the bodies are drawn.
#
#   scripts/check_scenes.sh [--screenshots DIR] [--at FRACTION] [PAGE.html ...]
#
# Pages default to target/charts/*.html (`cargo run --release --example
# seed_examples` writes them). With --screenshots DIR, a PNG of each page at
# FRACTION of its duration (default 0.45) goes to DIR/NAME.png. Without Chromium (Debian:
# `apt-get install chromium`) the check fails in CI (CI set: `.ci/run` installs it) and is
# skipped elsewhere with a message, status 0.
set -euo pipefail

shots=""
at=0.45
pages=()
while (($#)); do
    case "$1" in
        --screenshots) shots="$2"; shift 2 ;;
        --at) at="$2"; shift 2 ;;
        -h|--help) sed -n '2,13p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
        *) pages+=("$1"); shift ;;
    esac
done
if ((${#pages[@]} == 0)); then
    shopt -s nullglob
    pages=(target/charts/*.html)
fi

browser=""
for candidate in chromium chromium-browser google-chrome; do
    if command -v "$candidate" >/dev/null 2>&1; then browser="$candidate"; break; fi
done
if [[ -z "$browser" ]]; then
    if [[ -n "${CI:-}" ]]; then
        echo "check_scenes: Chromium is not installed, and CI must check the scenes (.ci/run installs it: apt-get install chromium)" >&2
        exit 1
    fi
    echo "check_scenes: Chromium is not installed (Debian: apt-get install chromium); browser check skipped"
    exit 0
fi
if ((${#pages[@]} == 0)); then
    echo "check_scenes: no page to check (run: cargo run --release --example seed_examples)" >&2
    exit 1
fi

profile="$(mktemp -d)"
trap 'rm -rf "$profile"' EXIT
flags=(--headless --no-sandbox --disable-gpu --disable-quic --no-first-run
    --disable-background-networking --disable-component-update --disable-sync
    --user-data-dir="$profile" --virtual-time-budget=5000 --window-size=1000,900)

# The page's status line: `<pre id="status" data-state=... data-grid=...>`.
status_at() { # PAGE QUERY
    "$browser" "${flags[@]}" --dump-dom "file://$(realpath "$1")?$2" 2>/dev/null |
        grep -o '<pre id="status"[^>]*>[^<]*' || true
}
attribute() { # STATUS NAME
    sed -n "s/.* data-$2=\"\([^\"]*\)\".*/\1/p" <<<"$1"
}

failed=0
for page in "${pages[@]}"; do
    name="$(basename "$page" .html)"
    first="$(status_at "$page" f=0)"
    # Not half-way: a motion of period half the run looks the same there.
    second="$(status_at "$page" f=0.37)"
    problem=""
    for status in "$first" "$second"; do
        if [[ "$(attribute "$status" state)" != ok ]]; then
            problem="the page did not run cleanly: ${status:-no status line}"
        fi
    done
    if [[ -z "$problem" ]]; then
        grid_a="$(attribute "$first" grid)"
        grid_b="$(attribute "$second" grid)"
        # Cells where parts are drawn at either instant.
        declare -A drawn=()
        for cell in $(attribute "$first" cells) $(attribute "$second" cells); do drawn[$cell]=1; done
        changed=0
        changed_where_drawn=0
        for ((cell = 0; cell < ${#grid_a} / 2; cell++)); do
            a=$((16#${grid_a:2*cell:2}))
            b=$((16#${grid_b:2*cell:2}))
            if (((a > b ? a - b : b - a) > 4)); then
                changed=$((changed + 1))
                [[ -n "${drawn[$cell]:-}" ]] && changed_where_drawn=$((changed_where_drawn + 1))
            fi
        done
        unset drawn
        if ((changed_where_drawn == 0)); then
            problem="the canvas did not change where the bodies are ($changed cells changed)"
        fi
    fi
    if [[ -n "$problem" ]]; then
        echo "FAIL $page: $problem"
        failed=1
        continue
    fi
    echo "ok   $page: $(attribute "$second" frames) frames; $changed_where_drawn grid cells changed where parts are drawn, no script error"
    if [[ -n "$shots" ]]; then
        mkdir -p "$shots"
        "$browser" "${flags[@]}" --screenshot="$shots/$name.png" \
            "file://$(realpath "$page")?f=$at" >/dev/null 2>&1
        echo "     screenshot $shots/$name.png"
    fi
done
exit "$failed"
