#!/usr/bin/env python3
"""Merge the `chains` criterion medians with the Pinocchio/MuJoCo peer CSV.

Usage: python3 benches/chains_table.py PEER_CSV [TARGET_DIR]
  PEER_CSV     output of the Pinocchio/MuJoCo peer harness (`run.sh --ns ...`, see BENCHMARKS.md)
  TARGET_DIR   default: $CARGO_TARGET_DIR or target

Writes docs/charts/chains.csv (family,n,tool,ns_per_call: the input of
`cargo run --example chain_chart`) and prints the Markdown ratio tables of
BENCHMARKS.md. Pinocchio M + f = pin_crba_sym + pin_nle; MuJoCo M + f = mj_M_f.
"""
import csv
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scripts", "bench", "lib"))
from criterion_table import estimates  # noqa: E402  (the one reader of criterion's results)

peer_csv = sys.argv[1]
target = sys.argv[2] if len(sys.argv) > 2 else os.environ.get("CARGO_TARGET_DIR", "target")

ours = {}  # (family, n, function) -> median ns
for bench, median in estimates(target):
    family, _, n = bench["group_id"].partition("/")
    if family in ("planar", "spatial") and n.isdigit():  # the spellings bench's groups are FAMILY/SPELLING/N
        ours[(family, int(n), bench["function_id"])] = median

peer = {}  # (family, n, algo) -> median ns (thread CPU time)
with open(peer_csv) as f:
    for row in csv.DictReader(line for line in f if not line.startswith("#")):
        peer[(row["family"], int(row["n"]), row["algo"])] = float(row["median_ns"])

series = {
    "dalembert M + f": lambda fam, n: ours.get((fam, n, "mass_matrix+forcing")),
    "dalembert accelerations": lambda fam, n: ours.get((fam, n, "accelerations")),
    "Pinocchio crba_sym + nle": lambda fam, n: peer.get((fam, n, "pin_crba_sym"), 0) + peer[(fam, n, "pin_nle")]
    if (fam, n, "pin_nle") in peer else None,
    "Pinocchio aba": lambda fam, n: peer.get((fam, n, "pin_aba")),
    "MuJoCo M + f": lambda fam, n: peer.get((fam, n, "mj_M_f")),
    "MuJoCo forward": lambda fam, n: peer.get((fam, n, "mj_forward")),
    "hand-derived C++ M + f": lambda fam, n: peer.get((fam, n, "min_pairwise_M_f")),
}
ns = sorted({n for (_, n, _) in ours} & {n for (_, n, _) in peer})

os.makedirs("docs/charts", exist_ok=True)
with open("docs/charts/chains.csv", "w", newline="") as f:
    out = csv.writer(f)
    out.writerow(["family", "n", "tool", "ns_per_call"])
    for family in ("planar", "spatial"):
        for tool, value in series.items():
            for n in ns:
                v = value(family, n)
                if v:
                    out.writerow([family, n, tool, f"{v:.2f}"])

for family in ("planar", "spatial"):
    print(f"\n**{family}** (ns per call; ratio = peer / dalembert)\n")
    print("| n | dalembert M + f | Pinocchio crba_sym + nle | ratio | MuJoCo M + f | ratio "
          "| dalembert accelerations | Pinocchio aba | ratio | MuJoCo forward |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for n in ns:
        mf, acc = series["dalembert M + f"](family, n), series["dalembert accelerations"](family, n)
        pin, aba = series["Pinocchio crba_sym + nle"](family, n), series["Pinocchio aba"](family, n)
        mj, mjf = series["MuJoCo M + f"](family, n), series["MuJoCo forward"](family, n)
        fmt = lambda x: f"{x:.1f}" if x else "–"
        ratio = lambda a, b: f"**{a / b:.1f}×**" if a and b else "–"
        print(f"| {n} | {fmt(mf)} | {fmt(pin)} | {ratio(pin, mf)} | {fmt(mj)} | {ratio(mj, mf)} "
              f"| {fmt(acc)} | {fmt(aba)} | {ratio(aba, acc)} | {fmt(mjf)} |")
