#!/usr/bin/env python3
"""Merge the `robots` criterion medians with the peer harness's URDF CSVs.

Usage: python3 benches/robots_table.py PEER_CSV... [--target TARGET_DIR] [--since FILE]
  PEER_CSV     one output of the peers' harness `run.sh --urdf ROBOT.urdf` per
               robot, named ROBOT.csv (e.g. panda.csv, cart_pole_3.csv)
  TARGET_DIR   default: $CARGO_TARGET_DIR or target
  --since FILE read only the criterion results written after FILE was

Prints the Markdown table of BENCHMARKS.md: per robot, the median ns per
call of `mass_matrix` + `forcing` and of `dalembert::accelerations`, and the
ratios (ours / theirs) to Pinocchio's crba_sym + nle and aba of the same run,
and the summary rows of BENCHMARKS.md's opening table. A robot without
figures on either side fails the script.
"""
import csv
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scripts", "bench", "lib"))
from criterion_table import estimates  # noqa: E402  (the one reader of criterion's results)

args = sys.argv[1:]
target = os.environ.get("CARGO_TARGET_DIR", "target")
if "--target" in args:
    i = args.index("--target")
    target = args[i + 1]
    del args[i : i + 2]
since = None
if "--since" in args:
    i = args.index("--since")
    since = args[i + 1]
    del args[i : i + 2]

ours = {}  # (robot, function) -> median ns
for bench, median in estimates(target, since):
    group = bench["group_id"].split("/")
    if len(group) == 2 and group[0] == "robots":
        ours[(group[1], bench["function_id"])] = median

print("| robot | nv | M + f (ns) | Pinocchio crba_sym + nle (ns) | ratio | accelerations (ns) | Pinocchio aba (ns) | ratio |")
print("|---|---|---|---|---|---|---|---|")
mf_ratios, acc_ratios = [], []
for peer_csv in args:
    robot = os.path.splitext(os.path.basename(peer_csv))[0]
    peer = {}
    nv = "?"
    with open(peer_csv) as f:
        for row in csv.DictReader(line for line in f if not line.startswith("#")):
            peer[row["algo"]] = float(row["median_ns"])
            nv = row["nv"]
    mf = ours.get((robot, "mass_matrix+forcing"))
    acc = ours.get((robot, "accelerations"))
    crba, nle, aba = peer.get("pin_crba_sym"), peer.get("pin_nle"), peer.get("pin_aba")
    if None in (mf, acc, crba, nle, aba):
        sys.exit(f"{robot}: missing figures (ours or Pinocchio's)")
    mf_ratios.append(mf / (crba + nle))
    acc_ratios.append(acc / aba)
    print(f"| {robot} | {nv} | {mf:.0f} | {crba:.0f} + {nle:.0f} | **{mf / (crba + nle):.2f}** "
          f"| {acc:.0f} | {aba:.0f} | **{acc / aba:.2f}** |")

names = ", ".join(os.path.splitext(os.path.basename(p))[0] for p in args)
span = lambda values: f"{min(values):.2f}–{max(values):.2f}"
print()
print(f"<!-- summary: `mass_matrix` + `forcing`, {names} | Pinocchio `crba` + `nonLinearEffects` | {span(mf_ratios)} -->")
print(f"<!-- summary: `accelerations`, {names} | Pinocchio `aba` | {span(acc_ratios)} -->")
