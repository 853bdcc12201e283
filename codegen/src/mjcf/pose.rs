//! MuJoCo's numeric rules, computed as its compiler computes them: unit
//! quaternions `(w, x, y, z)` from the orientation alternatives (`quat`,
//! `axisangle`, `euler` with `eulerseq`, `xyaxes`, `zaxis`, a geom's
//! `fromto`), and the volume, mass and central inertia of the primitive
//! geoms (`mjCGeom::GetVolume`, `SetInertia`).

use std::f64::consts::PI;

use crate::rigid::{cross, quaternion_rotation};
use crate::urdf::inertia::{Mat3, Vec3};

/// A quaternion `(w, x, y, z)`, MuJoCo's order.
pub(super) type Quat = [f64; 4];

/// The identity rotation.
pub(super) const IDENTITY: Quat = [1.0, 0.0, 0.0, 0.0];

/// MuJoCo's `mjEPS`.
pub(super) const EPS: f64 = 1e-14;

/// `v / |v|` and `|v|` (`v` unchanged when it is zero), as `mjuu_normvec`.
pub(super) fn normalized<const N: usize>(v: [f64; N]) -> ([f64; N], f64) {
    let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
    if norm < 1e-15 {
        return (v, norm);
    }
    (v.map(|x| x / norm), norm)
}

/// The Hamilton product `a b`.
pub(super) fn mul(a: Quat, b: Quat) -> Quat {
    [
        a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
        a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
        a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
        a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0],
    ]
}

/// The rotation matrix of the unit quaternion `q` (columns: the rotated
/// frame's axes in the original's).
pub(super) fn matrix([w, x, y, z]: Quat) -> Mat3 {
    quaternion_rotation([x, y, z, w])
}

/// The axis and angle of the unit quaternion `q` (angle in `[0, 2π)`,
/// axis `z` for the identity).
pub(super) fn axis_angle(q: Quat) -> (Vec3, f64) {
    let (axis, s) = normalized([q[1], q[2], q[3]]);
    if s == 0.0 {
        return ([0.0, 0.0, 1.0], 0.0);
    }
    (axis, 2.0 * s.atan2(q[0]))
}

/// `axisangle="x y z a"` (`a` in radians).
pub(super) fn from_axis_angle(axis: Vec3, angle: f64) -> Option<Quat> {
    let (axis, norm) = normalized(axis);
    if norm < EPS {
        return None;
    }
    let (s, c) = (angle / 2.0).sin_cos();
    Some([c, s * axis[0], s * axis[1], s * axis[2]])
}

/// `euler="a b c"` (radians) turned in the sequence `sequence`: lower
/// case about the moving axes, upper case about the fixed ones.
pub(super) fn from_euler(angles: Vec3, sequence: &[u8; 3]) -> Quat {
    let mut q = IDENTITY;
    for (angle, axis) in angles.into_iter().zip(sequence) {
        let (s, c) = (angle / 2.0).sin_cos();
        let mut turn = [c, 0.0, 0.0, 0.0];
        turn[1 + (axis.to_ascii_lowercase() - b'x') as usize] = s;
        q = if axis.is_ascii_lowercase() {
            mul(q, turn)
        } else {
            mul(turn, q)
        };
    }
    normalized(q).0
}

/// `xyaxes="x1 x2 x3 y1 y2 y3"`: `y` made orthogonal to `x`; `None` when
/// an axis is too small.
pub(super) fn from_xy_axes(axes: [f64; 6]) -> Option<Quat> {
    let (x, nx) = normalized([axes[0], axes[1], axes[2]]);
    if nx < EPS {
        return None;
    }
    let d = x[0] * axes[3] + x[1] * axes[4] + x[2] * axes[5];
    let (y, ny) = normalized([axes[3] - x[0] * d, axes[4] - x[1] * d, axes[5] - x[2] * d]);
    if ny < EPS {
        return None;
    }
    let (z, nz) = normalized(cross(x, y));
    if nz < EPS {
        return None;
    }
    Some(from_frame(x, y, z))
}

/// The quaternion of the frame whose axes are `x`, `y`, `z`
/// (`mjuu_frame2quat`).
fn from_frame(x: Vec3, y: Vec3, z: Vec3) -> Quat {
    let m = [x, y, z]; // m[column][row]
    let q = if m[0][0] + m[1][1] + m[2][2] > 0.0 {
        let w = 0.5 * (1.0 + m[0][0] + m[1][1] + m[2][2]).sqrt();
        [
            w,
            0.25 * (m[1][2] - m[2][1]) / w,
            0.25 * (m[2][0] - m[0][2]) / w,
            0.25 * (m[0][1] - m[1][0]) / w,
        ]
    } else if m[0][0] > m[1][1] && m[0][0] > m[2][2] {
        let x = 0.5 * (1.0 + m[0][0] - m[1][1] - m[2][2]).sqrt();
        [
            0.25 * (m[1][2] - m[2][1]) / x,
            x,
            0.25 * (m[1][0] + m[0][1]) / x,
            0.25 * (m[2][0] + m[0][2]) / x,
        ]
    } else if m[1][1] > m[2][2] {
        let y = 0.5 * (1.0 - m[0][0] + m[1][1] - m[2][2]).sqrt();
        [
            0.25 * (m[2][0] - m[0][2]) / y,
            0.25 * (m[1][0] + m[0][1]) / y,
            y,
            0.25 * (m[2][1] + m[1][2]) / y,
        ]
    } else {
        let z = 0.5 * (1.0 - m[0][0] - m[1][1] + m[2][2]).sqrt();
        [
            0.25 * (m[0][1] - m[1][0]) / z,
            0.25 * (m[2][0] + m[0][2]) / z,
            0.25 * (m[2][1] + m[1][2]) / z,
            z,
        ]
    };
    normalized(q).0
}

/// The minimal rotation taking `z` to the direction `v` (`mjuu_z2quat`);
/// `None` when `v` is too small.
pub(super) fn from_z_axis(v: Vec3) -> Option<Quat> {
    let (v, norm) = normalized(v);
    if norm < EPS {
        return None;
    }
    Some(z_to(v))
}

/// `mjuu_z2quat` of `v`.
fn z_to(v: Vec3) -> Quat {
    let (mut axis, s) = normalized(cross([0.0, 0.0, 1.0], v));
    if s < 1e-10 {
        axis = [1.0, 0.0, 0.0];
    }
    let angle = s.atan2(v[2]);
    let (sin, cos) = (angle / 2.0).sin_cos();
    [cos, axis[0] * sin, axis[1] * sin, axis[2] * sin]
}

/// A geom's `fromto`: its centre, orientation (z from `to` towards
/// `from`, as MuJoCo takes it) and half-length; `None` when the two points
/// are too close.
pub(super) fn from_to(ends: [f64; 6]) -> Option<(Vec3, Quat, f64)> {
    let v = [ends[0] - ends[3], ends[1] - ends[4], ends[2] - ends[5]];
    let (unit, length) = normalized(v);
    let half = length / 2.0;
    if half < EPS {
        return None;
    }
    let center = [0, 1, 2].map(|i| (ends[i] + ends[i + 3]) / 2.0);
    Some((center, z_to(unit), half))
}

/// The primitive shapes whose mass properties MuJoCo computes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Shape {
    Sphere,
    Capsule,
    Cylinder,
    Ellipsoid,
    Box,
}

impl Shape {
    /// The volume of the shape of sizes `size` (radius, half-length,
    /// semi-axes or half-sides, as MuJoCo's `size`).
    pub fn volume(self, size: Vec3) -> f64 {
        match self {
            Shape::Sphere => 4.0 * PI * size[0] * size[0] * size[0] / 3.0,
            Shape::Capsule => {
                let (radius, height) = (size[0], 2.0 * size[1]);
                PI * (radius * radius * height + 4.0 * radius * radius * radius / 3.0)
            }
            Shape::Cylinder => PI * size[0] * size[0] * 2.0 * size[1],
            Shape::Ellipsoid => 4.0 * PI * size[0] * size[1] * size[2] / 3.0,
            Shape::Box => size[0] * size[1] * size[2] * 8.0,
        }
    }

    /// The principal moments of a solid of mass `mass` about its centre,
    /// in its own axes.
    pub fn inertia(self, mass: f64, size: Vec3) -> Vec3 {
        match self {
            Shape::Sphere => [2.0 * mass * size[0] * size[0] / 5.0; 3],
            Shape::Capsule => {
                let (radius, height) = (size[0], 2.0 * size[1]);
                let sphere_mass = mass * 4.0 * radius / (4.0 * radius + 3.0 * height);
                let cylinder_mass = mass - sphere_mass;
                let sphere = 2.0 * sphere_mass * radius * radius / 5.0;
                let across = cylinder_mass * (3.0 * radius * radius + height * height) / 12.0
                    + sphere
                    + sphere_mass * height * (3.0 * radius + 2.0 * height) / 8.0;
                [
                    across,
                    across,
                    cylinder_mass * radius * radius / 2.0 + sphere,
                ]
            }
            Shape::Cylinder => {
                let (radius, height) = (size[0], 2.0 * size[1]);
                let across = mass * (3.0 * radius * radius + height * height) / 12.0;
                [across, across, mass * radius * radius / 2.0]
            }
            Shape::Ellipsoid | Shape::Box => {
                let divisor = if self == Shape::Box { 3.0 } else { 5.0 };
                let s = size.map(|x| x * x);
                [
                    mass * (s[1] + s[2]) / divisor,
                    mass * (s[0] + s[2]) / divisor,
                    mass * (s[0] + s[1]) / divisor,
                ]
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: &[f64], b: &[f64]) -> bool {
        a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-15)
    }

    #[test]
    fn orientations_agree_with_each_other() {
        let h = std::f64::consts::FRAC_1_SQRT_2;
        // A quarter turn about x, five ways.
        let expected = [h, h, 0.0, 0.0];
        let quarter = PI / 2.0;
        assert!(close(
            &from_axis_angle([2.0, 0.0, 0.0], quarter).unwrap(),
            &expected
        ));
        assert!(close(&from_euler([quarter, 0.0, 0.0], b"xyz"), &expected));
        assert!(close(
            &from_xy_axes([1.0, 0.0, 0.0, 0.0, 0.0, 1.0]).unwrap(),
            &expected
        ));
        assert!(close(&from_z_axis([0.0, -1.0, 0.0]).unwrap(), &expected));
        // Moving axes post-multiply, fixed axes pre-multiply.
        let (a, b) = (0.3, -0.7);
        let moving = from_euler([a, b, 0.0], b"xyz");
        let fixed = from_euler([b, a, 0.0], b"YXZ");
        assert!(close(&moving, &fixed));
        let (axis, angle) = axis_angle(expected);
        assert!(close(&axis, &[1.0, 0.0, 0.0]) && (angle - quarter).abs() < 1e-15);
        assert!(from_axis_angle([0.0; 3], 1.0).is_none());
    }

    #[test]
    fn fromto_points_z_from_the_far_end() {
        let (center, q, half) = from_to([0.0, 0.0, 0.0, 0.0, 0.0, 1.0]).unwrap();
        assert_eq!((center, half), ([0.0, 0.0, 0.5], 0.5));
        // z from `to` towards `from`: a half turn.
        assert!((matrix(q)[2][2] + 1.0).abs() < 1e-15);
    }

    #[test]
    fn a_capsule_is_a_cylinder_and_two_hemispheres() {
        // Independently: the hemispheres' centres of mass 3r/8 beyond the
        // cylinder's ends, their own moments across 83/320 m r².
        let (r, half) = (0.3, 0.7);
        let size = [r, half, 0.0];
        let density = 2.0;
        let cylinder_mass = density * PI * r * r * 2.0 * half;
        let sphere_mass = density * 4.0 * PI * r * r * r / 3.0;
        let mass = Shape::Capsule.volume(size) * density;
        assert!((mass - cylinder_mass - sphere_mass).abs() < 1e-14);
        let cylinder = Shape::Cylinder.inertia(cylinder_mass, size);
        let offset = half + 3.0 * r / 8.0;
        let across = cylinder[0] + sphere_mass * (83.0 / 320.0 * r * r + offset * offset);
        let along = cylinder[2] + 2.0 * sphere_mass * r * r / 5.0;
        let capsule = Shape::Capsule.inertia(mass, size);
        assert!(close(&capsule, &[across, across, along]), "{capsule:?}");
        assert_eq!(Shape::Box.inertia(3.0, [1.0, 2.0, 3.0]), [13.0, 10.0, 5.0]);
    }
}
