"""Pinocchio's control outputs for the Unitree Z1 arm of example-robot-data.

Writes tests/reference/z1_outputs.json, which tests/suite/urdf_outputs.rs reads:
for the arm on a fixed base and on Pinocchio's free flyer, at 3 random
states each, the inverse dynamics and its derivatives
(`computeRNEADerivatives`), the forward dynamics and its derivatives
(`computeABADerivatives`), and, for the frames of the links `link03`,
`link06` and `gripperMover`, their placement, velocity, classical
acceleration and frame jacobian in `LOCAL_WORLD_ALIGNED` axes (the origin's
velocity and the angular velocity in the world's axes, which are the
`position`, `velocity`, `acceleration`, `jacobian`, `rotation`,
`angular_velocity` and `angular_jacobian` outputs of the link's origin point
and frame).

    pip install pin example-robot-data
    python3 scripts/z1_outputs_reference.py
"""

import json
import pathlib
import sys

import numpy as np
import pinocchio as pin

FRAMES = ["link03", "link06", "gripperMover"]


def urdf_path():
    """The URDF the `example-robot-data` wheel installs in this environment."""
    found = pathlib.Path(sys.prefix).glob("lib/python3*/site-packages/cmeel.prefix/share/example-robot-data/robots")
    return str(next(found) / "z1_description/urdf/z1.urdf")


def frame_outputs(model, data, frame):
    world = pin.ReferenceFrame.LOCAL_WORLD_ALIGNED
    fid = model.getFrameId(frame)
    placement = data.oMf[fid]
    velocity = pin.getFrameVelocity(model, data, fid, world)
    jacobian = pin.getFrameJacobian(model, data, fid, world)
    return {
        "position": placement.translation.tolist(),
        "rotation": placement.rotation.tolist(),
        "velocity": velocity.linear.tolist(),
        "angular_velocity": velocity.angular.tolist(),
        "acceleration": pin.getFrameClassicalAcceleration(model, data, fid, world).linear.tolist(),
        "jacobian": jacobian[:3].tolist(),
        "angular_jacobian": jacobian[3:].tolist(),
    }


def state(model, data, rng, floating):
    q = rng.uniform(-np.pi, np.pi, model.nq)
    if floating:
        q[3:7] /= np.linalg.norm(q[3:7])
    v, vdot, tau = (rng.uniform(-2, 2, model.nv) for _ in range(3))
    if floating:
        tau[:6] = 0.0
    out = {"q": q.tolist(), "v": v.tolist(), "vdot": vdot.tolist(), "tau": tau.tolist()}
    out["rnea"] = pin.rnea(model, data, q, v, vdot).tolist()
    dq, dv, da = pin.computeRNEADerivatives(model, data, q, v, vdot)
    out.update(dtau_dq=dq.tolist(), dtau_dv=dv.tolist(), dtau_da=da.tolist())
    out["aba"] = pin.aba(model, data, q, v, tau).tolist()
    dq, dv, dtau = pin.computeABADerivatives(model, data, q, v, tau)
    out.update(ddq_dq=dq.tolist(), ddq_dv=dv.tolist(), ddq_dtau=dtau.tolist())
    pin.forwardKinematics(model, data, q, v, vdot)
    pin.updateFramePlacements(model, data)
    pin.computeJointJacobians(model, data, q)
    out["frames"] = {frame: frame_outputs(model, data, frame) for frame in FRAMES}
    return out


def main():
    rng = np.random.default_rng(7)
    document = {"pinocchio": pin.__version__, "urdf": "example-robot-data z1_description/urdf/z1.urdf"}
    for name, floating in [("fixed", False), ("floating", True)]:
        path = urdf_path()
        model = pin.buildModelFromUrdf(path, pin.JointModelFreeFlyer()) if floating else pin.buildModelFromUrdf(path)
        data = model.createData()
        document[name] = [state(model, data, rng, floating) for _ in range(3)]
    target = pathlib.Path(__file__).resolve().parent.parent / "tests/reference/z1_outputs.json"
    target.write_text(json.dumps(document) + "\n")


if __name__ == "__main__":
    main()
