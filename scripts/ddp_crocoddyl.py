"""The problems of `examples/ddp.rs` posed to Crocoddyl's SolverFDDP.

A UR5 (tests/reference/urdf/ur5_robot.urdf, as Pinocchio reads it) reaching
a joint-space pose, horizon 100 x 10 ms; the same UR5's tool flange `tool0`
reaching a pose (ResidualModelFrameTranslation and ResidualModelFrameRotation
under ActivationModelQuad, with state and control regularisation), 100 x
10 ms, from the torques that hold the start against gravity; and a cart-pole (the model of
generated/models/cart_pole.dal built as a Pinocchio model) swinging up,
150 x 20 ms. Both: IntegratedActionModelEuler (semi-implicit Euler) over
DifferentialActionModelFreeFwdDynamics, running cost
dt * (1/2 |x - x*|^2_Q + 1/2 |u|^2_R), terminal cost 1/2 |x_T - x*|^2_QT,
zero initial inputs rolled out from the start (a feasible guess),
th_stop = 1e-12, one thread.

The cart-pole's actuation (the force on the cart only) is a Python
ActuationModelAbstract: its calls cost Python time at every node, so only
the UR5's time per iteration (all C++) is a fair comparison.

Run in a virtual environment of its own, with libpinocchio 4.0.0: crocoddyl
3.2.1 was built against it, and beside libpinocchio 4.1 (what a plain
`pip install crocoddyl` resolves today) its forward dynamics return garbage
(denormal accelerations) without an error:

    python3 -m venv ~/.cache/crocoddyl-venv
    ~/.cache/crocoddyl-venv/bin/pip install crocoddyl==3.2.1 pin==4.0.0 libpinocchio==4.0.0
    OMP_NUM_THREADS=1 ~/.cache/crocoddyl-venv/bin/python scripts/ddp_crocoddyl.py

Prints one JSON line per problem: final cost, iterations, stopping value,
seconds per iteration (best of 5 solves, CPU time of the thread: the
machine is shared); with `--inputs DIR`, first the cost
in Crocoddyl's problem of the inputs `DIR/ddp_NAME_inputs.json` that
`lab/examples/ddp.rs` writes (the same problem gives the same cost).
"""

import json
import os
import sys
import time

import crocoddyl
import numpy as np
import pinocchio as pin

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
REPEATS = 5
# `--inputs DIR`: also cost the inputs `DIR/ddp_NAME_inputs.json`.
INPUTS = sys.argv[sys.argv.index("--inputs") + 1] if "--inputs" in sys.argv else None


def quadratic(state, nu, xref, state_weights, input_weights, pose=None):
    """The cost 1/2 |x - x*|^2_Q (+ 1/2 |u|^2_R when input_weights), plus
    with `pose = (frame, (p*, R*), (w_p, w_R))` the frame's pose error
    1/2 w_p |p - p*|^2 + 1/2 w_R |log3(R*^T R)|^2."""
    costs = crocoddyl.CostModelSum(state, nu)
    if pose is not None:
        frame, (position, rotation), (wp, wr) = pose
        for name, residual, weight in (
            ("translation", crocoddyl.ResidualModelFrameTranslation(state, frame, position, nu), wp),
            ("rotation", crocoddyl.ResidualModelFrameRotation(state, frame, rotation, nu), wr),
        ):
            costs.addCost(
                name,
                crocoddyl.CostModelResidual(state, crocoddyl.ActivationModelQuad(3), residual),
                weight,
            )
    costs.addCost(
        "state",
        crocoddyl.CostModelResidual(
            state,
            crocoddyl.ActivationModelWeightedQuad(np.array(state_weights, dtype=float)),
            crocoddyl.ResidualModelState(state, xref, nu),
        ),
        1.0,
    )
    if input_weights is not None:
        costs.addCost(
            "input",
            crocoddyl.CostModelResidual(
                state,
                crocoddyl.ActivationModelWeightedQuad(np.array(input_weights, dtype=float)),
                crocoddyl.ResidualModelControl(state, nu),
            ),
            1.0,
        )
    return costs


def problem(state, actuation, start, target, horizon, dt, weights, pose=None):
    """With `pose = (frame, (p*, R*), running (w_p, w_R), terminal (w_p, w_R))`
    the frame's pose error costs too."""
    running_weights, input_weights, terminal_weights = weights
    running_pose, terminal_pose = (None, None) if pose is None else (pose[:3], pose[:2] + pose[3:])
    running = crocoddyl.IntegratedActionModelEuler(
        crocoddyl.DifferentialActionModelFreeFwdDynamics(
            state,
            actuation,
            quadratic(state, actuation.nu, target, running_weights, input_weights, running_pose),
        ),
        dt,
    )
    terminal = crocoddyl.IntegratedActionModelEuler(
        crocoddyl.DifferentialActionModelFreeFwdDynamics(
            state,
            actuation,
            quadratic(state, actuation.nu, target, terminal_weights, None, terminal_pose),
        ),
        0.0,
    )
    shooting = crocoddyl.ShootingProblem(start, [running] * horizon, terminal)
    shooting.nthreads = 1
    return shooting


def cost_of(name, shooting, path):
    """The cost in this problem of the inputs in `path` (dalembert's
    optimum, written by the example), rolled out by Crocoddyl."""
    us = [np.array(u, dtype=float) for u in json.load(open(path))]
    xs = shooting.rollout(us)
    print(json.dumps({"costed": name, "inputs": path, "cost": shooting.calc(xs, us)}))


def solve(name, shooting, nu, guess=None):
    """Solves from the inputs `guess` (zero when None) rolled out."""
    best, solver = float("inf"), None
    for _ in range(REPEATS):
        solver = crocoddyl.SolverFDDP(shooting)
        solver.th_stop = 1e-12
        us = [np.zeros(nu) if guess is None else guess.copy() for _ in range(shooting.T)]
        xs = shooting.rollout(us)
        began = time.thread_time()
        solver.solve(xs, us, 500, True, 1e-9)
        seconds = (time.thread_time() - began) / max(solver.iter, 1)
        best = min(best, seconds)
    if INPUTS:
        cost_of(name, shooting, os.path.join(INPUTS, f"ddp_{name}_inputs.json"))
    print(
        json.dumps(
            {
                "solver": "crocoddyl",
                "problem": name,
                "cost": solver.cost,
                "iterations": solver.iter,
                "stop": solver.stop,
                "seconds_per_iteration": best,
            }
        )
    )
    sys.stdout.flush()
    return solver


def ur5():
    model = pin.buildModelFromUrdf(os.path.join(ROOT, "tests/reference/urdf/ur5_robot.urdf"))
    state = crocoddyl.StateMultibody(model)
    actuation = crocoddyl.ActuationModelFull(state)
    start = np.array([0.0, -1.5, 1.0, -1.0, 0.0, 0.0] + [0.0] * 6)
    target = np.array([1.0, -1.0, 1.5, -1.5, 0.8, 0.5] + [0.0] * 6)
    weights = ([1.0] * 6 + [0.1] * 6, [1e-3] * 6, [1e3] * 6 + [10.0] * 6)
    return solve("ur5", problem(state, actuation, start, target, 100, 0.01, weights), 6)


# The UR5's tool flange `tool0` at (1, -1, 1.5, -1.5, 0.8, 0.5), as Pinocchio
# 4.0 computes it, to 17 digits (lab/src/ddp.rs's UR5_TOOL_TARGET).
TOOL_TARGET = (
    np.array([0.23022976075720533, 0.6667019958705028, 0.2572689936541279]),
    np.array(
        [
            [-0.9261982387312231, -0.01208504409715379, -0.3768431693428319],
            [-0.27730725263608436, -0.6553517176574692, 0.7025772653586448],
            [-0.25545549554982644, 0.7552271697129115, 0.6036343362672622],
        ]
    ),
)


def ur5_pose():
    """The UR5's tool reaching TOOL_TARGET (lab/src/ddp.rs's ur5_pose_reach):
    the state drawn to the start's posture at rest, the speeds to zero at the
    end, the frame's translation and rotation errors weighted (100, 10) per
    second and (1e4, 1e3) at the end; from the torques holding the start
    against gravity."""
    model = pin.buildModelFromUrdf(os.path.join(ROOT, "tests/reference/urdf/ur5_robot.urdf"))
    state = crocoddyl.StateMultibody(model)
    actuation = crocoddyl.ActuationModelFull(state)
    q0 = np.array([0.0, -1.5, 1.0, -1.0, 0.0, 0.0])
    start = np.concatenate([q0, np.zeros(6)])
    weights = ([1e-2] * 6 + [0.1] * 6, [1e-3] * 6, [0.0] * 6 + [10.0] * 6)
    pose = (model.getFrameId("tool0"), TOOL_TARGET, (100.0, 10.0), (1e4, 1e3))
    hold = pin.rnea(model, model.createData(), q0, np.zeros(6), np.zeros(6))
    shooting = problem(state, actuation, start, start, 100, 0.01, weights, pose)
    return solve("ur5_pose", shooting, 6, hold)


class CartActuation(crocoddyl.ActuationModelAbstract):
    """The force on the cart only: tau = (u, 0)."""

    def __init__(self, state):
        crocoddyl.ActuationModelAbstract.__init__(self, state, 1)

    def calc(self, data, x, u):
        data.tau[0] = u[0]
        data.tau[1] = 0.0

    def calcDiff(self, data, x, u):
        data.dtau_du = np.array([[1.0], [0.0]])

    def commands(self, data, x, tau):
        data.u[0] = tau[0]

    def torqueTransform(self, data, x, tau):
        data.Mtau = np.array([[1.0, 0.0]])


def cart_pole():
    m_c, m_p, l, g = 1.0, 0.3, 0.5, 9.81
    model = pin.Model()
    model.gravity.linear = np.array([0.0, -g, 0.0])
    slide = model.addJoint(0, pin.JointModelPX(), pin.SE3.Identity(), "x")
    model.appendBodyToJoint(slide, pin.Inertia(m_c, np.zeros(3), np.zeros((3, 3))), pin.SE3.Identity())
    hinge = model.addJoint(slide, pin.JointModelRZ(), pin.SE3.Identity(), "theta")
    rod = np.diag([m_p * l * l / 3.0, 0.0, m_p * l * l / 3.0])
    model.appendBodyToJoint(hinge, pin.Inertia(m_p, np.array([0.0, l, 0.0]), rod), pin.SE3.Identity())
    state = crocoddyl.StateMultibody(model)
    actuation = CartActuation(state)
    start = np.array([0.0, np.pi, 0.0, 0.0])
    target = np.zeros(4)
    weights = ([0.1, 0.1, 0.01, 0.01], [0.01], [100.0, 100.0, 10.0, 10.0])
    return solve("cart_pole", problem(state, actuation, start, target, 150, 0.02, weights), 1)


if __name__ == "__main__":
    ur5()
    ur5_pose()
    cart_pole()
