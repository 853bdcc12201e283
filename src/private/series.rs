//! Truncated Taylor series `x(t₀ + τ) = Σₖ xₖ τᵏ` held as their
//! coefficients `[x₀, x₁, …]` in a `[f64; K]`, and the recurrences that give
//! the coefficient of order `k` of an elementary operation from the lower
//! orders of its operands (automatic differentiation in Taylor form, as in
//! Jorba & Zou 2005 and heyoka).
//!
//! The code that `outputs taylor;` generates (`taylor_coefficients`) calls
//! these functions once per node of the model's expression DAG and per
//! order; [`Taylor`](crate::integrate::Taylor) sums the series. Each function writes
//! order `k` of its result, reading orders `0..=k` of its operands and
//! `0..k` of its own result; a `k` at or beyond `K` writes nothing. None
//! allocates or panics: coefficients are read and written by `get`, and the
//! only indexing is of `[_; N]` arrays by loops over `0..N`.
//!
//! The generated code emits each order up to 31 as its own copy with `k` a
//! constant, so the loops below are written over plain indices (no slices,
//! no iterator adaptors) that unroll to compile-time lengths there and
//! leave nothing to call out of line.

/// `1/k` for the orders the integrator uses, so that the recurrences
/// multiply where they would divide (a division is several times the
/// latency of a multiplication, and the orders form one chain).
const INVERSES: [f64; 64] = {
    let mut inverses = [0.0; 64];
    let mut k = 1;
    while k < 64 {
        inverses[k] = 1.0 / k as f64;
        k += 1;
    }
    inverses
};

/// `1/k` (`k ≥ 1`), from the table below 64.
#[inline(always)]
fn inverse(k: usize) -> f64 {
    match INVERSES.get(k) {
        Some(&r) if k > 0 => r,
        _ => 1.0 / k as f64,
    }
}

/// Writes `value` as coefficient `k` of `x` (nothing if `k ≥ K`).
#[inline(always)]
fn set<const K: usize>(x: &mut [f64; K], k: usize, value: f64) {
    if let Some(slot) = x.get_mut(k) {
        *slot = value;
    }
}

/// Coefficient `k` of `x` (`0` beyond the array).
#[inline(always)]
pub fn at<const K: usize>(x: &[f64; K], k: usize) -> f64 {
    x.get(k).copied().unwrap_or(0.0)
}

/// Coefficient `k` of a constant `c`: `c` at order 0, else 0.
#[inline(always)]
pub fn constant_at(c: f64, k: usize) -> f64 {
    if k == 0 { c } else { 0.0 }
}

/// `Σⱼ wⱼ aⱼ b_{k−j}` for `j` from `from` to `to` (`wⱼ = j` when
/// `weighted`, else 1; `0` when `from > to` or beyond the arrays), its two
/// end terms added last. Those are the terms that hold the newest
/// coefficient of each operand (`a₀ bₖ` and `aₖ b₀` of a product's order
/// `k`), the ones written in the same order as the sum: the interior, from
/// older coefficients, is summed while the previous orders still run, so
/// that the chain from one order to the next waits on two products and two
/// additions only. The interior runs in two independent partial sums, the
/// two lanes of one vector register.
#[inline(always)]
fn reversed_dot<const K: usize>(
    a: &[f64; K],
    b: &[f64; K],
    k: usize,
    (from, to): (usize, usize),
    weighted: bool,
) -> f64 {
    if from > to || to > k || to >= K || k - from >= K {
        return 0.0;
    }
    let term = |j: usize| {
        let w = if weighted { j as f64 } else { 1.0 };
        w * at(a, j) * at(b, k - j)
    };
    if from == to {
        return term(from);
    }
    let mut sums = [0.0; 2];
    let mut j = from + 1;
    while j + 1 < to {
        sums[0] += term(j);
        sums[1] += term(j + 1);
        j += 2;
    }
    let tail = if j < to { term(j) } else { 0.0 };
    ((sums[0] + sums[1]) + tail) + (term(from) + term(to))
}

/// `Σⱼ j aⱼ b_{k−j}` for `j` from `from` to `to`.
#[inline(always)]
fn weighted_cauchy<const K: usize>(
    a: &[f64; K],
    b: &[f64; K],
    k: usize,
    range: (usize, usize),
) -> f64 {
    reversed_dot(a, b, k, range, true)
}

/// `Σⱼ aⱼ b_{k−j}` for `j` from `from` to `to`.
#[inline(always)]
fn cauchy<const K: usize>(a: &[f64; K], b: &[f64; K], k: usize, range: (usize, usize)) -> f64 {
    reversed_dot(a, b, k, range, false)
}

/// The series of a quantity worth `x` now, whose higher coefficients are
/// filled in order by order ([`integral`]).
#[inline(always)]
pub fn start<const K: usize>(x: f64) -> [f64; K] {
    let mut series = [0.0; K];
    set(&mut series, 0, x);
    series
}

/// The series of the time `t₀ + τ`: `[t₀, 1, 0, …]`.
#[inline(always)]
pub fn time<const K: usize>(t: f64) -> [f64; K] {
    let mut series = start(t);
    set(&mut series, 1, 1.0);
    series
}

/// Writes `values[i]` as coefficient `k` of `series[i]`.
#[inline(always)]
pub fn assign_all<const K: usize, const N: usize>(
    series: [&mut [f64; K]; N],
    k: usize,
    values: [f64; N],
) {
    for i in 0..N {
        set(series[i], k, values[i]);
    }
}

/// `x` with `ẋ = rate`: `xₖ = rate_{k−1} / k` (`k ≥ 1`).
#[inline(always)]
pub fn integral<const K: usize>(x: &mut [f64; K], rate: &[f64; K], k: usize) {
    if let Some(below) = k.checked_sub(1) {
        set(x, k, at(rate, below) * inverse(k));
    }
}

/// `c = constant + Σ wᵢ aᵢ`, linear: `cₖ = Σ wᵢ aᵢₖ` (plus the constant at
/// order 0).
#[inline(always)]
pub fn linear<const K: usize, const T: usize>(
    c: &mut [f64; K],
    k: usize,
    constant: f64,
    terms: [(f64, &[f64; K]); T],
) {
    let mut sum = 0.0;
    for (w, a) in terms {
        sum += w * at(a, k);
    }
    set(c, k, constant_at(constant, k) + sum);
}

/// `c = a b`: `cₖ = Σⱼ aⱼ b_{k−j}`.
#[inline(always)]
pub fn product<const K: usize>(c: &mut [f64; K], a: &[f64; K], b: &[f64; K], k: usize) {
    set(c, k, cauchy(a, b, k, (0, k)));
}

/// `c = a / b`: `cₖ = (aₖ − Σ_{j≥1} bⱼ c_{k−j}) / b₀`.
#[inline(always)]
pub fn quotient<const K: usize>(c: &mut [f64; K], a: &[f64; K], b: &[f64; K], k: usize) {
    let value = (at(a, k) - cauchy(b, c, k, (1, k))) / at(b, 0);
    set(c, k, value);
}

/// `c = 1 / b`: `cₖ = (δₖ₀ − Σ_{j≥1} bⱼ c_{k−j}) / b₀`.
#[inline(always)]
pub fn reciprocal<const K: usize>(c: &mut [f64; K], b: &[f64; K], k: usize) {
    let value = (constant_at(1.0, k) - cauchy(b, c, k, (1, k))) / at(b, 0);
    set(c, k, value);
}

/// `s = sin x`, `c = cos x` together: `ṡ = c ẋ`, `ċ = −s ẋ`, so
/// `sₖ = (1/k) Σⱼ j xⱼ c_{k−j}` and `cₖ = −(1/k) Σⱼ j xⱼ s_{k−j}`.
#[inline(always)]
pub fn sin_cos<const K: usize>(s: &mut [f64; K], c: &mut [f64; K], x: &[f64; K], k: usize) {
    if k == 0 {
        let (sine, cosine) = at(x, 0).sin_cos();
        set(s, 0, sine);
        set(c, 0, cosine);
        return;
    }
    let sine = weighted_cauchy(x, c, k, (1, k)) * inverse(k);
    let cosine = -weighted_cauchy(x, s, k, (1, k)) * inverse(k);
    set(s, k, sine);
    set(c, k, cosine);
}

/// `t = tan x` with `w = 1 + t²`: `ṫ = w ẋ`, so `tₖ = (1/k) Σⱼ j xⱼ w_{k−j}`,
/// then `wₖ = Σⱼ tⱼ t_{k−j}` (`k ≥ 1`).
#[inline(always)]
pub fn tan<const K: usize>(t: &mut [f64; K], w: &mut [f64; K], x: &[f64; K], k: usize) {
    if k == 0 {
        let tangent = at(x, 0).tan();
        set(t, 0, tangent);
        set(w, 0, 1.0 + tangent * tangent);
        return;
    }
    let tangent = weighted_cauchy(x, w, k, (1, k)) * inverse(k);
    set(t, k, tangent);
    set(w, k, cauchy(t, t, k, (0, k)));
}

/// `e = exp x`: `ė = e ẋ`, so `eₖ = (1/k) Σⱼ j xⱼ e_{k−j}`.
#[inline(always)]
pub fn exp<const K: usize>(e: &mut [f64; K], x: &[f64; K], k: usize) {
    let value = match k {
        0 => at(x, 0).exp(),
        _ => weighted_cauchy(x, e, k, (1, k)) * inverse(k),
    };
    set(e, k, value);
}

/// `l = ln x`: `x l̇ = ẋ`, so `lₖ = (xₖ − (1/k) Σ_{1≤j<k} j lⱼ x_{k−j}) / x₀`.
#[inline(always)]
pub fn ln<const K: usize>(l: &mut [f64; K], x: &[f64; K], k: usize) {
    let value = match k {
        0 => at(x, 0).ln(),
        _ => {
            let below = weighted_cauchy(l, x, k, (1, k - 1));
            (at(x, k) - below * inverse(k)) / at(x, 0)
        }
    };
    set(l, k, value);
}

/// `s = √x`: `s² = x`, so `sₖ = (xₖ − Σ_{1≤j<k} sⱼ s_{k−j}) / (2 s₀)`.
#[inline(always)]
pub fn sqrt<const K: usize>(s: &mut [f64; K], x: &[f64; K], k: usize) {
    let value = match k {
        0 => at(x, 0).sqrt(),
        _ => {
            let inner = cauchy(s, s, k, (1, k - 1));
            (at(x, k) - inner) / (2.0 * at(s, 0))
        }
    };
    set(s, k, value);
}

/// `a = |x|` away from a zero of `x`: `aₖ = sign(x₀) xₖ`.
#[inline(always)]
pub fn abs<const K: usize>(a: &mut [f64; K], x: &[f64; K], k: usize) {
    let sign = if at(x, 0) < 0.0 { -1.0 } else { 1.0 };
    set(a, k, sign * at(x, k));
}

/// `Σ_{j≥1} mⱼ a_{k−j}`: the part of coefficient `k` of the product `m a`
/// that the orders `≥ 1` of `m` give (of `M(q) v̇`, what the mass matrix's
/// motion adds to `M₀ v̇ₖ`).
#[inline(always)]
pub fn convolution_tail<const K: usize>(m: &[f64; K], a: &[f64; K], k: usize) -> f64 {
    cauchy(m, a, k, (1, k))
}

/// The sum `Σₖ xₖ τᵏ` of the first `n` coefficients (Horner).
#[inline(always)]
pub fn sum<const K: usize>(x: &[f64; K], n: usize, tau: f64) -> f64 {
    x.iter().take(n).rev().fold(0.0, |acc, c| acc * tau + c)
}

#[cfg(test)]
mod tests {
    use super::*;

    const K: usize = 12;

    /// The series of `f(x(t))` built order by order with `step`, for
    /// `x(τ) = x₀ + τ`.
    fn of_line(x0: f64, step: impl Fn(&mut [f64; K], &[f64; K], usize)) -> [f64; K] {
        let x = time::<K>(x0);
        let mut c = [0.0; K];
        for k in 0..K {
            step(&mut c, &x, k);
        }
        c
    }

    /// The Taylor coefficients `f⁽ᵏ⁾(x₀)/k!` from closed-form derivatives.
    fn expected(derivative: impl Fn(usize) -> f64) -> [f64; K] {
        let mut factorial = 1.0;
        std::array::from_fn(|k| {
            if k > 0 {
                factorial *= k as f64;
            }
            derivative(k) / factorial
        })
    }

    fn close(a: &[f64; K], b: &[f64; K]) {
        close_to(a, b, 1e-14);
    }

    fn close_to(a: &[f64; K], b: &[f64; K], tolerance: f64) {
        for (k, (x, y)) in a.iter().zip(b).enumerate() {
            assert!(
                (x - y).abs() <= tolerance * y.abs().max(1.0),
                "order {k}: {x} vs {y}"
            );
        }
    }

    #[test]
    fn elementary_functions_match_their_derivatives() {
        let x0: f64 = 0.7;
        close(&of_line(x0, exp), &expected(|_| x0.exp()));
        close(
            &of_line(x0, ln),
            &expected(|k| match k {
                0 => x0.ln(),
                _ => {
                    (-1f64).powi(k as i32 + 1) * (1..k).product::<usize>() as f64
                        / x0.powi(k as i32)
                }
            }),
        );
        // √x: derivatives (1/2)(−1/2)…(1/2 − k + 1) x^(1/2 − k).
        close(
            &of_line(x0, sqrt),
            &expected(|k| {
                let falling: f64 = (0..k).map(|i| 0.5 - i as f64).product();
                falling * x0.powf(0.5 - k as f64)
            }),
        );
        let sines = expected(|k| (x0 + k as f64 * std::f64::consts::FRAC_PI_2).sin());
        let cosines = expected(|k| (x0 + k as f64 * std::f64::consts::FRAC_PI_2).cos());
        let x = time::<K>(x0);
        let (mut s, mut c) = ([0.0; K], [0.0; K]);
        for k in 0..K {
            sin_cos(&mut s, &mut c, &x, k);
        }
        close(&s, &sines);
        close(&c, &cosines);
        // 1 / x: derivatives (−1)ᵏ k! / x^(k+1).
        close(
            &of_line(x0, reciprocal),
            &expected(|k| {
                (-1f64).powi(k as i32) * (1..=k).product::<usize>() as f64 / x0.powi(k as i32 + 1)
            }),
        );
    }

    #[test]
    fn tangent_is_sine_over_cosine_and_products_multiply() {
        let x = time::<K>(0.4);
        let (mut s, mut c, mut q, mut t, mut w) =
            ([0.0; K], [0.0; K], [0.0; K], [0.0; K], [0.0; K]);
        let (mut square, mut back) = ([0.0; K], [0.0; K]);
        for k in 0..K {
            sin_cos(&mut s, &mut c, &x, k);
            quotient(&mut q, &s, &c, k);
            tan(&mut t, &mut w, &x, k);
            product(&mut square, &x, &x, k);
            quotient(&mut back, &square, &x, k);
        }
        close(&t, &q);
        // Each order of a quotient divides the rounding of the lower ones
        // by `x₀ = 0.4`: 2.5¹¹ ≈ 2e4 ulps at order 11.
        close_to(&back, &x, 1e-11);
        // (0.4 + τ)² = 0.16 + 0.8 τ + τ².
        let mut polynomial = [0.0; K];
        polynomial[..3].copy_from_slice(&[0.16, 0.8, 1.0]);
        close(&square, &polynomial);
        assert!((sum(&square, K, 0.5) - 0.81).abs() < 1e-15);
    }
}
