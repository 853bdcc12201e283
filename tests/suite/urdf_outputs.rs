//! The control outputs of a robot no other test holds, the Unitree Z1 arm of
//! `example-robot-data` (6 revolute joints and a gripper's), as `dalembert
//! urdf` writes it with `outputs` added, against Pinocchio
//! (`tests/reference/z1_outputs.json`, `scripts/z1_outputs_reference.py`):
//! on a fixed base the inverse dynamics and its derivatives
//! (`computeRNEADerivatives`), the accelerations and theirs
//! (`computeABADerivatives`), and the kinematic outputs of three links'
//! origins and frames (Pinocchio's frame placements, velocities, classical
//! accelerations and `LOCAL_WORLD_ALIGNED` frame jacobians); on a free
//! flyer, the inverse dynamics, the accelerations and the kinematic outputs,
//! whose speeds are the base's in its own axes as Pinocchio's are, and the
//! inverse dynamics' derivatives against central differences.

use dalembert_fixtures::reference::{assert_close, flat, reference};
use serde_json::Value;

/// The arm's links from `link01` on, as `dalembert urdf` writes them,
/// carried by the frame `$root` at the point `$origin`, with `outputs`.
macro_rules! z1 {
    ($(#[$doc:meta])* $name:ident, $root:ident, $origin:ident, $($base:tt)*) => {
        dalembert::dalembert! {
            $(#[$doc])*
            pub $name {
            $($base)*
            coordinates joint1, joint2, joint3, joint4, joint5, joint6, jointGripper;
            inputs tau_joint1, tau_joint2, tau_joint3, tau_joint4, tau_joint5, tau_joint6, tau_jointGripper;
            joint revolute link01_origin { parent: $root, child: link01, axis: z, coordinate: joint1, at: $origin + 0.0585 * $root.z };
            body link01_body { mass: 0.67332551, center: link01_origin + 2.47e-6 * link01.x - 0.00025198 * link01.y + 0.02317169 * link01.z, frame: link01, inertia: [0.00128328, 0.00071931, 0.00083936, -6e-8, 5e-7, -4e-7] };
            torque tau_joint1 * $root.z on link01 reacting $root;
            joint revolute link02_origin { parent: link01, child: link02, axis: y, coordinate: joint2, at: link01_origin + 0.045 * link01.z };
            body link02_body { mass: 1.19132258, center: link02_origin - 0.11012601 * link02.x + 0.00240029 * link02.y + 0.00158266 * link02.z, frame: link02, inertia: [0.00102138, 0.02429457, 0.02466114, 0.00062358, -2.1e-6, 5.13e-6] };
            torque tau_joint2 * link01.y on link02 reacting link01;
            joint revolute link03_origin { parent: link02, child: link03, axis: y, coordinate: joint3, at: link02_origin - 0.35 * link02.x };
            body link03_body { mass: 0.83940874, center: link03_origin + 0.10609208 * link03.x - 0.00541815 * link03.y + 0.03476383 * link03.z, frame: link03, inertia: [0.00108061, 0.00954238, 0.00886621, -8.669e-5, -1.332e-5, -0.00208102] };
            torque tau_joint3 * link02.y on link03 reacting link02;
            joint revolute link04_origin { parent: link03, child: link04, axis: y, coordinate: joint4, at: link03_origin + 0.218 * link03.x + 0.057 * link03.z };
            body link04_body { mass: 0.56404563, center: link04_origin + 0.04366681 * link04.x + 0.00364738 * link04.y - 0.00170192 * link04.z, frame: link04, inertia: [0.00031576, 0.00092996, 0.00097912, 8.13e-5, -5.96e-6, 4.091e-5] };
            torque tau_joint4 * link03.y on link04 reacting link03;
            joint revolute link05_origin { parent: link04, child: link05, axis: z, coordinate: joint5, at: link04_origin + 0.07 * link04.x };
            body link05_body { mass: 0.38938492, center: link05_origin + 0.03121533 * link05.x + 0.00646316 * link05.z, frame: link05, inertia: [0.00017605, 0.00055896, 0.0005386, 4e-7, -1.3e-7, 5.689e-5] };
            torque tau_joint5 * link04.z on link05 reacting link04;
            joint revolute link06_origin { parent: link05, child: link06, axis: x, coordinate: joint6, at: link05_origin + 0.0492 * link05.x };
            body link06_body { mass: 0.81479462, center: link06_origin + 0.07224641626776021 * link06.x - 0.0002927547495257148 * link06.y - 0.002118493062097293 * link06.z, frame: link06, inertia: [0.0005703230092387275, 0.001868195845425298, 0.0018440855472965714, 1.9395459744603157e-7, 2.1337591549081808e-6, 9.178026233463511e-5] };
            torque tau_joint6 * link05.x on link06 reacting link05;
            point gripperStator_origin = link06_origin + 0.051 * link06.x;
            joint revolute gripperMover_origin { parent: link06, child: gripperMover, axis: y, coordinate: jointGripper, at: gripperStator_origin + 0.049 * link06.x };
            body gripperMover_body { mass: 0.27621302, center: gripperMover_origin + 0.01320633 * gripperMover.x + 0.00476708 * gripperMover.y + 0.00380534 * gripperMover.z, frame: gripperMover, inertia: [0.00017716, 0.00026787, 0.00035728, 1.683e-5, 2.62e-6, -1.786e-5] };
            torque tau_jointGripper * link06.y on gripperMover reacting link06;
            gravity -9.81 * N.z;
            outputs inverse_dynamics;
            outputs position(link03_origin), velocity(link03_origin), acceleration(link03_origin), jacobian(link03_origin);
            outputs rotation(link03), angular_velocity(link03), angular_jacobian(link03);
            outputs position(link06_origin), velocity(link06_origin), acceleration(link06_origin), jacobian(link06_origin);
            outputs rotation(link06), angular_velocity(link06), angular_jacobian(link06);
            outputs position(gripperMover_origin), velocity(gripperMover_origin), acceleration(gripperMover_origin), jacobian(gripperMover_origin);
            outputs rotation(gripperMover), angular_velocity(gripperMover), angular_jacobian(gripperMover);
            }
        }
    };
}

z1! {
    /// The arm on a fixed base, with its derivatives.
    FixedZ1, N, O,
    outputs inverse_dynamics_jacobian, accelerations_jacobian;
}

z1! {
    /// The arm on a free flyer; the base link `world` carries `link00`.
    FloatingZ1, world, root_joint,
    outputs inverse_dynamics_jacobian;
    joint free root_joint { parent: N, child: world, at: O };
    body world_body { mass: 0.47247481, center: root_joint - 0.00334984 * world.x - 0.00013615 * world.y + 0.02495843 * world.z, frame: world, inertia: [0.00037937, 0.00041521, 0.00053066, -3.5e-7, -9.9e-7, -1.037e-5] };
}

/// Agreement with Pinocchio, relative to the quantity's largest entry.
const TOLERANCE: f64 = 1e-12;

/// The step and the agreement, relative to the largest entry, of the
/// central differences that check the floating arm's derivatives.
const STEP: f64 = 1e-6;
const DIFFERENCES: f64 = 1e-7;

fn numbers(value: &Value) -> Vec<f64> {
    match value {
        Value::Array(entries) => entries.iter().flat_map(numbers).collect(),
        _ => vec![value.as_f64().expect("a number")],
    }
}

fn array<const N: usize>(value: &Value) -> [f64; N] {
    numbers(value).try_into().expect("the model's size")
}

/// `got` against the reference's `key` (matrices row by row).
fn check(what: &str, got: &[f64], state: &Value, key: &str) {
    assert_close(
        &format!("{what}: {key}"),
        got,
        &numbers(&state[key]),
        TOLERANCE,
    );
}

/// A link's origin and frame outputs, by their method names, against the
/// reference's entry for the link's frame.
macro_rules! check_link {
    (
        $system:expr, $frames:expr, $frame:literal,
        [$position:ident, $velocity:ident, $acceleration:ident, $jacobian:ident],
        [$rotation:ident, $angular_velocity:ident, $angular_jacobian:ident],
        ($t:expr, $q:expr, $v:expr, $a:expr)
    ) => {{
        let expected = &$frames[$frame];
        check($frame, &$system.$position($t, $q), expected, "position");
        check($frame, &$system.$velocity($t, $q, $v), expected, "velocity");
        check(
            $frame,
            &$system.$acceleration($t, $q, $v, $a),
            expected,
            "acceleration",
        );
        check(
            $frame,
            &flat(&$system.$jacobian($t, $q)),
            expected,
            "jacobian",
        );
        check(
            $frame,
            &flat(&$system.$rotation($t, $q)),
            expected,
            "rotation",
        );
        check(
            $frame,
            &$system.$angular_velocity($t, $q, $v),
            expected,
            "angular_velocity",
        );
        check(
            $frame,
            &flat(&$system.$angular_jacobian($t, $q)),
            expected,
            "angular_jacobian",
        );
    }};
}

/// The three links' outputs against the reference.
macro_rules! check_links {
    ($system:expr, $frames:expr, $state:tt) => {{
        check_link!(
            $system,
            $frames,
            "link03",
            [
                position_link03_origin,
                velocity_link03_origin,
                acceleration_link03_origin,
                jacobian_link03_origin
            ],
            [
                rotation_link03,
                angular_velocity_link03,
                angular_jacobian_link03
            ],
            $state
        );
        check_link!(
            $system,
            $frames,
            "link06",
            [
                position_link06_origin,
                velocity_link06_origin,
                acceleration_link06_origin,
                jacobian_link06_origin
            ],
            [
                rotation_link06,
                angular_velocity_link06,
                angular_jacobian_link06
            ],
            $state
        );
        check_link!(
            $system,
            $frames,
            "gripperMover",
            [
                position_gripperMover_origin,
                velocity_gripperMover_origin,
                acceleration_gripperMover_origin,
                jacobian_gripperMover_origin
            ],
            [
                rotation_gripperMover,
                angular_velocity_gripperMover,
                angular_jacobian_gripperMover
            ],
            $state
        );
    }};
}

#[test]
fn fixed_z1_matches_pinocchio() {
    let document = reference("z1_outputs.json");
    let z1 = FixedZ1 {};
    for state in document["fixed"].as_array().expect("states") {
        let (q, v, vdot, tau) = (
            array::<7>(&state["q"]),
            array::<7>(&state["v"]),
            array::<7>(&state["vdot"]),
            array::<7>(&state["tau"]),
        );
        let zero = [0.0; 7];
        check(
            "fixed",
            &z1.inverse_dynamics(0.0, &q, &v, &vdot, &zero),
            state,
            "rnea",
        );
        let (dq, dv, da) = z1.inverse_dynamics_jacobian(0.0, &q, &v, &vdot, &zero);
        check("fixed", &flat(&dq), state, "dtau_dq");
        check("fixed", &flat(&dv), state, "dtau_dv");
        check("fixed", &flat(&da), state, "dtau_da");
        let accelerations = dalembert::accelerations(&z1, 0.0, &q, &v, &tau).expect("regular");
        check("fixed", &accelerations, state, "aba");
        let (dq, dv, du) = z1
            .accelerations_jacobian(0.0, &q, &v, &tau)
            .expect("regular");
        check("fixed", &flat(&dq), state, "ddq_dq");
        check("fixed", &flat(&dv), state, "ddq_dv");
        check("fixed", &flat(&du), state, "ddq_dtau");
        check_links!(z1, &state["frames"], (0.0, &q, &v, &vdot));
    }
}

#[test]
fn floating_z1_matches_pinocchio() {
    let document = reference("z1_outputs.json");
    let z1 = FloatingZ1 {};
    for state in document["floating"].as_array().expect("states") {
        let (q, v, vdot) = (
            array::<14>(&state["q"]),
            array::<13>(&state["v"]),
            array::<13>(&state["vdot"]),
        );
        let tau: [f64; 13] = array(&state["tau"]);
        let joint_torques: [f64; 7] = std::array::from_fn(|i| tau[6 + i]);
        check(
            "floating",
            &z1.inverse_dynamics(0.0, &q, &v, &vdot, &[0.0; 7]),
            state,
            "rnea",
        );
        let accelerations =
            dalembert::accelerations(&z1, 0.0, &q, &v, &joint_torques).expect("regular");
        check("floating", &accelerations, state, "aba");
        check_links!(z1, &state["frames"], (0.0, &q, &v, &vdot));
    }
}

/// The floating arm's `inverse_dynamics_jacobian` is a body of some 3600
/// temporaries, which this test builds in the default `dev` profile with
/// full debug information (each temporary a `let` of its own, nested one
/// scope a `let`, overflowed rustc's stack): against central differences
/// of its `inverse_dynamics`, by `q` along `integrate_configuration` (the
/// tangent space), by `v`, and by `v̇` against the mass matrix.
#[test]
fn floating_z1_inverse_dynamics_jacobian_matches_central_differences() {
    use dalembert::MultibodySystem;
    use dalembert_fixtures::differences::central_differences;
    let document = reference("z1_outputs.json");
    let z1 = FloatingZ1 {};
    let u = [0.0; 7];
    for state in document["floating"]
        .as_array()
        .expect("states")
        .iter()
        .take(3)
    {
        let (q, v, vdot) = (
            array::<14>(&state["q"]),
            array::<13>(&state["v"]),
            array::<13>(&state["vdot"]),
        );
        let (by_q, by_v, by_vdot) = z1.inverse_dynamics_jacobian(0.0, &q, &v, &vdot, &u);
        let along = central_differences(&[0.0; 13], STEP, |delta| {
            z1.inverse_dynamics(
                0.0,
                &z1.integrate_configuration(&q, delta, 1.0),
                &v,
                &vdot,
                &u,
            )
        });
        assert_close("∂τ/∂q", &flat(&by_q), &flat(&along), DIFFERENCES);
        let by_speeds =
            central_differences(&v, STEP, |v| z1.inverse_dynamics(0.0, &q, v, &vdot, &u));
        assert_close("∂τ/∂v", &flat(&by_v), &flat(&by_speeds), DIFFERENCES);
        let mass = MultibodySystem::mass_matrix(&z1, &q);
        assert_close("∂τ/∂v̇", &flat(&by_vdot), &flat(&mass), 1e-12);
    }
}
