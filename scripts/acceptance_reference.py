"""Regenerates the SymPy literals of the acceptance tests that compare a
model with dal_sympy's values (`Expected { .. }` and `Constraints { .. }` in
tests/suite/spun_hoop_and_spherical_pendulum.rs, massless_frames.rs and
sled_with_a_driven_slider.rs) and checks them against the files.

For every `dalembert::dalembert! { .. }` model of those files it reads the
model's text, the parameters of the `let system = Name { .. }` beside it and
the state (t, q, v, u) of each `Expected`, derives the model with
`dal_sympy.py` (an independent SymPy reading of the language, in this
folder), evaluates M, f, T, V (and A, b and the residual) at 30 digits,
solves for the accelerations (with the constraints' multipliers where there
are rows: [[M, -Aᵀ], [A, 0]] [v̇; λ] = [f; b]) and prints the largest
difference from each literal, relative to max(1, |value|).

    python3 scripts/acceptance_reference.py            # exit 1 unless all agree to 4e-15 (a few ulps)
    python3 scripts/acceptance_reference.py --print    # the values, to paste into a test

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

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
FILES = [
    "tests/suite/spun_hoop_and_spherical_pendulum.rs",
    "tests/suite/massless_frames.rs",
    "tests/suite/sled_with_a_driven_slider.rs",
]
TOLERANCE = 4e-15


def block(text, start):
    """The text between the brace at or after `start` and its match."""
    open_ = text.index("{", start)
    depth = 0
    for i in range(open_, len(text)):
        depth += {"{": 1, "}": -1}.get(text[i], 0)
        if depth == 0:
            return text[open_ + 1 : i], i + 1
    raise ValueError("unbalanced braces")


def literal(body):
    """A Rust struct literal's fields (numbers and arrays of them) as a dict."""
    text = re.sub(r"(\w+):", r'"\1":', body)
    text = re.sub(r",(\s*[\]}])", r"\1", "{" + text + "}")
    return json.loads(re.sub(r",\s*$", "", text))


def models(text):
    """(model source, parameters, [(expected, constraints or None)]) per model."""
    starts = [m.start() for m in re.finditer(r"dalembert::dalembert! \{", text)] + [len(text)]
    for start, end in zip(starts, starts[1:]):
        source, _ = block(text, start)
        source = "\n".join(l for l in source.splitlines() if not l.strip().startswith("///"))
        name = re.search(r"pub (\w+) \{", source).group(1)
        chunk = text[start:end]
        at = re.search(r"let system = " + name + r" \{", chunk)
        parameters = literal(block(chunk, at.start())[0])
        states = []
        for m in re.finditer(r"\bExpected \{", chunk):
            expected, after = block(chunk, m.start())
            rows = re.match(r"\s*\},?\s*Constraints \{", chunk[after - 1 :])
            constraints = literal(block(chunk, after)[0]) if rows else None
            states.append((literal(expected), constraints))
        yield name, source, parameters, states


def solve(mass, forcing, jacobian=None, bias=None):
    """The accelerations, then the multipliers where there are rows."""
    n = len(forcing)
    if jacobian is None:
        x = mpmath.lu_solve(mpmath.matrix(mass), mpmath.matrix(forcing))
        return [x[i] for i in range(n)]
    c = len(bias)
    kkt = mpmath.zeros(n + c, n + c)
    for i in range(n):
        for j in range(n):
            kkt[i, j] = mass[i][j]
        for k in range(c):
            kkt[i, n + k] = -jacobian[k][i]
            kkt[n + k, i] = jacobian[k][i]
    x = mpmath.lu_solve(kkt, mpmath.matrix(list(forcing) + list(bias)))
    return [x[i] for i in range(n + c)]


def flat(x):
    if not isinstance(x, list):
        return [x]
    return [v for row in x for v in (row if isinstance(row, list) else [row])]


def evaluate(name, source, parameters, states):
    model = dal_sympy.Model(source)
    exprs = model.derive()
    args = [model.t] + model.coords + model.qd + model.inputs + model.params
    funcs = {k: sp.lambdify(args, e, modules="mpmath", cse=True) for k, e in exprs.items()}
    mpmath.mp.dps = 30
    out = []
    for expected, _ in states:
        values = [mpmath.mpf(x) for x in [expected["t"]] + expected["q"] + expected["v"] + expected["u"]]
        values += [mpmath.mpf(parameters[str(p)]) for p in model.params]
        got = {k: dal_sympy.rows(fn(*values)) for k, fn in funcs.items()}
        mass = got["M"]
        forcing = [r[0] for r in got["f"]]
        fields = {
            "mass": mass,
            "forcing": forcing,
            "kinetic": got["T"][0][0],
            "potential": got["V"][0][0],
        }
        rows = None
        if "A" in got:
            rows = {
                "jacobian": got["A"],
                "bias": [r[0] for r in got["b"]],
                "residual": [r[0] for r in got["Phi"]],
            }
        fields["accelerations"] = solve(
            mass, forcing, rows and rows["jacobian"], rows and rows["bias"]
        )[: len(forcing)]
        out.append((fields, rows))
    return out


def main(argv):
    worst = 0.0
    count = 0
    for path in FILES:
        text = open(os.path.join(ROOT, path)).read()
        found = list(models(text))
        assert found, f"no model in {path}"
        for name, source, parameters, states in found:
            assert states, f"{path}: {name} has no Expected state"
            for (fields, rows), (expected, constraints) in zip(
                evaluate(name, source, parameters, states), states
            ):
                pairs = [(k, fields[k], expected[k]) for k in fields]
                if rows is not None:
                    pairs += [(k, rows[k], constraints[k]) for k in rows]
                for key, mine, stored in pairs:
                    mine, stored = flat(mine), flat(stored)
                    assert len(mine) == len(stored), (name, key)
                    error = max(
                        [0.0] + [float(abs(a - b) / max(1, abs(b))) for a, b in zip(mine, stored)]
                    )
                    worst = max(worst, error)
                    count += 1
                    if "--print" in argv:
                        print(f"{name} t={expected['t']!r} {key}: {[float(x) for x in mine]}")
            print(f"{path}: {name}: {len(states)} states checked")
    print(f"{count} quantities, largest difference {worst:.1e} (relative to max(1, |value|))")
    return 0 if worst <= TOLERANCE else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
