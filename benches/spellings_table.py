#!/usr/bin/env python3
"""Merge the `spellings` criterion medians with the Pinocchio/MuJoCo peer CSV.

Usage: python3 benches/spellings_table.py PEER_CSV [TARGET_DIR] [--since FILE]
  PEER_CSV     output of the peers' harness `run.sh --ns 2,6,12,30`
  TARGET_DIR   default: $CARGO_TARGET_DIR or target
  --since FILE read only the criterion results written after FILE was

Prints the Markdown table of BENCHMARKS.md: per family and n, for each
spelling (joints / symbolic / seed in one cell), the median ns per call of
`mass_matrix` + `forcing` and of the generated `accelerations`, with the
ratios to Pinocchio (crba_sym + nle; aba) and to MuJoCo (M + f; forward) of
the same run, and the slowest-to-fastest spelling ratio; and the summary rows of BENCHMARKS.md's opening table (n ≤ 12).
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
print("| family | n | M + f (ns) | / Pinocchio crba+nle | / MuJoCo M+f | accelerations (ns) | / Pinocchio aba "
      "| / MuJoCo forward | slowest / fastest, M + f; accelerations |")
print("|---|---|---|---|---|---|---|---|---|")
if not ours:
    sys.exit("no criterion results of the spellings bench: did it run?")
headline = {"M + f": [], "Pinocchio": [], "MuJoCo": []}
ratio = lambda a, b: f"{a / b:.2f}" if b else "–"
cells = lambda values: " / ".join(values)
for family in ["planar", "spatial"]:
    for n in sorted({k[2] for k in ours if k[0] == family}):
        pin_mf = peer.get((family, n, "pin_crba_sym"), 0) + peer.get((family, n, "pin_nle"), 0)
        pin_aba = peer.get((family, n, "pin_aba"))
        mj_mf = peer.get((family, n, "mj_M_f"))
        mj_fwd = peer.get((family, n, "mj_forward"))
        found = [(ours.get((family, s, n, "mass_matrix+forcing")), ours.get((family, s, n, "accelerations")))
                 for s in spellings]
        found = [(mf, acc) for mf, acc in found if mf is not None and acc is not None]
        if not found:
            continue
        for mf, acc in found:
            if n <= 12 and pin_mf and pin_aba:
                headline["M + f"].append(mf / pin_mf)
                headline["Pinocchio"].append(acc / pin_aba)
            if n <= 12 and mj_fwd:
                headline["MuJoCo"].append(acc / mj_fwd)
        row_mf, row_acc = [mf for mf, _ in found], [acc for _, acc in found]
        print(f"| {family} | {n} | {cells(f'{mf:.0f}' for mf in row_mf)} | {cells(ratio(mf, pin_mf) for mf in row_mf)} "
              f"| {cells(ratio(mf, mj_mf) for mf in row_mf)} | {cells(f'{acc:.0f}' for acc in row_acc)} "
              f"| {cells(ratio(acc, pin_aba) for acc in row_acc)} | {cells(ratio(acc, mj_fwd) for acc in row_acc)} "
              f"| {max(row_mf) / min(row_mf):.2f}; {max(row_acc) / min(row_acc):.2f} |")

if not all(headline.values()):
    sys.exit("the peers' CSV lacks Pinocchio's or MuJoCo's rows")
span = lambda values: f"{min(values):.2f}–{max(values):.2f}"
print()
print(f"<!-- summary: `mass_matrix` + `forcing`, chains n ≤ 12 | Pinocchio `crba` + `nonLinearEffects` | {span(headline['M + f'])} -->")
print(f"<!-- summary: `accelerations`, chains n ≤ 12 | Pinocchio `aba` | {span(headline['Pinocchio'])} -->")
print(f"<!-- summary: `accelerations`, chains n ≤ 12 | MuJoCo `mj_forward` | {span(headline['MuJoCo'])} -->")
