//! The UR5 of `tests/reference/urdf/ur5_robot.urdf`, shared by the DDP
//! example and its test: the model as
//! `dalembert urdf tests/reference/urdf/ur5_robot.urdf --name Ur5 --outputs
//! "accelerations_jacobian, inverse_dynamics_adjoint, position(tool0_origin),
//! rotation(tool0), jacobian(tool0_origin), angular_jacobian(tool0)"` prints
//! it (its comment lines left out), with the tool flange `tool0`'s pose
//! outputs, the derivatives of its accelerations and the adjoint of its
//! inverse dynamics.

use dalembert_lab::pose::FrameOutputs;

dalembert::dalembert! {
    /// The UR5 with the derivatives of its dynamics and the tool flange's
    /// position, rotation and jacobians.
    pub Ur5 {
        coordinates shoulder_pan_joint, shoulder_lift_joint, elbow_joint, wrist_1_joint, wrist_2_joint, wrist_3_joint;
        inputs tau_shoulder_pan_joint, tau_shoulder_lift_joint, tau_elbow_joint, tau_wrist_1_joint, tau_wrist_2_joint, tau_wrist_3_joint;
        frame world = N.rotate_z(0);
        point world_origin = O;
        frame base_link = world.rotate_z(0);
        point base_link_origin = world_origin;
        frame base = base_link.rotate_z(-3.14159265359);
        point base_origin = base_link_origin;
        joint revolute shoulder_link_origin { parent: base_link, child: shoulder_link, axis: z, coordinate: shoulder_pan_joint, at: base_link_origin + 0.089159 * base_link.z };
        body shoulder_link_body { mass: 3.7, center: shoulder_link_origin, frame: shoulder_link, inertia: [0.010267495893, 0.010267495893, 0.00666] };
        torque tau_shoulder_pan_joint * base_link.z on shoulder_link reacting base_link;
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
        frame ee_link = wrist_3_link.rotate_z(1.57079632679);
        point ee_link_origin = wrist_3_link_origin + 0.0823 * wrist_3_link.y;
        frame tool0 = wrist_3_link.rotate_x(-1.57079632679);
        point tool0_origin = wrist_3_link_origin + 0.0823 * wrist_3_link.y;
        gravity -9.81 * N.z;
        outputs accelerations_jacobian, inverse_dynamics_adjoint, position(tool0_origin), rotation(tool0), jacobian(tool0_origin), angular_jacobian(tool0);
    }
}

dalembert::differentiable!(Ur5; inverse);

/// The tool flange `tool0`'s outputs, for its pose costs.
pub fn tool() -> FrameOutputs<Ur5, 6, 6> {
    FrameOutputs {
        position: Ur5::position_tool0_origin,
        rotation: Ur5::rotation_tool0,
        jacobian: Ur5::jacobian_tool0_origin,
        angular_jacobian: Ur5::angular_jacobian_tool0,
    }
}

/// The torques that hold the arm still at `q` against gravity,
/// `−f(q, 0, 0)`: the DDP's first guess on the pose reach (and Crocoddyl's).
pub fn holding(q: &[f64; 6]) -> [f64; 6] {
    Ur5 {}.forcing(0.0, q, &[0.0; 6], &[0.0; 6]).map(|f| -f)
}
