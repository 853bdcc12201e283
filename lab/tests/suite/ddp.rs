//! The DDP solver of `dalembert_lab::ddp` on the DDP example's problems
//! against Crocoddyl's `SolverFDDP` on the same problems
//! (`scripts/ddp_crocoddyl.py`, its optima stored in
//! `tests/data/ddp_crocoddyl.jsonl`): the cart-pole swing-up, and the UR5's
//! tool reaching a pose over the generated kinematic outputs of `tool0`
//! (`lab/models/ur5.rs`).

#[path = "../../models/ur5.rs"]
mod ur5;

use dalembert::control::{Differentiated, euler_step, euler_step_jacobian};
use dalembert_fixtures::cart_pole::{CART_POLE, CartPole};
use dalembert_lab::ddp::{
    Settings, Solve, UR5_TOOL_TARGET, cart_pole_swing_up, solve, ur5_pose_reach,
};
use ur5::Ur5;

/// Crocoddyl's optimal cost of `problem` in the stored run.
fn crocoddyls_cost(problem: &str) -> f64 {
    let runs = include_str!("../data/ddp_crocoddyl.jsonl");
    let costs: Vec<f64> = runs
        .lines()
        .map(|line| serde_json::from_str::<serde_json::Value>(line).expect("a JSON line"))
        .filter(|run| run["problem"] == problem)
        .map(|run| run["cost"].as_f64().expect("a cost"))
        .collect();
    assert_eq!(costs.len(), 1, "one run of {problem}");
    costs[0]
}

fn norm(e: &[f64; 3]) -> f64 {
    e.iter().map(|a| a * a).sum::<f64>().sqrt()
}

/// Asserts that `solved` stopped on the threshold, its cost falling at
/// every iteration, at Crocoddyl's optimal cost of `problem` to 1e-6
/// relative.
fn assert_converged_to_crocoddyls<const NQ: usize, const NV: usize, const NU: usize>(
    solved: &Solve<NQ, NV, NU>,
    settings: &Settings,
    problem: &str,
) {
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
    let crocoddyl = crocoddyls_cost(problem);
    assert!(
        (cost - crocoddyl).abs() <= 1e-6 * crocoddyl,
        "cost {cost}, Crocoddyl's {crocoddyl}"
    );
}

#[test]
fn the_swing_up_reaches_crocoddyls_optimal_cost() {
    let cart_pole = Differentiated::new(&CART_POLE, CartPole::accelerations_jacobian);
    let problem = cart_pole_swing_up();
    let settings = Settings::default();
    let solved = solve::<_, _, 2, 2, 1, 4>(
        &cart_pole,
        &problem,
        (euler_step, euler_step_jacobian),
        vec![[0.0]; problem.horizon],
        &settings,
    )
    .expect("the swing-up solves");
    assert_converged_to_crocoddyls(&solved, &settings, "cart_pole");
    let end = solved.states.last().expect("the end");
    assert!(end.q[1].abs() < 0.1, "the pole ends at θ = {}", end.q[1]);
}

#[test]
fn the_target_is_the_tools_placement_at_the_joint_space_target() {
    // Pinocchio's placement of `tool0` at (1, −1, 1.5, −1.5, 0.8, 0.5),
    // to 17 digits; ours from the generated outputs.
    let q = [1.0, -1.0, 1.5, -1.5, 0.8, 0.5];
    let placement = ur5::tool().placement(&Ur5 {}, &q);
    for i in 0..3 {
        assert!((placement.position[i] - UR5_TOOL_TARGET.position[i]).abs() < 1e-13);
        for j in 0..3 {
            assert!((placement.rotation[i][j] - UR5_TOOL_TARGET.rotation[i][j]).abs() < 1e-13);
        }
    }
}

#[test]
fn the_tools_pose_error_jacobians_match_central_differences() {
    let ur5 = Ur5 {};
    let tool = ur5::tool();
    let h = 1e-6;
    for q in [
        [0.0, -1.5, 1.0, -1.0, 0.0, 0.0],
        [0.7, -0.4, 2.1, 0.3, -1.2, 2.5],
    ] {
        let error = tool.error(&ur5, &q, &UR5_TOOL_TARGET);
        for j in 0..6 {
            let moved = |step: f64| {
                let mut q = q;
                q[j] += step;
                tool.errors(&ur5, &q, &UR5_TOOL_TARGET)
            };
            let ((tp, rp), (tm, rm)) = (moved(h), moved(-h));
            for i in 0..3 {
                let dt = (tp[i] - tm[i]) / (2.0 * h);
                let dr = (rp[i] - rm[i]) / (2.0 * h);
                assert!((dt - error.translation_jacobian[i][j]).abs() < 1e-8);
                assert!(
                    (dr - error.rotation_jacobian[i][j]).abs() < 1e-8,
                    "∂r[{i}]/∂q[{j}] at {q:?}: {dr} by differences, {} exact",
                    error.rotation_jacobian[i][j]
                );
            }
        }
    }
}

#[test]
fn the_tool_reaches_the_pose_at_crocoddyls_optimal_cost() {
    let ur5 = Ur5 {};
    let problem = ur5_pose_reach(&ur5, ur5::tool());
    let start = problem.regularisation.start;
    let settings = Settings::default();
    let solved = solve::<_, _, 6, 6, 6, 12>(
        &ur5,
        &problem,
        (euler_step, euler_step_jacobian),
        vec![ur5::holding(&start.q); problem.regularisation.horizon],
        &settings,
    )
    .expect("the pose reach solves");
    assert_converged_to_crocoddyls(&solved, &settings, "ur5_pose");
    let end = solved.states.last().expect("the end");
    let (translation, rotation) = ur5::tool().errors(&ur5, &end.q, &UR5_TOOL_TARGET);
    assert!(norm(&translation) < 1e-4, "{translation:?} m off");
    assert!(norm(&rotation) < 1e-4, "{rotation:?} rad off");
    assert!(
        end.v.iter().all(|v| v.abs() < 0.05),
        "moving at {:?}",
        end.v
    );
}
