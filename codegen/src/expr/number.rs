//! Exact arithmetic on [`Rational`]s (checked, `None` on `i128` overflow) and
//! on [`Number`]s (never fails: an overflow falls back to `f64`).

use std::fmt;
use std::hash::{Hash, Hasher};
use std::ops::{Add, Mul, Neg};

use super::{Number, Rational};

/// Greatest common divisor of the magnitudes, as `u128` (so `i128::MIN` is
/// fine); `gcd(0, 0) = 0`.
fn gcd(a: i128, b: i128) -> u128 {
    let (mut a, mut b) = (a.unsigned_abs(), b.unsigned_abs());
    while b != 0 {
        (a, b) = (b, a % b);
    }
    a
}

/// `a / g` for a positive divisor `g` of `a` given as `u128`; `None` only
/// when `g` itself does not fit in `i128`.
fn div_exact(a: i128, g: u128) -> Option<i128> {
    a.checked_div(i128::try_from(g).ok()?)
}

impl Rational {
    /// Zero.
    pub const ZERO: Rational = Rational { num: 0, den: 1 };
    /// One.
    pub const ONE: Rational = Rational { num: 1, den: 1 };

    /// The reduced fraction `num/den` with a positive denominator; `None` if
    /// `den == 0` or the result does not fit in `i128`.
    pub fn new(num: i128, den: i128) -> Option<Rational> {
        if den == 0 {
            return None;
        }
        let g = gcd(num, den);
        let (num, den) = (div_exact(num, g)?, div_exact(den, g)?);
        if den < 0 {
            Some(Rational {
                num: num.checked_neg()?,
                den: den.checked_neg()?,
            })
        } else {
            Some(Rational { num, den })
        }
    }

    /// The integer `i`.
    pub fn int(i: i128) -> Rational {
        Rational { num: i, den: 1 }
    }

    /// The nearest `f64` (exact when numerator and denominator are below
    /// 2⁵³).
    pub fn to_f64(self) -> f64 {
        self.num as f64 / self.den as f64
    }

    /// Whether the value is an integer.
    pub fn is_integer(self) -> bool {
        self.den == 1
    }

    /// `self + other`, `None` on overflow.
    pub fn checked_add(self, other: Rational) -> Option<Rational> {
        let g = i128::try_from(gcd(self.den, other.den)).ok()?;
        let (bd, dd) = (self.den / g, other.den / g);
        let num = self
            .num
            .checked_mul(dd)?
            .checked_add(other.num.checked_mul(bd)?)?;
        Rational::new(num, self.den.checked_mul(dd)?)
    }

    /// `self * other`, `None` on overflow. Cross-cancels first so that
    /// products of reduced fractions overflow only when the result does.
    pub fn checked_mul(self, other: Rational) -> Option<Rational> {
        let g1 = gcd(self.num, other.den);
        let g2 = gcd(other.num, self.den);
        let num = div_exact(self.num, g1)?.checked_mul(div_exact(other.num, g2)?)?;
        let den = div_exact(self.den, g2)?.checked_mul(div_exact(other.den, g1)?)?;
        Rational::new(num, den)
    }

    /// `1 / self`, `None` for zero or on overflow.
    pub fn checked_recip(self) -> Option<Rational> {
        Rational::new(self.den, self.num)
    }

    /// `self ^ exp` (`0⁰ = 1`), `None` on overflow or for `0` to a negative
    /// power.
    pub fn checked_pow(self, exp: i32) -> Option<Rational> {
        let base = if exp < 0 { self.checked_recip()? } else { self };
        let e = exp.unsigned_abs();
        Some(Rational {
            num: base.num.checked_pow(e)?,
            den: base.den.checked_pow(e)?,
        })
    }

    /// The exact square root, if `self` is the square of a rational.
    pub fn sqrt_exact(self) -> Option<Rational> {
        if self.num < 0 {
            return None;
        }
        let (n, d) = (self.num.isqrt(), self.den.isqrt());
        (n * n == self.num && d * d == self.den).then_some(Rational { num: n, den: d })
    }
}

impl fmt::Display for Rational {
    /// `3`, `-1/2`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.den == 1 {
            write!(f, "{}", self.num)
        } else {
            write!(f, "{}/{}", self.num, self.den)
        }
    }
}

impl From<Rational> for Number {
    fn from(r: Rational) -> Number {
        Number::Rational(r)
    }
}

impl From<i64> for Number {
    fn from(i: i64) -> Number {
        Number::Rational(Rational::int(i128::from(i)))
    }
}

impl Number {
    /// Zero (exact).
    pub const ZERO: Number = Number::Rational(Rational::ZERO);
    /// One (exact).
    pub const ONE: Number = Number::Rational(Rational::ONE);

    /// The exact value of `num/den`; a float (`±inf`, `NaN` or the nearest
    /// value) when `den == 0` or the reduced fraction does not fit.
    pub fn ratio(num: i128, den: i128) -> Number {
        match Rational::new(num, den) {
            Some(r) => Number::Rational(r),
            None => Number::Float(num as f64 / den as f64),
        }
    }

    /// The nearest `f64`.
    pub fn to_f64(self) -> f64 {
        match self {
            Number::Rational(r) => r.to_f64(),
            Number::Float(x) => x,
        }
    }

    /// The exact value, if this is not a float.
    pub fn as_rational(self) -> Option<Rational> {
        match self {
            Number::Rational(r) => Some(r),
            Number::Float(_) => None,
        }
    }

    /// Whether the value is zero (a float zero counts).
    pub fn is_zero(self) -> bool {
        self.to_f64() == 0.0
    }

    /// Whether the value is one (a float one counts).
    pub fn is_one(self) -> bool {
        match self {
            Number::Rational(r) => r == Rational::ONE,
            Number::Float(x) => x == 1.0,
        }
    }

    /// Whether the value is below zero.
    pub fn is_negative(self) -> bool {
        match self {
            Number::Rational(r) => r.num < 0,
            Number::Float(x) => x < 0.0,
        }
    }

    /// Applies an exact operation, or the float one if either operand is a
    /// float or the exact one overflows.
    fn combine(
        self,
        other: Number,
        exact: fn(Rational, Rational) -> Option<Rational>,
        float: fn(f64, f64) -> f64,
    ) -> Number {
        if let (Number::Rational(a), Number::Rational(b)) = (self, other) {
            if let Some(r) = exact(a, b) {
                return Number::Rational(r);
            }
        }
        Number::Float(float(self.to_f64(), other.to_f64()))
    }

    /// `self ^ exp`; `0` to a negative power is `inf`.
    pub fn powi(self, exp: i32) -> Number {
        if let Number::Rational(r) = self {
            if let Some(p) = r.checked_pow(exp) {
                return Number::Rational(p);
            }
        }
        Number::Float(self.to_f64().powi(exp))
    }

    /// `|self|`.
    pub fn abs(self) -> Number {
        if self.is_negative() { -self } else { self }
    }
}

impl Add for Number {
    type Output = Number;
    /// Exact, or a float on overflow.
    fn add(self, other: Number) -> Number {
        self.combine(other, Rational::checked_add, |a, b| a + b)
    }
}

impl Mul for Number {
    type Output = Number;
    /// Exact, or a float on overflow.
    fn mul(self, other: Number) -> Number {
        self.combine(other, Rational::checked_mul, |a, b| a * b)
    }
}

impl Neg for Number {
    type Output = Number;
    /// Exact, or a float on overflow (`-i128::MIN`).
    fn neg(self) -> Number {
        self * Number::from(-1)
    }
}

/// Numbers compare structurally: rationals by value, floats by bit pattern
/// (so `NaN == NaN` and a float never equals a rational), which is what
/// hash-consing needs.
impl PartialEq for Number {
    fn eq(&self, other: &Number) -> bool {
        match (self, other) {
            (Number::Rational(a), Number::Rational(b)) => a == b,
            (Number::Float(a), Number::Float(b)) => a.to_bits() == b.to_bits(),
            _ => false,
        }
    }
}

impl Eq for Number {}

impl Hash for Number {
    fn hash<H: Hasher>(&self, state: &mut H) {
        match self {
            Number::Rational(r) => r.hash(state),
            Number::Float(x) => x.to_bits().hash(state),
        }
    }
}

impl fmt::Display for Number {
    /// Rationals as `3` or `-1/2`, floats with Rust's shortest round-trip
    /// form (`1e60`, `inf`, `NaN`).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Number::Rational(r) => r.fmt(f),
            Number::Float(x) => write!(f, "{x:?}"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn r(num: i128, den: i128) -> Rational {
        Rational::new(num, den).unwrap()
    }

    #[test]
    fn new_reduces_and_normalises_sign() {
        assert_eq!(r(6, -4), Rational { num: -3, den: 2 });
        assert_eq!(r(0, -7), Rational::ZERO);
        assert_eq!(Rational::new(1, 0), None);
        assert_eq!(Rational::new(1, i128::MIN), None);
        assert_eq!(r(i128::MIN, 2).num, i128::MIN / 2);
    }

    #[test]
    fn checked_arithmetic() {
        assert_eq!(r(1, 3).checked_add(r(1, 6)), Some(r(1, 2)));
        assert_eq!(r(2, 3).checked_mul(r(3, 4)), Some(r(1, 2)));
        assert_eq!(r(-2, 3).checked_recip(), Some(r(-3, 2)));
        assert_eq!(Rational::ZERO.checked_recip(), None);
        assert_eq!(r(2, 3).checked_pow(-3), Some(r(27, 8)));
        assert_eq!(r(5, 7).checked_pow(0), Some(Rational::ONE));
        assert_eq!(Rational::int(i128::MAX).checked_add(Rational::ONE), None);
        assert_eq!(Rational::int(10).checked_pow(40), None);
    }

    #[test]
    fn cross_cancellation_avoids_spurious_overflow() {
        let big = Rational::int(i128::MAX);
        assert_eq!(big.checked_mul(r(1, i128::MAX)), Some(Rational::ONE));
    }

    #[test]
    fn exact_square_roots() {
        assert_eq!(r(9, 4).sqrt_exact(), Some(r(3, 2)));
        assert_eq!(r(2, 1).sqrt_exact(), None);
        assert_eq!(r(-4, 1).sqrt_exact(), None);
    }

    #[test]
    fn numbers_fall_back_to_floats() {
        let big = Number::from(10).powi(30);
        assert_eq!(big.as_rational(), Some(Rational::int(10i128.pow(30))));
        let square = big * big;
        assert!(matches!(square, Number::Float(x) if (x / 1e60 - 1.0).abs() < 1e-12));
        assert!(matches!(Number::ratio(-1, 0), Number::Float(x) if x == f64::NEG_INFINITY));
        assert!(matches!(Number::ratio(0, 0), Number::Float(x) if x.is_nan()));
        assert!(matches!(Number::ZERO.powi(-1), Number::Float(x) if x == f64::INFINITY));
    }

    #[test]
    fn predicates_and_display() {
        assert!(Number::ZERO.is_zero() && Number::Float(0.0).is_zero());
        assert!(Number::ONE.is_one() && !Number::from(2).is_one());
        assert!(Number::ratio(-1, 2).is_negative());
        assert_eq!(Number::ratio(-1, 2).abs(), Number::ratio(1, 2));
        assert_eq!(r(-1, 2).to_string(), "-1/2");
        assert_eq!(Rational::int(3).to_string(), "3");
        assert_eq!(Number::Float(1e60).to_string(), "1e60");
        assert_eq!(Number::Float(f64::NAN), Number::Float(f64::NAN));
        assert_ne!(Number::Float(1.0), Number::ONE);
    }
}
