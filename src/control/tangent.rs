//! The configuration space as a product of groups, read from a system's
//! coordinate and speed names: plain coordinates (`dt(x)`, the vector space
//! `ℝ`), spherical joints (`J_wx, J_wy, J_wz` over the quaternion
//! `J_qx … J_qw`: SO(3)) and free joints (`J_vx … J_wz` over
//! `J_x, J_y, J_z, J_qx … J_qw`: SE(3)), as the generator names them.
//!
//! On each group the system's update is `q ⊕ w = q · Exp(w)` with `w` in the
//! child's axes (DESIGN §7: Pinocchio's free flyer and spherical joint), so
//! the tangent-space derivatives of the update are those of Pinocchio's
//! `dIntegrate`:
//!
//! * by `q`, along `q ⊕ δ`: `Ad(Exp(w))⁻¹` (`Exp(w)ᵀ` on SO(3));
//! * by `w`: the right Jacobian `J_r(w)` of the exponential
//!   (`Jexp3`, `Jexp6` in Pinocchio).
//!
//! Both depend on `w` only. [`ConfigurationSpace::difference`] is the
//! inverse of the update (Pinocchio's `difference`, `q₀ ⊕ d = q₁`), for
//! costs on a state and for central differences in the tangent space.

use super::ControlError;

/// One factor of the configuration space.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Joint {
    /// A coordinate whose rate is the speed: `q + w`.
    Plain {
        /// The coordinate's index in `q`.
        coordinate: usize,
        /// The speed's index in `v`.
        speed: usize,
    },
    /// A spherical joint: three angular speeds from `speed` over the unit
    /// quaternion `(x, y, z, w)` at `quaternion`.
    Rotation {
        /// The first angular speed.
        speed: usize,
        /// The quaternion's coordinates, `x, y, z, w`.
        quaternion: [usize; 4],
    },
    /// A free joint: linear then angular speeds from `speed` over the
    /// position `position` and the quaternion `quaternion`.
    Rigid {
        /// The first of the six speeds.
        speed: usize,
        /// The position's coordinates.
        position: [usize; 3],
        /// The quaternion's coordinates, `x, y, z, w`.
        quaternion: [usize; 4],
    },
}

/// A system's configuration space as a product of vector spaces, SO(3) and
/// SE(3) factors (see the module's docs), read once from its names by
/// [`ConfigurationSpace::of`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ConfigurationSpace<const NQ: usize, const NV: usize> {
    joints: [Joint; NV],
    count: usize,
    /// Every speed is the rate of the coordinate of the same index.
    vector: bool,
}

/// `[x]×`: the matrix of `y ↦ x × y`.
fn skew(x: [f64; 3]) -> [[f64; 3]; 3] {
    [[0.0, -x[2], x[1]], [x[2], 0.0, -x[0]], [-x[1], x[0], 0.0]]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn product(a: &[[f64; 3]; 3], b: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum()))
}

fn transpose(a: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    std::array::from_fn(|i| std::array::from_fn(|j| a[j][i]))
}

fn apply(a: &[[f64; 3]; 3], x: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|i| dot(a[i], x))
}

/// The coefficients of `Exp` on SO(3) at the angle `θ = |ω|`:
/// `(sin θ / θ, (1 − cos θ) / θ², (θ − sin θ) / θ³)`, by their series
/// near zero.
fn coefficients(theta: f64) -> (f64, f64, f64) {
    let t2 = theta * theta;
    // Four terms: below 0.1 the first left out is under 3e-14 relative, and
    // above it the closed forms lose fewer digits to cancellation.
    if theta < 0.1 {
        (
            1.0 - t2 / 6.0 * (1.0 - t2 / 20.0 * (1.0 - t2 / 42.0)),
            0.5 - t2 / 24.0 * (1.0 - t2 / 30.0 * (1.0 - t2 / 56.0)),
            1.0 / 6.0 - t2 / 120.0 * (1.0 - t2 / 42.0 * (1.0 - t2 / 72.0)),
        )
    } else {
        let (s, c) = theta.sin_cos();
        (s / theta, (1.0 - c) / t2, (theta - s) / (t2 * theta))
    }
}

/// `I + a [ω]× + b [ω]ײ`.
fn rodrigues(omega: [f64; 3], a: f64, b: f64) -> [[f64; 3]; 3] {
    let k = skew(omega);
    let k2 = product(&k, &k);
    std::array::from_fn(|i| {
        std::array::from_fn(|j| f64::from(u8::from(i == j)) + a * k[i][j] + b * k2[i][j])
    })
}

/// `Exp(ω)` on SO(3): `I + (sin θ/θ) [ω]× + ((1 − cos θ)/θ²) [ω]ײ`.
fn rotation_exp(omega: [f64; 3]) -> [[f64; 3]; 3] {
    let (a, b, _) = coefficients(dot(omega, omega).sqrt());
    rodrigues(omega, a, b)
}

/// The right Jacobian of SO(3)'s exponential:
/// `I − ((1 − cos θ)/θ²) [ω]× + ((θ − sin θ)/θ³) [ω]ײ`.
fn rotation_jacobian(omega: [f64; 3]) -> [[f64; 3]; 3] {
    let (_, b, c) = coefficients(dot(omega, omega).sqrt());
    rodrigues(omega, -b, c)
}

/// `(1/θ) d/dθ` of `(1 − cos θ)/θ²` and of `(θ − sin θ)/θ³`.
fn coefficient_slopes(theta: f64) -> (f64, f64) {
    let t2 = theta * theta;
    // The closed forms lose `ε/θ⁴` to cancellation: below 0.2 the four
    // terms are closer (the first left out is under 1e-12 relative).
    if theta < 0.2 {
        let t4 = t2 * t2;
        (
            -1.0 / 12.0 + t2 / 180.0 - t4 / 6720.0 + t4 * t2 / 453_600.0,
            -1.0 / 60.0 + t2 / 1260.0 - t4 / 60480.0 + t4 * t2 / 4_989_600.0,
        )
    } else {
        let (s, c) = theta.sin_cos();
        let t4 = t2 * t2;
        (
            (theta * s - 2.0 * (1.0 - c)) / t4,
            (1.0 - c) / t4 - 3.0 * (theta - s) / (t4 * theta),
        )
    }
}

/// The rigid motion `Exp(ν)` of SE(3), `ν = (v, ω)`: `(R, p)` with
/// `R = Exp(ω)` and `p = J_l(ω) v`, and its right Jacobian
/// `[[J_r(ω), Rᵀ ∂(J_l(ω) v)/∂ω], [0, J_r(ω)]]` as its two upper blocks.
struct RigidExp {
    rotation: [[f64; 3]; 3],
    position: [f64; 3],
    jacobian: [[f64; 3]; 3],
    coupling: [[f64; 3]; 3],
}

fn rigid_exp(v: [f64; 3], omega: [f64; 3]) -> RigidExp {
    let theta = dot(omega, omega).sqrt();
    let (a, b, c) = coefficients(theta);
    let (db, dc) = coefficient_slopes(theta);
    let rotation = rodrigues(omega, a, b);
    let (wv, wwv) = (cross(omega, v), cross(omega, cross(omega, v)));
    let position = std::array::from_fn(|i| v[i] + b * wv[i] + c * wwv[i]);
    // ∂(J_l(ω) v)/∂ω = −b [v]× + wv (db ωᵀ) + c ((ω·v) I + ω vᵀ − 2 v ωᵀ) + wwv (dc ωᵀ).
    let (sv, wdv) = (skew(v), dot(omega, v));
    let by_omega: [[f64; 3]; 3] = std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let identity = f64::from(u8::from(i == j));
            -b * sv[i][j]
                + db * wv[i] * omega[j]
                + c * (wdv * identity + omega[i] * v[j] - 2.0 * v[i] * omega[j])
                + dc * wwv[i] * omega[j]
        })
    });
    RigidExp {
        coupling: product(&transpose(&rotation), &by_omega),
        jacobian: rodrigues(omega, -b, c),
        rotation,
        position,
    }
}

/// The quaternion `(x, y, z, w)` at `indices` of `q`.
fn quaternion<const NQ: usize>(q: &[f64; NQ], indices: [usize; 4]) -> [f64; 4] {
    indices.map(|i| q[i])
}

/// The rotation matrix of a unit quaternion `(x, y, z, w)`.
fn quaternion_matrix([x, y, z, w]: [f64; 4]) -> [[f64; 3]; 3] {
    [
        [
            1.0 - 2.0 * (y * y + z * z),
            2.0 * (x * y - w * z),
            2.0 * (x * z + w * y),
        ],
        [
            2.0 * (x * y + w * z),
            1.0 - 2.0 * (x * x + z * z),
            2.0 * (y * z - w * x),
        ],
        [
            2.0 * (x * z - w * y),
            2.0 * (y * z + w * x),
            1.0 - 2.0 * (x * x + y * y),
        ],
    ]
}

/// `Log` on SO(3) of the unit quaternion `p₀⁻¹ ⊗ p₁` (the shorter way).
fn rotation_log(p0: [f64; 4], p1: [f64; 4]) -> [f64; 3] {
    let (a, b) = ([p0[0], p0[1], p0[2]], [p1[0], p1[1], p1[2]]);
    // conj(p₀) ⊗ p₁ = (w₀ b − w₁ a − a × b, w₀ w₁ + a·b).
    let ab = cross(a, b);
    let mut xyz: [f64; 3] = std::array::from_fn(|i| p0[3] * b[i] - p1[3] * a[i] - ab[i]);
    let mut w = p0[3] * p1[3] + dot(a, b);
    if w < 0.0 {
        xyz = xyz.map(|x| -x);
        w = -w;
    }
    let s = dot(xyz, xyz).sqrt();
    let scale = if s < 1e-8 {
        2.0 / w
    } else {
        2.0 * s.atan2(w) / s
    };
    xyz.map(|x| scale * x)
}

impl<const NQ: usize, const NV: usize> ConfigurationSpace<NQ, NV> {
    /// The space of a system with these coordinate and speed names, or
    /// [`ControlError::UnsupportedSpeed`] naming the first speed that is
    /// neither a coordinate's rate (`dt(x)`) nor one of a spherical or free
    /// joint's (a `speeds` statement's).
    pub fn from_names(
        coordinates: &[&'static str; NQ],
        speeds: &[&'static str; NV],
    ) -> Result<Self, ControlError> {
        let vector = NQ == NV
            && speeds.iter().zip(coordinates).all(|(s, c)| {
                s.strip_prefix("dt(")
                    .and_then(|s| s.strip_suffix(')'))
                    .is_some_and(|s| s == *c)
            });
        let mut space = Self {
            joints: [Joint::Plain {
                coordinate: 0,
                speed: 0,
            }; NV],
            count: 0,
            vector,
        };
        if vector {
            return Ok(space);
        }
        // `prefix_suffix`, compared without building it.
        let is = |name: &str, prefix: &str, suffix: &str| {
            name.strip_prefix(prefix)
                .and_then(|r| r.strip_prefix('_'))
                .is_some_and(|r| r == suffix)
        };
        let find =
            |prefix: &str, suffix: &str| coordinates.iter().position(|c| is(c, prefix, suffix));
        let mut k = 0;
        while k < NV {
            let speed = speeds[k];
            let unsupported = ControlError::UnsupportedSpeed { speed };
            let named = |prefix: &str, suffixes: [&str; 3]| -> Option<[usize; 3]> {
                let [a, b, c] = suffixes.map(|s| find(prefix, s));
                Some([a?, b?, c?])
            };
            let follows = |prefix: &str, suffixes: &[&str]| {
                suffixes
                    .iter()
                    .enumerate()
                    .all(|(i, s)| speeds.get(k + 1 + i).is_some_and(|n| is(n, prefix, s)))
            };
            let quaternion_of = |prefix: &str| {
                let [x, y, z] = named(prefix, ["qx", "qy", "qz"])?;
                Some([x, y, z, find(prefix, "qw")?])
            };
            let (joint, width) =
                if let Some(name) = speed.strip_prefix("dt(").and_then(|s| s.strip_suffix(')')) {
                    let coordinate = coordinates
                        .iter()
                        .position(|c| *c == name)
                        .ok_or(unsupported)?;
                    (
                        Joint::Plain {
                            coordinate,
                            speed: k,
                        },
                        1,
                    )
                } else if let Some(prefix) = speed.strip_suffix("_vx") {
                    let position = named(prefix, ["x", "y", "z"]);
                    match (
                        follows(prefix, &["vy", "vz", "wx", "wy", "wz"]),
                        position,
                        quaternion_of(prefix),
                    ) {
                        (true, Some(p), Some(quaternion)) => (
                            Joint::Rigid {
                                speed: k,
                                position: p,
                                quaternion,
                            },
                            6,
                        ),
                        _ => return Err(unsupported),
                    }
                } else if let Some(prefix) = speed.strip_suffix("_wx") {
                    match (follows(prefix, &["wy", "wz"]), quaternion_of(prefix)) {
                        (true, Some(quaternion)) => (
                            Joint::Rotation {
                                speed: k,
                                quaternion,
                            },
                            3,
                        ),
                        _ => return Err(unsupported),
                    }
                } else {
                    return Err(unsupported);
                };
            space.joints[space.count] = joint;
            space.count += 1;
            k += width;
        }
        Ok(space)
    }

    /// Whether every speed is the rate of the coordinate of its index (the
    /// update is `q + w`, both derivatives the identity).
    pub fn is_vector_space(&self) -> bool {
        self.vector
    }

    fn joints(&self) -> &[Joint] {
        &self.joints[..self.count]
    }

    /// `d` with `q₀ ⊕ d = q₁` (Pinocchio's `difference`): `q₁ − q₀` for
    /// plain coordinates, `Log(p₀⁻¹ p₁)` for a quaternion (the shorter
    /// rotation), `Log((R₀, r₀)⁻¹ (R₁, r₁))` on SE(3) for a free joint.
    pub fn difference(&self, q0: &[f64; NQ], q1: &[f64; NQ]) -> [f64; NV] {
        if self.vector {
            return std::array::from_fn(|i| q1[i] - q0[i]);
        }
        let mut d = [0.0; NV];
        for joint in self.joints() {
            match *joint {
                Joint::Plain { coordinate, speed } => d[speed] = q1[coordinate] - q0[coordinate],
                Joint::Rotation {
                    speed,
                    quaternion: p,
                } => {
                    let omega = rotation_log(quaternion(q0, p), quaternion(q1, p));
                    d[speed..speed + 3].copy_from_slice(&omega);
                }
                Joint::Rigid {
                    speed,
                    position,
                    quaternion: p,
                } => {
                    let omega = rotation_log(quaternion(q0, p), quaternion(q1, p));
                    let r0 = quaternion_matrix(quaternion(q0, p));
                    let offset = position.map(|i| q1[i] - q0[i]);
                    let t = apply(&transpose(&r0), offset);
                    // v = J_l(ω)⁻¹ t, J_l⁻¹ = I − ½ [ω]× + e [ω]ײ.
                    let theta = dot(omega, omega).sqrt();
                    let e = if theta < 0.05 {
                        let t2 = theta * theta;
                        1.0 / 12.0 + t2 / 720.0 + t2 * t2 / 30240.0
                    } else {
                        let (s, c) = theta.sin_cos();
                        (1.0 - theta * s / (2.0 * (1.0 - c))) / (theta * theta)
                    };
                    let v = apply(&rodrigues(omega, -0.5, e), t);
                    d[speed..speed + 3].copy_from_slice(&v);
                    d[speed + 3..speed + 6].copy_from_slice(&omega);
                }
            }
        }
        d
    }

    /// The derivatives of `q ⊕ w` in the tangent spaces at the step `w`,
    /// joint by joint (see the module's docs).
    pub(crate) fn update_derivatives(&self, w: &[f64; NV]) -> UpdateDerivatives<NV> {
        let zero = [[0.0; 3]; 3];
        let mut blocks = UpdateDerivatives {
            joints: [Blocks {
                speed: 0,
                size: 0,
                by_q: [[zero; 2]; 2],
                by_w: [[zero; 2]; 2],
            }; NV],
            count: 0,
        };
        if self.vector {
            return blocks;
        }
        for joint in self.joints() {
            let block = match *joint {
                Joint::Plain { .. } => continue,
                Joint::Rotation { speed, .. } => {
                    let omega = [w[speed], w[speed + 1], w[speed + 2]];
                    Blocks {
                        speed,
                        size: 1,
                        by_q: [[transpose(&rotation_exp(omega)), zero], [zero; 2]],
                        by_w: [[rotation_jacobian(omega), zero], [zero; 2]],
                    }
                }
                Joint::Rigid { speed, .. } => {
                    let v = [w[speed], w[speed + 1], w[speed + 2]];
                    let omega = [w[speed + 3], w[speed + 4], w[speed + 5]];
                    let e = rigid_exp(v, omega);
                    // Ad(Exp(ν))⁻¹ = [[Rᵀ, −Rᵀ [p]×], [0, Rᵀ]].
                    let rt = transpose(&e.rotation);
                    let corner = product(&rt, &skew(e.position)).map(|row| row.map(|x| -x));
                    Blocks {
                        speed,
                        size: 2,
                        by_q: [[rt, corner], [zero, rt]],
                        by_w: [[e.jacobian, e.coupling], [zero, e.jacobian]],
                    }
                }
            };
            blocks.joints[blocks.count] = block;
            blocks.count += 1;
        }
        blocks
    }
}

/// One Lie-group joint's derivatives of `q ⊕ w`: `size` × `size` blocks of
/// 3 × 3 over the speeds from `speed`.
#[derive(Clone, Copy, Debug)]
struct Blocks {
    speed: usize,
    size: usize,
    by_q: [[[[f64; 3]; 3]; 2]; 2],
    by_w: [[[[f64; 3]; 3]; 2]; 2],
}

/// `∂(q ⊕ w)/∂q` and `∂(q ⊕ w)/∂w` at one `w`, in the tangent spaces: the
/// identity on plain coordinates, a block per spherical or free joint.
#[derive(Clone, Copy, Debug)]
pub(crate) struct UpdateDerivatives<const NV: usize> {
    joints: [Blocks; NV],
    count: usize,
}

impl<const NV: usize> UpdateDerivatives<NV> {
    fn blocks(&self) -> &[Blocks] {
        &self.joints[..self.count]
    }

    /// `rows ← ∂(q ⊕ w)/∂q · rows`.
    pub(crate) fn by_configuration<const N: usize>(&self, rows: &mut [[f64; N]; NV]) {
        for b in self.blocks() {
            mix(&b.by_q, b.size, b.speed, rows);
        }
    }

    /// `rows ← ∂(q ⊕ w)/∂w · rows`.
    pub(crate) fn by_step<const N: usize>(&self, rows: &mut [[f64; N]; NV]) {
        for b in self.blocks() {
            mix(&b.by_w, b.size, b.speed, rows);
        }
    }

    /// `x ← (∂(q ⊕ w)/∂q)ᵀ x`.
    pub(crate) fn by_configuration_transposed(&self, x: &mut [f64; NV]) {
        for b in self.blocks() {
            mix_transposed(&b.by_q, b.size, b.speed, x);
        }
    }

    /// `x ← (∂(q ⊕ w)/∂w)ᵀ x`.
    pub(crate) fn by_step_transposed(&self, x: &mut [f64; NV]) {
        for b in self.blocks() {
            mix_transposed(&b.by_w, b.size, b.speed, x);
        }
    }
}

/// Rows `start..start + 3 size` of `rows` replaced by the block matrix
/// `blocks` (its first `size` × `size` blocks of 3 × 3) times them.
fn mix<const N: usize, const NV: usize>(
    blocks: &[[[[f64; 3]; 3]; 2]; 2],
    size: usize,
    start: usize,
    rows: &mut [[f64; N]; NV],
) {
    let old: [[[f64; N]; 3]; 2] = std::array::from_fn(|b| {
        std::array::from_fn(|i| match b < size {
            true => rows[start + 3 * b + i],
            false => [0.0; N],
        })
    });
    for (bi, row_blocks) in blocks.iter().enumerate().take(size) {
        for i in 0..3 {
            let row = &mut rows[start + 3 * bi + i];
            *row = [0.0; N];
            for (bj, block) in row_blocks.iter().enumerate().take(size) {
                for k in 0..3 {
                    let a = block[i][k];
                    if a != 0.0 {
                        for (x, y) in row.iter_mut().zip(&old[bj][k]) {
                            *x += a * y;
                        }
                    }
                }
            }
        }
    }
}

/// Entries `start..start + 3 size` of `x` replaced by the transpose of the
/// block matrix `blocks` times them.
fn mix_transposed<const NV: usize>(
    blocks: &[[[[f64; 3]; 3]; 2]; 2],
    size: usize,
    start: usize,
    x: &mut [f64; NV],
) {
    let old: [f64; 6] = std::array::from_fn(|i| match i < 3 * size {
        true => x[start + i],
        false => 0.0,
    });
    for bj in 0..size {
        for j in 0..3 {
            x[start + 3 * bj + j] = (0..size)
                .flat_map(|bi| (0..3).map(move |i| (bi, i)))
                .map(|(bi, i)| blocks[bi][bj][i][j] * old[3 * bi + i])
                .sum();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Below the switch, the series agree with the closed forms (whose
    /// cancellation costs a few digits there).
    #[test]
    fn the_series_near_zero_match_the_closed_forms() {
        let closed = |theta: f64| {
            let (s, c) = theta.sin_cos();
            let t2 = theta * theta;
            [
                s / theta,
                (1.0 - c) / t2,
                (theta - s) / (t2 * theta),
                (theta * s - 2.0 * (1.0 - c)) / (t2 * t2),
                (1.0 - c) / (t2 * t2) - 3.0 * (theta - s) / (t2 * t2 * theta),
            ]
        };
        // Just below each switch, where the series are the farthest from
        // their sums and the closed forms the most accurate they are there.
        let (a, b, c) = coefficients(0.0999);
        let (db, dc) = coefficient_slopes(0.1999);
        let (low, high) = (closed(0.0999), closed(0.1999));
        let pairs = [
            (a, low[0]),
            (b, low[1]),
            (c, low[2]),
            (db, high[3]),
            (dc, high[4]),
        ];
        for (series, closed) in pairs {
            assert!(
                (series - closed).abs() <= 1e-11 * closed.abs(),
                "{series} against {closed}"
            );
        }
    }

    /// `Exp(ν)` composed by hand through `rigid_exp` must match `Exp(ν)·Exp(J_r dν)`
    /// to first order: checked by central differences of the translation and
    /// rotation of `Exp(ν)⁻¹ Exp(ν + ε eⱼ)`.
    #[test]
    fn the_right_jacobian_of_se3_matches_central_differences() {
        for (v, omega) in [
            ([0.3, -0.7, 1.1], [0.4, -1.2, 0.9]),
            ([0.3, -0.7, 1.1], [1e-3, 2e-3, -1e-3]),
            ([1.0, 2.0, -0.5], [0.0, 0.0, 0.0]),
        ] {
            let e = rigid_exp(v, omega);
            let nu = [v[0], v[1], v[2], omega[0], omega[1], omega[2]];
            let h = 1e-6;
            for j in 0..6 {
                let moved = |s: f64| {
                    let mut n = nu;
                    n[j] += s;
                    let m = rigid_exp([n[0], n[1], n[2]], [n[3], n[4], n[5]]);
                    // Exp(ν)⁻¹ Exp(ν + s eⱼ): (Rᵀ R', Rᵀ (p' − p)).
                    let rt = transpose(&e.rotation);
                    let r = product(&rt, &m.rotation);
                    let p = apply(&rt, std::array::from_fn(|i| m.position[i] - e.position[i]));
                    // The rotation's vector to first order: the skew part.
                    let w = [
                        0.5 * (r[2][1] - r[1][2]),
                        0.5 * (r[0][2] - r[2][0]),
                        0.5 * (r[1][0] - r[0][1]),
                    ];
                    [p[0], p[1], p[2], w[0], w[1], w[2]]
                };
                let (plus, minus) = (moved(h), moved(-h));
                for i in 0..6 {
                    let numeric = (plus[i] - minus[i]) / (2.0 * h);
                    let exact = match (i < 3, j < 3) {
                        (true, true) => e.jacobian[i][j],
                        (true, false) => e.coupling[i][j - 3],
                        (false, true) => 0.0,
                        (false, false) => e.jacobian[i - 3][j - 3],
                    };
                    assert!(
                        (exact - numeric).abs() < 1e-8,
                        "[{i}][{j}]: {exact} against {numeric}"
                    );
                }
            }
        }
    }
}
