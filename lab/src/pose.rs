//! The pose error of a frame, as Crocoddyl's residuals measure it: the
//! translation `p − p*` (`ResidualModelFrameTranslation`) and the rotation
//! `log₃(R*ᵀ R)` (`ResidualModelFrameRotation`), with their jacobians by the
//! speeds from a system's generated kinematic outputs (`position(P)`,
//! `rotation(F)`, `jacobian(P)`, `angular_jacobian(F)`, all in `N`'s axes).
//!
//! The rotation's jacobian is Pinocchio's: `Jlog₃(R*ᵀ R) J_ω` with `J_ω`
//! the angular jacobian in the frame's own axes (`Rᵀ` times the generated
//! one), `log₃` and `Jlog₃` as `pinocchio/spatial/log.hxx` computes them
//! (the matrix renormalised first, Taylor series near zero, the axis from
//! the diagonal near π).

/// A 3 × 3 matrix as rows.
pub type Matrix3 = [[f64; 3]; 3];

/// The placement of a frame: its origin's position and the rotation taking
/// its components to `N`'s.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placement {
    /// The origin's position in `N`.
    pub position: [f64; 3],
    /// The rotation matrix, frame axes to `N`'s.
    pub rotation: Matrix3,
}

/// A frame's generated kinematic outputs on a system `S` with `NQ`
/// coordinates and `NV` speeds: `position_P`, `rotation_F`, `jacobian_P`,
/// `angular_jacobian_F` (for a URDF link `L`, `P = L_origin`, `F = L`).
pub struct FrameOutputs<S, const NQ: usize, const NV: usize> {
    /// `position_P(t, &q)`.
    pub position: fn(&S, f64, &[f64; NQ]) -> [f64; 3],
    /// `rotation_F(t, &q)`.
    pub rotation: fn(&S, f64, &[f64; NQ]) -> Matrix3,
    /// `jacobian_P(t, &q)`: `v_P = J v`.
    pub jacobian: fn(&S, f64, &[f64; NQ]) -> [[f64; NV]; 3],
    /// `angular_jacobian_F(t, &q)`: `ω_F = J v`.
    pub angular_jacobian: fn(&S, f64, &[f64; NQ]) -> [[f64; NV]; 3],
}

impl<S, const NQ: usize, const NV: usize> Clone for FrameOutputs<S, NQ, NV> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<S, const NQ: usize, const NV: usize> Copy for FrameOutputs<S, NQ, NV> {}

/// The translation and rotation errors of a frame from its target, and
/// their jacobians by the speeds.
#[derive(Clone, Copy, Debug)]
pub struct PoseError<const NV: usize> {
    /// `p − p*`.
    pub translation: [f64; 3],
    /// `log₃(R*ᵀ R)`.
    pub rotation: [f64; 3],
    /// `∂(p − p*)/∂v`: the generated `jacobian_P`.
    pub translation_jacobian: [[f64; NV]; 3],
    /// `Jlog₃(R*ᵀ R) Rᵀ J_ω`.
    pub rotation_jacobian: [[f64; NV]; 3],
}

impl<S, const NQ: usize, const NV: usize> FrameOutputs<S, NQ, NV> {
    /// The frame's placement at `q` (time 0).
    pub fn placement(&self, system: &S, q: &[f64; NQ]) -> Placement {
        Placement {
            position: (self.position)(system, 0.0, q),
            rotation: (self.rotation)(system, 0.0, q),
        }
    }

    /// The frame's errors from `target` at `q`, without their jacobians.
    pub fn errors(&self, system: &S, q: &[f64; NQ], target: &Placement) -> ([f64; 3], [f64; 3]) {
        let placement = self.placement(system, q);
        (
            translation_error(&placement, target),
            log3(&relative_rotation(&placement, target)).0,
        )
    }

    /// The frame's errors from `target` at `q` and their jacobians.
    pub fn error(&self, system: &S, q: &[f64; NQ], target: &Placement) -> PoseError<NV> {
        pose_error(
            &self.placement(system, q),
            (self.jacobian)(system, 0.0, q),
            &(self.angular_jacobian)(system, 0.0, q),
            target,
        )
    }
}

/// `p − p*`.
fn translation_error(placement: &Placement, target: &Placement) -> [f64; 3] {
    std::array::from_fn(|i| placement.position[i] - target.position[i])
}

/// `R*ᵀ R`.
fn relative_rotation(placement: &Placement, target: &Placement) -> Matrix3 {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            (0..3)
                .map(|k| target.rotation[k][i] * placement.rotation[k][j])
                .sum()
        })
    })
}

/// The errors of a frame at `placement` with the world-axes jacobians
/// `linear` (of its origin) and `angular`, from `target`.
pub fn pose_error<const NV: usize>(
    placement: &Placement,
    linear: [[f64; NV]; 3],
    angular: &[[f64; NV]; 3],
    target: &Placement,
) -> PoseError<NV> {
    let (rotation, theta) = log3(&relative_rotation(placement, target));
    let jlog = jlog3(theta, &rotation);
    let r = &placement.rotation;
    // The angular jacobian in the frame's axes: Rᵀ J_ω.
    let local: [[f64; NV]; 3] = std::array::from_fn(|i| {
        std::array::from_fn(|j| (0..3).map(|k| r[k][i] * angular[k][j]).sum())
    });
    PoseError {
        translation: translation_error(placement, target),
        rotation,
        translation_jacobian: linear,
        rotation_jacobian: std::array::from_fn(|i| {
            std::array::from_fn(|j| (0..3).map(|k| jlog[i][k] * local[k][j]).sum())
        }),
    }
}

/// `ε^(1/(degree + 1))`: Pinocchio's `TaylorSeriesExpansion::precision`.
fn precision(degree: i32) -> f64 {
    f64::EPSILON.powf(1.0 / f64::from(degree + 1))
}

/// The rotation matrix nearest-by-columns to `r`, as Pinocchio's
/// `renormalize_rotation_matrix`: the first two columns normalised, the
/// third their cross product, the first then rebuilt from the other two.
fn renormalized(r: &Matrix3) -> Matrix3 {
    let column = |j: usize| [r[0][j], r[1][j], r[2][j]];
    let unit = |c: [f64; 3]| {
        let n = (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt();
        c.map(|x| x / n)
    };
    let (c0, c1) = (unit(column(0)), unit(column(1)));
    let c2 = cross(&c0, &c1);
    let c0 = cross(&c1, &c2);
    std::array::from_fn(|i| [c0[i], c1[i], c2[i]])
}

fn cross(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// The angle and unit axis of a rotation near π from the diagonal entry
/// `i0`, as Pinocchio's `internal::compute_theta_axis`.
fn theta_axis(i0: usize, value: f64, r: &Matrix3) -> (f64, [f64; 3]) {
    let eps = f64::EPSILON;
    let (i1, i2) = ((i0 + 1) % 3, (i0 + 2) % 3);
    let sign = if r[i2][i1] >= r[i1][i2] { 1.0 } else { -1.0 };
    let s = (value + eps + eps * eps).sqrt() * sign;
    let mut axis = [0.0; 3];
    axis[i0] = s / 2.0;
    axis[i1] = (r[i1][i0] + r[i0][i1]) / (2.0 * s);
    axis[i2] = (r[i2][i0] + r[i0][i2]) / (2.0 * s);
    let w = (r[i2][i1] - r[i1][i2]) / (2.0 * s);
    let norm = (axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]).sqrt();
    (2.0 * norm.atan2(w), axis.map(|a| a / norm))
}

/// `log₃(R)`, the rotation vector `θ a` with `R = exp(θ [a]×)`, and `θ`,
/// as Pinocchio's `log3`.
pub fn log3(r: &Matrix3) -> ([f64; 3], f64) {
    let eps = f64::EPSILON;
    let prec = precision(2);
    let r = renormalized(r);
    let trace = r[0][0] + r[1][1] + r[2][2];
    let cos = (trace - 1.0) / 2.0;
    if cos < -1.0 + prec {
        let values: [f64; 3] = std::array::from_fn(|i| 2.0 * r[i][i] - trace + 1.0);
        let i0 = match (
            values[0] >= values[1],
            values[0] >= values[2],
            values[1] >= values[2],
        ) {
            (true, true, _) => 0,
            (true, false, _) | (false, _, false) => 2,
            (false, _, true) => 1,
        };
        let (theta, axis) = theta_axis(i0, values[i0], &r);
        return (axis.map(|a| theta * a), theta);
    }
    let expansion = (2.0 * (1.0 - cos) + eps * eps).sqrt();
    let theta = match (trace <= 3.0 - prec, trace >= -1.0 + prec) {
        (true, true) => cos.acos(),
        (true, false) => std::f64::consts::PI - expansion,
        (false, _) => expansion,
    };
    let antisymmetric = [
        0.5 * (r[2][1] - r[1][2]),
        0.5 * (r[0][2] - r[2][0]),
        0.5 * (r[1][0] - r[0][1]),
    ];
    let n2: f64 = antisymmetric.iter().map(|a| a * a).sum();
    let t = match theta >= prec {
        true => theta / theta.sin(),
        false => 1.0 + n2 / 6.0 + n2 * n2 * 3.0 / 40.0,
    };
    (antisymmetric.map(|a| t * a), theta)
}

/// `Jlog₃` at the rotation vector `log` of angle `theta`: the derivative
/// of `log₃(R exp([δ]×))` by `δ` at `δ = 0`, as Pinocchio's `Jlog3`.
pub fn jlog3(theta: f64, log: &[f64; 3]) -> Matrix3 {
    let (st, ct) = theta.sin_cos();
    let st_1mct = st / (1.0 - ct);
    let prec = precision(3);
    let (alpha, diagonal) = match theta < prec {
        true => (
            1.0 / 12.0 + theta * theta / 720.0,
            0.5 * (2.0 - theta * theta / 6.0),
        ),
        false => (
            1.0 / (theta * theta) - st_1mct / (2.0 * theta),
            0.5 * (theta * st_1mct),
        ),
    };
    let half = log.map(|x| 0.5 * x);
    let skew = [
        [0.0, -half[2], half[1]],
        [half[2], 0.0, -half[0]],
        [-half[1], half[0], 0.0],
    ];
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            alpha * log[i] * log[j] + f64::from(u8::from(i == j)) * diagonal + skew[i][j]
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `exp([w]×)` by Rodrigues' formula.
    fn exp3(w: &[f64; 3]) -> Matrix3 {
        let theta = (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt();
        let (a, b) = match theta < 1e-8 {
            true => (1.0, 0.5),
            false => (theta.sin() / theta, (1.0 - theta.cos()) / (theta * theta)),
        };
        let k = [[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]];
        std::array::from_fn(|i| {
            std::array::from_fn(|j| {
                let kk: f64 = (0..3).map(|m| k[i][m] * k[m][j]).sum();
                f64::from(u8::from(i == j)) + a * k[i][j] + b * kk
            })
        })
    }

    fn product(a: &Matrix3, b: &Matrix3) -> Matrix3 {
        std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum()))
    }

    fn close(a: &[f64], b: &[f64], tolerance: f64) -> bool {
        a.iter().zip(b).all(|(x, y)| (x - y).abs() <= tolerance)
    }

    /// Rotation vectors from small to near π, away from and along axes.
    const VECTORS: [[f64; 3]; 6] = [
        [1e-7, -2e-7, 3e-8],
        [1e-3, 2e-3, -5e-4],
        [0.3, -0.2, 0.5],
        [-1.2, 0.7, 0.4],
        [0.0, 0.0, 3.0],
        [1.8, -1.5, 1.2],
    ];

    #[test]
    fn log3_inverts_the_exponential() {
        for w in VECTORS {
            let (log, theta) = log3(&exp3(&w));
            assert!(close(&log, &w, 1e-13), "{log:?} for {w:?}");
            let norm = w.iter().map(|x| x * x).sum::<f64>().sqrt();
            // Near zero θ is Pinocchio's √(2 (1 − cos θ)) = 2 sin(θ / 2),
            // off by θ³ / 24 and by the rounding of cos θ, ε / θ (it feeds
            // nothing but Jlog₃'s series there).
            assert!(
                (theta - norm).abs() < 1e-13 + norm.powi(3) / 20.0 + 1e-15 / norm,
                "θ = {theta}, ‖w‖ = {norm}"
            );
        }
        // Near π, through the diagonal's branch.
        let w = [0.0, (std::f64::consts::PI - 1e-9) / 2f64.sqrt(), 0.0];
        let w = [w[1], w[1], 0.0];
        let (log, _) = log3(&exp3(&w));
        assert!(close(&log, &w, 1e-7), "{log:?} for {w:?}");
    }

    #[test]
    fn jlog3_is_the_derivative_of_log3_along_a_right_perturbation() {
        let h = 1e-6;
        for w in &VECTORS[1..] {
            let r = exp3(w);
            let (log, theta) = log3(&r);
            let jacobian = jlog3(theta, &log);
            for j in 0..3 {
                let mut d = [0.0; 3];
                d[j] = h;
                let plus = log3(&product(&r, &exp3(&d))).0;
                d[j] = -h;
                let minus = log3(&product(&r, &exp3(&d))).0;
                let column: Vec<f64> = (0..3).map(|i| (plus[i] - minus[i]) / (2.0 * h)).collect();
                let exact: Vec<f64> = (0..3).map(|i| jacobian[i][j]).collect();
                assert!(
                    close(&column, &exact, 1e-8),
                    "{column:?} vs {exact:?} at {w:?}"
                );
            }
        }
    }

    /// A frame turned by `Rz(q₀) Ry(q₁) Rx(q₂)` about `O`, its origin at
    /// `R c` for a fixed `c`: the angular jacobian's columns are the three
    /// axes in `N`, the linear one's their cross products with the origin.
    fn wrist(q: &[f64; 3]) -> (Placement, [[f64; 3]; 3], [[f64; 3]; 3]) {
        let (z, y, x) = ([0.0, 0.0, q[0]], [0.0, q[1], 0.0], [q[2], 0.0, 0.0]);
        let (rz, ry) = (exp3(&z), exp3(&y));
        let rotation = product(&product(&rz, &ry), &exp3(&x));
        let c = [0.1, -0.3, 0.2];
        let position: [f64; 3] =
            std::array::from_fn(|i| (0..3).map(|k| rotation[i][k] * c[k]).sum());
        let rzy = product(&rz, &ry);
        let axes = [
            [0.0, 0.0, 1.0],
            [rz[0][1], rz[1][1], rz[2][1]],
            [rzy[0][0], rzy[1][0], rzy[2][0]],
        ];
        let linear_columns = axes.map(|a| cross(&a, &position));
        let angular = std::array::from_fn(|i| std::array::from_fn(|j| axes[j][i]));
        let linear = std::array::from_fn(|i| std::array::from_fn(|j| linear_columns[j][i]));
        (Placement { position, rotation }, linear, angular)
    }

    #[test]
    fn the_pose_errors_jacobians_match_central_differences() {
        let target = Placement {
            position: [0.2, 0.1, -0.1],
            rotation: exp3(&[0.4, -1.1, 0.9]),
        };
        let h = 1e-6;
        for q in [[0.3, -0.5, 1.2], [2.0, 0.4, -2.5], [-0.1, 1.3, 0.2]] {
            let (placement, linear, angular) = wrist(&q);
            let error = pose_error(&placement, linear, &angular, &target);
            for j in 0..3 {
                let errors = |step: f64| {
                    let mut moved = q;
                    moved[j] += step;
                    let (placement, linear, angular) = wrist(&moved);
                    let e = pose_error(&placement, linear, &angular, &target);
                    (e.translation, e.rotation)
                };
                let ((tp, rp), (tm, rm)) = (errors(h), errors(-h));
                for i in 0..3 {
                    let (dt, dr) = ((tp[i] - tm[i]) / (2.0 * h), (rp[i] - rm[i]) / (2.0 * h));
                    assert!(
                        (dt - error.translation_jacobian[i][j]).abs() < 1e-8,
                        "translation [{i}][{j}] at {q:?}"
                    );
                    assert!(
                        (dr - error.rotation_jacobian[i][j]).abs() < 1e-8,
                        "rotation [{i}][{j}] at {q:?}"
                    );
                }
            }
        }
    }
}
