//! The exact value of a Rust numeric literal's text (`1.3` is `13/10`, not
//! the float nearest to it).

use super::{Number, Rational};

/// Type suffixes a numeric literal may carry.
const SUFFIXES: [&str; 14] = [
    "f32", "f64", "i8", "i16", "i32", "i64", "i128", "isize", "u8", "u16", "u32", "u64", "u128",
    "usize",
];

/// The exact value of a Rust integer or float literal (`2`, `1.3`, `1e-3`,
/// `2.5E+2`, `1_000.25`, `3f64`, `2.0_f64`, `0x1F`); `None` if `text` is not
/// one. Values that do not fit an `i128` fraction become the nearest float.
pub(super) fn parse_literal(text: &str) -> Option<Number> {
    if !text.starts_with(|c: char| c.is_ascii_digit()) {
        return None;
    }
    let body = strip_suffix(text);
    let digits: String = body.chars().filter(|&c| c != '_').collect();
    match radix_prefix(&digits) {
        Some((radix, rest)) => i128::from_str_radix(rest, radix)
            .ok()
            .map(|i| Rational::int(i).into()),
        None => parse_decimal(&digits),
    }
}

/// `text` without a type suffix (and the `_` before it). A float literal
/// cannot have an integer suffix, but that is the language's business: the
/// value is the same. In a hexadecimal literal `f32`/`f64` are digits.
fn strip_suffix(text: &str) -> &str {
    let is_hex = text.starts_with("0x") || text.starts_with("0X");
    SUFFIXES
        .iter()
        .filter(|s| !(is_hex && s.starts_with('f')))
        .find_map(|s| text.strip_suffix(s))
        .unwrap_or(text)
}

/// The radix and digits of a `0x`/`0o`/`0b` literal.
fn radix_prefix(digits: &str) -> Option<(u32, &str)> {
    let radix = match digits.get(..2)? {
        "0x" | "0X" => 16,
        "0o" => 8,
        "0b" => 2,
        _ => return None,
    };
    let rest = &digits[2..];
    // `from_str_radix` would also take a sign.
    rest.chars()
        .all(|c| c.is_digit(radix))
        .then_some((radix, rest))
}

/// A decimal mantissa with optional fraction and exponent.
fn parse_decimal(digits: &str) -> Option<Number> {
    let (mantissa, exponent) = match digits.find(['e', 'E']) {
        Some(i) => (&digits[..i], digits[i + 1..].parse::<i64>().ok()?),
        None => (digits, 0),
    };
    let (int_part, frac_part) = mantissa.split_once('.').unwrap_or((mantissa, ""));
    let all_digits = |s: &str| s.chars().all(|c| c.is_ascii_digit());
    if int_part.is_empty() || !all_digits(int_part) || !all_digits(frac_part) {
        return None;
    }
    let frac_part = frac_part.trim_end_matches('0');
    let exact = exact_value(int_part, frac_part, exponent);
    // The float fallback parses the same text, so it is the nearest f64.
    exact
        .map(Number::Rational)
        .or_else(|| digits.parse::<f64>().ok().map(Number::Float))
}

/// `int_part.frac_part × 10^exponent` exactly, `None` on overflow.
fn exact_value(int_part: &str, frac_part: &str, exponent: i64) -> Option<Rational> {
    let mantissa: i128 = format!("{int_part}{frac_part}").parse().ok()?;
    if mantissa == 0 {
        return Some(Rational::ZERO);
    }
    let scale = exponent.checked_sub(i64::try_from(frac_part.len()).ok()?)?;
    let power = Rational::int(10).checked_pow(i32::try_from(scale).ok()?)?;
    Rational::int(mantissa).checked_mul(power)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn exact(text: &str) -> Rational {
        parse_literal(text).and_then(Number::as_rational).unwrap()
    }

    #[test]
    fn decimals_are_exact() {
        assert_eq!(exact("1.3"), Rational::new(13, 10).unwrap());
        assert_eq!(exact("0.5"), Rational::new(1, 2).unwrap());
        assert_eq!(exact("2"), Rational::int(2));
        assert_eq!(exact("1e-3"), Rational::new(1, 1000).unwrap());
        assert_eq!(exact("2.5E+2"), Rational::int(250));
        assert_eq!(exact("1_000.25"), Rational::new(400_100, 400).unwrap());
        assert_eq!(exact("1."), Rational::ONE);
        assert_eq!(exact("0.000"), Rational::ZERO);
    }

    #[test]
    fn suffixes_and_radixes() {
        assert_eq!(exact("3f64"), Rational::int(3));
        assert_eq!(exact("2.0_f64"), Rational::int(2));
        assert_eq!(exact("7_u8"), Rational::int(7));
        assert_eq!(exact("0x1F"), Rational::int(31));
        assert_eq!(exact("0x1f32"), Rational::int(0x1f32));
        assert_eq!(exact("0x1Fi64"), Rational::int(31));
        assert_eq!(exact("0b101"), Rational::int(5));
        assert_eq!(exact("0o17i64"), Rational::int(15));
    }

    #[test]
    fn huge_or_tiny_values_become_floats() {
        assert!(matches!(parse_literal("1e400"), Some(Number::Float(x)) if x.is_infinite()));
        assert!(matches!(parse_literal("1e-60"), Some(Number::Float(x)) if x == 1e-60));
        let many = "123456789012345678901234567890123456789012.5";
        assert!(matches!(parse_literal(many), Some(Number::Float(_))));
    }

    #[test]
    fn non_numbers_are_rejected() {
        for text in [
            "", "x", "_1", "-1", ".5", "1.2.3", "1e", "1ee3", "f64", "1.5x", "0xZZ", "0x-1", "0b",
        ] {
            assert!(parse_literal(text).is_none(), "{text:?} parsed");
        }
    }
}
