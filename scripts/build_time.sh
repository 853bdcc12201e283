#!/usr/bin/env bash
# Times what a user pays to compile a large model: a fresh crate holding one
# `dalembert!` invocation of the seed-spelled spatial chain of N links
# (symbolic parameters, torque inputs: `dalembert chain spatial N seed`),
# depending on this repository by path.
#
#   scripts/build_time.sh [N | MODEL.dal ...]     (default: 12 30 60)
#
# A MODEL.dal argument times that model instead of a chain (its name
# stands for N in the output).
# For each N it prints one CSV line
#
#   n,expand_s,build_default_s,build_engine_optimised_s
#
# expand_s: `dalembert generate` on the model (the macro's work plus
# formatting) with the engine built in release; build_*: the wall time of
# `cargo build --release` of the user crate alone (its
# dependencies built beforehand), first with Cargo's defaults, where the
# release profile compiles proc macros without optimisation
# (`build-override`), then with the engine optimised by
# `[profile.release.package.dalembert-codegen] opt-level = 3` in the user's
# Cargo.toml: their difference is the time the unoptimised engine adds to
# the expansion (the code it expands to is the same). The crates live under
# target/build-time/, one target directory per profile shared by every N.
set -euo pipefail

cd "$(dirname "$0")/.."
repo=$(pwd)
sizes=("$@")
((${#sizes[@]})) || sizes=(12 30 60)

cargo build --quiet --release -p dalembert-codegen --bin dalembert

seconds() { # runs "$@" quietly, prints its wall time in seconds
    local start end
    start=$(date +%s.%N)
    "$@" > /dev/null 2>&1 || { echo "failed: $*" >&2; return 1; }
    end=$(date +%s.%N)
    echo "$end - $start" | bc -l | xargs printf '%.1f'
}

user_crate() { # DIR N OPTIMISED: writes the crate
    local dir=$1 n=$2 optimised=$3
    mkdir -p "$dir/src"
    {
        printf '[package]\nname = "chain-%s"\nversion = "0.1.0"\nedition = "2024"\npublish = false\n\n' "$n"
        printf '[dependencies]\ndalembert = { path = "%s" }\n\n[workspace]\n' "$repo"
        if [[ $optimised == yes ]]; then
            printf '\n[profile.release.package.dalembert-codegen]\nopt-level = 3\n'
        fi
    } > "$dir/Cargo.toml"
    {
        echo '//! A user crate holding one large model.'
        echo 'dalembert::dalembert! {'
        cat "$dir/chain.dal"
        echo '}'
    } > "$dir/src/lib.rs"
}

echo "n,expand_s,build_default_s,build_engine_optimised_s"
for n in "${sizes[@]}"; do
    if [[ $n == *.dal ]]; then
        model=$n
        n=$(basename "$n" .dal | tr '_' '-')
        base="target/build-time/model_$n"
        mkdir -p "$base"
        cp "$model" "$base/chain.dal"
    else
        base="target/build-time/spatial_$n"
        mkdir -p "$base"
        target/release/dalembert chain spatial "$n" seed > "$base/chain.dal"
    fi
    line="$n"
    line+=,$(seconds target/release/dalembert generate "$base/chain.dal")
    for optimised in no yes; do
        dir="$base/optimised_$optimised"
        mkdir -p "$dir"
        cp "$base/chain.dal" "$dir/chain.dal"
        user_crate "$dir" "$n" "$optimised"
        # Dependencies first (an empty model would not compile: build the
        # dependency tree through `dalembert` alone).
        export CARGO_TARGET_DIR="$repo/target/build-time/target_$optimised"
        (cd "$dir" && cargo build --quiet --release -p dalembert > /dev/null 2>&1)
        (cd "$dir" && cargo clean --quiet --release -p "chain-$n" 2> /dev/null || true)
        line+=,$(cd "$dir" && seconds cargo build --release)
    done
    echo "$line"
done
