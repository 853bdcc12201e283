"""SciPy's side of the DOP853 comparison in BENCHMARKS.md.

Seed example 1 (double pendulum, m = L = 1, g = 9.81, both links at 2 rad at
rest) integrated to t = 10 s by `scipy.integrate.solve_ivp(method="DOP853")`
over a sweep of tolerances (rtol = atol), with the fastest pure-Python
right-hand side we know: SymPy solves M(q) q'' = f symbolically (the M and f
of tests/reference/seed_examples.json, an independent SymPy derivation) and
`lambdify(..., cse=True, modules="math")` turns (q, q') -> (q', q'') into one
flat scalar function. Reported per tolerance: the final-state error (max abs)
against the 25-digit reference of tests/reference/chaotic_double_pendulum.json,
the median thread CPU time of several runs (the clock of our side, which
another process holding the core does not inflate) and the number of RHS calls.

Run it through scripts/scipy_baseline.sh, which provides the venv.
"""

import argparse
import csv
import json
import pathlib
import statistics
import time

import numpy as np
import scipy
import sympy
from scipy.integrate import solve_ivp

ROOT = pathlib.Path(__file__).resolve().parent.parent
REFERENCE = ROOT / "tests" / "reference"


def right_hand_side():
    """The first-order right-hand side of seed example 1 as one lambdified
    scalar function of (theta1, theta2, theta1_dot, theta2_dot)."""
    seed = json.loads((REFERENCE / "seed_examples.json").read_text())["systems"]["S1"]
    names = seed["coordinates"] + seed["speeds"] + list(seed["parameters"])
    symbols = {name: sympy.Symbol(name) for name in names}
    mass = sympy.Matrix(
        [[sympy.sympify(entry, locals=symbols) for entry in row] for row in seed["symbolic"]["M"]]
    )
    forcing = sympy.Matrix([sympy.sympify(entry, locals=symbols) for entry in seed["symbolic"]["f"]])
    chaotic = json.loads((REFERENCE / "chaotic_double_pendulum.json").read_text())
    values = {symbols[name]: value for name, value in chaotic["parameters"].items()}
    accelerations = mass.subs(values).LUsolve(forcing.subs(values))
    speeds = [symbols[name] for name in seed["speeds"]]
    state = [symbols[name] for name in seed["coordinates"] + seed["speeds"]]
    rates = sympy.lambdify(state, speeds + list(accelerations), modules="math", cse=True)
    calls = [0]

    def rhs(_t, y):
        calls[0] += 1
        return rates(y[0], y[1], y[2], y[3])

    return rhs, calls, chaotic


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=str(ROOT / "target" / "charts" / "scipy_dop853.csv"))
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args()

    rhs, calls, chaotic = right_hand_side()
    y0 = np.array(chaotic["initial_state"], dtype=float)
    t_end = chaotic["t_final"]
    reference = np.array([float(x) for x in chaotic["final_state_25_digits"]])
    print(f"SciPy {scipy.__version__}, SymPy {sympy.__version__}, NumPy {np.__version__}")
    print(f"{'rtol = atol':>12} {'error':>10} {'median s':>10} {'RHS calls':>10}")
    rows = []
    for exponent in range(4, 15):
        tolerance = 10.0 ** -exponent
        times = []
        for _ in range(args.repeats):
            calls[0] = 0
            start = time.thread_time()
            solution = solve_ivp(
                rhs, (0.0, t_end), y0, method="DOP853", rtol=tolerance, atol=tolerance
            )
            times.append(time.thread_time() - start)
        error = float(np.max(np.abs(solution.y[:, -1] - reference)))
        seconds = statistics.median(times)
        rows.append(("SciPy DOP853", tolerance, seconds, calls[0], error))
        print(f"{tolerance:>12.0e} {error:>10.3e} {seconds:>10.4f} {calls[0]:>10}")

    out = pathlib.Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    with out.open("w", newline="") as file:
        writer = csv.writer(file)
        writer.writerow(["method", "rtol", "seconds", "rhs_evaluations", "error"])
        writer.writerows(rows)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
