#!/usr/bin/env python3
"""Pinocchio's frame jacobians of a link of four robots of tests/reference/,
for codegen/tests/suite/urdf_jacobians.rs: the outputs `position(L_origin)`,
`jacobian(L_origin)` and `angular_jacobian(L)` of the models `dalembert urdf
[--floating] --outputs ...` writes.

For each robot, at random configurations (joints U(-1.2, 1.2), on a free
flyer a position U(-1, 1)^3 and a random unit quaternion): `oMf` of the
link's BODY frame (its translation) and `getFrameJacobian` in
LOCAL_WORLD_ALIGNED (rows 0-2: the origin's velocity in the world's axes,
rows 3-5: the angular velocity in the world's axes, per speed; the free
flyer's speeds are in the base's axes, as dalembert's). The robots have no
continuous joint, so q is Pinocchio's and dalembert's alike.

usage (in a Python environment with `pin` and `numpy`):
    python scripts/urdf_jacobians_reference.py   # writes tests/reference/robots/jacobians.json
"""
import json
import os

import numpy as np
import pinocchio as pin

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
REFERENCE = os.path.join(ROOT, "tests", "reference")
OUT = os.path.join(REFERENCE, "robots", "jacobians.json")
SEED = 20261128
STATES = 3
# (file under tests/reference/, floating base, link)
CASES = [
    ("robots/a1.urdf", True, "FL_foot"),
    ("urdf/solo12.urdf", True, "HR_FOOT"),
    ("urdf/ur5_robot.urdf", False, "tool0"),
    ("urdf/panda.urdf", False, "panda_hand"),
]


def state(model, data, floating, link, rng):
    q = pin.neutral(model)
    start = 7 if floating else 0
    if floating:
        q[:3] = rng.uniform(-1.0, 1.0, 3)
        quaternion = rng.normal(size=4)
        q[3:7] = quaternion / np.linalg.norm(quaternion)
    q[start:] = rng.uniform(-1.2, 1.2, model.nq - start)
    pin.computeJointJacobians(model, data, q)
    pin.framesForwardKinematics(model, data, q)
    frame = model.getFrameId(link, pin.FrameType.BODY)
    jacobian = pin.getFrameJacobian(model, data, frame, pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)
    return {
        "q": [float(x) for x in q],
        "position": [float(x) for x in data.oMf[frame].translation],
        "jacobian": [[float(x) for x in row] for row in jacobian[:3]],
        "angular_jacobian": [[float(x) for x in row] for row in jacobian[3:]],
    }


def main():
    rng = np.random.default_rng(SEED)
    robots = []
    for file, floating, link in CASES:
        path = os.path.join(REFERENCE, file)
        model = (pin.buildModelFromUrdf(path, pin.JointModelFreeFlyer()) if floating
                 else pin.buildModelFromUrdf(path))
        assert model.nq == model.nv + (1 if floating else 0), "no continuous joint"
        data = model.createData()
        robots.append({
            "urdf": file, "floating": floating, "link": link, "nv": model.nv,
            "states": [state(model, data, floating, link, rng) for _ in range(STATES)],
        })
    document = {
        "generator": "scripts/urdf_jacobians_reference.py, Pinocchio %s (its URDF parser)"
                     % pin.__version__,
        "seed": SEED,
        "robots": robots,
    }
    with open(OUT, "w") as f:
        json.dump(document, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main()
