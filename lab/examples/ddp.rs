//! Differential dynamic programming over the exact step derivatives
//! (`dalembert::control::euler_step_jacobian`): a UR5 reaching a joint-space
//! pose (horizon 100 × 10 ms) and a cart-pole swinging up (150 × 20 ms),
//! quadratic costs, semi-implicit Euler steps, solved by
//! `dalembert_lab::ddp` from zero inputs. `scripts/ddp_crocoddyl.py` poses
//! the same problems to Crocoddyl's `SolverFDDP`; `scripts/ddp_compare.sh`
//! runs both and compares cost and time per iteration.
//!
//! ```text
//! cargo run --release -p dalembert-lab --example ddp [-- --out DIR]
//! ```
//!
//! Prints one JSON line per problem (final cost, iterations, seconds per
//! iteration) and per timed call (the UR5's step jacobians and adjoints),
//! and writes to `DIR` (default `target/charts`) the charts, both solves
//! animated (`ddp_ur5.html`, `ddp_cart_pole.html`) and the optimal inputs
//! (`ddp_*_inputs.json`, which `scripts/ddp_crocoddyl.py --inputs` costs in
//! Crocoddyl's problems).

use dalembert::State;
use dalembert::control::{
    Differentiated, accelerations_adjoint, euler_step, euler_step_adjoint, euler_step_jacobian,
    rk4_step_adjoint, rk4_step_jacobian,
};
use dalembert_fixtures::cart_pole::{CART_POLE, CartPole};
use dalembert_fixtures::cpu_time::thread_time_of;
use dalembert_lab::ddp::{Settings, Solve, cart_pole_swing_up, solve, ur5_reach};
use dalembert_lab::{Series, line_chart, line_chart_log_y};
use std::path::{Path, PathBuf};

/// The cart-pole's model text (that of `dalembert_fixtures::cart_pole`),
/// for its animation.
const CART_POLE_MODEL: &str = include_str!("../../generated/models/cart_pole.dal");

/// The UR5's URDF file, whose import the UR5's animation draws.
const UR5_URDF: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../tests/reference/urdf/ur5_robot.urdf"
);

dalembert::dalembert! {
    /// The UR5 of `tests/reference/urdf/ur5_robot.urdf` as `dalembert urdf
    /// tests/reference/urdf/ur5_robot.urdf --name Ur5` prints it (its comment
    /// lines left out), asking for the derivatives of its accelerations and
    /// of its inverse dynamics.
    pub Ur5 {
        coordinates shoulder_pan_joint, shoulder_lift_joint, elbow_joint, wrist_1_joint, wrist_2_joint, wrist_3_joint;
        inputs tau_shoulder_pan_joint, tau_shoulder_lift_joint, tau_elbow_joint, tau_wrist_1_joint, tau_wrist_2_joint, tau_wrist_3_joint;
        joint revolute shoulder_link_origin { parent: N, child: shoulder_link, axis: z, coordinate: shoulder_pan_joint, at: O + 0.089159 * N.z };
        body shoulder_link_body { mass: 3.7, center: shoulder_link_origin, frame: shoulder_link, inertia: [0.010267495893, 0.010267495893, 0.00666] };
        torque tau_shoulder_pan_joint * N.z on shoulder_link reacting N;
        frame shoulder_lift_joint_frame = shoulder_link.rotate_y(1.57079632679);
        joint revolute upper_arm_link_origin { parent: shoulder_lift_joint_frame, child: upper_arm_link, axis: y, coordinate: shoulder_lift_joint, at: shoulder_link_origin + 0.13585 * shoulder_link.y };
        body upper_arm_link_body { mass: 8.393, center: upper_arm_link_origin + 0.28 * upper_arm_link.z, frame: upper_arm_link, inertia: [0.22689067591, 0.22689067591, 0.0151074] };
        torque tau_shoulder_lift_joint * shoulder_lift_joint_frame.y on upper_arm_link reacting shoulder_lift_joint_frame;
        joint revolute forearm_link_origin { parent: upper_arm_link, child: forearm_link, axis: y, coordinate: elbow_joint, at: upper_arm_link_origin - 0.1197 * upper_arm_link.y + 0.425 * upper_arm_link.z };
        body forearm_link_body { mass: 2.275, center: forearm_link_origin + 0.25 * forearm_link.z, frame: forearm_link, inertia: [0.049443313556, 0.049443313556, 0.004095] };
        torque tau_elbow_joint * upper_arm_link.y on forearm_link reacting upper_arm_link;
        frame wrist_1_joint_frame = forearm_link.rotate_y(1.57079632679);
        joint revolute wrist_1_link_origin { parent: wrist_1_joint_frame, child: wrist_1_link, axis: y, coordinate: wrist_1_joint, at: forearm_link_origin + 0.39225 * forearm_link.z };
        body wrist_1_link_body { mass: 1.219, center: wrist_1_link_origin, frame: wrist_1_link, inertia: [0.111172755531, 0.111172755531, 0.21942] };
        torque tau_wrist_1_joint * wrist_1_joint_frame.y on wrist_1_link reacting wrist_1_joint_frame;
        joint revolute wrist_2_link_origin { parent: wrist_1_link, child: wrist_2_link, axis: z, coordinate: wrist_2_joint, at: wrist_1_link_origin + 0.093 * wrist_1_link.y };
        body wrist_2_link_body { mass: 1.219, center: wrist_2_link_origin, frame: wrist_2_link, inertia: [0.111172755531, 0.111172755531, 0.21942] };
        torque tau_wrist_2_joint * wrist_1_link.z on wrist_2_link reacting wrist_1_link;
        joint revolute wrist_3_link_origin { parent: wrist_2_link, child: wrist_3_link, axis: y, coordinate: wrist_3_joint, at: wrist_2_link_origin + 0.09465 * wrist_2_link.z };
        body wrist_3_link_body { mass: 0.1879, center: wrist_3_link_origin, frame: wrist_3_link, inertia: [0.0171364731454, 0.0171364731454, 0.033822] };
        torque tau_wrist_3_joint * wrist_2_link.y on wrist_3_link reacting wrist_2_link;
        gravity -9.81 * N.z;
        outputs accelerations_jacobian, inverse_dynamics_adjoint;
    }
}

dalembert::differentiable!(Ur5; inverse);

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
fn path<const NQ: usize, const NV: usize, const NU: usize>(
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

fn charts(
    out: &Path,
    ur5: &Solve<6, 6, 6>,
    cart_pole: &Solve<2, 2, 1>,
) -> Result<(), Box<dyn std::error::Error>> {
    let joints: Vec<Vec<(f64, f64)>> = (0..6).map(|i| path(ur5, |s| s.q[i])).collect();
    let names = ["q1", "q2", "q3", "q4", "q5", "q6"];
    let series: Vec<Series<'_>> = joints
        .iter()
        .zip(names)
        .map(|(points, name)| Series { name, points })
        .collect();
    line_chart(
        &out.join("ddp_ur5.svg"),
        "UR5 reaching a pose: DDP over exact Euler-step jacobians",
        "t (s)",
        "joint angle (rad)",
        &series,
    )?;
    let (x, theta) = (path(cart_pole, |s| s.q[0]), path(cart_pole, |s| s.q[1]));
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
    let (a, b) = (convergence(ur5), convergence(cart_pole));
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
        ],
    )?;
    Ok(())
}

/// The recording of a solve's states, with their energies.
fn recording<S, const NQ: usize, const NV: usize, const NU: usize>(
    system: &S,
    solved: &Solve<NQ, NV, NU>,
) -> dalembert_lab::Recording
where
    S: dalembert::MultibodySystem<NQ, NV, NU>,
{
    let mut recording = dalembert_lab::Recording::new();
    for s in &solved.states {
        recording.push(s.t, &s.q, dalembert::energy(system, &s.q, &s.v));
    }
    recording
}

/// Both solves as animated scenes: the cart-pole, and the UR5 as the
/// segments between its joints.
fn scenes(
    out: &Path,
    ur5: &Solve<6, 6, 6>,
    cart_pole: &Solve<2, 2, 1>,
) -> Result<(), Box<dyn std::error::Error>> {
    let p = CART_POLE;
    dalembert_lab::Scene::new(CART_POLE_MODEL, &[p.m_c, p.m_p, p.l, p.g])?
        .title("Cart-pole swing-up by DDP (semi-implicit Euler, h = 20 ms)")
        .write(
            out.join("ddp_cart_pole.html"),
            &recording(&CART_POLE, cart_pole),
        )?;
    let model = dalembert_codegen::Urdf::read(UR5_URDF)?.model()?;
    let mut scene = dalembert_lab::Scene::new(&model, &[])?
        .title("UR5 reaching a pose by DDP (semi-implicit Euler, h = 10 ms)");
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
    scene.write(out.join("ddp_ur5.html"), &recording(&Ur5 {}, ur5))?;
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
        solve::<_, 6, 6, 6, 12>(
            &ur5,
            &problem,
            (euler_step, euler_step_jacobian),
            vec![[0.0; 6]; problem.horizon],
            &settings,
        )
        .expect("the UR5 problem solves")
    });
    report("ur5", &ur5_solve, ur5_seconds);

    // The fixtures' cart-pole asks for `linearize`, which brings its
    // `accelerations_jacobian`.
    let cart_pole = Differentiated::new(&CART_POLE, CartPole::accelerations_jacobian);
    let problem = cart_pole_swing_up();
    let (cart_pole_solve, cart_pole_seconds) = timed(5, || {
        solve::<_, 2, 2, 1, 4>(
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
    write_inputs(&out.join("ddp_cart_pole_inputs.json"), &cart_pole_solve)?;
    charts(&out, &ur5_solve, &cart_pole_solve)?;
    scenes(&out, &ur5_solve, &cart_pole_solve)?;
    Ok(())
}
