//! Elementary functions the generated code calls.
//!
//! Every generated function starts by taking the sine and the cosine of
//! each angle it needs. `f64::sin_cos` compiles to the platform's `sincos`
//! (glibc's, on Linux); [`sin_cos`] is the `sincos` of the `libm` crate, a
//! port of musl's (the same polynomial kernels as FreeBSD's, error below
//! one unit in the last place), which costs about six tenths of it per
//! call on this project's benchmark machine (6.8 against 11.1 ns of thread
//! CPU time, medians of 15 interleaved rounds of 12 angles; BENCHMARKS.md,
//! "Sines and cosines"). A robot's `mass_matrix` and `forcing` take two
//! sines and cosines per joint, a quarter to a third of their time.

/// The sine and the cosine of `x` (radians), with one argument reduction.
///
/// Never inlined: the generated code calls it once per angle, and a copy of
/// the argument reduction at every call would cost instruction cache for no
/// gain (measured: a call costs the same as the inlined body).
#[inline(never)]
pub fn sin_cos(x: f64) -> (f64, f64) {
    libm::sincos(x)
}

#[cfg(test)]
mod tests {
    use super::sin_cos;

    /// Agrees with the platform's `sin` and `cos` to within two units in
    /// the last place of 1 (both are accurate to under one unit), from tiny
    /// to huge arguments, near multiples of π/2 and at the special values.
    #[test]
    fn agrees_with_the_platform_functions() {
        let mut x = 1e-300_f64;
        while x < 1e300 {
            let near_quarter_turns =
                (x * std::f64::consts::FRAC_2_PI).round() * std::f64::consts::FRAC_PI_2;
            for y in [x, -x, 1.000_000_1 * x, near_quarter_turns] {
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
            x *= 1.37;
        }
        assert_eq!(sin_cos(0.0), (0.0, 1.0));
        let (s, c) = sin_cos(f64::NAN);
        assert!(s.is_nan() && c.is_nan());
        let (s, c) = sin_cos(f64::INFINITY);
        assert!(s.is_nan() && c.is_nan());
    }
}
