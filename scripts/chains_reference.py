"""Pinocchio's numbers for the benchmark chains: writes
tests/reference/chains.json (schema and conventions in
tests/reference/README_chains.md).

Two families of serial chains of uniform slender rods, n = 1..6: `planar`
(every axis +z, rods along the link's -y, gravity -9.81 y) and `spatial`
(axes z, y, z, y, ..., rods along +x, gravity -9.81 z); link i has mass
1 + 0.1 i and length 0.5 + 0.05 i. At 10 random states each (numpy
`default_rng(20240611)`, drawn family by family, n by n, state by state as
q ~ U(-pi, pi), qd ~ U(-2, 2), tau ~ U(-10, 10)) and two special ones:
Pinocchio's crba (mirrored to the full matrix), nonLinearEffects,
computeGeneralizedGravity, aba, and the energies.

    python3 scripts/chains_reference.py > tests/reference/chains.json
    python3 scripts/chains_reference.py --check tests/reference/chains.json

With --check it compares with the stored file instead and prints the largest
difference of every field (exit 1 unless all agree to 1e-15 relative).
"""

import json
import math
import sys

import numpy as np
import pinocchio as pin

SEED = 20240611
GRAVITY = {"planar": [0.0, -9.81, 0.0], "spatial": [0.0, 0.0, -9.81]}


def links(family, n):
    """The links of a chain of `n`, as README_chains.md describes them."""
    out = []
    parent_child = [0.0, 0.0, 0.0]
    for i in range(1, n + 1):
        mass = 1.0 + 0.1 * i
        length = 0.5 + 0.05 * i
        transverse = mass * length**2 / 12
        if family == "planar":
            axis = [0.0, 0.0, 1.0]
            rod = [0.0, -1.0, 0.0]
            inertia = [[transverse, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, transverse]]
        else:
            axis = [0.0, 0.0, 1.0] if i % 2 == 1 else [0.0, 1.0, 0.0]
            rod = [1.0, 0.0, 0.0]
            inertia = [[0.0, 0.0, 0.0], [0.0, transverse, 0.0], [0.0, 0.0, transverse]]
        child = [length * r for r in rod]
        out.append(
            {
                "index": i,
                "mass": mass,
                "length": length,
                "joint_axis_local": axis,
                "joint_origin_in_parent": parent_child,
                "joint_rotation_in_parent": np.eye(3).tolist(),
                "com_local": [c / 2 for c in child],
                "inertia_about_com_local": inertia,
                "rod_direction_local": rod,
                "child_joint_local": child,
            }
        )
        parent_child = child
    return out


def model_of(family, chain):
    model = pin.Model()
    model.gravity.linear = np.array(GRAVITY[family])
    parent = 0
    for link in chain:
        axis = link["joint_axis_local"]
        joint = pin.JointModelRZ() if axis == [0.0, 0.0, 1.0] else pin.JointModelRY()
        placement = pin.SE3(np.eye(3), np.array(link["joint_origin_in_parent"]))
        parent = model.addJoint(parent, joint, placement, f"joint{link['index']}")
        inertia = pin.Inertia(
            link["mass"], np.array(link["com_local"]), np.array(link["inertia_about_com_local"])
        )
        model.appendBodyToJoint(parent, inertia, pin.SE3.Identity())
    return model


def values(model, data, q, qd, tau):
    q, qd, tau = (np.array(x, dtype=float) for x in (q, qd, tau))
    m = pin.crba(model, data, q)
    m = np.triu(m) + np.triu(m, 1).T
    nle = pin.nonLinearEffects(model, data, q, qd)
    gravity = pin.computeGeneralizedGravity(model, data, q)
    qdd = pin.aba(model, data, q, qd, tau)
    kinetic = pin.computeKineticEnergy(model, data, q, qd)
    potential = pin.computePotentialEnergy(model, data, q)
    return {
        "q": q.tolist(),
        "qd": qd.tolist(),
        "tau": tau.tolist(),
        "M": m.tolist(),
        "nle": nle.tolist(),
        "gravity_torque": gravity.tolist(),
        "coriolis_times_qd": (nle - gravity).tolist(),
        "f": (tau - nle).tolist(),
        "qdd": qdd.tolist(),
        "T": float(kinetic),
        "V": float(potential),
    }


def absolute(state):
    """The planar chain in absolute link angles: theta = T q, T lower-triangular ones."""
    n = len(state["q"])
    t = np.tril(np.ones((n, n)))
    t_inv_t = np.linalg.inv(t).T
    m = np.array(state["M"])
    return {
        "theta": (t @ state["q"]).tolist(),
        "thetadot": (t @ state["qd"]).tolist(),
        "M": (t_inv_t @ m @ np.linalg.inv(t)).tolist(),
        "nle": (t_inv_t @ state["nle"]).tolist(),
        "tau": (t_inv_t @ state["tau"]).tolist(),
        "f": (t_inv_t @ state["f"]).tolist(),
        "thetaddot": (t @ state["qdd"]).tolist(),
    }


def reference():
    rng = np.random.default_rng(SEED)
    models = []
    for family in ["planar", "spatial"]:
        for n in range(1, 7):
            chain = links(family, n)
            model = model_of(family, chain)
            data = model.createData()
            states = []
            for _ in range(10):
                q = rng.uniform(-math.pi, math.pi, n)
                qd = rng.uniform(-2.0, 2.0, n)
                tau = rng.uniform(-10.0, 10.0, n)
                state = values(model, data, q, qd, tau)
                if family == "planar":
                    state["absolute"] = absolute(state)
                states.append(state)
            special = [
                dict(name="rest", **values(model, data, [0.0] * n, [0.0] * n, [0.0] * n)),
                dict(
                    name="quarter_turn",
                    **values(model, data, [math.pi / 2] * n, [1.0] * n, [0.0] * n),
                ),
            ]
            if family == "planar":
                for state in special:
                    state["absolute"] = absolute(state)
            models.append(
                {
                    "family": family,
                    "n": n,
                    "nq": model.nq,
                    "nv": model.nv,
                    "gravity": GRAVITY[family],
                    "links": chain,
                    "states": states,
                    "special_states": special,
                }
            )
    return models


def numbers(x):
    if isinstance(x, dict):
        return [v for key in sorted(x) if key != "name" for v in numbers(x[key])]
    if isinstance(x, list):
        return [v for item in x for v in numbers(item)]
    return [x] if isinstance(x, (int, float)) else []


def check(path):
    stored = json.load(open(path))["models"]
    fresh = reference()
    assert len(stored) == len(fresh) > 0
    worst = {}
    for old, new in zip(stored, fresh):
        assert (old["family"], old["n"]) == (new["family"], new["n"])
        assert old["links"] == new["links"], (old["family"], old["n"], "links")
        for kind in ["states", "special_states"]:
            assert len(old[kind]) == len(new[kind]) > 0
            for a, b in zip(old[kind], new[kind]):
                for field in a:
                    x, y = numbers(a[field]), numbers(b[field])
                    assert len(x) == len(y), field
                    scale = max([1.0] + [abs(v) for v in x])
                    error = max([0.0] + [abs(u - v) / scale for u, v in zip(x, y)])
                    worst[field] = max(worst.get(field, 0.0), error)
    for field, error in sorted(worst.items()):
        print(f"{field}: largest difference {error:.1e} (relative to max(1, |value|))")
    return all(e <= 1e-15 for e in worst.values())


if __name__ == "__main__":
    if sys.argv[1:2] == ["--check"]:
        sys.exit(0 if check(sys.argv[2]) else 1)
    document = {
        "schema": "chains/1",
        "generator": "scripts/chains_reference.py (Pinocchio Python bindings)",
        "pinocchio_version": pin.__version__,
        "units": "SI: kg, m, s, rad, N m",
        "seed": SEED,
        "notes": "See README_chains.md beside this file for conventions. q are RELATIVE joint angles; M is the full symmetric joint-space inertia; nle = C(q,qd) qd + g(q); f = tau - nle; M qdd = f; T, V kinetic and potential energy. Planar entries also carry the same quantities in absolute link angles (key 'absolute').",
        "models": reference(),
    }
    json.dump(document, sys.stdout, indent=1)
    print()
