#!/usr/bin/env python3
"""Pinocchio's values for branching robots and every link's frame.

Writes tests/reference/robots/pinocchio.json, which
codegen/tests/suite/urdf_branching.rs and codegen/tests/suite/urdf_frames.rs read (see
tests/reference/robots/README.md):

* "dynamics": for three branching robots whose siblings are not listed in
  byte order of their joint names (`branches.urdf`, written for the tests,
  on a fixed base; the Unitree A1 quadruped and the simple humanoid of
  example-robot-data on Pinocchio's free flyer), at random states: crba (M,
  full), f = tau - nle, aba (qdd), the kinetic and potential energies, and
  computeABADerivatives (d qdd / d q in the tangent space, d qdd / d v,
  d qdd / d tau).
* "frames": for those three and the UR5 and Panda of tests/reference/urdf/
  (fixed base), at random configurations: every link's frame placement
  (`oMf` of its BODY frame after updateFramePlacements), position and
  rotation.

Pinocchio's own parser builds each model (buildModelFromUrdf, mimic joints
independent: its default). Its `q` and `v` are dalembert's: the order is
checked here against coordinate_order (depth first, children by joint name),
these robots have no continuous joint, and the free flyer is dalembert's
`--floating` (x, y, z, qx, qy, qz, qw; speeds in the base's axes).

usage (in a Python environment with `pin` and `numpy`):
    python scripts/robots_reference.py
"""
import os
import sys

import numpy as np
import pinocchio as pin

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from urdf_reference import ROOT, coordinate_order, self_check, write_document  # noqa: E402

OUT = os.path.join(ROOT, "tests", "reference", "robots", "pinocchio.json")
SEED = 20261128
STATES = 3
FRAME_STATES = 3
# (name, file under tests/reference/, floating base)
DYNAMICS = [
    ("branches", "robots/branches.urdf", False),
    ("a1_floating", "robots/a1.urdf", True),
    ("simple_humanoid_floating", "robots/simple_humanoid_classical.urdf", True),
]
FRAMES = DYNAMICS + [
    ("ur5_robot", "urdf/ur5_robot.urdf", False),
    ("panda", "urdf/panda.urdf", False),
]


def build(file, floating):
    path = os.path.join(ROOT, "tests", "reference", file)
    if floating:
        model = pin.buildModelFromUrdf(path, pin.JointModelFreeFlyer())
    else:
        model = pin.buildModelFromUrdf(path)
    order = coordinate_order(path)
    expected = (["root_joint"] if floating else []) + order
    assert list(model.names)[1:] == expected, (list(model.names), expected)
    assert model.nq == model.nv + (1 if floating else 0), "no continuous joint"
    return model, model.createData()


def random_configuration(model, floating, rng):
    """Joints within their limits (U(-pi, pi) where they have none); a base
    position U(-1, 1)^3 and a unit quaternion."""
    lower = np.where(np.isfinite(model.lowerPositionLimit), model.lowerPositionLimit, -np.pi)
    upper = np.where(np.isfinite(model.upperPositionLimit), model.upperPositionLimit, np.pi)
    q = rng.uniform(np.maximum(lower, -np.pi), np.minimum(upper, np.pi))
    if floating:
        q[:3] = rng.uniform(-1.0, 1.0, 3)
        quaternion = rng.normal(size=4)
        q[3:7] = quaternion / np.linalg.norm(quaternion)
    return q


def floats(a):
    return [float(x) for x in np.ravel(a)]


def rows(m):
    return [floats(row) for row in m]


def dynamics_state(model, data, floating, rng):
    q = random_configuration(model, floating, rng)
    v = rng.uniform(-2.0, 2.0, model.nv)
    tau = rng.uniform(-10.0, 10.0, model.nv)
    if floating:
        tau[:6] = 0.0
    M = pin.crba(model, data, q).copy()
    M = np.triu(M) + np.triu(M, 1).T
    f = tau - pin.nonLinearEffects(model, data, q, v)
    qdd = pin.aba(model, data, q, v, tau).copy()
    T = pin.computeKineticEnergy(model, data, q, v)
    V = pin.computePotentialEnergy(model, data, q)
    self_check(M, v, T, qdd, f)
    dq, dv, dtau = pin.computeABADerivatives(model, data, q, v, tau)
    inputs = slice(6, None) if floating else slice(None)
    return {
        "q": floats(q), "v": floats(v), "tau": floats(tau[inputs]),
        "M": rows(M), "f": floats(f), "qdd": floats(qdd), "T": float(T), "V": float(V),
        "ddq_dq": rows(dq), "ddq_dv": rows(dv), "ddq_dtau": rows(np.asarray(dtau)[:, inputs]),
    }


def links(model):
    """The links: Pinocchio's BODY frames, one per URDF link."""
    return [frame.name for frame in model.frames if frame.type == pin.FrameType.BODY]


def frames_state(model, data, floating, rng):
    q = random_configuration(model, floating, rng)
    pin.framesForwardKinematics(model, data, q)
    placements = {}
    for name in links(model):
        placement = data.oMf[model.getFrameId(name, pin.FrameType.BODY)]
        placements[name] = {
            "position": floats(placement.translation),
            "rotation": rows(placement.rotation),
        }
    return {"q": floats(q), "links": placements}


def main():
    rng = np.random.default_rng(SEED)
    dynamics = []
    for name, file, floating in DYNAMICS:
        model, data = build(file, floating)
        dynamics.append({
            "robot": name, "urdf": file, "floating": floating,
            "nq": model.nq, "nv": model.nv, "coordinates": list(model.names)[1:],
            "states": [dynamics_state(model, data, floating, rng) for _ in range(STATES)],
        })
    frames = []
    for name, file, floating in FRAMES:
        model, data = build(file, floating)
        frames.append({
            "robot": name, "urdf": file, "floating": floating, "links": links(model),
            "states": [frames_state(model, data, floating, rng) for _ in range(FRAME_STATES)],
        })
    write_document(
        OUT,
        "robots/1",
        "scripts/robots_reference.py (Pinocchio Python bindings, its URDF parser)",
        SEED,
        "See README.md beside this file. q and v are Pinocchio's and dalembert's (same order, "
        "no continuous joint); M full symmetric; f = tau - nle; qdd = aba; ddq_* = "
        "computeABADerivatives (d/dq in the tangent space), tau and ddq_dtau without the "
        "free flyer's six; frames: oMf of every link's BODY frame, rotation taking the link's "
        "components to the world's.",
        {"dynamics": dynamics, "frames": frames},
    )


if __name__ == "__main__":
    main()
