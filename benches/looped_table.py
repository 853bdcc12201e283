#!/usr/bin/env python3
"""Tabulate rounds of the `looped` bench (generated/benches/looped.rs): unrolled against looped.

Usage: python3 benches/looped_table.py BASELINE... [--target TARGET_DIR] [--binary BENCH]
  BASELINE     names given to `cargo bench ... --bench looped -- --save-baseline NAME`, one a round
  TARGET_DIR   default: $CARGO_TARGET_DIR or target
  BENCH        the bench executable (`cargo bench ... --no-run` names it): adds the
               machine-code size of each unrolled `accelerations` (from `nm`)

For each chain (group `forms/FAMILY/n`), prints the median over the rounds of
criterion's median per call of each form, the median and range over the rounds
of the ratio looped / unrolled (each round's two figures come from the same
window), and each form's cost per link.
"""
import glob
import json
import os
import re
import statistics
import subprocess
import sys


def option(args, name, default):
    """Removes `name VALUE` from `args` and returns VALUE (or `default`)."""
    if name not in args:
        return default
    at = args.index(name)
    value = args[at + 1]
    del args[at : at + 2]
    return value


def code_sizes(binary):
    """(family, n) -> bytes of machine code of the generated `accelerations`."""
    symbols = subprocess.run(["nm", "-C", "-S", binary], capture_output=True, text=True, check=True)
    sizes = {}
    looped = []
    for line in symbols.stdout.splitlines():
        if line.endswith("dalembert_fixtures::looped::aba::<impl dalembert_fixtures::looped::table::Chain<_>>::accelerations"):
            looped.append(int(line.split()[1], 16))
        found = re.search(r"^\S+ (\S+) \S (dalembert_generated::(planar|spatial)_chain_(\d+)::\w+::accelerations)$", line)
        if found:
            sizes[(found.group(3), int(found.group(4)))] = int(found.group(1), 16)
    if looped:
        print(f"looped `accelerations`: {min(looped) / 1024:.1f}–{max(looped) / 1024:.1f} KiB of code for every n")
    return sizes


args = sys.argv[1:]
target = option(args, "--target", os.environ.get("CARGO_TARGET_DIR", "target"))
binary = option(args, "--binary", None)
sizes = code_sizes(binary) if binary else {}
baselines = args

rounds = {}  # (family, n) -> {baseline: {form: median ns}}
for baseline in baselines:
    pattern = os.path.join(target, "criterion", "forms_*", "*", baseline, "benchmark.json")
    for path in glob.glob(pattern):
        with open(path) as f:
            bench = json.load(f)
        _, family, n = bench["group_id"].split("/")
        with open(path.replace("benchmark.json", "estimates.json")) as f:
            median = json.load(f)["median"]["point_estimate"]
        rounds.setdefault((family, int(n)), {}).setdefault(baseline, {})[bench["function_id"]] = median

print(f"{len(baselines)} rounds: {' '.join(baselines)}\n")
print(
    "| family | n | unrolled (ns) | looped (ns) | looped / unrolled (range) "
    "| unrolled ns/link | looped ns/link | unrolled code (KiB) |"
)
print("|---|---|---|---|---|---|---|---|")
for (family, n), by_round in sorted(rounds.items()):
    complete = [forms for forms in by_round.values() if len(forms) == 2]
    unrolled = [forms["unrolled"] for forms in complete]
    looped = [forms["looped"] for forms in complete]
    ratios = [forms["looped"] / forms["unrolled"] for forms in complete]
    u, l = statistics.median(unrolled), statistics.median(looped)
    size = f"{sizes[(family, n)] / 1024:.1f}" if (family, n) in sizes else "–"
    print(
        f"| {family} | {n} | {u:.0f} | {l:.0f} | {statistics.median(ratios):.2f} "
        f"({min(ratios):.2f}–{max(ratios):.2f}) | {u / n:.1f} | {l / n:.1f} "
        f"| {size} |"
    )
