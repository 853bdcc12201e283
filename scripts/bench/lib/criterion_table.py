#!/usr/bin/env python3
"""Markdown tables from criterion's medians and the peers' harness CSVs.

Usage: criterion_table.py [--target DIR] [--since FILE] TABLE [PEER_CSV...]

  --target DIR   cargo's target directory (criterion's results are under
                 DIR/criterion); default $CARGO_TARGET_DIR or target
  --since FILE   read only the results written after FILE was
  TABLE          seed | chains60 | derivatives | integrators | throughput | mjcf |
                 drift_watch | list
                 (list: every benchmark whose id starts with $BENCH_PREFIX)

Ours are criterion's medians (the `median` of `new/estimates.json`), the
peers' the `median_ns` column of their CSV (thread CPU time): one window,
read the ratios. A peer CSV named NAME.csv holds `run.sh --urdf` rows for
the robot NAME; any other holds `run.sh --ns` rows of the chains.
"""
import argparse
import csv
import glob
import json
import os
import sys


def estimates(target, since=None, baseline="new"):
    """Criterion's median in ns per benchmark, as (its benchmark.json, median):
    the results saved under `baseline` (`new`: the last run), and with `since`
    only those written after that file was."""
    floor = os.path.getmtime(since) if since else 0.0
    found = []
    pattern = os.path.join(target, "criterion", "**", baseline, "estimates.json")
    for path in glob.glob(pattern, recursive=True):
        if os.path.getmtime(path) < floor:
            continue
        with open(path.replace("estimates.json", "benchmark.json")) as f:
            bench = json.load(f)
        with open(path) as f:
            found.append((bench, json.load(f)["median"]["point_estimate"]))
    if not found:
        sys.exit("no criterion results found: did the bench run?")
    return found


def medians(target, since):
    """Criterion's median per benchmark id, in ns."""
    return {bench["full_id"]: median for bench, median in estimates(target, since)}


def peer_rows(paths):
    """(system, algo) -> median ns, systems named `planar_12` or after the CSV."""
    rows = {}
    for path in paths:
        robot = os.path.splitext(os.path.basename(path))[0]
        with open(path) as f:
            for row in csv.DictReader(line for line in f if not line.startswith("#")):
                system = f"{row['family']}_{row['n']}" if "family" in row else robot
                rows[(system, row["algo"])] = float(row["median_ns"])
    return rows


def summary(measure, against, ratios):
    """A row of BENCHMARKS.md's opening table: the span of ours / theirs."""
    ratios = [r for r in ratios if r is not None]
    if not ratios:
        sys.exit(f"no ratio for the summary of {measure} against {against}: missing figures")
    span = f"{min(ratios):.2f}" if len(ratios) == 1 else f"{min(ratios):.2f}–{max(ratios):.2f}"
    print(f"<!-- summary: {measure} | {against} | {span} -->")


def quotient(a, b):
    return a / b if a is not None and b else None


def ratio(a, b):
    return f"{a / b:.2f}" if a is not None and b else "–"


def required(ours, keys):
    """Fails the table when one of its benchmarks has no fresh result."""
    missing = [k for k in keys if k not in ours]
    if missing:
        sys.exit("no fresh result for " + ", ".join(missing) + ": did the bench run?")


def ns(x):
    return "–" if x is None else (f"{x:.1f}" if x < 100 else f"{x:.0f}")


def seed(ours, _peers):
    required(ours, ["harness_overhead"] + [f"{g}/{f}" for g in ("seed1_double_pendulum", "seed2_rotating_bar")
                                           for f in ("mass_matrix", "forcing", "mass_matrix+forcing", "accelerations")])
    print("| system | `mass_matrix` | `forcing` | both | `cholesky_accelerations` |")
    print("|---|---|---|---|---|")
    for group, label in [("seed1_double_pendulum", "seed example 1, double pendulum"),
                         ("seed2_rotating_bar", "seed example 2, rotating bar")]:
        cells = [ns(ours.get(f"{group}/{f}")) for f in
                 ("mass_matrix", "forcing", "mass_matrix+forcing", "accelerations")]
        print(f"| {label} | " + " | ".join(cells) + " |")
    print()
    print(f"ns per call; the loop alone (`harness_overhead`) costs {ns(ours.get('harness_overhead'))} ns.")


def derivatives(ours, peers):
    print("| system | `accelerations` (ns) | `accelerations_jacobian` (ns) | jacobian / accelerations "
          "| Pinocchio `computeABADerivatives` (ns) | ours / Pinocchio |")
    print("|---|---|---|---|---|---|")
    systems = sorted({k.split("/")[1] for k in ours if k.startswith("derivatives/")})
    if not systems:
        sys.exit("no results of the derivatives bench")
    ratios = []
    for system in systems:
        acc = ours.get(f"derivatives/{system}/accelerations")
        jac = ours.get(f"derivatives/{system}/accelerations_jacobian")
        key = system.replace("_chain_0", "_").replace("_chain_", "_").replace("_robot", "")
        pin = peers.get((key, "pin_aba_derivatives"))
        print(f"| {system} | {ns(acc)} | {ns(jac)} | {ratio(jac, acc)} | {ns(pin)} | {ratio(jac, pin)} |")
        ratios.append(quotient(jac, pin))
    print()
    summary("`accelerations_jacobian`, chains n ≤ 12, panda, UR5", "Pinocchio `computeABADerivatives`", ratios)


def integrators(ours, _peers):
    methods = [("floor: bare accelerations loop", "floor (bare `accelerations` loop)"),
               ("rk4", "RK4"), ("gauss4", "Gauss 4"), ("dopri5", "DOPRI5"), ("dop853", "DOP853")]
    systems = [("planar_12", "planar chain of 12"), ("seed_1", "seed example 1")]
    required(ours, [f"integrators/{s}/{m}" for s, _ in systems for m, _ in methods])
    print("| | " + " | ".join(f"{label} (ns) | / floor" for _, label in systems) + " |")
    print("|---|" + "---|---|" * len(systems))
    for method, label in methods:
        cells = []
        for system, _ in systems:
            value = ours.get(f"integrators/{system}/{method}")
            floor = ours.get(f"integrators/{system}/floor: bare accelerations loop")
            cells += [ns(value), "" if method.startswith("floor") else ratio(value, floor)]
        print(f"| {label} | " + " | ".join(cells) + " |")
    print()
    print("ns per evaluation of the right-hand side.")


def throughput(ours, peers):
    print("| family | n | ours per RK4 step (ns) | MuJoCo `mj_step` RK4 (ns) | MuJoCo / ours |")
    print("|---|---|---|---|---|")
    keys = [k.split("/")[2:4] for k in ours if k.startswith("throughput/rk4_1ms/")]
    if not keys:
        sys.exit("no results of the throughput benches")
    ratios = []
    for family, n in sorted(keys, key=lambda k: (k[0], int(k[1]))):
        key = f"throughput/rk4_1ms/{family}/{n}"
        step = ours[key]
        theirs = peers.get((f"{family}_{n}", "mj_step_rk4"))
        print(f"| {family} | {n} | {ns(step)} | {ns(theirs)} | {ratio(theirs, step)}× |")
        if int(n) <= 12:
            ratios.append(quotient(step, theirs))
    print()
    summary("one RK4 step, chains n ≤ 12", "MuJoCo's RK4 step (`mj_step`)", ratios)


def chains60(ours, peers):
    print("| family | M + f (ns) | / Pinocchio `crba` + `nle` | / MuJoCo M + f "
          "| `accelerations` (ns) | / Pinocchio `aba` | / MuJoCo `mj_forward` |")
    print("|---|---|---|---|---|---|---|")
    mf_ratios, acc_ratios = [], []
    for family in ("planar", "spatial"):
        mf = ours.get(f"{family}/60/mass_matrix+forcing")
        acc = ours.get(f"{family}/60/accelerations")
        key = f"{family}_60"
        crba, nle = peers.get((key, "pin_crba_sym")), peers.get((key, "pin_nle"))
        pin_mf = crba + nle if crba and nle else None
        if mf is None or acc is None or pin_mf is None:
            sys.exit(f"{family}/60: missing figures (ours or the peers')")
        mf_ratios.append(mf / pin_mf)
        acc_ratios.append(quotient(acc, peers.get((key, "pin_aba"))))
        print(f"| {family} | {ns(mf)} | {ratio(mf, pin_mf)} | {ratio(mf, peers.get((key, 'mj_M_f')))} "
              f"| {ns(acc)} | {ratio(acc, peers.get((key, 'pin_aba')))} "
              f"| {ratio(acc, peers.get((key, 'mj_forward')))} |")
    print()
    summary("`mass_matrix` + `forcing`, chains n = 60", "Pinocchio `crba` + `nonLinearEffects`", mf_ratios)
    summary("`accelerations`, chains n = 60", "Pinocchio `aba`", acc_ratios)


def listing(ours, _peers, prefix=""):
    print("| benchmark | median |")
    print("|---|---|")
    for key in sorted(k for k in ours if k.startswith(prefix)):
        value = ours[key]
        unit, scale = next((u, s) for u, s in (("s", 1e9), ("ms", 1e6), ("µs", 1e3), ("ns", 1))
                           if value >= s or s == 1)
        print(f"| `{key}` | {value / scale:.3g} {unit} |")


def mjcf(ours, peers):
    print("| model | `mass_matrix` + `forcing` (ns) | `accelerations` (ns) | MuJoCo `mj_forward` (ns) "
          "| M + f / `mj_forward` | accelerations / `mj_forward` |")
    print("|---|---|---|---|---|---|")
    models = ("cheetah", "humanoid")
    required(ours, [f"robots/{m}/{f}" for m in models for f in ("mass_matrix+forcing", "accelerations")])
    for model in models:
        mf, acc = ours[f"robots/{model}/mass_matrix+forcing"], ours[f"robots/{model}/accelerations"]
        forward = peers.get((model, "mj_forward"))
        print(f"| {model} | {ns(mf)} | {ns(acc)} | {ns(forward)} | {ratio(mf, forward)} | **{ratio(acc, forward)}** |")
    print()
    summary("`accelerations`, dm_control humanoid (27 speeds)", "MuJoCo `mj_forward`",
            [quotient(ours["robots/humanoid/accelerations"], peers.get(("humanoid", "mj_forward")))])


def drift_watch(ours, _peers, steps=1000):
    systems = [("seed_3", "seed example 3 (3 coordinates, 2 rows)"),
               ("four_bars_10", "IFToMM A02, ten four-bars (21 coordinates, 20 rows)")]
    keys = [f"drift_watch/{s}/{st}/{w}" for s, _ in systems for st in ("unstabilised", "projected")
            for w in ("watched", "unwatched")]
    required(ours, keys)
    print("| system | stabilisation | watched (µs/step) | unwatched (µs/step) | watch's share |")
    print("|---|---|---|---|---|")
    for system, label in systems:
        for stabilisation in ("unstabilised", "projected"):
            w = ours[f"drift_watch/{system}/{stabilisation}/watched"] / steps / 1e3
            u = ours[f"drift_watch/{system}/{stabilisation}/unwatched"] / steps / 1e3
            print(f"| {label} | {stabilisation} | {w:.2f} | {u:.2f} | {(w - u) / w:.0%} |")


TABLES = {"mjcf": mjcf, "drift_watch": drift_watch, "list": listing, "chains60": chains60, "seed": seed, "derivatives": derivatives, "integrators": integrators,
          "throughput": throughput}

if __name__ == "__main__":
    parser = argparse.ArgumentParser()
    parser.add_argument("--target", default=os.environ.get("CARGO_TARGET_DIR", "target"))
    parser.add_argument("--since")
    parser.add_argument("table", choices=TABLES)
    parser.add_argument("peers", nargs="*")
    args = parser.parse_args()
    ours = medians(args.target, args.since)
    if args.table == "list":
        listing(ours, None, os.environ.get("BENCH_PREFIX", ""))
    else:
        TABLES[args.table](ours, peer_rows(args.peers))
