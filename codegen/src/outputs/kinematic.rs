//! Kinematic outputs: where a point is and how it moves, how a frame is
//! turned and how fast it turns, and their Jacobians with respect to the
//! speeds — every vector measured in `N` and given in the axes the request
//! names (`N`'s unless `in F`).

use super::{Argument, Body, Function, Value, doc_lines};
use crate::expr::{ExprId, Pool, Sym};
use crate::kinematics::{Kinematics, Vec3};
use crate::model::{FrameId, Model, NEWTONIAN, Output, OutputKind};

use Argument::{Accelerations, Coordinates, Speeds, Time};

/// The function computing `output`, if it is a kinematic one.
pub fn function(
    model: &Model,
    kinematics: &Kinematics,
    pool: &mut Pool,
    output: &Output,
) -> Option<Function> {
    let nv = model.nv();
    let axes = Axes {
        model,
        kinematics,
        to: output.axes,
    };
    let (arguments, value, what): (&[Argument], Value, &str) = match output.kind {
        OutputKind::Position(p) => {
            let r = axes.convert_newtonian(pool, &kinematics.position(p));
            (
                &[Time, Coordinates],
                Value::vector(r.to_vec()),
                "The position of `{P}` from `O`, in `{F}`'s axes.",
            )
        }
        OutputKind::Velocity(p) => {
            let v = kinematics.velocity(pool, p);
            let v = axes.convert_newtonian(pool, &v);
            let arguments = &[Time, Coordinates, Speeds];
            (
                arguments,
                Value::vector(v.to_vec()),
                "The velocity of `{P}` in `N`, in `{F}`'s axes.",
            )
        }
        OutputKind::Acceleration(p) => {
            let mut a = kinematics.acceleration_bias(pool, p);
            for k in 0..nv {
                let partial = kinematics.partial_velocity(pool, p, k);
                let rate = pool.sym(Sym::Accel(k as u32));
                a = [0, 1, 2].map(|i| {
                    let term = pool.mul(partial[i], rate);
                    pool.add(a[i], term)
                });
            }
            let a = axes.convert_newtonian(pool, &a);
            let arguments = &[Time, Coordinates, Speeds, Accelerations];
            let what = "The acceleration of `{P}` in `N` (`J v̇ + J̇ v`), in `{F}`'s axes.";
            (arguments, Value::vector(a.to_vec()), what)
        }
        OutputKind::Jacobian(p) => {
            let columns: Vec<Vec3> = (0..nv)
                .map(|k| {
                    let partial = kinematics.partial_velocity(pool, p, k);
                    axes.convert_newtonian(pool, &partial)
                })
                .collect();
            let what = "The Jacobian `J` of `{P}`'s velocity by the speeds (`v = J q̇`), in\n\
                        `{F}`'s axes: row `i` holds the partials of component `i`.";
            (&[Time, Coordinates], transposed(&columns, nv), what)
        }
        OutputKind::Rotation(f) => {
            let columns: Vec<Vec3> = (0..3)
                .map(|j| {
                    let mut unit = [pool.zero(); 3];
                    unit[j] = pool.one();
                    axes.convert(pool, f, &unit)
                })
                .collect();
            let what = "The rotation matrix of `{P}`: it maps `{P}`'s components to `{F}`'s.";
            (&[Time, Coordinates], transposed(&columns, 3), what)
        }
        OutputKind::AngularVelocity(f) => {
            let omega = axes.convert(pool, f, &kinematics.angular_velocity(f));
            let arguments = &[Time, Coordinates, Speeds];
            (
                arguments,
                Value::vector(omega.to_vec()),
                "The angular velocity of `{P}` in `N`, in `{F}`'s axes.",
            )
        }
        OutputKind::AngularJacobian(f) => {
            let columns: Vec<Vec3> = (0..nv)
                .map(|k| {
                    let partial = kinematics.partial_angular_velocity(pool, f, k);
                    axes.convert(pool, f, &partial)
                })
                .collect();
            let what = "The Jacobian `J` of `{P}`'s angular velocity by the speeds (`ω = J q̇`),\n\
                        in `{F}`'s axes: row `i` holds the partials of component `i`.";
            (&[Time, Coordinates], transposed(&columns, nv), what)
        }
        OutputKind::InverseDynamics
        | OutputKind::Regressor
        | OutputKind::InverseDynamicsJacobian
        | OutputKind::InverseDynamicsAdjoint
        | OutputKind::AccelerationsJacobian
        | OutputKind::Linearize
        | OutputKind::AccelerationsX4
        | OutputKind::Taylor => return None,
    };
    let subject = output.subject.as_deref().unwrap_or_default();
    let docs = what
        .replace("{P}", subject)
        .replace("{F}", &output.axes_name);
    Some(Function {
        name: output.function.clone(),
        docs: doc_lines(&docs),
        arguments: arguments.to_vec(),
        results: vec![value],
        body: Body::Explicit,
    })
}

/// A `3 × n` matrix from its `n` columns.
fn transposed(columns: &[Vec3], n: usize) -> Value {
    let rows: Vec<Vec<ExprId>> = (0..3)
        .map(|i| columns.iter().map(|c| c[i]).collect())
        .collect();
    Value::matrix(&rows, n)
}

/// The axes an output is given in.
struct Axes<'a> {
    model: &'a Model,
    kinematics: &'a Kinematics,
    to: FrameId,
}

impl Axes<'_> {
    /// Components given in `N`'s axes, in the output's.
    fn convert_newtonian(&self, pool: &mut Pool, c: &Vec3) -> Vec3 {
        self.convert(pool, NEWTONIAN, c)
    }

    /// Components given in `frame`'s axes, in the output's.
    fn convert(&self, pool: &mut Pool, frame: FrameId, c: &Vec3) -> Vec3 {
        if frame == self.to {
            return *c;
        }
        self.kinematics
            .rotate_between(pool, self.model, frame, self.to, c)
    }
}
