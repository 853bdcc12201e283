//! Linear-quadratic regulators for the state-space matrices that a
//! generated system's `linearize` returns: the gain `K = R⁻¹ Bᵀ P` of the
//! feedback `δu = −K δx` minimising `∫ δxᵀ Q δx + δuᵀ R δu dt`, where `P` is
//! the stabilising solution of the continuous-time algebraic Riccati
//! equation `Aᵀ P + P A − P B R⁻¹ Bᵀ P + Q = 0`.
//!
//! `P` is the limit of the Riccati differential equation
//! `Ṗ = Aᵀ P + P A − P B R⁻¹ Bᵀ P + Q` from `P = 0` (the cost of a horizon
//! growing to infinity), integrated here by RK4 until the residual of the
//! algebraic equation is negligible: slow for stiff problems, but simple and
//! sure for the small systems of the examples, stabilisable and detectable.

use nalgebra::SMatrix;

/// The Riccati flow did not settle: `(A, B)` is not stabilisable, `Q` does
/// not see an unstable mode, or the problem is too stiff for the fixed step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RiccatiError {
    /// The residual of the algebraic Riccati equation, relative to `|P|`,
    /// when the integration gave up.
    pub residual: f64,
}

impl std::fmt::Display for RiccatiError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "the Riccati equation did not settle (relative residual {:e}): \
             is the system stabilisable, and does Q see every unstable mode?",
            self.residual
        )
    }
}

impl std::error::Error for RiccatiError {}

/// Step of the Riccati flow, in the problem's time unit.
const STEP: f64 = 1e-3;
/// Longest horizon tried.
const HORIZON: f64 = 100.0;
/// Largest `|P|` before the flow counts as diverging.
const DIVERGED: f64 = 1e12;
/// Relative residual accepted.
const RESIDUAL: f64 = 1e-11;

/// The LQR gain `K` (`NU × N`) and the Riccati solution `P` for `A`
/// (`N × N`), `B` (`N × NU`) and the weights `Q` (`N × N`, positive
/// semidefinite) and `R` (`NU × NU`, positive definite).
#[allow(clippy::type_complexity)]
pub fn lqr<const N: usize, const NU: usize>(
    a: &[[f64; N]; N],
    b: &[[f64; NU]; N],
    q: &[[f64; N]; N],
    r: &[[f64; NU]; NU],
) -> Result<([[f64; N]; NU], [[f64; N]; N]), RiccatiError> {
    let a = SMatrix::<f64, N, N>::from_fn(|i, j| a[i][j]);
    let b = SMatrix::<f64, N, NU>::from_fn(|i, j| b[i][j]);
    let q = SMatrix::<f64, N, N>::from_fn(|i, j| q[i][j]);
    let r_inverse = SMatrix::<f64, NU, NU>::from_fn(|i, j| r[i][j])
        .try_inverse()
        .ok_or(RiccatiError {
            residual: f64::INFINITY,
        })?;
    let s = b * r_inverse * b.transpose();
    let rate = |p: &SMatrix<f64, N, N>| a.transpose() * p + p * a - p * s * p + q;
    let mut p = SMatrix::<f64, N, N>::zeros();
    let mut residual = f64::INFINITY;
    for _ in 0..(HORIZON / STEP) as usize {
        let k1 = rate(&p);
        residual = k1.norm() / p.norm().max(f64::MIN_POSITIVE);
        if residual <= RESIDUAL {
            let p = (p + p.transpose()) / 2.0;
            let gain = r_inverse * b.transpose() * p;
            let rows = |m: &SMatrix<f64, N, N>| {
                std::array::from_fn(|i| std::array::from_fn(|j| m[(i, j)]))
            };
            return Ok((
                std::array::from_fn(|i| std::array::from_fn(|j| gain[(i, j)])),
                rows(&p),
            ));
        }
        let k2 = rate(&(p + k1 * (STEP / 2.0)));
        let k3 = rate(&(p + k2 * (STEP / 2.0)));
        let k4 = rate(&(p + k3 * STEP));
        p += (k1 + k2 * 2.0 + k3 * 2.0 + k4) * (STEP / 6.0);
        let norm = p.norm();
        if norm.is_nan() || norm > DIVERGED {
            residual = f64::INFINITY;
            break;
        }
    }
    Err(RiccatiError { residual })
}

#[cfg(test)]
mod tests {
    use super::lqr;

    /// `ẋ = x + u` with `Q = R = 1`: `2P − P² + 1 = 0`, `P = K = 1 + √2`.
    #[test]
    fn the_scalar_problem_has_its_closed_form() {
        let (gain, p) = lqr(&[[1.0]], &[[1.0]], &[[1.0]], &[[1.0]]).expect("settles");
        let expected = 1.0 + 2.0_f64.sqrt();
        assert!((p[0][0] - expected).abs() < 1e-9, "{}", p[0][0]);
        assert!((gain[0][0] - expected).abs() < 1e-9, "{}", gain[0][0]);
    }

    /// The double integrator `ẍ = u` with `Q = 1`, `R = 1`: the closed form
    /// `P = [[√3, 1], [1, √3]]`, `K = [1, √3]`.
    #[test]
    fn the_double_integrator_has_its_closed_form() {
        let (gain, p) = lqr(
            &[[0.0, 1.0], [0.0, 0.0]],
            &[[0.0], [1.0]],
            &[[1.0, 0.0], [0.0, 1.0]],
            &[[1.0]],
        )
        .expect("settles");
        let root = 3.0_f64.sqrt();
        let close = |x: f64, y: f64| (x - y).abs() < 1e-9;
        assert!(
            close(p[0][0], root) && close(p[0][1], 1.0) && close(p[1][1], root),
            "{p:?}"
        );
        assert!(
            close(gain[0][0], 1.0) && close(gain[0][1], root),
            "{gain:?}"
        );
    }

    #[test]
    fn an_unreachable_unstable_mode_is_an_error() {
        let error = lqr(&[[1.0]], &[[0.0]], &[[1.0]], &[[1.0]]).expect_err("not stabilisable");
        assert!(error.residual > 1e-11);
    }
}
