#!/usr/bin/env python3
"""Tabulate rounds of the `looped` bench (generated/benches/looped.rs): unrolled against looped.

Usage: python3 benches/looped_table.py BASELINE... [--target TARGET_DIR] [--binary BENCH]
  BASELINE     names given to `cargo bench ... --bench looped -- --save-baseline NAME`, one a round
  TARGET_DIR   default: $CARGO_TARGET_DIR or target
  BENCH        the bench executable (`cargo bench ... --no-run` names it): adds the
               machine-code size of each unrolled `accelerations` (from `nm`)

For each computation (`accelerations`, and `M+f`: `mass_matrix` + `forcing`) and
each chain (group `forms/FAMILY/n`), prints the median over the rounds of
criterion's median per call of each form, the median and range over the rounds
of the ratio looped / unrolled (each round's two figures come from the same
window), and each form's cost per link.
"""
import os
import re
import statistics
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scripts", "bench", "lib"))
from criterion_table import estimates  # noqa: E402  (the one reader of criterion's results)


def option(args, name, default):
    """Removes `name VALUE` from `args` and returns VALUE (or `default`)."""
    if name not in args:
        return default
    at = args.index(name)
    value = args[at + 1]
    del args[at : at + 2]
    return value


def code_sizes(binary):
    """(family, n, function) -> bytes of machine code of a generated function."""
    symbols = subprocess.run(["nm", "-C", "-S", binary], capture_output=True, text=True, check=True)
    sizes = {}
    looped = []
    for line in symbols.stdout.splitlines():
        if re.search(r"dalembert_fixtures::looped::.*::(accelerations|mass_matrix|forcing)$", line):
            looped.append(int(line.split()[1], 16))
        found = re.search(r"^\S+ (\S+) \S dalembert_generated::(planar|spatial)_chain_(\d+)::\w+::(\w+)$", line)
        if found:
            key = (found.group(2), int(found.group(3)), found.group(4))
            sizes[key] = int(found.group(1), 16)
    if looped:
        print(f"looped functions: {min(looped) / 1024:.1f}–{max(looped) / 1024:.1f} KiB of code each, for every n")
    return sizes


args = sys.argv[1:]
target = option(args, "--target", os.environ.get("CARGO_TARGET_DIR", "target"))
binary = option(args, "--binary", None)
sizes = code_sizes(binary) if binary else {}
baselines = args

rounds = {}  # (family, n) -> {baseline: {form: median ns}}
for baseline in baselines:
    for bench, median in estimates(target, baseline=baseline):
        group = bench["group_id"].split("/")
        if len(group) != 3 or group[0] != "forms":
            continue
        _, family, n = group
        rounds.setdefault((family, int(n)), {}).setdefault(baseline, {})[bench["function_id"]] = median

print(f"{len(baselines)} rounds: {' '.join(baselines)}")
for title, suffix, functions in [
    ("accelerations", "", ["accelerations"]),
    ("M+f", " M+f", ["mass_matrix", "forcing"]),
]:
    print(f"\n{title}\n")
    print(
        "| family | n | unrolled (ns) | looped (ns) | looped / unrolled (range) "
        "| unrolled ns/link | looped ns/link | unrolled code (KiB) |"
    )
    print("|---|---|---|---|---|---|---|---|")
    for (family, n), by_round in sorted(rounds.items()):
        complete = [f for f in by_round.values() if "unrolled" + suffix in f and "looped" + suffix in f]
        if not complete:
            continue
        unrolled = statistics.median(f["unrolled" + suffix] for f in complete)
        looped = statistics.median(f["looped" + suffix] for f in complete)
        ratios = [f["looped" + suffix] / f["unrolled" + suffix] for f in complete]
        code = [sizes.get((family, n, function)) for function in functions]
        size = f"{sum(code) / 1024:.1f}" if None not in code else "–"
        print(
            f"| {family} | {n} | {unrolled:.0f} | {looped:.0f} | {statistics.median(ratios):.2f} "
            f"({min(ratios):.2f}–{max(ratios):.2f}) | {unrolled / n:.1f} | {looped / n:.1f} | {size} |"
        )
