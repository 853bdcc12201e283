//! Elementary functions the generated code calls.
//!
//! Every generated function starts by taking the sine and the cosine of
//! each angle it needs. `f64::sin_cos` compiles to the platform's `sincos`
//! (glibc's, on Linux); [`sin_cos`] is the `sincos` of the `libm` crate, a
//! port of musl's (the same polynomial kernels as FreeBSD's, error below
//! one unit in the last place), which costs about six tenths of it per
//! call on this project's benchmark machine (6.8 against 11.1 ns of thread
//! CPU time, medians of 15 interleaved rounds of 12 angles; BENCHMARKS.md,
//! "Sines and cosines"). A function that needs several angles takes them
//! all at once with [`sin_cos_all`], whose one loop over the angles has no
//! call and no branch and so runs several angles per instruction.

use core::f64::consts::FRAC_2_PI;
use core::ops::{Add, Mul, Sub};

/// The sine and the cosine of `x` (radians), with one argument reduction.
///
/// Never inlined: the generated code calls it once per angle, and a copy of
/// the argument reduction at every call would cost instruction cache for no
/// gain (measured: a call costs the same as the inlined body).
#[inline(never)]
pub fn sin_cos(x: f64) -> (f64, f64) {
    libm::sincos(x)
}

/// The sines and the cosines of the angles `x` (radians), in their order.
///
/// Angles of magnitude up to [`REDUCED_DIRECTLY`] are reduced to `r` in
/// `[−π/4, π/4]` and a quadrant `n` by `x = n π/2 + r`, with π/2 in three
/// parts (Cody and Waite) of which the first two have 33 significant bits,
/// so that `n` times either is exact; the sine and the cosine of `r` are the
/// minimax polynomials of FreeBSD's `k_sin.c` and `k_cos.c` (as in `libm`'s
/// `sincos`), and the quadrant swaps and negates them. The loop doing this
/// for every angle is branch-free (selections are bit masks), so the
/// compiler runs it on several angles at once. Larger angles, infinities
/// and NaN are then recomputed by [`libm::sincos`]. Both results are within
/// a few units in the last place of 1 of the exact values, as `libm`'s.
///
/// The angles of a system of at most [`INLINED_ANGLES`] are computed in the
/// caller's body, the others in a function of their own: returned through
/// memory, a pair of results stored as two 64-bit halves and read back as
/// one 128-bit vector (as AVX builds do) misses the store-to-load
/// forwarding, a stall of about 4 of the double pendulum's 38 ns per
/// evaluation (BENCHMARKS.md, "The host CPU's slowdowns"). Only in
/// optimised builds: inlined into a generated function of thousands of
/// nested `let` scopes, the unoptimised build's debug information
/// overflowed the compiler's stack.
#[cfg_attr(debug_assertions, inline)]
#[cfg_attr(not(debug_assertions), inline(always))]
pub fn sin_cos_all<const K: usize>(x: [f64; K]) -> ([f64; K], [f64; K]) {
    if K <= INLINED_ANGLES {
        sin_cos_each(x)
    } else {
        sin_cos_out_of_line(x)
    }
}

/// The most angles whose sines and cosines [`sin_cos_all`] computes in its
/// caller's body.
pub const INLINED_ANGLES: usize = 2;

/// [`sin_cos_each`] behind a call, for many angles.
#[inline(never)]
fn sin_cos_out_of_line<const K: usize>(x: [f64; K]) -> ([f64; K], [f64; K]) {
    sin_cos_each(x)
}

/// The sines and the cosines of the angles `x`: the body of [`sin_cos_all`].
///
/// The angles go through the kernel in two loops, an even count of them
/// then the odd one out: over an odd count the compiler kept the single
/// loop scalar, one angle at a time (the eleven angles of the spatial chain
/// of 12 on SSE2), where an even count runs two angles an instruction
/// (BENCHMARKS.md, "Spatial 12 at the peer's instruction set").
#[inline(always)]
fn sin_cos_each<const K: usize>(x: [f64; K]) -> ([f64; K], [f64; K]) {
    let mut sines = [0.0; K];
    let mut cosines = [0.0; K];
    let even = K & !1;
    for k in 0..even {
        (sines[k], cosines[k]) = reduced_sin_cos(x[k]);
    }
    for k in even..K {
        (sines[k], cosines[k]) = reduced_sin_cos(x[k]);
    }
    for k in 0..K {
        if x[k].is_nan() || x[k].abs() > REDUCED_DIRECTLY {
            (sines[k], cosines[k]) = libm::sincos(x[k]);
        }
    }
    (sines, cosines)
}

/// The largest angle [`sin_cos_all`] reduces with its three-part π/2: the
/// quadrant then stays below 2²⁰, so that its products with the 33-bit parts
/// are exact.
pub const REDUCED_DIRECTLY: f64 = 1.0e6;

/// 1.5 · 2⁵²: added to a number of magnitude below 2⁵¹, rounds it to an
/// integer held in the low bits of the sum's significand.
const ROUND_TO_INTEGER: f64 = 6_755_399_441_055_744.0;
/// π/2 in three parts: the first 33 bits, the next 33, the rest (musl's
/// `pio2_1`, `pio2_2`, `pio2_2t`: bits 0x3FF921FB54400000,
/// 0x3DD0B4611A600000, 0x3BA3198A2E037073).
const PIO2_1: f64 = 1.5707963267341256;
const PIO2_2: f64 = 6.077100506303966e-11;
const PIO2_2T: f64 = 2.0222662487959506e-21;
/// The sine's polynomial on `[−π/4, π/4]`: `sin r ≈ r + r³ (S1 + r² (S2 + …))`.
const S: [f64; 6] = [
    -0.16666666666666632,
    0.00833333333332249,
    -0.0001984126982985795,
    2.7557313707070068e-06,
    -2.5050760253406863e-08,
    1.58969099521155e-10,
];
/// The cosine's: `cos r ≈ 1 − r²/2 + r⁴ (C1 + r² (C2 + …))`.
const C: [f64; 6] = [
    0.0416666666666666,
    -0.001388888888887411,
    2.480158728947673e-05,
    -2.7557314351390663e-07,
    2.087572321298175e-09,
    -1.1359647557788195e-11,
];

/// The first steps of the kernel of [`sin_cos_all`], on one angle or on
/// the lanes of `super::lanes` (the same operations in the same order, so
/// the same values): the reduction `x = n π/2 + r`, with `n` held in the
/// low bits of the returned `shifted`, and the polynomials' `sin r` and
/// `cos r`, which the quadrant then swaps and negates.
#[inline(always)]
pub(crate) fn reduced<T>(x: T) -> (T, T, T)
where
    T: Copy + From<f64> + Add<Output = T> + Sub<Output = T> + Mul<Output = T>,
{
    let k = T::from;
    let shifted = x * k(FRAC_2_PI) + k(ROUND_TO_INTEGER);
    let n = shifted - k(ROUND_TO_INTEGER);
    let r = ((x - n * k(PIO2_1)) - n * k(PIO2_2)) - n * k(PIO2_2T);
    let z = r * r;
    let w = z * z;
    let sine_tail = k(S[1]) + z * (k(S[2]) + z * k(S[3])) + z * w * (k(S[4]) + z * k(S[5]));
    let sine = r + z * r * (k(S[0]) + z * sine_tail);
    let cosine_tail = z * (k(C[0]) + z * (k(C[1]) + z * k(C[2])))
        + w * w * (k(C[3]) + z * (k(C[4]) + z * k(C[5])));
    let half = k(0.5) * z;
    let one_minus_half = k(1.0) - half;
    let cosine = one_minus_half + (((k(1.0) - one_minus_half) - half) + z * cosine_tail);
    (shifted, sine, cosine)
}

/// The sine and the cosine of `x`, for `|x| ≤ REDUCED_DIRECTLY`, without a
/// branch.
#[inline(always)]
fn reduced_sin_cos(x: f64) -> (f64, f64) {
    let (shifted, sine, cosine) = reduced(x);
    let quadrant = shifted.to_bits();
    // Quadrant n: (sin x, cos x) = (sin r, cos r), (cos r, −sin r),
    // (−sin r, −cos r), (−cos r, sin r) for n ≡ 0, 1, 2, 3 (mod 4).
    let swap = 0u64.wrapping_sub(quadrant & 1);
    let (s, c) = (sine.to_bits(), cosine.to_bits());
    let sine_bits = (s & !swap) | (c & swap);
    let cosine_bits = (c & !swap) | (s & swap);
    let sine_sign = (quadrant & 2) << 62;
    let cosine_sign = (quadrant.wrapping_add(1) & 2) << 62;
    (
        f64::from_bits(sine_bits ^ sine_sign),
        f64::from_bits(cosine_bits ^ cosine_sign),
    )
}

#[cfg(test)]
mod tests {
    use super::{INLINED_ANGLES, REDUCED_DIRECTLY, sin_cos, sin_cos_all};

    /// Tiny to huge angles, of either sign, near multiples of π/2 too.
    fn angles() -> Vec<f64> {
        let mut angles = Vec::new();
        let mut x = 1e-300_f64;
        while x < 1e300 {
            let near_quarter_turns =
                (x * std::f64::consts::FRAC_2_PI).round() * std::f64::consts::FRAC_PI_2;
            angles.extend([x, -x, 1.000_000_1 * x, near_quarter_turns]);
            x *= 1.37;
        }
        angles
    }

    /// Agrees with the platform's `sin` and `cos` to within two units in
    /// the last place of 1 (both are accurate to under one unit), from tiny
    /// to huge arguments, near multiples of π/2 and at the special values.
    #[test]
    fn agrees_with_the_platform_functions() {
        for y in angles() {
            let (s, c) = sin_cos(y);
            assert!(
                (s - y.sin()).abs() <= 4.5e-16,
                "sin {y}: {s} vs {}",
                y.sin()
            );
            assert!(
                (c - y.cos()).abs() <= 4.5e-16,
                "cos {y}: {c} vs {}",
                y.cos()
            );
        }
        assert_eq!(sin_cos(0.0), (0.0, 1.0));
        let (s, c) = sin_cos(f64::NAN);
        assert!(s.is_nan() && c.is_nan());
        let (s, c) = sin_cos(f64::INFINITY);
        assert!(s.is_nan() && c.is_nan());
    }

    /// Within 10⁻¹⁵ of `libm`'s `sincos` relative to the value (a few units
    /// in its last place: the sine of an angle near a multiple of π is
    /// small, and still accurate), in batches of 7, over the angles above,
    /// a dense sweep of the directly reduced range and either side of its
    /// limit; NaN where `libm` gives NaN. Batches of two take the path
    /// inlined into the caller, of seven the one behind a call.
    #[test]
    fn batches_agree_with_libm() {
        batches_of_agree_with_libm::<INLINED_ANGLES>();
        batches_of_agree_with_libm::<7>();
    }

    fn batches_of_agree_with_libm<const K: usize>() {
        let mut all = angles();
        all.extend((-200_000..=200_000).map(|i| f64::from(i) * 1e-3 * 1.000_3));
        let limit = REDUCED_DIRECTLY;
        all.extend([limit, -limit, limit.next_up(), limit.next_down(), 0.0, -0.0]);
        all.extend([f64::NAN, f64::INFINITY, f64::NEG_INFINITY, f64::MAX]);
        for batch in all.chunks(K) {
            let mut angles = [0.0; K];
            angles[..batch.len()].copy_from_slice(batch);
            let (sines, cosines) = sin_cos_all(angles);
            for (k, &x) in angles.iter().enumerate() {
                let (s, c) = libm::sincos(x);
                for (name, ours, theirs) in [("sin", sines[k], s), ("cos", cosines[k], c)] {
                    let agree = match theirs.is_nan() {
                        true => ours.is_nan(),
                        false => (ours - theirs).abs() <= 1e-15 * theirs.abs(),
                    };
                    assert!(agree, "{name} {x}: {ours} vs {theirs}");
                }
            }
        }
    }

    /// Angles that are exact: the sine of 0 is 0, the cosine 1.
    #[test]
    fn zero_is_exact() {
        assert_eq!(sin_cos_all([0.0, -0.0]), ([0.0, -0.0], [1.0, 1.0]));
    }
}
