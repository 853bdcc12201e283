"""Checks that tests/reference/seed_examples.json regenerates: the seed's
three worked examples as written in the language (generated/models/
double_pendulum.dal, rotating_bar.dal, constrained_pendulum.dal), derived by
`dal_sympy.py` (an independent SymPy reading of the language, in this folder)
and evaluated at 30 digits at every stored state, give the stored M, f, T, V
(and A, b and the constraint residual) to rounding; the accelerations (and
multipliers) solved from them at 30 digits, [[M, -Aᵀ], [A, 0]] [q̈; λ] = [f; b],
give the stored `qdd` (and `lambda`).

    python3 scripts/seed_examples_reference.py     # exit 1 unless all agree to 4e-15

The states themselves (times, coordinates, speeds, inputs and parameters)
are the file's: the script recomputes every value at them. Needs SymPy and
mpmath (`pip install sympy mpmath`).
"""

import json
import os
import sys

import mpmath
import sympy as sp

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import dal_sympy  # noqa: E402
from acceptance_reference import solve  # noqa: E402

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
MODELS = {
    "S1": "generated/models/double_pendulum.dal",
    "S2": "generated/models/rotating_bar.dal",
    "S3": "generated/models/constrained_pendulum.dal",
}
TOLERANCE = 4e-15


def main():
    reference = json.load(open(os.path.join(ROOT, "tests/reference/seed_examples.json")))
    ok = True
    for system, path in MODELS.items():
        stored = reference["systems"][system]
        model = dal_sympy.Model(open(os.path.join(ROOT, path)).read())
        dal_sympy.TOL = TOLERANCE
        ok &= dal_sympy.check(model, stored, system, False)
        exprs = model.derive()
        args = [model.t] + model.coords + model.qd + model.inputs + model.params
        funcs = {k: sp.lambdify(args, e, modules="mpmath", cse=True) for k, e in exprs.items()}
        mpmath.mp.dps = 30
        worst = 0.0
        assert stored["states"], f"{system}: no states"
        for state in stored["states"]:
            values = [mpmath.mpf(x) for x in [state["t"]] + state["q"] + state["qd"] + state["inputs"]]
            values += [mpmath.mpf(stored["parameters"][str(p)]) for p in model.params]
            got = {k: dal_sympy.rows(fn(*values)) for k, fn in funcs.items()}
            forcing = [r[0] for r in got["f"]]
            if "A" in got:
                bias = [r[0] for r in got["b"]]
                solution = solve(got["M"], forcing, got["A"], bias)
                expected = state["qdd"] + state["lambda"]
            else:
                solution = solve(got["M"], forcing)
                expected = state["qdd"]
            assert len(solution) == len(expected)
            pairs = zip(solution, expected)
            worst = max([worst] + [float(abs(a - b) / max(1, abs(b))) for a, b in pairs])
        print(f"  qdd{' and lambda' if 'A' in exprs else ''} worst rel err {worst:9.2e}")
        ok &= worst <= TOLERANCE
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
