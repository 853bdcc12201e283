#!/usr/bin/env python3
"""Tabulate rounds of the `looped` bench (generated/benches/looped.rs): unrolled against looped.

Usage: python3 benches/looped_table.py BASELINE... [--target TARGET_DIR]
  BASELINE     names given to `cargo bench ... --bench looped -- --save-baseline NAME`, one a round
  TARGET_DIR   default: $CARGO_TARGET_DIR or target

For each chain (group `forms/FAMILY/n`), prints the median over the rounds of
criterion's median per call of each form, the median and range over the rounds
of the ratio looped / unrolled (each round's two figures come from the same
window), and each form's cost per link.
"""
import glob
import json
import os
import statistics
import sys

args = sys.argv[1:]
target = os.environ.get("CARGO_TARGET_DIR", "target")
if "--target" in args:
    at = args.index("--target")
    target = args[at + 1]
    del args[at : at + 2]
baselines = args

rounds = {}  # (family, n) -> {form: [median ns per round]}
for baseline in baselines:
    pattern = os.path.join(target, "criterion", "forms_*", "*", baseline, "benchmark.json")
    for path in glob.glob(pattern):
        with open(path) as f:
            bench = json.load(f)
        _, family, n = bench["group_id"].split("/")
        with open(path.replace("benchmark.json", "estimates.json")) as f:
            median = json.load(f)["median"]["point_estimate"]
        rounds.setdefault((family, int(n)), {}).setdefault(bench["function_id"], []).append(median)

print(f"{len(baselines)} rounds: {' '.join(baselines)}\n")
print("| family | n | unrolled (ns) | looped (ns) | looped / unrolled (range) | unrolled ns/link | looped ns/link |")
print("|---|---|---|---|---|---|---|")
for (family, n), forms in sorted(rounds.items()):
    unrolled, looped = forms["unrolled"], forms["looped"]
    ratios = [b / a for a, b in zip(unrolled, looped)]
    u, l = statistics.median(unrolled), statistics.median(looped)
    print(
        f"| {family} | {n} | {u:.0f} | {l:.0f} | {statistics.median(ratios):.2f} "
        f"({min(ratios):.2f}–{max(ratios):.2f}) | {u / n:.1f} | {l / n:.1f} |"
    )
