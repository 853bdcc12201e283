"""Writes tests/reference/dal_sympy_states.json: `M`, `f`, `T` and `V` of
models of the root test suite at chosen states, from dal_sympy.py (an
independent SymPy reading of the language, in this folder) evaluated at
30 digits and rounded to doubles.

For each system below it reads the model's text from its test file (the
`dalembert::dalembert! { .. }` block, without its doc comment, its
`outputs` statements and the points only outputs use) and the parameters
of the test's `= Name { .. }` literal, derives the model with dal_sympy
and evaluates it at the states listed here. The tests read the file and
check that its parameters are their own.

    python3 scripts/dal_sympy_states_reference.py > tests/reference/dal_sympy_states.json
    python3 scripts/dal_sympy_states_reference.py --check tests/reference/dal_sympy_states.json

Needs SymPy and mpmath (`pip install sympy mpmath`).
"""

import json
import os
import re
import sys

import mpmath
import sympy as sp

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import dal_sympy  # noqa: E402
from acceptance_reference import block, literal  # noqa: E402

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")

# (system, test file, statements dropped besides `outputs`, states as (t, q, v, u)).
SYSTEMS = [
    (
        "FullInertia",
        "tests/suite/outputs_against_derivatives.rs",
        [],
        [(0.3, [0.7, -1.1], [1.3, -0.4], [0.8]), (-0.5, [-2.2, 0.9], [-0.6, 1.7], [-1.2])],
    ),
    (
        "ShakenSprings",
        "tests/suite/outputs_against_derivatives.rs",
        ["point Marker"],
        [(0.3, [0.2, -1.1], [1.3, -0.4], [0.8]), (1.7, [-0.4, 2.5], [-0.6, 1.7], [-1.2])],
    ),
    (
        "SwingEuler",
        "tests/suite/ball_and_free_joints.rs",
        [],
        [
            (0.0, [0.4, 0.7, -0.5, 0.9], [1.1, -0.6, 0.8, 1.3], [0.7]),
            (0.0, [-1.2, -0.3, 1.1, -0.4], [-0.5, 1.7, -1.2, 0.4], [-1.9]),
        ],
    ),
]


def model_and_parameters(name, path, dropped):
    """The model's text as dal_sympy reads it and the test's parameters."""
    text = open(os.path.join(ROOT, path)).read()
    start = re.search(r"dalembert::dalembert! \{\s*(///[^\n]*\n\s*)*pub " + name + r" \{", text)
    source, _ = block(text, start.start())
    kept = [
        line
        for line in source.splitlines()
        if not line.strip().startswith(("///", "outputs", *dropped))
    ]
    parameters = literal(block(text, re.search(r"= " + name + r" \{", text).start())[0])
    return "\n".join(kept), parameters


def evaluate(source, parameters, states):
    model = dal_sympy.Model(source)
    exprs = model.derive()
    args = [model.t] + model.coords + model.qd + model.inputs + model.params
    funcs = {k: sp.lambdify(args, exprs[k], modules="mpmath", cse=True) for k in "MfTV"}
    mpmath.mp.dps = 30
    out = []
    for t, q, v, u in states:
        values = [mpmath.mpf(x) for x in [t] + q + v + u]
        values += [mpmath.mpf(parameters[str(p)]) for p in model.params]
        got = {k: [[float(x) for x in row] for row in dal_sympy.rows(fn(*values))] for k, fn in funcs.items()}
        out.append(
            {
                "t": t,
                "q": q,
                "v": v,
                "u": u,
                "mass": got["M"],
                "forcing": [row[0] for row in got["f"]],
                "kinetic": got["T"][0][0],
                "potential": got["V"][0][0],
            }
        )
    return [str(p) for p in model.params], out


def reference():
    systems = {}
    for name, path, dropped, states in SYSTEMS:
        source, parameters = model_and_parameters(name, path, dropped)
        order, values = evaluate(source, parameters, states)
        systems[name] = {
            "test": path,
            "parameters": [parameters[p] for p in order],
            "parameter_names": order,
            "states": values,
        }
    return {
        "how": "dal_sympy.py (SymPy) derivation of each model, evaluated with mpmath at 30 digits and rounded to doubles: scripts/dal_sympy_states_reference.py",
        "convention": "M(q) v' = f(t, q, v, u); T and V the kinetic and potential energy",
        "systems": systems,
    }


if __name__ == "__main__":
    fresh = reference()
    if sys.argv[1:2] == ["--check"]:
        stored = json.load(open(sys.argv[2]))
        same = stored == fresh
        print("the stored file is this script's output" if same else "the stored file differs")
        sys.exit(0 if same else 1)
    json.dump(fresh, sys.stdout, indent=1)
    print()
