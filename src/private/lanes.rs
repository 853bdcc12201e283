//! Four states at once: the arithmetic of the generated
//! `accelerations_x4` (`outputs accelerations_x4;`), one state in each lane
//! of a [`Lanes`] (`wide::f64x4`: SIMD on stable Rust without `unsafe` in
//! the generated code). The straight-line body of `accelerations` is written
//! again over lanes: its operators are `wide`'s, its functions the ones
//! below (generic over [`LaneMath`], so that a body's constants, which are
//! plain `f64`, take them too), its pivots tested and its results handed
//! out state by state by [`per_state`], which leaves every state the lanes
//! cannot answer (a non-finite value, a pivot that fails) to the scalar
//! `accelerations`, whose error it returns.
//!
//! Sines and cosines are the kernel of [`super::math::sin_cos_all`]
//! (FreeBSD's polynomials after a three-part reduction, branch-free), lane by
//! lane, which the compiler runs on the lanes together: the same values as
//! the scalar body's for the angles it takes together, and within a unit in
//! the last place of `libm`'s `sincos`. (`wide`'s own `sin_cos`, Cephes'
//! polynomials, was measured against `f64::sin` and `f64::cos`: see the
//! tests below.)

use super::math::sin_cos_lanes;
use crate::dynamics::DynamicsError;
use crate::dynamics::cholesky::{check_pivots, pivot_tolerance};

/// Four `f64`, one state each.
pub type Lanes = wide::f64x4;

/// The number of states a [`Lanes`] holds.
pub const LANES: usize = 4;

/// The elementary functions of a generated body, on one value (`f64`) or
/// on the lanes.
pub trait LaneMath: Copy {
    /// The sine.
    fn sin(self) -> Self;
    /// The cosine.
    fn cos(self) -> Self;
    /// The tangent.
    fn tan(self) -> Self;
    /// The square root (correctly rounded, as `f64::sqrt`).
    fn sqrt(self) -> Self;
    /// `eˣ`.
    fn exp(self) -> Self;
    /// The natural logarithm.
    fn ln(self) -> Self;
    /// The absolute value.
    fn abs(self) -> Self;
    /// `xⁿ`, as `f64::powi`.
    fn powi(self, n: i32) -> Self;
}

impl LaneMath for f64 {
    #[inline]
    fn sin(self) -> f64 {
        f64::sin(self)
    }
    #[inline]
    fn cos(self) -> f64 {
        f64::cos(self)
    }
    #[inline]
    fn tan(self) -> f64 {
        f64::tan(self)
    }
    #[inline]
    fn sqrt(self) -> f64 {
        f64::sqrt(self)
    }
    #[inline]
    fn exp(self) -> f64 {
        f64::exp(self)
    }
    #[inline]
    fn ln(self) -> f64 {
        f64::ln(self)
    }
    #[inline]
    fn abs(self) -> f64 {
        f64::abs(self)
    }
    #[inline]
    fn powi(self, n: i32) -> f64 {
        f64::powi(self, n)
    }
}

/// `f` on each lane.
#[inline(always)]
fn each(x: Lanes, f: impl Fn(f64) -> f64) -> Lanes {
    Lanes::new(x.to_array().map(f))
}

impl LaneMath for Lanes {
    #[inline]
    fn sin(self) -> Lanes {
        sin_cos(self).0
    }
    #[inline]
    fn cos(self) -> Lanes {
        sin_cos(self).1
    }
    #[inline]
    fn tan(self) -> Lanes {
        each(self, f64::tan)
    }
    #[inline]
    fn sqrt(self) -> Lanes {
        wide::f64x4::sqrt(self)
    }
    #[inline]
    fn exp(self) -> Lanes {
        each(self, f64::exp)
    }
    #[inline]
    fn ln(self) -> Lanes {
        each(self, f64::ln)
    }
    #[inline]
    fn abs(self) -> Lanes {
        wide::f64x4::abs(self)
    }
    #[inline]
    fn powi(self, n: i32) -> Lanes {
        each(self, |x| x.powi(n))
    }
}

/// The sine.
#[inline]
pub fn sin<T: LaneMath>(x: T) -> T {
    x.sin()
}

/// The cosine.
#[inline]
pub fn cos<T: LaneMath>(x: T) -> T {
    x.cos()
}

/// The tangent.
#[inline]
pub fn tan<T: LaneMath>(x: T) -> T {
    x.tan()
}

/// The square root.
#[inline]
pub fn sqrt<T: LaneMath>(x: T) -> T {
    x.sqrt()
}

/// `eˣ`.
#[inline]
pub fn exp<T: LaneMath>(x: T) -> T {
    x.exp()
}

/// The natural logarithm.
#[inline]
pub fn ln<T: LaneMath>(x: T) -> T {
    x.ln()
}

/// The absolute value.
#[inline]
pub fn abs<T: LaneMath>(x: T) -> T {
    x.abs()
}

/// `xⁿ`.
#[inline]
pub fn powi<T: LaneMath>(x: T, n: i32) -> T {
    x.powi(n)
}

/// The sine and the cosine of each lane of `x`.
#[inline]
pub fn sin_cos(x: Lanes) -> (Lanes, Lanes) {
    let (s, c) = sin_cos_lanes(x.to_array());
    (Lanes::new(s), Lanes::new(c))
}

/// The sines and the cosines of the angles `x`, lane by lane.
#[inline]
pub fn sin_cos_all<const K: usize>(x: [Lanes; K]) -> ([Lanes; K], [Lanes; K]) {
    let mut sines = [Lanes::ZERO; K];
    let mut cosines = [Lanes::ZERO; K];
    for ((angle, s), c) in x.into_iter().zip(&mut sines).zip(&mut cosines) {
        (*s, *c) = sin_cos(angle);
    }
    (sines, cosines)
}

/// `x` in every lane: a parameter or a constant of a body over lanes.
#[inline]
pub fn splat(x: f64) -> Lanes {
    Lanes::splat(x)
}

/// The four states' times, one a lane.
#[inline]
pub fn gather(t: [f64; LANES]) -> Lanes {
    Lanes::new(t)
}

/// The four states' arrays as one [`Lanes`] per entry.
#[inline]
pub fn columns<const N: usize>(states: &[[f64; N]; LANES]) -> [Lanes; N] {
    let [a, b, c, d] = states;
    core::array::from_fn(|i| Lanes::new([a[i], b[i], c[i], d[i]]))
}

/// Whether, in each lane, every pivot `Dⱼ` of the unrolled `L D Lᵀ` solve
/// of `M` is above the tolerance of the lane's diagonal (the scalar
/// solve's test, [`pivot_tolerance`]).
#[inline]
pub fn factorised_pivots_hold<const N: usize>(
    pivots: [Lanes; N],
    diagonal: [Lanes; N],
) -> [bool; LANES] {
    let (pivots, diagonal) = (pivots.map(Lanes::to_array), diagonal.map(Lanes::to_array));
    core::array::from_fn(|k| {
        let tolerance = pivot_tolerance(diagonal.map(|d| d[k]));
        pivots.iter().all(|p| p[k] > tolerance)
    })
}

/// Whether, in each lane, the articulated-body recursion's pivots pass
/// the scalar route's test ([`check_pivots`]).
#[inline]
pub fn articulated_pivots_hold<const N: usize>(pivots: [Lanes; N]) -> [bool; LANES] {
    let pivots = pivots.map(Lanes::to_array);
    core::array::from_fn(|k| check_pivots(pivots.map(|p| p[k]), [""; N]).is_ok())
}

/// Four states: their times, coordinates, speeds and inputs.
pub type States<'a, const NQ: usize, const NV: usize, const NU: usize> = (
    [f64; LANES],
    &'a [[f64; NQ]; LANES],
    &'a [[f64; NV]; LANES],
    &'a [[f64; NU]; LANES],
);

/// The accelerations of each state: the lanes' `solved` where the state,
/// its pivots (`hold`) and its result are all good, else what the scalar
/// `accelerations` (`scalar`) says of that state, an error or a value.
#[inline]
pub fn per_state<const NQ: usize, const NV: usize, const NU: usize>(
    solved: [Lanes; NV],
    hold: [bool; LANES],
    states: States<'_, NQ, NV, NU>,
    scalar: impl Fn(f64, &[f64; NQ], &[f64; NV], &[f64; NU]) -> Result<[f64; NV], DynamicsError>,
) -> [Result<[f64; NV], DynamicsError>; LANES] {
    let (t, q, v, u) = states;
    let solved = solved.map(Lanes::to_array);
    let finite = |x: &[f64]| x.iter().all(|x| x.is_finite());
    core::array::from_fn(|k| {
        let lane: [f64; NV] = core::array::from_fn(|i| solved[i][k]);
        let state = t[k].is_finite() && finite(&q[k]) && finite(&v[k]) && finite(&u[k]);
        match hold[k] && state && finite(&lane) {
            true => Ok(lane),
            false => scalar(t[k], &q[k], &v[k], &u[k]),
        }
    })
}

#[cfg(test)]
mod tests {
    use super::{LaneMath, Lanes, columns, per_state, sin_cos};

    /// The distance of `ours` from `theirs` in units of the last place of
    /// `theirs`.
    fn ulps(ours: f64, theirs: f64) -> f64 {
        let unit =
            (theirs.abs().max(f64::MIN_POSITIVE)).next_up() - theirs.abs().max(f64::MIN_POSITIVE);
        (ours - theirs).abs() / unit
    }

    /// Angles of a robot's range and well beyond it.
    fn angles() -> impl Iterator<Item = f64> {
        (-400_000..=400_000).map(|i| f64::from(i) * 1.000_3e-4)
    }

    /// The lanes' sines and cosines are within two units in the last place
    /// of `f64::sin` and `f64::cos` over `[−40, 40]` (the same kernel as
    /// the scalar `sin_cos_all`, so identical to it: checked too).
    #[test]
    fn lane_sines_and_cosines_agree_with_f64() {
        let mut worst: f64 = 0.0;
        let all: Vec<f64> = angles().collect();
        assert!(!all.is_empty());
        for chunk in all.chunks_exact(4) {
            let x = [chunk[0], chunk[1], chunk[2], chunk[3]];
            let (s, c) = sin_cos(Lanes::new(x));
            let (scalar_s, scalar_c) = crate::__private::math::sin_cos_all(x);
            assert_eq!((s.to_array(), c.to_array()), (scalar_s, scalar_c));
            for ((s, c), x) in s.to_array().into_iter().zip(c.to_array()).zip(x) {
                worst = worst.max(ulps(s, x.sin()));
                worst = worst.max(ulps(c, x.cos()));
            }
        }
        assert!(worst <= 2.0, "{worst} ulps");
    }

    /// `wide`'s own `sin_cos` (Cephes' polynomials), measured the same way:
    /// within two units in the last place too over this range; not used,
    /// since the kernel above gives the scalar body's values exactly.
    #[test]
    fn wide_sines_and_cosines_agree_with_f64() {
        let mut worst: f64 = 0.0;
        for x in angles() {
            let (s, c) = Lanes::splat(x).sin_cos();
            worst = worst.max(ulps(s.to_array()[0], x.sin()));
            worst = worst.max(ulps(c.to_array()[0], x.cos()));
        }
        assert!(worst <= 2.0, "{worst} ulps");
    }

    #[test]
    fn functions_act_lane_by_lane() {
        let x = Lanes::new([0.5, 2.0, 9.0, 1e-3]);
        for (i, &v) in x.to_array().iter().enumerate() {
            assert_eq!(x.sqrt().to_array()[i], v.sqrt());
            assert_eq!(x.exp().to_array()[i], v.exp());
            assert_eq!(x.ln().to_array()[i], v.ln());
            assert_eq!(x.powi(5).to_array()[i], v.powi(5));
            assert_eq!((-x).abs().to_array()[i], v);
        }
    }

    /// A lane whose state is not finite, or whose pivots fail, takes the
    /// scalar answer; the others keep the lanes'.
    #[test]
    fn bad_lanes_take_the_scalar_answer() {
        let q = [[1.0], [f64::NAN], [3.0], [4.0]];
        let v = [[0.0]; 4];
        let u: [[f64; 0]; 4] = [[]; 4];
        let solved = columns(&[[10.0], [20.0], [30.0], [40.0]]);
        let results = per_state(
            solved,
            [true, true, false, true],
            ([0.0; 4], &q, &v, &u),
            |_, q, _, _| Ok([-q[0]]),
        );
        assert_eq!(results[0], Ok([10.0]));
        assert!(results[1].as_ref().is_ok_and(|x| x[0].is_nan()));
        assert_eq!(results[2], Ok([-3.0]));
        assert_eq!(results[3], Ok([40.0]));
    }
}
