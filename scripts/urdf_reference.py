#!/usr/bin/env python3
"""Pinocchio reference values for the URDF robots of tests/reference/urdf/.

For each robot, Pinocchio's own URDF parser builds the model (fixed base, mimic
joints independent: Pinocchio's defaults), and at random states this script
records crba (the full symmetric M), nle, the generalized gravity, f = tau - nle,
aba with random torques, and the kinetic and potential energies, in the schema
of tests/reference/README_chains.md (see tests/reference/urdf/README.md).

Coordinates are written in dalembert's order, which is Pinocchio's
(depth-first from the root link, the child joints of a link in ascending byte
order of their names, as urdfdom's std::map keeps them), computed here from
the XML, checked against Pinocchio's `model.names`, and matched to
Pinocchio's joints by name.
Continuous joints, which Pinocchio stores as (cos, sin) in q, are written as
one angle.

With --floating the robots of FLOATING are also written on Pinocchio's free
flyer (pinocchio.JointModelFreeFlyer) as "<robot>_floating": q starts with the
base position and unit quaternion (x, y, z, qx, qy, qz, qw), v with the base's
linear and angular velocity in its own axes (dalembert's `--floating`
convention); `tau` holds the joint torques only (the base has no input) and f,
M, qdd cover every speed.

usage (in a Python environment with `pin` and `numpy`):
    python scripts/urdf_reference.py [--out tests/reference/urdf/pinocchio.json]
"""
import argparse
import json
import math
import os
import xml.etree.ElementTree as ET

import numpy as np
import pinocchio as pin

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ROBOTS = os.path.join(ROOT, "tests", "reference", "urdf")
FILES = ["panda.urdf", "ur5_robot.urdf", "solo12.urdf", "features.urdf"]
FLOATING = ["solo12.urdf"]
# Added later, drawn after all of the above (fixed base, then floating), so
# that the states above do not change.
ADDED = ["anymal_c.urdf"]
# Added later still, drawn last: the double pendulum, whose products of
# inertia of 1e-13 beside moments of 1e-3 the import once wrote as zero.
ADDED_LATER = ["regressions/double_pendulum.urdf"]
FREE = ["root_joint_" + c for c in ["x", "y", "z", "qx", "qy", "qz", "qw"]]
STATES = 10
SEED = 20261123


def coordinate_order(path):
    """Names of the non-fixed joints, depth-first from the root link, the
    children of a link sorted by joint name (byte order, as urdfdom's
    std::map<std::string, ...>), whatever their order in the file."""
    robot = ET.parse(path).getroot()
    joints = [
        (j.get("name"), j.get("type"), j.find("parent").get("link"), j.find("child").get("link"))
        for j in robot.findall("joint")
    ]
    children = {j[3] for j in joints}
    roots = [l.get("name") for l in robot.findall("link") if l.get("name") not in children]
    assert len(roots) == 1, roots
    order = []

    by_name = sorted(joints, key=lambda joint: joint[0].encode())

    def visit(link):
        for name, kind, parent, child in by_name:
            if parent == link:
                if kind != "fixed":
                    order.append(name)
                visit(child)

    visit(roots[0])
    return order


def set_angles(model, q, order, angles):
    """Writes the joints' angles (or displacements) into Pinocchio's `q`, a
    continuous joint's as (cos, sin); returns the joints' indices in v."""
    idx_v = []
    for name, angle in zip(order, angles):
        joint = model.joints[model.getJointId(name)]
        if joint.nq == 2:  # continuous: (cos, sin)
            q[joint.idx_q] = math.cos(angle)
            q[joint.idx_q + 1] = math.sin(angle)
        else:
            q[joint.idx_q] = angle
        idx_v.append(joint.idx_v)
    return idx_v


def self_check(M, v, T, qdd, f):
    """Pinocchio's algorithms agree with each other at a state: T = 1/2 v^T M v
    (1e-12 relative) and M qdd = f (1e-9 of the larger of |f| and |M| |qdd|,
    so that an ill-conditioned M, whose qdd is large, passes and a singular
    one, whose qdd is garbage, does not)."""
    if len(v) == 0:
        raise ValueError("nothing moves: Pinocchio's model has nv = 0")
    if abs(T - 0.5 * v @ M @ v) > 1e-12 * max(1.0, abs(T)):
        raise ValueError(f"T = {T} but 1/2 v^T M v = {0.5 * v @ M @ v}")
    scale = max(np.abs(f).max(), np.abs(M).max() * np.abs(qdd).max())
    residual = np.abs(M @ qdd - f).max()
    if not residual <= 1e-9 * scale:
        raise ValueError(f"M qdd - f = {residual:.3e} (cond M = {np.linalg.cond(M):.3e})")


def state_values(model, data, order, q_angles, v, tau):
    """Pinocchio's quantities at one state, permuted into `order`."""
    q = pin.neutral(model)
    perm = np.array(set_angles(model, q, order, q_angles), dtype=int)
    vp = np.zeros(model.nv)
    taup = np.zeros(model.nv)
    vp[perm] = v
    taup[perm] = tau

    M = pin.crba(model, data, q).copy()
    M = np.triu(M) + np.triu(M, 1).T
    nle = pin.nonLinearEffects(model, data, q, vp).copy()
    g = pin.computeGeneralizedGravity(model, data, q).copy()
    qdd = pin.aba(model, data, q, vp, taup).copy()
    T = pin.computeKineticEnergy(model, data, q, vp)
    V = pin.computePotentialEnergy(model, data, q)

    M = M[np.ix_(perm, perm)]
    nle, g, qdd = nle[perm], g[perm], qdd[perm]
    f = np.asarray(tau) - nle
    # Self-checks: T = 1/2 v^T M v, M qdd = f.
    self_check(M, v, T, qdd, f)
    floats = lambda a: [float(x) for x in a]
    return {
        "q": floats(q_angles), "qd": floats(v), "tau": floats(tau),
        "M": [floats(row) for row in M], "nle": floats(nle), "gravity_torque": floats(g),
        "coriolis_times_qd": floats(nle - g), "f": floats(f), "qdd": floats(qdd),
        "T": float(T), "V": float(V),
    }


def robot_entry(file, rng):
    path = os.path.join(ROBOTS, file)
    model = pin.buildModelFromUrdf(path)
    data = model.createData()
    order = coordinate_order(path)
    assert order == list(model.names)[1:], (order, list(model.names))
    kinds, lower, upper = [], [], []
    for name in order:
        joint = model.joints[model.getJointId(name)]
        kinds.append(joint.shortname())
        lo = model.lowerPositionLimit[joint.idx_q]
        hi = model.upperPositionLimit[joint.idx_q]
        finite = joint.nq == 1 and np.isfinite(lo) and np.isfinite(hi) and hi > lo
        lower.append(lo if finite else -math.pi)
        upper.append(hi if finite else math.pi)
    states = []
    for _ in range(STATES):
        q = rng.uniform(lower, upper)
        v = rng.uniform(-2.0, 2.0, model.nv)
        tau = rng.uniform(-10.0, 10.0, model.nv)
        states.append(state_values(model, data, order, q, v, tau))
    return {
        "robot": os.path.splitext(file)[0], "urdf": file, "name": model.name,
        "nq": model.nv, "nv": model.nv, "gravity": [float(x) for x in model.gravity.linear],
        "coordinates": order, "pinocchio_order": list(model.names)[1:],
        "pinocchio_joint_kinds": kinds, "states": states,
    }


def write_document(path, schema, generator, seed, notes, models):
    """Writes a reference document: its header (Pinocchio's version, the units) and models."""
    document = {
        "schema": schema,
        "generator": generator,
        "pinocchio_version": pin.__version__,
        "units": "SI: kg, m, s, rad, N m",
        "seed": seed,
        "notes": notes,
        "models": models,
    }
    with open(path, "w") as out:
        json.dump(document, out, indent=1)
        out.write("\n")
    print(f"wrote {path}")


def floating_state(model, data, order, rng):
    """Pinocchio's quantities at one random state of the free-flyer model, in
    dalembert's order: the base first, then the joints of `order`."""
    q = pin.neutral(model)
    q[:3] = rng.uniform(-1.0, 1.0, 3)
    quaternion = rng.normal(size=4)
    q[3:7] = quaternion / np.linalg.norm(quaternion)
    angles = rng.uniform(-math.pi, math.pi, len(order))
    perm = np.array(list(range(6)) + set_angles(model, q, order, angles))
    v = rng.uniform(-2.0, 2.0, model.nv)
    tau_joints = rng.uniform(-10.0, 10.0, len(order))
    vp = np.zeros(model.nv)
    vp[perm] = v
    taup = np.zeros(model.nv)
    taup[perm[6:]] = tau_joints
    M = pin.crba(model, data, q).copy()
    M = np.triu(M) + np.triu(M, 1).T
    nle = pin.nonLinearEffects(model, data, q, vp).copy()
    qdd = pin.aba(model, data, q, vp, taup).copy()
    T = pin.computeKineticEnergy(model, data, q, vp)
    V = pin.computePotentialEnergy(model, data, q)
    M = M[np.ix_(perm, perm)]
    nle, qdd, tau = nle[perm], qdd[perm], taup[perm]
    f = tau - nle
    self_check(M, v, T, qdd, f)
    floats = lambda a: [float(x) for x in a]
    return {
        "q": floats(list(q[:7]) + list(angles)), "qd": floats(v), "tau": floats(tau_joints),
        "M": [floats(row) for row in M], "nle": floats(nle), "f": floats(f),
        "qdd": floats(qdd), "T": float(T), "V": float(V),
    }


def floating_entry(file, rng):
    path = os.path.join(ROBOTS, file)
    model = pin.buildModelFromUrdf(path, pin.JointModelFreeFlyer())
    data = model.createData()
    order = coordinate_order(path)
    assert ["root_joint"] + order == list(model.names)[1:], (order, list(model.names))
    return {
        "robot": os.path.splitext(file)[0] + "_floating", "urdf": file, "name": model.name,
        # dalembert's nq: the base's 7, then one angle per joint (continuous too).
        "nq": len(FREE) + len(order), "nv": model.nv,
        "gravity": [float(x) for x in model.gravity.linear],
        "coordinates": FREE + order, "pinocchio_order": list(model.names)[1:],
        "states": [floating_state(model, data, order, rng) for _ in range(STATES)],
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=os.path.join(ROBOTS, "pinocchio.json"))
    parser.add_argument("--floating", action="store_true",
                        help="also write the FLOATING robots on a free flyer")
    args = parser.parse_args()
    rng = np.random.default_rng(SEED)
    write_document(
        args.out,
        "urdf/1 (states as chains/1)",
        "scripts/urdf_reference.py (Pinocchio Python bindings, its URDF parser)",
        SEED,
        "See README.md beside this file. q in dalembert's coordinate order "
        "(`coordinates`); continuous joints as one angle; fixed base; mimic joints "
        "independent; M full symmetric; nle = C(q,qd) qd + g(q); f = tau - nle; "
        "M qdd = f; V leaves out the masses fixed to the ground.",
        [robot_entry(file, rng) for file in FILES]
        # Drawn after the fixed-base states, which therefore do not change.
        + ([floating_entry(file, rng) for file in FLOATING] if args.floating else [])
        + added_entries(ADDED, rng, args.floating)
        + added_entries(ADDED_LATER, rng, args.floating),
    )


def added_entries(files, rng, floating):
    """The entries of robots added later: fixed base, then (with --floating)
    floating, drawn after everything before them."""
    return [robot_entry(file, rng) for file in files] + (
        [floating_entry(file, rng) for file in files] if floating else []
    )


if __name__ == "__main__":
    main()
