//! Numbers in lanes: `W` numbers under one name, added, subtracted and
//! multiplied lane by lane, so that the tree recursion's work that does not
//! depend on the other links ([`TreeRecursion`](super::TreeRecursion)) runs
//! for `W` links at once, one link a lane (structure of arrays), which LLVM
//! compiles to packed instructions. Each lane's result is that of `f64`
//! arithmetic on its numbers, to the bit.

use std::ops::{Add, Mul, Sub};

/// The arithmetic the recursion's formulas need, of one number (`f64`) or
/// of one number a link ([`Lanes`]).
pub(super) trait Scalar:
    Copy + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self>
{
    /// `x` in every lane.
    fn splat(x: f64) -> Self;

    /// Whether every lane is zero (either sign).
    fn is_zero(self) -> bool;
}

impl Scalar for f64 {
    #[inline(always)]
    fn splat(x: f64) -> Self {
        x
    }

    #[inline(always)]
    fn is_zero(self) -> bool {
        self == 0.0
    }
}

/// `W` numbers, one a link.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Lanes<const W: usize>(pub(super) [f64; W]);

impl<const W: usize> Lanes<W> {
    /// Lane `k`, if there is one (zero otherwise).
    #[inline(always)]
    pub(super) fn lane(self, k: usize) -> f64 {
        self.0.get(k).copied().unwrap_or_default()
    }

    /// `f` of each pair of lanes.
    #[inline(always)]
    fn zip(self, other: Self, f: impl Fn(f64, f64) -> f64) -> Self {
        let mut lanes = self.0;
        for (a, b) in lanes.iter_mut().zip(other.0) {
            *a = f(*a, b);
        }
        Lanes(lanes)
    }
}

impl<const W: usize> Add for Lanes<W> {
    type Output = Self;

    #[inline(always)]
    fn add(self, other: Self) -> Self {
        self.zip(other, |a, b| a + b)
    }
}

impl<const W: usize> Sub for Lanes<W> {
    type Output = Self;

    #[inline(always)]
    fn sub(self, other: Self) -> Self {
        self.zip(other, |a, b| a - b)
    }
}

impl<const W: usize> Mul for Lanes<W> {
    type Output = Self;

    #[inline(always)]
    fn mul(self, other: Self) -> Self {
        self.zip(other, |a, b| a * b)
    }
}

impl<const W: usize> Scalar for Lanes<W> {
    #[inline(always)]
    fn splat(x: f64) -> Self {
        Lanes([x; W])
    }

    #[inline(always)]
    fn is_zero(self) -> bool {
        self.0.iter().all(|x| *x == 0.0)
    }
}

/// Lane `k` is `field(&each[k])`: one number of each of `W` links.
#[inline(always)]
pub(super) fn gathered<const W: usize, S>(each: &[S; W], field: impl Fn(&S) -> f64) -> Lanes<W> {
    let mut lanes = [0.0; W];
    for (lane, item) in lanes.iter_mut().zip(each) {
        *lane = field(item);
    }
    Lanes(lanes)
}

#[cfg(test)]
mod tests {
    use super::{Lanes, Scalar, gathered};

    /// Numbers of many magnitudes and both signs, whose sums, differences
    /// and products round.
    const A: [f64; 4] = [0.1, -3.7e5, 2.0 / 3.0, -1.0e-9];
    const B: [f64; 4] = [7.3, 1.0 / 7.0, -0.3, 5.5e12];

    #[test]
    fn each_lane_is_the_arithmetic_of_its_numbers_to_the_bit() {
        let (a, b) = (Lanes(A), Lanes(B));
        for (k, (x, y)) in A.iter().zip(B).enumerate() {
            assert_eq!((a + b).lane(k).to_bits(), (x + y).to_bits(), "{x} + {y}");
            assert_eq!((a - b).lane(k).to_bits(), (x - y).to_bits(), "{x} - {y}");
            assert_eq!((a * b).lane(k).to_bits(), (x * y).to_bits(), "{x} * {y}");
        }
    }

    #[test]
    fn lanes_are_zero_only_when_every_one_is() {
        assert!(Lanes([0.0, -0.0]).is_zero());
        assert!(!Lanes([0.0, 1e-300]).is_zero());
        assert!(!Lanes([-2.0, 0.0]).is_zero());
        assert!(0.0_f64.is_zero() && !1e-300_f64.is_zero());
    }

    #[test]
    fn a_gather_takes_one_number_of_each_item_in_order() {
        let items = [(1.0, 'a'), (2.5, 'b'), (-4.0, 'c')];
        assert_eq!(gathered(&items, |item| item.0), Lanes([1.0, 2.5, -4.0]));
        assert_eq!(Lanes::<3>::splat(0.5), Lanes([0.5; 3]));
        assert_eq!(Lanes([1.0, 2.0]).lane(2), 0.0);
    }
}
