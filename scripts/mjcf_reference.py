#!/usr/bin/env python3
"""MuJoCo reference values for the MJCF models of tests/reference/mjcf/.

For each model, MuJoCo's own compiler loads the file; contacts, constraints
(joint limits, friction loss, equality) and actuation are disabled
(m.opt.disableflags) and energies enabled (mjENBL_ENERGY). At random states
with random joint forces (qfrc_applied, zero on free joints) this script
records, after mj_forward:

    M    mj_fullM (armature included)
    f    qfrc_applied - qfrc_bias + qfrc_passive
    qdd  qacc
    T, V energy[1], energy[0]

converted to dalembert's conventions (the schema of
tests/reference/README_chains.md, read by codegen/tests/suite/mjcf_import.rs): a free
joint's qpos (x, y, z, w, x, y, z) becomes (x, y, z, qx, qy, qz, qw), and its
linear velocity, which MuJoCo gives in world axes, is taken in the body's axes,
v_body = R^T v_world. With T the map from our speeds to MuJoCo's (R on each free
joint's linear block, the identity elsewhere), M_ours = T^T M T,
f_ours = T^T (f - M dT/dt v_ours) and qdd_ours = T^-1 (qacc - dT/dt v_ours),
dT/dt v_ours = (R (w x v_body), 0) on a free joint. `tau` holds the forces on the
speeds that are not a free joint's, in speed order (the model's inputs).

usage (in a Python environment with `mujoco` and `numpy`):
    python scripts/mjcf_reference.py [--out tests/reference/mjcf/mujoco.json]
    python scripts/mjcf_reference.py --files features/gravcomp.xml features/free_armature.xml \
        --out tests/reference/mjcf/passive.json
"""
import argparse
import json
import os

import mujoco
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MODELS = os.path.join(ROOT, "tests", "reference", "mjcf")
FILES = [
    "features/features.xml",
    "dm_control/pendulum.xml",
    "dm_control/acrobot.xml",
    "dm_control/cartpole.xml",
    "dm_control/reacher.xml",
    "dm_control/point_mass.xml",
    "dm_control/ball_in_cup.xml",
    "dm_control/cheetah.xml",
    "dm_control/hopper.xml",
    "dm_control/walker.xml",
    "dm_control/humanoid.xml",
    "dm_control/finger.xml",
]
STATES = 4
SEED = 35


def load(path):
    m = mujoco.MjModel.from_xml_path(path)
    m.opt.disableflags |= (mujoco.mjtDisableBit.mjDSBL_CONTACT
                           | mujoco.mjtDisableBit.mjDSBL_CONSTRAINT
                           | mujoco.mjtDisableBit.mjDSBL_ACTUATION)
    m.opt.enableflags |= mujoco.mjtEnableBit.mjENBL_ENERGY
    return m


def random_state(m, rng):
    """qpos, qvel and qfrc_applied (zero on free joints) in MuJoCo's form."""
    qpos = np.zeros(m.nq)
    qvel = rng.normal(size=m.nv)
    tau = rng.uniform(-2, 2, size=m.nv)
    for j in range(m.njnt):
        a, d = m.jnt_qposadr[j], m.jnt_dofadr[j]
        kind = m.jnt_type[j]
        if kind == mujoco.mjtJoint.mjJNT_FREE:
            qpos[a:a + 3] = rng.uniform(-1, 1, size=3)
            quat = rng.normal(size=4)
            qpos[a + 3:a + 7] = quat / np.linalg.norm(quat)
            tau[d:d + 6] = 0.0
        elif kind == mujoco.mjtJoint.mjJNT_BALL:
            quat = rng.normal(size=4)
            qpos[a:a + 4] = quat / np.linalg.norm(quat)
        elif kind == mujoco.mjtJoint.mjJNT_HINGE:
            qpos[a] = rng.uniform(-np.pi, np.pi)
        else:
            qpos[a] = rng.uniform(-0.5, 0.5)
    return qpos, qvel, tau


def entry_state(m, d, qpos, qvel, tau):
    d.qpos[:] = qpos
    d.qvel[:] = qvel
    d.qfrc_applied[:] = tau
    mujoco.mj_forward(m, d)
    full = np.zeros((m.nv, m.nv))
    mujoco.mj_fullM(m, d, full)
    f = d.qfrc_applied - d.qfrc_bias + d.qfrc_passive
    # Our speeds: v_ours = T^-1 qvel; T is R on free joints' linear blocks.
    t = np.eye(m.nv)
    tdot_v = np.zeros(m.nv)
    q_ours = qpos.copy()
    v_ours = qvel.copy()
    inputs = []
    for j in range(m.njnt):
        a, dof = m.jnt_qposadr[j], m.jnt_dofadr[j]
        kind = m.jnt_type[j]
        if kind == mujoco.mjtJoint.mjJNT_FREE:
            w, x, y, z = qpos[a + 3:a + 7]
            q_ours[a + 3:a + 7] = [x, y, z, w]
            r = np.zeros(9)
            mujoco.mju_quat2Mat(r, qpos[a + 3:a + 7])
            r = r.reshape(3, 3)
            t[dof:dof + 3, dof:dof + 3] = r
            v_body = r.T @ qvel[dof:dof + 3]
            omega = qvel[dof + 3:dof + 6]
            v_ours[dof:dof + 3] = v_body
            tdot_v[dof:dof + 3] = r @ np.cross(omega, v_body)
        elif kind == mujoco.mjtJoint.mjJNT_BALL:
            w, x, y, z = qpos[a:a + 4]
            q_ours[a:a + 4] = [x, y, z, w]
            inputs.extend(tau[dof:dof + 3])
        else:
            inputs.append(tau[dof])
    m_ours = t.T @ full @ t
    f_ours = t.T @ (f - full @ tdot_v)
    qdd_ours = np.linalg.solve(t, d.qacc - tdot_v)
    return {
        "q": q_ours.tolist(), "qd": v_ours.tolist(), "tau": inputs,
        "M": m_ours.tolist(), "f": f_ours.tolist(), "qdd": qdd_ours.tolist(),
        "T": float(d.energy[1]), "V": float(d.energy[0]),
    }


def entry(file, rng):
    m = load(os.path.join(MODELS, file))
    d = mujoco.MjData(m)
    states = [entry_state(m, d, *random_state(m, rng)) for _ in range(STATES)]
    names = [m.joint(j).name for j in range(m.njnt)]
    return {"model": os.path.splitext(os.path.basename(file))[0], "file": file,
            "nq": m.nq, "nv": m.nv, "joints": names, "states": states}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--out", default=os.path.join(MODELS, "mujoco.json"))
    parser.add_argument("--files", nargs="+", default=FILES,
                        help="models under tests/reference/mjcf/ (default: the suite's list)")
    args = parser.parse_args()
    rng = np.random.default_rng(SEED)
    out = {
        "source": "MuJoCo %s, scripts/mjcf_reference.py (seed %d, %d states per model)"
                  % (mujoco.__version__, SEED, STATES),
        "models": [entry(file, rng) for file in args.files],
    }
    with open(args.out, "w") as f:
        json.dump(out, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main()
