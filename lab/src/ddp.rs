//! Differential dynamic programming over the exact step derivatives of
//! `dalembert::control`: the quadratic problems of the DDP example,
//! written to match Crocoddyl's `SolverFDDP` on a feasible start.
//!
//! The problem: a start `x₀`, a horizon of `T` steps of length `h`
//! (semi-implicit Euler, or any step with its jacobian), the running cost
//! `h (½ ‖x ⊖ x*‖²_Q + ½ ‖u‖²_R)` (Crocoddyl's `IntegratedActionModelEuler`
//! scales the running cost by the step) and the terminal cost
//! `½ ‖x_T ⊖ x*‖²_{Q_T}`, with diagonal weights ([`Problem`]), and a frame
//! reaching a pose, with the pose error's costs added ([`PoseProblem`]);
//! any other [`Objective`] will do. The configuration space must
//! be a vector space (the cost's derivatives by `q` are then plain).
//!
//! The solver is DDP with the Gauss–Newton model of the dynamics (iLQR;
//! the quadratic costs' Hessians are exact, the pose error's Gauss–Newton's
//! as Crocoddyl's): a backward pass of the Riccati recursion with
//! `μ I` added to `Q_uu` and the value function updated as Crocoddyl's
//! `computeValueFunction` updates it, a forward pass of the feedback policy from
//! `x₀` with a backtracking line search (`α = 1, ½, ¼, …`, accepted when
//! the cost falls by at least a tenth of the expected improvement), `μ`
//! divided by 10 after a full step and multiplied by 10 after a
//! failure, as Crocoddyl's defaults do. It stops when
//! `Σₖ ‖Q_uₖ‖² < threshold` (Crocoddyl's `stoppingCriteria` and `th_stop`).

use crate::pose::{FrameOutputs, Placement};
use dalembert::State;
use dalembert::control::{ControlError, Differentiable, StepJacobian};
use nalgebra::{SMatrix, SVector};

/// A step with its jacobian: `euler_step_jacobian` or `rk4_step_jacobian`.
pub type StepWithJacobian<S, const NQ: usize, const NV: usize, const NU: usize> =
    fn(
        &S,
        &State<NQ, NV>,
        &[f64; NU],
        f64,
    ) -> Result<(State<NQ, NV>, StepJacobian<NV, NU>), ControlError>;

/// A step: `euler_step` or `rk4_group_step`.
pub type Step<S, const NQ: usize, const NV: usize, const NU: usize> =
    fn(&S, &State<NQ, NV>, &[f64; NU], f64) -> Result<State<NQ, NV>, ControlError>;

/// A reaching problem with quadratic costs (see the module's docs).
#[derive(Clone, Debug)]
pub struct Problem<const NQ: usize, const NV: usize, const NU: usize> {
    /// The start `x₀`.
    pub start: State<NQ, NV>,
    /// The target configuration and speeds `x*`.
    pub target: ([f64; NQ], [f64; NV]),
    /// Steps `T`.
    pub horizon: usize,
    /// Step length `h`.
    pub step: f64,
    /// Diagonal of `Q` on `(q, v)`: `NV` weights of the coordinates, then
    /// `NV` of the speeds.
    pub state_weights: ([f64; NV], [f64; NV]),
    /// Diagonal of `R`.
    pub input_weights: [f64; NU],
    /// Diagonal of `Q_T`.
    pub terminal_weights: ([f64; NV], [f64; NV]),
}

/// The UR5 reaching a joint-space pose: from `(0, −1.5, 1, −1, 0, 0)` at
/// rest to `(1, −1, 1.5, −1.5, 0.8, 0.5)` at rest in 100 steps of 10 ms
/// (`scripts/ddp_crocoddyl.py` writes the same numbers).
pub fn ur5_reach() -> Problem<6, 6, 6> {
    Problem {
        start: State {
            t: 0.0,
            q: [0.0, -1.5, 1.0, -1.0, 0.0, 0.0],
            v: [0.0; 6],
        },
        target: ([1.0, -1.0, 1.5, -1.5, 0.8, 0.5], [0.0; 6]),
        horizon: 100,
        step: 0.01,
        state_weights: ([1.0; 6], [0.1; 6]),
        input_weights: [1e-3; 6],
        terminal_weights: ([1e3; 6], [10.0; 6]),
    }
}

/// The cart-pole swing-up (`dalembert_fixtures::cart_pole`'s): from hanging
/// at rest to upright at rest in 150 steps of 20 ms (`scripts/ddp_crocoddyl.py`
/// writes the same numbers).
pub fn cart_pole_swing_up() -> Problem<2, 2, 1> {
    Problem {
        start: State {
            t: 0.0,
            q: [0.0, std::f64::consts::PI],
            v: [0.0; 2],
        },
        target: ([0.0; 2], [0.0; 2]),
        horizon: 150,
        step: 0.02,
        state_weights: ([0.1, 0.1], [0.01, 0.01]),
        input_weights: [0.01],
        terminal_weights: ([100.0, 100.0], [10.0, 10.0]),
    }
}

/// What a solve did.
#[derive(Clone, Debug)]
pub struct Solve<const NQ: usize, const NV: usize, const NU: usize> {
    /// The states `x₀ … x_T`.
    pub states: Vec<State<NQ, NV>>,
    /// The inputs `u₀ … u_{T−1}`.
    pub inputs: Vec<[f64; NU]>,
    /// The cost of each iterate, the initial guess first.
    pub costs: Vec<f64>,
    /// `Σ ‖Q_u‖²` at the last backward pass.
    pub stop: f64,
    /// Iterations taken (backward passes with a forward pass after them).
    pub iterations: usize,
}

/// The DDP solver's settings.
#[derive(Clone, Copy, Debug)]
pub struct Settings {
    /// Stop when `Σ ‖Q_u‖²` is below this.
    pub threshold: f64,
    /// Most iterations.
    pub max_iterations: usize,
    /// The first regularisation `μ`, and its floor and ceiling.
    pub regularisation: (f64, f64, f64),
}

impl Default for Settings {
    fn default() -> Self {
        Self {
            threshold: 1e-12,
            max_iterations: 500,
            regularisation: (1e-9, 1e-9, 1e9),
        }
    }
}

/// The derivatives of a cost at one node: gradients and Gauss–Newton
/// Hessians on the state `(q, v)` stacked in `NX = 2 NV` entries and on the
/// inputs (the costs here have no cross term `l_xu`).
#[derive(Clone, Copy, Debug)]
pub struct Expansion<const NX: usize, const NU: usize> {
    /// `∂l/∂x`.
    pub lx: SVector<f64, NX>,
    /// `∂l/∂u`.
    pub lu: SVector<f64, NU>,
    /// `∂²l/∂x²` (Gauss–Newton).
    pub lxx: SMatrix<f64, NX, NX>,
    /// `∂²l/∂u²`.
    pub luu: SMatrix<f64, NU, NU>,
}

/// What the solver asks of a problem: its start, horizon and step (a
/// [`Problem`]'s), its running cost per step (scaled by the step, as
/// Crocoddyl's `IntegratedActionModelEuler` scales it) and its terminal
/// cost, with their derivatives.
pub trait Objective<const NQ: usize, const NV: usize, const NU: usize> {
    /// The start, horizon and step (and the quadratic costs).
    fn problem(&self) -> &Problem<NQ, NV, NU>;

    /// The running cost of one step from `x` under `u`.
    fn running(&self, x: &State<NQ, NV>, u: &[f64; NU]) -> f64;

    /// The terminal cost at `x`.
    fn terminal(&self, x: &State<NQ, NV>) -> f64;

    /// The running cost's derivatives; `NX` is `2 NV`.
    fn running_derivatives<const NX: usize>(
        &self,
        x: &State<NQ, NV>,
        u: &[f64; NU],
    ) -> Expansion<NX, NU>;

    /// The terminal cost's derivatives (`lu`, `luu` zero); `NX` is `2 NV`.
    fn terminal_derivatives<const NX: usize>(&self, x: &State<NQ, NV>) -> Expansion<NX, NU>;

    /// The total cost of a trajectory.
    fn cost(&self, states: &[State<NQ, NV>], inputs: &[[f64; NU]]) -> f64 {
        let running: f64 = states
            .iter()
            .zip(inputs)
            .map(|(x, u)| self.running(x, u))
            .sum();
        running + self.terminal(&states[self.problem().horizon])
    }
}

impl<const NQ: usize, const NV: usize, const NU: usize> Problem<NQ, NV, NU> {
    /// `x ⊖ x*` on a vector space.
    fn error(&self, x: &State<NQ, NV>) -> ([f64; NV], [f64; NV]) {
        (
            std::array::from_fn(|i| x.q[i] - self.target.0[i]),
            std::array::from_fn(|i| x.v[i] - self.target.1[i]),
        )
    }

    /// `½ ‖x ⊖ x*‖²_W`.
    fn state_cost(&self, x: &State<NQ, NV>, (wq, wv): &([f64; NV], [f64; NV])) -> f64 {
        let (dq, dv) = self.error(x);
        0.5 * (0..NV)
            .map(|i| wq[i] * dq[i] * dq[i] + wv[i] * dv[i] * dv[i])
            .sum::<f64>()
    }

    /// The derivatives of `s ½ ‖x ⊖ x*‖²_W (+ s ½ ‖u‖²_R with `u`)`.
    fn quadratic<const NX: usize>(
        &self,
        x: &State<NQ, NV>,
        (wq, wv): &([f64; NV], [f64; NV]),
        u: Option<&[f64; NU]>,
        s: f64,
    ) -> Expansion<NX, NU> {
        let (dq, dv) = self.error(x);
        let weight = |i: usize| match i < NV {
            true => s * wq[i],
            false => s * wv[i - NV],
        };
        let r = SVector::<f64, NU>::from(self.input_weights) * s;
        let (lu, luu) = match u {
            Some(u) => (
                r.component_mul(&SVector::from(*u)),
                SMatrix::from_diagonal(&r),
            ),
            None => (SVector::zeros(), SMatrix::zeros()),
        };
        Expansion {
            lx: SVector::from_fn(|i, _| match i < NV {
                true => weight(i) * dq[i],
                false => weight(i) * dv[i - NV],
            }),
            lu,
            lxx: SMatrix::from_diagonal(&SVector::<f64, NX>::from_fn(|i, _| weight(i))),
            luu,
        }
    }
}

impl<const NQ: usize, const NV: usize, const NU: usize> Objective<NQ, NV, NU>
    for Problem<NQ, NV, NU>
{
    fn problem(&self) -> &Problem<NQ, NV, NU> {
        self
    }

    fn running(&self, x: &State<NQ, NV>, u: &[f64; NU]) -> f64 {
        let inputs = 0.5
            * (0..NU)
                .map(|i| self.input_weights[i] * u[i] * u[i])
                .sum::<f64>();
        self.step * (self.state_cost(x, &self.state_weights) + inputs)
    }

    fn terminal(&self, x: &State<NQ, NV>) -> f64 {
        self.state_cost(x, &self.terminal_weights)
    }

    fn running_derivatives<const NX: usize>(
        &self,
        x: &State<NQ, NV>,
        u: &[f64; NU],
    ) -> Expansion<NX, NU> {
        self.quadratic(x, &self.state_weights, Some(u), self.step)
    }

    fn terminal_derivatives<const NX: usize>(&self, x: &State<NQ, NV>) -> Expansion<NX, NU> {
        self.quadratic(x, &self.terminal_weights, None, 1.0)
    }
}

/// A frame reaching a pose: the quadratic costs of `regularisation` (its
/// `target` the posture the state is drawn to) plus, at every step and at
/// the end, `½ w_p ‖p − p*‖² + ½ w_R ‖log₃(R*ᵀ R)‖²` of the frame's pose
/// error ([`crate::pose`]), the running part scaled by the step as the
/// rest: Crocoddyl's `ResidualModelFrameTranslation` and
/// `ResidualModelFrameRotation` under `ActivationModelQuad`, with their
/// Gauss–Newton Hessians `w Jᵀ J`.
pub struct PoseProblem<'a, S, const NQ: usize, const NV: usize, const NU: usize> {
    /// Start, horizon, step and the quadratic state and input costs.
    pub regularisation: Problem<NQ, NV, NU>,
    /// The system whose frame it is.
    pub system: &'a S,
    /// The frame's kinematic outputs.
    pub frame: FrameOutputs<S, NQ, NV>,
    /// The pose to reach.
    pub target: Placement,
    /// `(w_p, w_R)` of the running cost.
    pub running_weights: (f64, f64),
    /// `(w_p, w_R)` of the terminal cost.
    pub terminal_weights: (f64, f64),
}

/// The UR5's tool flange reaching a pose (the tool's placement at
/// `(1, −1, 1.5, −1.5, 0.8, 0.5)`, 1.5 rad turned from the start's, 0.69 m
/// away) from `(0, −1.5, 1, −1, 0, 0)` at rest in 100 steps of 10 ms; the
/// state drawn to the start's posture at rest, the speeds to zero at the
/// end. `frame` gives `tool0`'s outputs. `scripts/ddp_crocoddyl.py` writes
/// the same numbers; both start from the inputs that hold the start
/// against gravity.
pub fn ur5_pose_reach<S>(system: &S, frame: FrameOutputs<S, 6, 6>) -> PoseProblem<'_, S, 6, 6, 6> {
    let start = [0.0, -1.5, 1.0, -1.0, 0.0, 0.0];
    PoseProblem {
        regularisation: Problem {
            start: State {
                t: 0.0,
                q: start,
                v: [0.0; 6],
            },
            target: (start, [0.0; 6]),
            horizon: 100,
            step: 0.01,
            state_weights: ([1e-2; 6], [0.1; 6]),
            input_weights: [1e-3; 6],
            terminal_weights: ([0.0; 6], [10.0; 6]),
        },
        system,
        frame,
        target: UR5_TOOL_TARGET,
        running_weights: (100.0, 10.0),
        terminal_weights: (1e4, 1e3),
    }
}

/// The UR5's `tool0` placement at `(1, −1, 1.5, −1.5, 0.8, 0.5)`, as
/// Pinocchio 4.0 computes it, to 17 digits (the same digits as
/// `scripts/ddp_crocoddyl.py`'s).
pub const UR5_TOOL_TARGET: Placement = Placement {
    position: [0.23022976075720533, 0.6667019958705028, 0.2572689936541279],
    rotation: [
        [
            -0.9261982387312231,
            -0.01208504409715379,
            -0.3768431693428319,
        ],
        [
            -0.27730725263608436,
            -0.6553517176574692,
            0.7025772653586448,
        ],
        [-0.25545549554982644, 0.7552271697129115, 0.6036343362672622],
    ],
};

impl<S, const NQ: usize, const NV: usize, const NU: usize> PoseProblem<'_, S, NQ, NV, NU> {
    /// `½ w_p ‖p − p*‖² + ½ w_R ‖log₃(R*ᵀ R)‖²` at `x`.
    fn pose_cost(&self, x: &State<NQ, NV>, (wp, wr): (f64, f64)) -> f64 {
        let (p, r) = self.frame.errors(self.system, &x.q, &self.target);
        let square = |e: [f64; 3]| e.iter().map(|a| a * a).sum::<f64>();
        0.5 * (wp * square(p) + wr * square(r))
    }

    /// Adds `s` times the pose cost's gradient and Gauss–Newton Hessian at
    /// `x` to `expansion`.
    fn add_pose<const NX: usize>(
        &self,
        expansion: &mut Expansion<NX, NU>,
        x: &State<NQ, NV>,
        (wp, wr): (f64, f64),
        s: f64,
    ) {
        let e = self.frame.error(self.system, &x.q, &self.target);
        let terms = [
            (s * wp, e.translation, e.translation_jacobian),
            (s * wr, e.rotation, e.rotation_jacobian),
        ];
        for (w, r, jacobian) in terms {
            for i in 0..NV {
                expansion.lx[i] += w * (0..3).map(|k| jacobian[k][i] * r[k]).sum::<f64>();
                for j in 0..NV {
                    expansion.lxx[(i, j)] +=
                        w * (0..3).map(|k| jacobian[k][i] * jacobian[k][j]).sum::<f64>();
                }
            }
        }
    }
}

impl<S, const NQ: usize, const NV: usize, const NU: usize> Objective<NQ, NV, NU>
    for PoseProblem<'_, S, NQ, NV, NU>
{
    fn problem(&self) -> &Problem<NQ, NV, NU> {
        &self.regularisation
    }

    fn running(&self, x: &State<NQ, NV>, u: &[f64; NU]) -> f64 {
        self.regularisation.running(x, u)
            + self.regularisation.step * self.pose_cost(x, self.running_weights)
    }

    fn terminal(&self, x: &State<NQ, NV>) -> f64 {
        self.regularisation.terminal(x) + self.pose_cost(x, self.terminal_weights)
    }

    fn running_derivatives<const NX: usize>(
        &self,
        x: &State<NQ, NV>,
        u: &[f64; NU],
    ) -> Expansion<NX, NU> {
        let mut expansion = self.regularisation.running_derivatives(x, u);
        self.add_pose(
            &mut expansion,
            x,
            self.running_weights,
            self.regularisation.step,
        );
        expansion
    }

    fn terminal_derivatives<const NX: usize>(&self, x: &State<NQ, NV>) -> Expansion<NX, NU> {
        let mut expansion = self.regularisation.terminal_derivatives(x);
        self.add_pose(&mut expansion, x, self.terminal_weights, 1.0);
        expansion
    }
}

/// The state-space matrices of a step's jacobian: `(F_x, F_u)`.
fn matrices<const NV: usize, const NU: usize, const NX: usize>(
    j: &StepJacobian<NV, NU>,
) -> (SMatrix<f64, NX, NX>, SMatrix<f64, NX, NU>) {
    let fx = SMatrix::from_fn(|i, k| match (i < NV, k < NV) {
        (true, true) => j.q_by_q[i][k],
        (true, false) => j.q_by_v[i][k - NV],
        (false, true) => j.v_by_q[i - NV][k],
        (false, false) => j.v_by_v[i - NV][k - NV],
    });
    let fu = SMatrix::from_fn(|i, k| match i < NV {
        true => j.q_by_u[i][k],
        false => j.v_by_u[i - NV][k],
    });
    (fx, fu)
}

/// The policy of one backward pass: feedforward `k` and gains `K` per
/// step, the expected improvement `(Σ kᵀ Q_u, ½ Σ kᵀ Q_uu k)` and
/// `Σ ‖Q_u‖²`.
struct Policy<const NX: usize, const NU: usize> {
    feedforward: Vec<SVector<f64, NU>>,
    gains: Vec<SMatrix<f64, NU, NX>>,
    expected: (f64, f64),
    stop: f64,
}

/// The dynamics' and costs' derivatives at one node: `(F_x, F_u)` and the
/// running cost's expansion.
type Node<const NX: usize, const NU: usize> = (
    SMatrix<f64, NX, NX>,
    SMatrix<f64, NX, NU>,
    Expansion<NX, NU>,
);

/// The backward pass from the terminal cost's expansion `terminal` over
/// the nodes `derivatives`, or `None` when some `Q_uu + μ I` is not
/// positive definite.
fn backward<const NX: usize, const NU: usize>(
    terminal: &Expansion<NX, NU>,
    derivatives: &[Node<NX, NU>],
    mu: f64,
) -> Option<Policy<NX, NU>> {
    let t = derivatives.len();
    let (mut vx, mut vxx) = (terminal.lx, terminal.lxx);
    let mut policy = Policy {
        feedforward: vec![SVector::zeros(); t],
        gains: vec![SMatrix::zeros(); t],
        expected: (0.0, 0.0),
        stop: 0.0,
    };
    for (k, (fx, fu, l)) in derivatives.iter().enumerate().rev() {
        let vxx_fx = vxx * fx;
        let vxx_fu = vxx * fu;
        let qx = l.lx + fx.transpose() * vx;
        let qu = l.lu + fu.transpose() * vx;
        let qxx = l.lxx + fx.transpose() * vxx_fx;
        let quu = l.luu + fu.transpose() * vxx_fu;
        let qux = fu.transpose() * vxx_fx;
        let mut regularised = quu;
        for i in 0..NU {
            regularised[(i, i)] += mu;
        }
        let factor = regularised.cholesky()?;
        let feedforward = -factor.solve(&qu);
        let gain = -factor.solve(&qux);
        policy.stop += qu.norm_squared();
        policy.expected.0 += feedforward.dot(&qu);
        policy.expected.1 += 0.5 * feedforward.dot(&(quu * feedforward));
        // Crocoddyl's value update: `Q_uu K = −Q_ux` and `Q_uu k = −Q_u`
        // fold the full expansion's terms into one each.
        vx = qx + gain.transpose() * qu;
        vxx = qxx + qux.transpose() * gain;
        vxx = 0.5 * (vxx + vxx.transpose());
        policy.feedforward[k] = feedforward;
        policy.gains[k] = gain;
    }
    Some(policy)
}

/// Solves `problem` for `system` with the step `step` and its jacobian
/// `with_jacobian`, from the inputs `guess` (rolled out from the start).
/// `NX` must be `2 NV`.
pub fn solve<S, O, const NQ: usize, const NV: usize, const NU: usize, const NX: usize>(
    system: &S,
    objective: &O,
    (step, with_jacobian): (Step<S, NQ, NV, NU>, StepWithJacobian<S, NQ, NV, NU>),
    guess: Vec<[f64; NU]>,
    settings: &Settings,
) -> Result<Solve<NQ, NV, NU>, ControlError>
where
    S: Differentiable<NQ, NV, NU>,
    O: Objective<NQ, NV, NU>,
{
    let problem = objective.problem();
    assert_eq!(NX, 2 * NV, "the state has 2 NV entries");
    assert_eq!(guess.len(), problem.horizon, "one input per step");
    let rollout = |inputs: &[[f64; NU]]| -> Result<Vec<State<NQ, NV>>, ControlError> {
        let mut states = Vec::with_capacity(inputs.len() + 1);
        states.push(problem.start);
        for u in inputs {
            let next = step(system, states.last().expect("the start"), u, problem.step)?;
            states.push(next);
        }
        Ok(states)
    };
    let mut inputs = guess;
    let mut states = rollout(&inputs)?;
    let mut costs = vec![objective.cost(&states, &inputs)];
    let (mut mu, floor, ceiling) = settings.regularisation;
    let mut stop = f64::INFINITY;
    let mut iterations = 0;
    let mut derivatives = Vec::with_capacity(problem.horizon);
    while iterations < settings.max_iterations {
        derivatives.clear();
        for (x, u) in states.iter().zip(&inputs) {
            let (_, jacobian) = with_jacobian(system, x, u, problem.step)?;
            let (fx, fu) = matrices::<NV, NU, NX>(&jacobian);
            derivatives.push((fx, fu, objective.running_derivatives::<NX>(x, u)));
        }
        let terminal = objective.terminal_derivatives::<NX>(&states[problem.horizon]);
        let policy = loop {
            match backward(&terminal, &derivatives, mu) {
                Some(policy) => break Some(policy),
                None if mu < ceiling => mu *= 10.0,
                None => break None,
            }
        };
        let Some(policy) = policy else { break };
        stop = policy.stop;
        if stop < settings.threshold {
            break;
        }
        iterations += 1;
        let current = *costs.last().expect("the first cost");
        let mut alpha = 1.0;
        let accepted = loop {
            let mut trial_states = Vec::with_capacity(states.len());
            let mut trial_inputs = Vec::with_capacity(inputs.len());
            trial_states.push(problem.start);
            for k in 0..problem.horizon {
                let x = trial_states[k];
                let dx = SVector::<f64, NX>::from_fn(|i, _| match i < NV {
                    true => x.q[i] - states[k].q[i],
                    false => x.v[i - NV] - states[k].v[i - NV],
                });
                let du = policy.feedforward[k] * alpha + policy.gains[k] * dx;
                let u: [f64; NU] = std::array::from_fn(|i| inputs[k][i] + du[i]);
                trial_states.push(step(system, &x, &u, problem.step)?);
                trial_inputs.push(u);
            }
            let cost = objective.cost(&trial_states, &trial_inputs);
            let expected = -(alpha * policy.expected.0 + alpha * alpha * policy.expected.1);
            if current - cost >= 0.1 * expected || alpha < 1e-3 && cost < current {
                break Some((trial_states, trial_inputs, cost));
            }
            alpha *= 0.5;
            if alpha < 1e-4 {
                break None;
            }
        };
        match accepted {
            Some((s, u, cost)) => {
                states = s;
                inputs = u;
                costs.push(cost);
                if alpha == 1.0 {
                    mu = (mu / 10.0).max(floor);
                }
            }
            None => mu = (mu * 10.0).min(ceiling),
        }
    }
    Ok(Solve {
        states,
        inputs,
        costs,
        stop,
        iterations,
    })
}
