#!/usr/bin/env python3
"""Merge the `spellings` criterion medians with the Pinocchio/MuJoCo peer CSV.

Usage: python3 benches/spellings_table.py PEER_CSV [TARGET_DIR] [--since FILE]
  PEER_CSV     output of the peers' harness `run.sh --ns 2,6,12,30`
  TARGET_DIR   default: $CARGO_TARGET_DIR or target
  --since FILE read only the criterion results written after FILE was

Prints the Markdown table of BENCHMARKS.md: per family, spelling and n, the
median ns per call of `mass_matrix` + `forcing` and of the generated
`accelerations`, with the ratios to Pinocchio (crba_sym + nle; aba) and to
MuJoCo (M + f; forward) of the same run, and the slowest-to-fastest spelling
ratio; and the summary rows of BENCHMARKS.md's opening table (n ≤ 12).
"""
import csv
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scripts", "bench", "lib"))
from criterion_table import estimates  # noqa: E402  (the one reader of criterion's results)

args = sys.argv[1:]
since = None
if "--since" in args:
    i = args.index("--since")
    since = args[i + 1]
    del args[i : i + 2]
peer_csv = args[0]
target = args[1] if len(args) > 1 else os.environ.get("CARGO_TARGET_DIR", "target")

ours = {}  # (family, spelling, n, function) -> median ns
for bench, median in estimates(target, since):
    group = bench["group_id"].split("/")
    if len(group) == 3 and group[1] in ("joints", "symbolic", "seed"):
        family, spelling, n = group
        ours[(family, spelling, int(n), bench["function_id"])] = median

peer = {}  # (family, n, algo) -> median ns
with open(peer_csv) as f:
    for row in csv.DictReader(line for line in f if not line.startswith("#")):
        peer[(row["family"], int(row["n"]), row["algo"])] = float(row["median_ns"])

spellings = ["joints", "symbolic", "seed"]
print("| family | n | spelling | M + f (ns) | / Pinocchio crba+nle | / MuJoCo M+f | accelerations (ns) | / Pinocchio aba | / MuJoCo forward |")
print("|---|---|---|---|---|---|---|---|---|")
if not ours:
    sys.exit("no criterion results of the spellings bench: did it run?")
spread = []
headline = {"M + f": [], "Pinocchio": [], "MuJoCo": []}
for family in ["planar", "spatial"]:
    for n in sorted({k[2] for k in ours if k[0] == family}):
        pin_mf = peer.get((family, n, "pin_crba_sym"), 0) + peer.get((family, n, "pin_nle"), 0)
        pin_aba = peer.get((family, n, "pin_aba"))
        mj_mf = peer.get((family, n, "mj_M_f"))
        mj_fwd = peer.get((family, n, "mj_forward"))
        row_mf, row_acc = [], []
        for spelling in spellings:
            mf = ours.get((family, spelling, n, "mass_matrix+forcing"))
            acc = ours.get((family, spelling, n, "accelerations"))
            if mf is None or acc is None:
                continue
            row_mf.append(mf)
            row_acc.append(acc)
            ratio = lambda a, b: f"{a / b:.2f}" if b else "–"
            if n <= 12 and pin_mf and pin_aba:
                headline["M + f"].append(mf / pin_mf)
                headline["Pinocchio"].append(acc / pin_aba)
            if n <= 12 and mj_fwd:
                headline["MuJoCo"].append(acc / mj_fwd)
            print(f"| {family} | {n} | {spelling} | {mf:.0f} | {ratio(mf, pin_mf)} | {ratio(mf, mj_mf)} "
                  f"| {acc:.0f} | {ratio(acc, pin_aba)} | {ratio(acc, mj_fwd)} |")
        if row_mf:
            spread.append((family, n, max(row_mf) / min(row_mf), max(row_acc) / min(row_acc)))
print()
print("| family | n | slowest / fastest spelling, M + f | accelerations |")
print("|---|---|---|---|")
for family, n, mf, acc in spread:
    print(f"| {family} | {n} | {mf:.2f} | {acc:.2f} |")

if not all(headline.values()):
    sys.exit("the peers' CSV lacks Pinocchio's or MuJoCo's rows")
span = lambda values: f"{min(values):.2f}–{max(values):.2f}"
print()
print(f"<!-- summary: `mass_matrix` + `forcing`, chains n ≤ 12 | Pinocchio `crba` + `nonLinearEffects` | {span(headline['M + f'])} -->")
print(f"<!-- summary: `accelerations`, chains n ≤ 12 | Pinocchio `aba` | {span(headline['Pinocchio'])} -->")
print(f"<!-- summary: `accelerations`, chains n ≤ 12 | MuJoCo `mj_forward` | {span(headline['MuJoCo'])} -->")
