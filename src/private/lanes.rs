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
//! (FreeBSD's polynomials after a three-part reduction, branch-free) written
//! over the lanes, its quadrant's swaps and signs as `wide::u64x4` bit
//! masks: the same operations on each lane as on one angle, so the same
//! values as the scalar body's for the angles it takes together, and within
//! a unit in the last place of `libm`'s `sincos`. (`wide`'s own `sin_cos`,
//! Cephes' polynomials, was measured against `f64::sin` and `f64::cos`: see
//! the tests below.)
//!
//! The pivot tests and the finiteness of the results are masks over the
//! lanes too, and a state the lanes cannot answer goes to the scalar call
//! out of the body: the per-state work left is handing out the four
//! results.

use super::math::{REDUCED_DIRECTLY, reduced};
use crate::dynamics::DynamicsError;
use crate::dynamics::cholesky::RELATIVE_PIVOT_TOLERANCE;

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

/// The sine and the cosine of each lane of `x`: the kernel of
/// [`super::math::sin_cos_all`] on the lanes together (its reduction and
/// polynomials, `math::reduced`, then the quadrant's swap and signs as bit
/// masks, the same operations on each lane as on one angle, so the same
/// values), and `libm`'s `sincos` for a lane beyond
/// [`REDUCED_DIRECTLY`] or NaN, as there.
#[inline(always)]
pub fn sin_cos(x: Lanes) -> (Lanes, Lanes) {
    let (shifted, sine, cosine) = reduced(x);
    let quadrant = shifted.to_bits();
    let [one, two] = [1, 2].map(wide::u64x4::splat);
    // Quadrant n: (sin x, cos x) = (sin r, cos r), (cos r, −sin r),
    // (−sin r, −cos r), (−cos r, sin r) for n ≡ 0, 1, 2, 3 (mod 4).
    let swap = wide::u64x4::ZERO - (quadrant & one);
    let (s, c) = (sine.to_bits(), cosine.to_bits());
    let sine_bits = (s & !swap) | (c & swap);
    let cosine_bits = (c & !swap) | (s & swap);
    let sine_sign = (quadrant & two) << 62u32;
    let cosine_sign = ((quadrant + one) & two) << 62u32;
    let sines = Lanes::from_bits(sine_bits ^ sine_sign);
    let cosines = Lanes::from_bits(cosine_bits ^ cosine_sign);
    match (x.is_nan() | x.abs().simd_gt(Lanes::splat(REDUCED_DIRECTLY))).any() {
        true => sin_cos_directly(x, sines, cosines),
        false => (sines, cosines),
    }
}

/// `sines` and `cosines` with the lanes whose angle `x` the kernel does
/// not reduce (beyond [`REDUCED_DIRECTLY`], or NaN) replaced by `libm`'s
/// `sincos`: rare, so out of the body.
#[cold]
#[inline(never)]
fn sin_cos_directly(x: Lanes, sines: Lanes, cosines: Lanes) -> (Lanes, Lanes) {
    let (mut s, mut c) = (sines.to_array(), cosines.to_array());
    for ((x, s), c) in x.to_array().into_iter().zip(&mut s).zip(&mut c) {
        if x.is_nan() || x.abs() > REDUCED_DIRECTLY {
            (*s, *c) = libm::sincos(x);
        }
    }
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

/// Where every pivot `Dⱼ` of the unrolled `L D Lᵀ` solve of `M` is above
/// the tolerance of the lane's diagonal (the scalar solve's test,
/// [`pivot_tolerance`](crate::dynamics::cholesky::pivot_tolerance)): a
/// mask, all ones in such a lane.
#[inline(always)]
pub fn factorised_pivots_hold<const N: usize>(pivots: [Lanes; N], diagonal: [Lanes; N]) -> Lanes {
    above(pivots, tolerance(diagonal))
}

/// Where the articulated-body recursion's pivots pass the scalar
/// recursion's test ([`check_pivots`](crate::dynamics::cholesky::check_pivots))
/// with [`RECURSION_PIVOT_MARGIN`] to spare: a mask, all ones in such a lane.
#[inline(always)]
pub fn articulated_pivots_hold<const N: usize>(pivots: [Lanes; N]) -> Lanes {
    above(
        pivots,
        Lanes::splat(RECURSION_PIVOT_MARGIN) * tolerance(pivots),
    )
}

/// How far above the scalar test a pivot of the lanes' articulated-body
/// recursion must be for the lanes to answer its state. The lanes take the
/// recursion where the scalar call may factorise `M` (the plan charges
/// the recursion less over lanes): the same pivots (a joint's articulated
/// inertia about its axis is the pivot of `M`'s elimination from the
/// leaves), but the factorisation measures them against `M`'s largest
/// diagonal entry and the recursion against the largest pivot, which is
/// smaller. A state within this margin of singular goes to the scalar
/// call, whose error is then the answer; only a model whose largest
/// diagonal entry of `M` exceeds its largest pivot ten thousand times could
/// still see the lanes answer a state that the scalar factorisation
/// refuses.
pub const RECURSION_PIVOT_MARGIN: f64 = 1e4;

/// [`RELATIVE_PIVOT_TOLERANCE`] times the largest of `values` in each
/// lane, NaN ignored: `pivot_tolerance`, lane by lane (`f64::max` keeps
/// the number when the other is NaN, as a comparison that fails does).
#[inline(always)]
fn tolerance<const N: usize>(values: [Lanes; N]) -> Lanes {
    let largest = values.into_iter().fold(Lanes::ZERO, |largest, x| {
        x.simd_gt(largest).select(x, largest)
    });
    Lanes::splat(RELATIVE_PIVOT_TOLERANCE) * largest
}

/// Where every one of `pivots` is above `tolerance` (false for NaN).
#[inline(always)]
fn above<const N: usize>(pivots: [Lanes; N], tolerance: Lanes) -> Lanes {
    pivots
        .into_iter()
        .fold(all_lanes(), |hold, p| hold & p.simd_gt(tolerance))
}

/// A mask with every lane set.
#[inline(always)]
fn all_lanes() -> Lanes {
    Lanes::ZERO.simd_eq(Lanes::ZERO)
}

/// Four states: their times, coordinates, speeds and inputs.
pub type States<'a, const NQ: usize, const NV: usize, const NU: usize> = (
    [f64; LANES],
    &'a [[f64; NQ]; LANES],
    &'a [[f64; NV]; LANES],
    &'a [[f64; NU]; LANES],
);

/// The accelerations of each state: the lanes' `solved` where the state,
/// its pivots (`hold`, a mask) and its result are all finite and good,
/// else what the scalar `accelerations` (`scalar`) says of that state, an
/// error or a value.
///
/// The tests are branch-free over the lanes: a result is finite where
/// `Σᵢ (xᵢ − xᵢ)` is zero (NaN from an infinite or NaN entry), a state
/// where none of its numbers is infinite or NaN.
#[inline(always)]
pub fn per_state<const NQ: usize, const NV: usize, const NU: usize>(
    solved: [Lanes; NV],
    hold: Lanes,
    states: States<'_, NQ, NV, NU>,
    scalar: impl Fn(f64, &[f64; NQ], &[f64; NV], &[f64; NU]) -> Result<[f64; NV], DynamicsError>,
) -> [Result<[f64; NV], DynamicsError>; LANES] {
    let (t, q, v, u) = states;
    // `x − x` is zero where `x` is finite, NaN where it is infinite or NaN.
    #[allow(clippy::eq_op)]
    let residue = solved.iter().fold(Lanes::ZERO, |sum, &x| sum + (x - x));
    let good = (hold & residue.simd_eq(Lanes::ZERO)).to_bitmask();
    let mut lanes = [[0.0; NV]; LANES];
    for (i, x) in solved.iter().enumerate() {
        for (lane, x) in lanes.iter_mut().zip(x.to_array()) {
            lane[i] = x;
        }
    }
    let finite = |x: &[f64]| x.iter().fold(true, |all, x| all & x.is_finite());
    let mut results = [Ok([0.0; NV]); LANES];
    for (k, (result, lane)) in results.iter_mut().zip(lanes).enumerate() {
        let state = t[k].is_finite() & finite(&q[k]) & finite(&v[k]) & finite(&u[k]);
        *result = match state && good & (1 << k) != 0 {
            true => Ok(lane),
            false => by_the_scalar_call(&scalar, t[k], &q[k], &v[k], &u[k]),
        };
    }
    results
}

/// `scalar` of a state the lanes could not answer: rare, so out of the
/// body that inlines [`per_state`].
#[cold]
#[inline(never)]
fn by_the_scalar_call<const NQ: usize, const NV: usize, const NU: usize>(
    scalar: &impl Fn(f64, &[f64; NQ], &[f64; NV], &[f64; NU]) -> Result<[f64; NV], DynamicsError>,
    t: f64,
    q: &[f64; NQ],
    v: &[f64; NV],
    u: &[f64; NU],
) -> Result<[f64; NV], DynamicsError> {
    scalar(t, q, v, u)
}

#[cfg(test)]
mod tests {
    use super::{
        LaneMath, Lanes, RECURSION_PIVOT_MARGIN, articulated_pivots_hold, columns, per_state,
        sin_cos,
    };
    use crate::dynamics::cholesky::{RELATIVE_PIVOT_TOLERANCE, check_pivots};

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
        // Beyond the kernel's reduction, NaN and infinite: `libm`'s, as there.
        let x = [1e7, f64::NAN, 0.5, f64::NEG_INFINITY];
        let (s, c) = sin_cos(Lanes::new(x));
        let (scalar_s, scalar_c) = crate::__private::math::sin_cos_all(x);
        let bits = |x: [f64; 4]| x.map(f64::to_bits);
        assert_eq!(bits(s.to_array()), bits(scalar_s));
        assert_eq!(bits(c.to_array()), bits(scalar_c));
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
        let set = u64::MAX;
        let hold = Lanes::from_bits(wide::u64x4::new([set, set, 0, set]));
        let results = per_state(solved, hold, ([0.0; 4], &q, &v, &u), |_, q, _, _| {
            Ok([-q[0]])
        });
        assert_eq!(results[0], Ok([10.0]));
        assert!(results[1].as_ref().is_ok_and(|x| x[0].is_nan()));
        assert_eq!(results[2], Ok([-3.0]));
        assert_eq!(results[3], Ok([40.0]));
    }

    /// The recursion's pivots over lanes: a lane holds where the scalar
    /// test passes with the margin to spare; a lane between the scalar
    /// tolerance and the margin is left to the scalar call, and one the
    /// scalar test refuses never holds.
    #[test]
    fn recursion_pivots_hold_with_the_margin() {
        let tolerance = RELATIVE_PIVOT_TOLERANCE;
        let small = [
            1.0,
            10.0 * tolerance * RECURSION_PIVOT_MARGIN,
            10.0 * tolerance,
            0.5 * tolerance,
        ];
        let names = ["a", "b"];
        let held = articulated_pivots_hold([Lanes::splat(1.0), Lanes::new(small)]).to_bitmask();
        for (k, x) in small.into_iter().enumerate() {
            let scalar = check_pivots([1.0, x], names).is_ok();
            assert_eq!(held & (1 << k) != 0, k < 2, "lane {k}");
            assert_eq!(scalar, k < 3, "lane {k}");
        }
    }
}
