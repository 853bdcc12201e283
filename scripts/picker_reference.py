#!/usr/bin/env python3
"""Pinocchio's values for `tests/reference/robots/picker.urdf` on a free flyer.

Writes tests/reference/robots/picker.json, which
codegen/tests/suite/urdf_picker.rs reads (see tests/reference/robots/README.md):
at random states, M (crba), f = tau - nle, the kinetic and potential
energies, and the end effector `tool-tip` (a link on a fixed joint):
its frame's placement (oMf after updateFramePlacements) and the linear rows
of its frame jacobian in LOCAL_WORLD_ALIGNED axes (the velocity of its
origin in the world's axes, per speed).

dalembert's `q` is Pinocchio's with each continuous joint's (cos, sin) as
its angle; the free flyer is dalembert's `--floating` (x, y, z, qx, qy, qz,
qw; speeds in the base's axes), so `v` is Pinocchio's.

usage (in a Python environment with `pin` and `numpy`):
    python scripts/picker_reference.py
"""
import json
import os

import numpy as np
import pinocchio as pin

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
URDF = os.path.join(ROOT, "tests", "reference", "robots", "picker.urdf")
OUT = os.path.join(ROOT, "tests", "reference", "robots", "picker.json")
SEED = 20261128
STATES = 4
ORDER = ["root_joint", "Wheel_left", "arm_yaw", "arm_lift", "wrist", "finger", "wheel_right"]


def main():
    model = pin.buildModelFromUrdf(URDF, pin.JointModelFreeFlyer())
    data = model.createData()
    assert list(model.names)[1:] == ORDER, list(model.names)
    tool = model.getFrameId("tool-tip")
    rng = np.random.default_rng(SEED)
    states = []
    for _ in range(STATES):
        angles = []
        q = np.zeros(model.nq)
        for j in range(1, model.njoints):
            joint = model.joints[j]
            i, nq = joint.idx_q, joint.nq
            if j == 1:
                quaternion = rng.normal(size=4)
                q[i:i + 3] = rng.uniform(-1, 1, 3)
                q[i + 3:i + 7] = quaternion / np.linalg.norm(quaternion)
                angles.extend(q[i:i + 7])
            elif nq == 2:
                angle = rng.uniform(-np.pi, np.pi)
                q[i:i + 2] = [np.cos(angle), np.sin(angle)]
                angles.append(angle)
            else:
                q[i] = rng.uniform(model.lowerPositionLimit[i], model.upperPositionLimit[i])
                angles.append(q[i])
        v = rng.uniform(-1, 1, model.nv)
        tau = rng.uniform(-1, 1, model.nv)
        tau[:6] = 0.0
        M = pin.crba(model, data, q)
        M = np.triu(M) + np.triu(M, 1).T
        f = tau - pin.nonLinearEffects(model, data, q, v)
        T = pin.computeKineticEnergy(model, data, q, v)
        V = pin.computePotentialEnergy(model, data, q)
        pin.forwardKinematics(model, data, q, v)
        pin.updateFramePlacements(model, data)
        placement = data.oMf[tool]
        pin.computeJointJacobians(model, data, q)
        J = pin.getFrameJacobian(model, data, tool, pin.LOCAL_WORLD_ALIGNED)
        assert abs(T - 0.5 * v @ M @ v) < 1e-12 * max(1.0, T)
        states.append({
            "q": list(angles),
            "v": list(v),
            "tau": list(tau[6:]),
            "M": M.tolist(),
            "f": f.tolist(),
            "kinetic": T,
            "potential": V,
            "tool_position": placement.translation.tolist(),
            "tool_rotation": placement.rotation.tolist(),
            "tool_jacobian": J[:3, :].tolist(),
        })
    document = {
        "generator": "scripts/picker_reference.py",
        "pinocchio_version": pin.__version__,
        "units": "SI: kg, m, s, rad, N m",
        "seed": SEED,
        "urdf": "picker.urdf",
        "coordinates": ORDER[1:],
        "states": states,
    }
    with open(OUT, "w") as out:
        json.dump(document, out, indent=1)


if __name__ == "__main__":
    main()
