//! The numeric algebra of the import: rotations from URDF's roll, pitch,
//! yaw, rigid placements and their composition, and mass properties moved
//! between frames and merged (parallel-axis theorem) when a fixed joint
//! welds a link to its parent's body. Also the physical checks on a body's
//! inertia: a tensor that is positive semi-definite and whose principal
//! moments satisfy the triangle inequality, up to rounding.

pub(crate) type Vec3 = [f64; 3];
pub(crate) type Mat3 = [[f64; 3]; 3];

const IDENTITY: Mat3 = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

/// The rotation of URDF's `rpy`: fixed-axis roll about x, then pitch
/// about y, then yaw about z, `R = Rz(yaw) Ry(pitch) Rx(roll)` (the
/// body-fixed sequence z, y, x).
pub(super) fn rotation_rpy([roll, pitch, yaw]: Vec3) -> Mat3 {
    let (sr, cr) = roll.sin_cos();
    let (sp, cp) = pitch.sin_cos();
    let (sy, cy) = yaw.sin_cos();
    [
        [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
        [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
        [-sp, cp * sr, cp * cr],
    ]
}

fn mat_mul(a: &Mat3, b: &Mat3) -> Mat3 {
    let mut c = [[0.0; 3]; 3];
    for (i, row) in c.iter_mut().enumerate() {
        for (j, entry) in row.iter_mut().enumerate() {
            *entry = (0..3).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    c
}

fn transpose(a: &Mat3) -> Mat3 {
    let mut t = [[0.0; 3]; 3];
    for (i, row) in a.iter().enumerate() {
        for (j, &x) in row.iter().enumerate() {
            t[j][i] = x;
        }
    }
    t
}

fn apply(a: &Mat3, v: &Vec3) -> Vec3 {
    [0, 1, 2].map(|i| (0..3).map(|k| a[i][k] * v[k]).sum())
}

/// `R I Rᵀ`: a tensor given in rotated axes, expressed in the original ones.
fn rotate_tensor(r: &Mat3, tensor: &Mat3) -> Mat3 {
    mat_mul(&mat_mul(r, tensor), &transpose(r))
}

/// A frame's placement in another: its origin and its axes (columns of
/// `rotation`) in the other frame's axes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Placement {
    pub rotation: Mat3,
    pub translation: Vec3,
}

impl Placement {
    pub const IDENTITY: Placement = Placement {
        rotation: IDENTITY,
        translation: [0.0; 3],
    };

    /// The placement of a URDF `<origin xyz rpy>`.
    pub fn from_xyz_rpy(xyz: Vec3, rpy: Vec3) -> Placement {
        Placement {
            rotation: rotation_rpy(rpy),
            translation: xyz,
        }
    }

    /// `self ∘ inner`: where a frame placed by `inner` in this frame is.
    pub fn then(&self, inner: &Placement) -> Placement {
        let moved = apply(&self.rotation, &inner.translation);
        Placement {
            rotation: mat_mul(&self.rotation, &inner.rotation),
            translation: [0, 1, 2].map(|i| self.translation[i] + moved[i]),
        }
    }
}

/// Mass, centre of mass and central inertia tensor, in some frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct MassProperties {
    pub mass: f64,
    pub center: Vec3,
    pub inertia: Mat3,
}

impl MassProperties {
    pub const NONE: MassProperties = MassProperties {
        mass: 0.0,
        center: [0.0; 3],
        inertia: [[0.0; 3]; 3],
    };

    /// The mass properties of a URDF `<inertial>`, given in the frame
    /// `origin` places in the link frame, expressed in the link frame.
    pub fn from_inertial(origin: &Placement, mass: f64, inertia: &Mat3) -> MassProperties {
        MassProperties {
            mass,
            center: origin.translation,
            inertia: rotate_tensor(&origin.rotation, inertia),
        }
    }

    /// The same body, expressed in the frame where `placement` places the
    /// frame these properties are given in.
    pub fn placed(&self, placement: &Placement) -> MassProperties {
        MassProperties {
            mass: self.mass,
            center: placement
                .then(&Placement {
                    rotation: IDENTITY,
                    translation: self.center,
                })
                .translation,
            inertia: rotate_tensor(&placement.rotation, &self.inertia),
        }
    }

    /// The rigid union of two bodies given in the same frame: total mass,
    /// centre of mass, and the inertia about that centre by the
    /// parallel-axis theorem.
    pub fn merged(&self, other: &MassProperties) -> MassProperties {
        // An empty side leaves the other exactly as it is.
        if self.is_empty() {
            return *other;
        }
        if other.is_empty() {
            return *self;
        }
        let mass = self.mass + other.mass;
        if mass == 0.0 {
            return MassProperties {
                mass,
                center: self.center,
                inertia: add(&self.inertia, &other.inertia),
            };
        }
        let center =
            [0, 1, 2].map(|i| (self.mass * self.center[i] + other.mass * other.center[i]) / mass);
        let shifted = |body: &MassProperties| {
            add(
                &body.inertia,
                &steiner(body.mass, &sub(&body.center, &center)),
            )
        };
        MassProperties {
            mass,
            center,
            inertia: add(&shifted(self), &shifted(other)),
        }
    }

    /// Whether the body has no mass and no inertia.
    pub fn is_empty(&self) -> bool {
        self.mass == 0.0 && self.inertia.iter().flatten().all(|&x| x == 0.0)
    }
}

fn add(a: &Mat3, b: &Mat3) -> Mat3 {
    [0, 1, 2].map(|i| [0, 1, 2].map(|j| a[i][j] + b[i][j]))
}

fn sub(a: &Vec3, b: &Vec3) -> Vec3 {
    [0, 1, 2].map(|i| a[i] - b[i])
}

/// The inertia of a point mass `m` at offset `d`: `m (|d|² 1 − d dᵀ)`.
fn steiner(m: f64, d: &Vec3) -> Mat3 {
    let d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    [0, 1, 2].map(|i| [0, 1, 2].map(|j| m * (if i == j { d2 } else { 0.0 } - d[i] * d[j])))
}

/// What is physically wrong with an inertia tensor, if anything.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum InertiaFault {
    /// A principal moment is negative.
    NotPositiveSemiDefinite { moments: Vec3 },
    /// A principal moment exceeds the sum of the other two.
    TriangleInequality { moments: Vec3 },
}

/// Relative tolerance of the checks, against the trace: URDF files print
/// inertias rounded to a few digits, so a thin rod or plate sits on the
/// boundary up to rounding.
const TOLERANCE: f64 = 1e-9;

/// Absolute tolerance of the checks, in kg m²: the moments of a tensor that
/// is zero up to rounding (iCub's head lists entries of 1e-35) are noise
/// whatever their signs. A gram at a micrometre has 1e-15.
const NEGLIGIBLE: f64 = 1e-15;

/// How far a principal moment of a tensor with these `moments` may be off
/// and still count as rounding.
fn slack(moments: &Vec3) -> f64 {
    TOLERANCE * moments.iter().map(|m| m.abs()).sum::<f64>() + NEGLIGIBLE
}

/// `tensor` with its rounding written as zero, and nothing else changed (as
/// Pinocchio keeps every entry): entries below [`NEGLIGIBLE`] (iCub's head
/// lists 1e-35), and a negative diagonal entry within the checks' slack,
/// which the language would refuse as a negative moment (`-5e-20` at
/// iCub's hips). A product of inertia far below the moments but above
/// [`NEGLIGIBLE`] is kept: `-3.854e-13` beside `1.2e-3` (the double
/// pendulum of example-robot-data) moves `M` by 1e-12 of its largest entry.
pub(crate) fn without_rounding(tensor: &Mat3) -> Mat3 {
    let slack = slack(&principal_moments(tensor));
    let mut cleaned = tensor.map(|row| row.map(|x| if x.abs() <= NEGLIGIBLE { 0.0 } else { x }));
    for (k, row) in cleaned.iter_mut().enumerate() {
        if (-slack..0.0).contains(&row[k]) {
            row[k] = 0.0;
        }
    }
    cleaned
}

/// Checks that `tensor` is the inertia of some mass distribution: its
/// principal moments are non-negative and each is at most the sum of the
/// other two.
pub(crate) fn check_inertia(tensor: &Mat3) -> Result<(), InertiaFault> {
    let moments = principal_moments(tensor);
    let slack = slack(&moments);
    if moments.iter().any(|&m| m < -slack) {
        return Err(InertiaFault::NotPositiveSemiDefinite { moments });
    }
    let total: f64 = moments.iter().sum();
    if moments.iter().any(|&m| total - m < m - slack) {
        return Err(InertiaFault::TriangleInequality { moments });
    }
    Ok(())
}

/// The eigenvalues of the symmetric `tensor`, ascending (cyclic Jacobi
/// rotations: exact enough for a check and short).
fn principal_moments(tensor: &Mat3) -> Vec3 {
    let mut a = *tensor;
    for _ in 0..50 {
        let off = a[0][1].abs() + a[0][2].abs() + a[1][2].abs();
        if off == 0.0 {
            break;
        }
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            if a[p][q] == 0.0 {
                continue;
            }
            let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
            let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
            let t = if theta == 0.0 { 1.0 } else { t };
            let c = 1.0 / (t * t + 1.0).sqrt();
            let s = t * c;
            let mut j = IDENTITY;
            j[p][p] = c;
            j[q][q] = c;
            j[p][q] = s;
            j[q][p] = -s;
            a = mat_mul(&transpose(&j), &mat_mul(&a, &j));
        }
    }
    let mut moments = [a[0][0], a[1][1], a[2][2]];
    moments.sort_by(f64::total_cmp);
    moments
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: &Mat3, b: &Mat3) -> bool {
        a.iter()
            .flatten()
            .zip(b.iter().flatten())
            .all(|(x, y)| (x - y).abs() < 1e-14)
    }

    #[test]
    fn rpy_is_the_fixed_axis_sequence() {
        // Roll a quarter turn about x: y goes to z.
        let r = rotation_rpy([std::f64::consts::FRAC_PI_2, 0.0, 0.0]);
        assert!(close(
            &r,
            &[[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]]
        ));
        // Roll then yaw (fixed axes): x stays on x by the roll, then goes to y.
        let r = rotation_rpy([
            std::f64::consts::FRAC_PI_2,
            0.0,
            std::f64::consts::FRAC_PI_2,
        ]);
        assert!((apply(&r, &[1.0, 0.0, 0.0])[1] - 1.0).abs() < 1e-15);
        // and z goes to −y by the roll, then to x by the yaw.
        assert!((apply(&r, &[0.0, 0.0, 1.0])[0] - 1.0).abs() < 1e-15);
    }

    #[test]
    fn merging_two_point_masses_gives_the_dumbbell() {
        let point = |x: f64| MassProperties {
            mass: 1.0,
            center: [x, 0.0, 0.0],
            inertia: [[0.0; 3]; 3],
        };
        let both = point(-1.0).merged(&point(1.0));
        assert_eq!(both.mass, 2.0);
        assert_eq!(both.center, [0.0; 3]);
        assert_eq!(
            both.inertia,
            [[0.0, 0.0, 0.0], [0.0, 2.0, 0.0], [0.0, 0.0, 2.0]]
        );
    }

    #[test]
    fn placing_rotates_the_tensor_and_moves_the_center() {
        let rod = MassProperties {
            mass: 3.0,
            center: [1.0, 0.0, 0.0],
            inertia: [[0.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        };
        // A quarter turn about z and a shift along z.
        let placement =
            Placement::from_xyz_rpy([0.0, 0.0, 2.0], [0.0, 0.0, std::f64::consts::FRAC_PI_2]);
        let placed = rod.placed(&placement);
        assert!((placed.center[1] - 1.0).abs() < 1e-15 && placed.center[2] == 2.0);
        assert!(close(
            &placed.inertia,
            &[[1.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 1.0]]
        ));
    }

    #[test]
    fn checks_the_physical_inertias() {
        assert_eq!(
            check_inertia(&[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 2.0]]),
            Ok(())
        );
        assert!(matches!(
            check_inertia(&[[1.0, 2.0, 0.0], [2.0, 1.0, 0.0], [0.0, 0.0, 1.0]]),
            Err(InertiaFault::NotPositiveSemiDefinite { .. })
        ));
        assert!(matches!(
            check_inertia(&[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 3.0]]),
            Err(InertiaFault::TriangleInequality { .. })
        ));
        // Zero up to rounding, as iCub's head: no fault, whatever the signs.
        assert_eq!(
            check_inertia(&[[2.4e-35, 0.0, 0.0], [0.0, -2.4e-35, 0.0], [0.0, 0.0, 0.0]]),
            Ok(())
        );
        assert_eq!(
            without_rounding(&[[-5e-20, 0.0, 1e-30], [0.0, -5e-20, 0.0], [1e-30, 0.0, 0.0]]),
            [[0.0; 3]; 3]
        );
        let kept = [[1.0, 1e-3, 0.0], [1e-3, 2.0, 0.0], [0.0, 0.0, 2.5]];
        assert_eq!(without_rounding(&kept), kept);
        // A product far below the moments is data, not rounding (the double
        // pendulum's link2); a negative moment within rounding is zero.
        let small = [
            [1.2e-3, -3.9e-13, 0.0],
            [-3.9e-13, 1.2e-3, 0.0],
            [0.0, 0.0, 1.5e-5],
        ];
        assert_eq!(without_rounding(&small), small);
        assert_eq!(
            without_rounding(&[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, -1e-12]]),
            [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 0.0]]
        );
        let moments = principal_moments(&[[2.0, 1.0, 0.0], [1.0, 2.0, 0.0], [0.0, 0.0, 5.0]]);
        assert!((moments[0] - 1.0).abs() < 1e-14 && (moments[1] - 3.0).abs() < 1e-14);
    }
}
