#!/usr/bin/env python3
"""Print the median of every criterion benchmark under $CARGO_TARGET_DIR/criterion.

Usage: python3 benches/medians.py [TARGET_DIR]   (default: $CARGO_TARGET_DIR or target)
Medians are criterion's median over samples, in ns (per call for the
`seed_examples` bench, per expansion for `expand`), with its 95% interval.
"""
import glob
import json
import os
import sys

target = sys.argv[1] if len(sys.argv) > 1 else os.environ.get("CARGO_TARGET_DIR", "target")
for path in sorted(glob.glob(os.path.join(target, "criterion", "**", "new", "estimates.json"), recursive=True)):
    with open(path) as f:
        median = json.load(f)["median"]
    with open(path.replace("estimates.json", "benchmark.json")) as f:
        name = json.load(f)["full_id"]
    ci = median["confidence_interval"]
    print(f"{name:45s} {median['point_estimate']:14.2f} ns  [{ci['lower_bound']:.2f}, {ci['upper_bound']:.2f}]")
