#!/usr/bin/env python3
"""MuJoCo's time per mj_forward on the MJCF models that
generated/benches/robots.rs times (dm_control's cheetah and humanoid), with
contacts, constraints and actuation disabled as in tests/reference/mjcf/, at
1000 random states, one call each, repeated; the best of several rounds, in
nanoseconds per call. mj_forward computes the positions, M and its
factorisation, the bias and passive forces and the accelerations: the
counterpart of `mass_matrix` + `forcing` + the solve, that is of
`dalembert::accelerations` (which runs the articulated-body recursion).

usage (in a Python environment with `mujoco` and `numpy`; run it in the same
quiet window as `cargo bench -p dalembert-generated --bench robots`):
    python scripts/mjcf_timing.py
"""
import os
import time

import mujoco
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MODELS = ["cheetah", "humanoid"]
STATES = 1000
ROUNDS = 7


def main():
    rng = np.random.default_rng(1)
    for name in MODELS:
        path = os.path.join(ROOT, "tests", "reference", "mjcf", "dm_control", name + ".xml")
        m = mujoco.MjModel.from_xml_path(path)
        m.opt.disableflags |= (mujoco.mjtDisableBit.mjDSBL_CONTACT
                               | mujoco.mjtDisableBit.mjDSBL_CONSTRAINT
                               | mujoco.mjtDisableBit.mjDSBL_ACTUATION)
        d = mujoco.MjData(m)
        qpos = np.tile(m.qpos0, (STATES, 1)) + rng.uniform(-0.5, 0.5, size=(STATES, m.nq))
        for j in range(m.njnt):
            if m.jnt_type[j] == mujoco.mjtJoint.mjJNT_FREE:
                a = m.jnt_qposadr[j] + 3
                qpos[:, a:a + 4] /= np.linalg.norm(qpos[:, a:a + 4], axis=1)[:, None]
        qvel = rng.normal(size=(STATES, m.nv))
        qfrc = rng.uniform(-1, 1, size=(STATES, m.nv))
        def per_call(forward):
            """The best time per state over the rounds, in nanoseconds."""
            best = float("inf")
            for _ in range(ROUNDS):
                start = time.perf_counter_ns()
                for i in range(STATES):
                    d.qpos[:] = qpos[i]
                    d.qvel[:] = qvel[i]
                    d.qfrc_applied[:] = qfrc[i]
                    forward()
                best = min(best, (time.perf_counter_ns() - start) / STATES)
            return best

        # Called from Python: the copies' time, measured alone, is subtracted.
        best = per_call(lambda: mujoco.mj_forward(m, d))
        overhead = per_call(lambda: None)
        print(f"{name}: nq {m.nq}, nv {m.nv}: mj_forward {best - overhead:.0f} ns per call "
              f"(the Python loop's {overhead:.0f} ns of copies subtracted; {best:.0f} ns in all)")


if __name__ == "__main__":
    main()
