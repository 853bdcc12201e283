#!/usr/bin/env bash
# Times `mass_matrix` and `forcing` of one generated model alone and called
# one after the other, in a fresh crate (target/pair-timing/) that includes
# the file `dalembert generate MODEL.dal` prints, built for the target CPU
# given (default: the baseline x86-64, SSE2; e.g. x86-64-v3 for AVX2,
# whose three-operand encoding makes the machine code smaller):
#
#   scripts/pair_timing.sh MODEL.dal STRUCT NQ NV NU [TARGET_CPU]
#
# e.g. scripts/pair_timing.sh generated/models/floating_solo12.dal FloatingSolo 19 18 12 x86-64-v3
#
# Thread CPU time per call over 2·10⁶ calls cycling through 1000
# pseudo-random states (coordinates and speeds in [−1, 1], the quaternion
# of a free joint, coordinates 3..7, normalised), five rounds (ROUNDS=n in
# the environment for another number; 0 to only build). It prints
# the sizes of the two functions' machine code and their register traffic
# (stores to the stack, instructions reading the stack, register-to-register
# copies: the spills and copies of values that did not stay in the 16 xmm
# registers), then per round M alone,
# f alone, their sum, and the pair called together. When the pair's code
# exceeds the instruction cache (32 KB per core on the AMD EPYC machines,
# 64 KB on the Intel Xeon ones: `lscpu`), together costs more than the sum.
# EXTRA_RUSTFLAGS in the environment are added to the build's flags (e.g.
# '-C no-vectorize-slp' to see the code without LLVM's SLP vectoriser).
set -euo pipefail

cd "$(dirname "$0")/.."
repo=$(pwd)
model=$1 name=$2 nq=$3 nv=$4 nu=$5 cpu=${6:-x86-64} rounds=${ROUNDS:-5}
dir=$repo/target/pair-timing
mkdir -p "$dir/src/bin"
cargo run -q -p dalembert-codegen --bin dalembert -- generate "$model" > "$dir/model.rs"
# A model with parameters is timed with all of them at 1.
fields=$(awk -v s="pub struct $name {" 'index($0, s) { inside = 1; next } inside && /^}/ { inside = 0 }
    inside && match($0, /pub [A-Za-z_0-9]+: f64/) { f = substr($0, RSTART + 4, RLENGTH - 9); printf "%s: 1.0, ", f }' "$dir/model.rs")
cat > "$dir/Cargo.toml" <<TOML
[package]
name = "pair-timing"
version = "0.1.0"
edition = "2024"
[dependencies]
dalembert = { path = "$repo" }
libc = "0.2"
[workspace]
TOML
cat > "$dir/src/lib.rs" <<RUST
#![allow(warnings)]
pub mod model { include!("../model.rs"); }
pub use model::$name as System;
#[unsafe(no_mangle)]
pub fn pair_mass_matrix(s: &System, q: &[f64; $nq]) -> [[f64; $nv]; $nv] { s.mass_matrix(q) }
#[unsafe(no_mangle)]
pub fn pair_forcing(s: &System, q: &[f64; $nq], v: &[f64; $nv], u: &[f64; $nu]) -> [f64; $nv] { s.forcing(0.0, q, v, u) }
RUST
cat > "$dir/src/bin/pair.rs" <<RUST
use pair_timing::{System, pair_forcing, pair_mass_matrix};
use std::hint::black_box;
fn now() -> f64 {
    let mut t = libc::timespec { tv_sec: 0, tv_nsec: 0 };
    // SAFETY: clock_gettime writes the timespec it is given.
    unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut t) };
    t.tv_sec as f64 * 1e9 + t.tv_nsec as f64
}
fn main() {
    let mut seed = 12345u64;
    let mut rnd = || {
        seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        ((seed >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    };
    let states: Vec<([f64; $nq], [f64; $nv], [f64; $nu])> = (0..1000)
        .map(|_| {
            let mut q = [0.0; $nq];
            q.iter_mut().for_each(|x| *x = rnd());
            if $nq > $nv {
                let n = (3..7).map(|k| q[k] * q[k]).sum::<f64>().sqrt();
                (3..7).for_each(|k| q[k] /= n);
            }
            let mut v = [0.0; $nv];
            v.iter_mut().for_each(|x| *x = rnd());
            let mut u = [0.0; $nu];
            u.iter_mut().for_each(|x| *x = rnd());
            (q, v, u)
        })
        .collect();
    let s = System { $fields };
    let n = 2_000_000;
    let time = |call: &dyn Fn(usize)| {
        let t = now();
        (0..n).for_each(|i| call(i % 1000));
        (now() - t) / n as f64
    };
    for round in 0..black_box($rounds) {
        let m = time(&|i| { black_box(pair_mass_matrix(black_box(&s), &states[i].0)); });
        let f = time(&|i| { let (q, v, u) = &states[i]; black_box(pair_forcing(black_box(&s), q, v, u)); });
        let both = time(&|i| {
            let (q, v, u) = &states[i];
            black_box((pair_mass_matrix(black_box(&s), q), pair_forcing(black_box(&s), q, v, u)));
        });
        println!("round {round}: M {m:.1} ns  f {f:.1} ns  sum {:.1} ns  together {both:.1} ns", m + f);
    }
}
RUST
export CARGO_TARGET_DIR=$dir/target-$cpu
RUSTFLAGS="-C target-cpu=$cpu ${EXTRA_RUSTFLAGS:-}" cargo build -q --release --manifest-path "$dir/Cargo.toml" --bin pair
bin=$CARGO_TARGET_DIR/release/pair
for function in mass_matrix forcing; do
    # The wrapper, and the model's function where the compiler kept it out
    # of line (a large one: the wrapper is then a call of a few bytes).
    symbols=$(nm "$bin" | awk -v w="pair_$function" \
        -v m="pair_timing5model${#name}${name}${#function}${function}17h" \
        '$3 == w || index($3, m) { print $3 }')
    size=0 code=
    for symbol in $symbols; do
        size=$((size + 16#$(nm -S "$bin" | awk -v s="$symbol" '$4 == s { print $2 }')))
        code+=$(objdump -d --no-show-raw-insn --disassemble="$symbol" "$bin")$'\n'
    done
    stores=$(grep -cE '%xmm[0-9]+,(-?0x[0-9a-f]+)?\(%rsp\)' <<<"$code" || true)
    reads=$(grep -cE '\(%rsp\),%xmm[0-9]+' <<<"$code" || true)
    copies=$(grep -cE 'mov(apd|aps|sd)\s+%xmm[0-9]+,%xmm[0-9]+$' <<<"$code" || true)
    echo "$function: $size bytes of machine code ($cpu), $stores stack stores, $reads stack reads, $copies register copies"
done
"$CARGO_TARGET_DIR/release/pair"
