//! Differential dynamic programming over the exact step derivatives
//! (`dalembert::control::euler_step_jacobian`): a UR5 reaching a joint-space
//! pose (horizon 100 × 10 ms) and a cart-pole swinging up (150 × 20 ms),
//! quadratic costs, from zero inputs; the UR5's tool flange `tool0`
//! reaching a pose (100 × 10 ms, `dalembert_lab::ddp::ur5_pose_reach`: the
//! translation and `log₃` rotation errors of `dalembert_lab::pose` over the
//! generated `position`, `rotation`, `jacobian` and `angular_jacobian` of
//! the tool, `lab/models/ur5.rs`) from the torques that hold the start;
//! semi-implicit Euler steps, solved by `dalembert_lab::ddp`.
//! `scripts/ddp_crocoddyl.py` poses the same problems to Crocoddyl's
//! `SolverFDDP`; `scripts/ddp_compare.sh` runs both and compares cost and
//! time per iteration.
//!
//! ```text
//! cargo run --release -p dalembert-lab --example ddp [-- --out DIR]
//! ```
//!
//! Prints one JSON line per problem (final cost, iterations, seconds per
//! iteration) and per timed call (the UR5's step jacobians and adjoints),
//! and the tool's final pose error, and writes to `DIR` (default
//! `target/charts`) the charts (`ddp_*.svg`: joints, the tool's position
//! against its target, the cost per iteration), the solves animated
//! (`ddp_ur5.html`, `ddp_ur5_pose.html`, `ddp_cart_pole.html`) and the optimal inputs
//! (`ddp_*_inputs.json`, which `scripts/ddp_crocoddyl.py --inputs` costs in
//! Crocoddyl's problems).

use dalembert::State;
use dalembert::control::{
    Differentiated, accelerations_adjoint, euler_step, euler_step_adjoint, euler_step_jacobian,
    rk4_step_adjoint, rk4_step_jacobian,
};
use dalembert_fixtures::cart_pole::{CART_POLE, CartPole};
use dalembert_fixtures::cpu_time::thread_time_of;
use dalembert_lab::ddp::{
    Settings, Solve, UR5_TOOL_TARGET, cart_pole_swing_up, solve, ur5_pose_reach, ur5_reach,
};
use dalembert_lab::{Series, line_chart, line_chart_log_y};
use std::path::{Path, PathBuf};

/// The cart-pole's model text (that of `dalembert_fixtures::cart_pole`),
/// for its animation.
const CART_POLE_MODEL: &str = include_str!("../../generated/models/cart_pole.dal");

#[path = "../models/ur5.rs"]
mod ur5;

use ur5::Ur5;

/// Solves `run` `repeats` times, returning the last solve and the best
/// time per iteration, in CPU time of the thread (the machine is shared:
/// the wall clock counts the time other processes hold the core).
fn timed<const NQ: usize, const NV: usize, const NU: usize>(
    repeats: usize,
    run: impl Fn() -> Solve<NQ, NV, NU>,
) -> (Solve<NQ, NV, NU>, f64) {
    let mut best = f64::INFINITY;
    let mut last = None;
    for _ in 0..repeats {
        let (time, solved) = thread_time_of(&run);
        let seconds = time.as_secs_f64() / solved.iterations.max(1) as f64;
        best = best.min(seconds);
        last = Some(solved);
    }
    (last.expect("one solve at least"), best)
}

/// Nanoseconds per call of `call` (the best of 5 runs of 20 000 calls, in
/// CPU time of the thread), printed as one JSON line.
fn per_call(name: &str, call: impl Fn() -> f64) {
    let mut best = f64::INFINITY;
    let mut sink = 0.0;
    for _ in 0..5 {
        let (time, ()) = thread_time_of(|| {
            for _ in 0..20_000 {
                sink += std::hint::black_box(call());
            }
        });
        best = best.min(time.as_secs_f64() / 20_000.0);
    }
    assert!(sink.is_finite());
    println!(
        "{{\"call\": \"{name}\", \"nanoseconds\": {:.1}}}",
        best * 1e9
    );
}

/// The UR5's step derivatives and adjoints per call, beside its
/// `accelerations_jacobian`.
fn step_timings() {
    let ur5 = Ur5 {};
    let state = ur5_reach().start;
    let u = [1.0, -2.0, 3.0, 0.5, -0.5, 0.1];
    let (q, v) = (state.q, state.v);
    per_call("ur5 accelerations_jacobian", || {
        let (by_q, _, _) = ur5
            .accelerations_jacobian(0.0, std::hint::black_box(&q), &v, &u)
            .expect("solvable");
        by_q[0][0]
    });
    let lambda = [0.3, -0.1, 0.7, 0.2, -0.5, 0.9];
    per_call("ur5 accelerations_adjoint", || {
        let (_, a) = accelerations_adjoint(&ur5, 0.0, std::hint::black_box(&q), &v, &u, &lambda)
            .expect("solvable");
        a.by_q[0]
    });
    per_call("ur5 euler_step_adjoint", || {
        let (_, a) = euler_step_adjoint(
            &ur5,
            std::hint::black_box(&state),
            &u,
            0.01,
            &lambda,
            &lambda,
        )
        .expect("a step");
        a.by_q[0]
    });
    per_call("ur5 rk4_step_adjoint", || {
        let (_, a) = rk4_step_adjoint(
            &ur5,
            std::hint::black_box(&state),
            &u,
            0.01,
            &lambda,
            &lambda,
        )
        .expect("a step");
        a.by_q[0]
    });
    per_call("ur5 euler_step_jacobian", || {
        let (_, j) =
            euler_step_jacobian(&ur5, std::hint::black_box(&state), &u, 0.01).expect("a step");
        j.q_by_q[0][0]
    });
    per_call("ur5 rk4_step_jacobian", || {
        let (_, j) =
            rk4_step_jacobian(&ur5, std::hint::black_box(&state), &u, 0.01).expect("a step");
        j.q_by_q[0][0]
    });
}

/// One JSON line of a solve.
fn report<const NQ: usize, const NV: usize, const NU: usize>(
    name: &str,
    solved: &Solve<NQ, NV, NU>,
    seconds: f64,
) {
    println!(
        "{{\"solver\": \"dalembert\", \"problem\": \"{name}\", \"cost\": {:.15e}, \"iterations\": {}, \"stop\": {:.3e}, \"seconds_per_iteration\": {:.6e}}}",
        solved.costs.last().expect("a cost"),
        solved.iterations,
        solved.stop,
        seconds
    );
}

/// Writes the inputs of a solve as a JSON array of arrays to `path` (for
/// `scripts/ddp_crocoddyl.py --inputs` to cost them in Crocoddyl's problem).
fn write_inputs<const NQ: usize, const NV: usize, const NU: usize>(
    path: &Path,
    solved: &Solve<NQ, NV, NU>,
) -> std::io::Result<()> {
    let rows: Vec<String> = solved
        .inputs
        .iter()
        .map(|u| format!("[{}]", u.map(|x| format!("{x:e}")).join(", ")))
        .collect();
    std::fs::write(path, format!("[{}]\n", rows.join(",\n")))
}

/// `(t, value)` of coordinate or speed `i` along a solve.
fn path_of<const NQ: usize, const NV: usize, const NU: usize>(
    solved: &Solve<NQ, NV, NU>,
    value: impl Fn(&State<NQ, NV>) -> f64,
) -> Vec<(f64, f64)> {
    solved.states.iter().map(|s| (s.t, value(s))).collect()
}

/// The cost per iteration, shifted by the final cost (log scale).
fn convergence<const NQ: usize, const NV: usize, const NU: usize>(
    solved: &Solve<NQ, NV, NU>,
) -> Vec<(f64, f64)> {
    let last = *solved.costs.last().expect("a cost");
    solved
        .costs
        .iter()
        .enumerate()
        .map(|(i, c)| (i as f64, (c - last) / last))
        .collect()
}

/// `‖e‖`.
fn norm(e: &[f64; 3]) -> f64 {
    e.iter().map(|a| a * a).sum::<f64>().sqrt()
}

/// The pose reach: the tool's translation and rotation errors, and the
/// joints.
fn pose_charts(out: &Path, pose: &Solve<6, 6, 6>) -> Result<(), Box<dyn std::error::Error>> {
    let ur5 = Ur5 {};
    // The translation error's components, then the rotation error's.
    let errors: Vec<(f64, [f64; 6])> = pose
        .states
        .iter()
        .map(|s| {
            let (p, r) = ur5::tool().errors(&ur5, &s.q, &UR5_TOOL_TARGET);
            (s.t, [p[0], p[1], p[2], r[0], r[1], r[2]])
        })
        .collect();
    let components: Vec<Vec<(f64, f64)>> = (0..6)
        .map(|i| errors.iter().map(|(t, e)| (*t, e[i])).collect())
        .collect();
    let names = ["x − x*", "y − y*", "z − z*", "log₃ x", "log₃ y", "log₃ z"];
    let series = named(&components, &names);
    line_chart(
        &out.join("ddp_ur5_pose_tool.svg"),
        "UR5's tool reaching a pose: p − p* and log₃(R*ᵀ R) of tool0",
        "t (s)",
        "translation error (m), rotation error (rad)",
        &series,
    )?;
    joint_chart(
        &out.join("ddp_ur5_pose_joints.svg"),
        "UR5's tool reaching a pose: DDP over exact Euler-step jacobians",
        pose,
    )
}

/// The joint angles of a UR5 solve.
fn joint_chart(
    path: &Path,
    title: &str,
    solved: &Solve<6, 6, 6>,
) -> Result<(), Box<dyn std::error::Error>> {
    let joints: Vec<Vec<(f64, f64)>> = (0..6).map(|i| path_of(solved, |s| s.q[i])).collect();
    let series = named(&joints, &["q1", "q2", "q3", "q4", "q5", "q6"]);
    line_chart(path, title, "t (s)", "joint angle (rad)", &series)?;
    Ok(())
}

/// The curves `points` as chart series named `names`.
fn named<'a>(points: &'a [Vec<(f64, f64)>], names: &[&'a str]) -> Vec<Series<'a>> {
    points
        .iter()
        .zip(names)
        .map(|(points, name)| Series { name, points })
        .collect()
}

fn charts(
    out: &Path,
    (ur5, pose): (&Solve<6, 6, 6>, &Solve<6, 6, 6>),
    cart_pole: &Solve<2, 2, 1>,
) -> Result<(), Box<dyn std::error::Error>> {
    joint_chart(
        &out.join("ddp_ur5.svg"),
        "UR5 reaching a joint-space pose: DDP over exact Euler-step jacobians",
        ur5,
    )?;
    let (x, theta) = (
        path_of(cart_pole, |s| s.q[0]),
        path_of(cart_pole, |s| s.q[1]),
    );
    let force: Vec<(f64, f64)> = cart_pole
        .states
        .iter()
        .zip(&cart_pole.inputs)
        .map(|(s, u)| (s.t, u[0] / 10.0))
        .collect();
    line_chart(
        &out.join("ddp_cart_pole.svg"),
        "Cart-pole swing-up: DDP over exact Euler-step jacobians",
        "t (s)",
        "x (m), θ (rad), F / 10 (N)",
        &[
            Series {
                name: "x",
                points: &x,
            },
            Series {
                name: "θ",
                points: &theta,
            },
            Series {
                name: "F / 10",
                points: &force,
            },
        ],
    )?;
    let (a, b, c) = (convergence(ur5), convergence(cart_pole), convergence(pose));
    line_chart_log_y(
        &out.join("ddp_convergence.svg"),
        "DDP: cost above the final cost, per iteration",
        "iteration",
        "(J − J*) / J*",
        &[
            Series {
                name: "UR5",
                points: &a,
            },
            Series {
                name: "cart-pole",
                points: &b,
            },
            Series {
                name: "UR5 tool pose",
                points: &c,
            },
        ],
    )?;
    Ok(())
}

/// The recording of a solve's states, with their energies and the power
/// of the inputs (each held over its step, the last one at the end).
fn recording<S, const NQ: usize, const NV: usize, const NU: usize>(
    system: &S,
    solved: &Solve<NQ, NV, NU>,
) -> dalembert_lab::Recording
where
    S: dalembert::MultibodySystem<NQ, NV, NU>,
{
    let mut recording = dalembert_lab::Recording::new();
    let last = solved.inputs.last().expect("one step at least");
    for (k, s) in solved.states.iter().enumerate() {
        let u = solved.inputs.get(k).unwrap_or(last);
        let power = dalembert_lab::input_power(system, s.t, &s.q, &s.v, u);
        recording.push_driven(s.t, &s.q, dalembert::energy(system, &s.q, &s.v), power);
    }
    recording
}

/// The UR5's scene: the segments between its joints and to its tool.
fn ur5_scene(title: &str) -> Result<dalembert_lab::Scene, dalembert_lab::SceneError> {
    let mut scene = dalembert_lab::Scene::of(&Ur5 {})?.title(title);
    let mut previous = "O".to_string();
    for link in [
        "shoulder",
        "upper_arm",
        "forearm",
        "wrist_1",
        "wrist_2",
        "wrist_3",
    ] {
        let origin = format!("{link}_link_origin");
        scene = scene
            .segment(&previous, &origin)?
            .body_size(&format!("{link}_link_body"), [0.08; 3])?;
        previous = origin;
    }
    scene.segment(&previous, "tool0_origin")
}

/// The solves as animated scenes: the cart-pole, and the UR5 as the
/// segments between its joints.
fn scenes(
    out: &Path,
    (ur5, pose): (&Solve<6, 6, 6>, &Solve<6, 6, 6>),
    cart_pole: &Solve<2, 2, 1>,
) -> Result<(), Box<dyn std::error::Error>> {
    let p = CART_POLE;
    dalembert_lab::Scene::new(CART_POLE_MODEL, &[p.m_c, p.m_p, p.l, p.g])?
        .title("Cart-pole swing-up by DDP (semi-implicit Euler, h = 20 ms)")
        .write(
            out.join("ddp_cart_pole.html"),
            &recording(&CART_POLE, cart_pole),
        )?;
    ur5_scene("UR5 reaching a joint-space pose by DDP (semi-implicit Euler, h = 10 ms)")?
        .write(out.join("ddp_ur5.html"), &recording(&Ur5 {}, ur5))?;
    ur5_scene("UR5's tool reaching a pose by DDP (semi-implicit Euler, h = 10 ms)")?
        .write(out.join("ddp_ur5_pose.html"), &recording(&Ur5 {}, pose))?;
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args()
        .skip_while(|arg| arg != "--out")
        .nth(1)
        .map_or_else(|| PathBuf::from("target/charts"), PathBuf::from);
    std::fs::create_dir_all(&out)?;
    let settings = Settings::default();

    let ur5 = Ur5 {};
    let problem = ur5_reach();
    let (ur5_solve, ur5_seconds) = timed(5, || {
        solve::<_, _, 6, 6, 6, 12>(
            &ur5,
            &problem,
            (euler_step, euler_step_jacobian),
            vec![[0.0; 6]; problem.horizon],
            &settings,
        )
        .expect("the UR5 problem solves")
    });
    report("ur5", &ur5_solve, ur5_seconds);

    let pose = ur5_pose_reach(&ur5, ur5::tool());
    let hold = ur5::holding(&pose.regularisation.start.q);
    let (pose_solve, pose_seconds) = timed(5, || {
        solve::<_, _, 6, 6, 6, 12>(
            &ur5,
            &pose,
            (euler_step, euler_step_jacobian),
            vec![hold; pose.regularisation.horizon],
            &settings,
        )
        .expect("the UR5 pose problem solves")
    });
    report("ur5_pose", &pose_solve, pose_seconds);
    let end = pose_solve.states.last().expect("the end");
    let (translation, rotation) = ur5::tool().errors(&ur5, &end.q, &UR5_TOOL_TARGET);
    println!(
        "{{\"pose_error\": \"ur5_pose\", \"translation\": {:.3e}, \"rotation\": {:.3e}}}",
        norm(&translation),
        norm(&rotation)
    );

    // The fixtures' cart-pole asks for `linearize`, which brings its
    // `accelerations_jacobian`.
    let cart_pole = Differentiated::new(&CART_POLE, CartPole::accelerations_jacobian);
    let problem = cart_pole_swing_up();
    let (cart_pole_solve, cart_pole_seconds) = timed(5, || {
        solve::<_, _, 2, 2, 1, 4>(
            &cart_pole,
            &problem,
            (euler_step, euler_step_jacobian),
            vec![[0.0]; problem.horizon],
            &settings,
        )
        .expect("the cart-pole problem solves")
    });
    report("cart_pole", &cart_pole_solve, cart_pole_seconds);

    step_timings();
    write_inputs(&out.join("ddp_ur5_inputs.json"), &ur5_solve)?;
    write_inputs(&out.join("ddp_ur5_pose_inputs.json"), &pose_solve)?;
    write_inputs(&out.join("ddp_cart_pole_inputs.json"), &cart_pole_solve)?;
    charts(&out, (&ur5_solve, &pose_solve), &cart_pole_solve)?;
    pose_charts(&out, &pose_solve)?;
    scenes(&out, (&ur5_solve, &pose_solve), &cart_pole_solve)?;
    Ok(())
}
