//! The DDP solver of `dalembert_lab::ddp` on the cart-pole swing-up of the
//! DDP example, against Crocoddyl's `SolverFDDP` on the same problem.

use dalembert::control::{Differentiated, euler_step, euler_step_jacobian};
use dalembert_fixtures::cart_pole::{CART_POLE, CartPole};
use dalembert_lab::ddp::{Settings, cart_pole_swing_up, solve};

/// Crocoddyl 3.2.1's optimal cost of the swing-up
/// (`scripts/ddp_crocoddyl.py`, 28 Nov 2026: 172 iterations of
/// `SolverFDDP`, `Σ ‖Q_u‖² = 8e-13` at the end).
const CROCODDYL_COST: f64 = 1.13941415063911;

#[test]
fn the_swing_up_reaches_crocoddyls_optimal_cost() {
    let cart_pole = Differentiated::new(&CART_POLE, CartPole::accelerations_jacobian);
    let problem = cart_pole_swing_up();
    let settings = Settings::default();
    let solved = solve::<_, 2, 2, 1, 4>(
        &cart_pole,
        &problem,
        (euler_step, euler_step_jacobian),
        vec![[0.0]; problem.horizon],
        &settings,
    )
    .expect("the swing-up solves");
    assert!(
        solved.stop < settings.threshold,
        "stopped at {:e}",
        solved.stop
    );
    assert!(solved.costs.len() > 1, "no iteration taken");
    for pair in solved.costs.windows(2) {
        assert!(pair[1] < pair[0], "the cost rose: {pair:?}");
    }
    let cost = *solved.costs.last().expect("a cost");
    assert!(
        (cost - CROCODDYL_COST).abs() <= 1e-6 * CROCODDYL_COST,
        "cost {cost}, Crocoddyl's {CROCODDYL_COST}"
    );
    let end = solved.states.last().expect("the end");
    assert!(end.q[1].abs() < 0.1, "the pole ends at θ = {}", end.q[1]);
}
