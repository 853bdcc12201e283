//! Four trajectories at once: [`rk4_group_step_x4`], the step of
//! [`rk4_group_step`](super::rk4_group_step) taken from four states in one go, its four
//! stages through the system's
//! [`accelerations_x4`](crate::MultibodySystem::accelerations_x4) (one state
//! in each SIMD lane for a generated system whose model asks for
//! `outputs accelerations_x4;`).

use super::ControlError;
use super::step::{NODES, WEIGHTS, moved};
use crate::{DynamicsError, MultibodySystem, State};

/// Four of [`rk4_group_step`](super::rk4_group_step) at once: entry `k` is the RK4 step
/// of length `h` from `states[k]` with the inputs `u[k]` held, at
/// `states[k].t + h`, each stage's accelerations of the four states taken
/// by one call of the system's
/// [`accelerations_x4`](crate::MultibodySystem::accelerations_x4).
///
/// The stages are those of `rk4_group_step`, operation for operation (moved by
/// the group update `q ⊕ w` from the step's start), so an entry is the
/// scalar step's to the rounding of `accelerations_x4` against
/// `accelerations`: bit for bit where those agree exactly (both on the
/// unrolled factorisation, as on the chains of 6, the panda, the UR5), to
/// rounding otherwise (the lanes may take another route, see
/// `accelerations_x4`). Where every speed is its coordinate's rate it
/// is also [`integrate::Rk4::step`](crate::integrate::Rk4::step) of each
/// state with its inputs held.
///
/// A state whose stage fails gets the error of the first stage that
/// failed, the scalar step's; the other three are unaffected. Allocates
/// nothing and never panics.
///
/// ```
/// use dalembert::State;
/// use dalembert::control::{rk4_group_step, rk4_group_step_x4};
///
/// dalembert::dalembert! {
///     pub CartPole {
///         parameters M, m, l, g;
///         coordinates x, theta;
///         inputs F;
///         frame B = N.rotate_z(theta);
///         point C = O + x * N.x;
///         particle cart { mass: M, at: C };
///         particle bob { mass: m, at: C - l * B.y };
///         gravity -g * N.y;
///         force F * N.x at C;
///         outputs accelerations_x4;
///     }
/// }
/// let cart_pole = CartPole { M: 1.0, m: 0.3, l: 0.5, g: 9.81 };
/// // Four rollouts from four angles, each with its own push.
/// let states = [0.1, 0.5, 1.0, 2.0].map(|angle| State { t: 0.0, q: [0.0, angle], v: [0.0; 2] });
/// let pushes = [[0.0], [0.5], [-0.5], [1.0]];
/// let ends = rk4_group_step_x4(&cart_pole, &states, &pushes, 1e-3);
/// for ((end, state), push) in ends.into_iter().zip(&states).zip(&pushes) {
///     // The scalar step's, to rounding.
///     let (end, one) = (end?, rk4_group_step(&cart_pole, state, push, 1e-3)?);
///     for (a, b) in end.q.iter().chain(&end.v).zip(one.q.iter().chain(&one.v)) {
///         assert!((a - b).abs() <= 1e-12 * b.abs().max(1.0));
///     }
/// }
/// # Ok::<(), dalembert::control::ControlError>(())
/// ```
pub fn rk4_group_step_x4<S, const NQ: usize, const NV: usize, const NU: usize>(
    system: &S,
    states: &[State<NQ, NV>; 4],
    u: &[[f64; NU]; 4],
    h: f64,
) -> [Result<State<NQ, NV>, ControlError>; 4]
where
    S: MultibodySystem<NQ, NV, NU> + ?Sized,
{
    let t = states.map(|s| s.t);
    let (q, v) = (states.map(|s| s.q), states.map(|s| s.v));
    let (mut qi, mut vi) = (q, v);
    let (mut sum_v, mut sum_a) = ([[0.0; NV]; 4], [[0.0; NV]; 4]);
    let mut failed: [Option<DynamicsError>; 4] = [None; 4];
    for (i, &weight) in WEIGHTS.iter().enumerate() {
        let c = if i == 0 { 0.0 } else { NODES[i - 1] };
        let stage = system.accelerations_x4(t.map(|t| t + c * h), &qi, &vi, u);
        // State by state, in place (no copies of the four states' arrays
        // a stage): a failed state goes on with no acceleration, its lanes
        // being its own, and its answer is its first error.
        for (k, stage) in stage.into_iter().enumerate() {
            let a = stage.unwrap_or_else(|cause| {
                failed[k].get_or_insert(cause);
                [0.0; NV]
            });
            sum_v[k] = moved(&sum_v[k], weight, &vi[k]);
            sum_a[k] = moved(&sum_a[k], weight, &a);
            if let Some(&next) = NODES.get(i) {
                qi[k] = system.integrate_configuration(&q[k], &vi[k], next * h);
                vi[k] = moved(&v[k], next * h, &a);
            }
        }
    }
    each(|k| match failed[k] {
        Some(cause) => Err(cause.into()),
        None => Ok(State {
            t: t[k] + h,
            q: system.integrate_configuration(&q[k], &sum_v[k], h),
            v: moved(&v[k], h, &sum_a[k]),
        }),
    })
}

/// `f` of each of the four states.
#[inline(always)]
fn each<T>(f: impl FnMut(usize) -> T) -> [T; 4] {
    std::array::from_fn(f)
}
