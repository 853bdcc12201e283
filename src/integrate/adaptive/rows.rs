//! The pairs' tableaux as the stepping loop reads them: one form for both
//! pairs, padded to DOP853's sixteen slopes, with the stage count a value
//! and every row without its zero weights.
//!
//! One form means one instantiation of the stepping loop for both pairs,
//! hence one call of the accelerations per system: with that single call
//! site the compiler inlines the system's accelerations into it, as into
//! RK4's and Gauss's stage loops (BENCHMARKS.md, "Integrators: cost per
//! evaluation").

use super::tableaux::{EmbeddedPair, ErrorEstimate};
use crate::integrate::runge_kutta::Rate;

/// The most slopes of one step of either pair: DOP853's twelve stages, the
/// slope at the step's end and the dense output's three extra stages.
pub(super) const MAX_SLOPES: usize = 16;

/// The slopes of one step, in the order of the pair's dense output: the
/// stages, the slope at the step's end, then the extra stages; those past
/// the pair's count are unused.
pub(super) type Slopes<const NQ: usize, const NV: usize> = [Rate<NQ, NV>; MAX_SLOPES];

/// A row of a tableau without its zero weights: `(slope, weight)` for the
/// first `count` entries, in the row's order. A quarter of DOP853's
/// weights are zero; skipping them leaves every sum as it was (a product
/// `0 · k` of a finite slope adds a zero, and a sum that starts from `+0`
/// is never `−0`), and so does the padding.
#[derive(Clone, Copy)]
pub(super) struct Terms {
    terms: [(usize, f64); MAX_SLOPES],
    count: usize,
}

impl Terms {
    /// The non-zero weights of `row` (at most [`MAX_SLOPES`] long).
    fn of<const R: usize>(row: &[f64; R]) -> Self {
        let mut terms = [(0, 0.0); MAX_SLOPES];
        let mut count = 0;
        for (j, &w) in row.iter().enumerate().filter(|(_, w)| **w != 0.0) {
            terms[count] = (j, w);
            count += 1;
        }
        Self { terms, count }
    }

    /// `Σⱼ wⱼ · slopes[j]` over the row's terms.
    #[inline(always)]
    pub(super) fn apply<const NQ: usize, const NV: usize>(
        &self,
        slopes: &Slopes<NQ, NV>,
    ) -> Rate<NQ, NV> {
        let mut sum = Rate::ZERO;
        for &(j, w) in self.terms.iter().take(self.count) {
            sum.add_scaled(w, &slopes[j]);
        }
        sum
    }
}

/// How the local error is estimated from the slopes of a step, with the
/// rows of [`Tableau::error`].
#[derive(Clone, Copy)]
pub(super) enum Estimate {
    /// DOPRI5's: the stages' row `e` and the weight `e_new` of the slope at
    /// the step's end, which is therefore evaluated before the error.
    Embedded { e_new: f64 },
    /// DOP853's blend of a fifth- and a third-order difference of the
    /// stages (rows `e5` and `e3`); the slope at the end is evaluated only
    /// for an accepted step.
    FifthAndThird,
}

/// An embedded pair as the stepping loop reads it.
pub(super) struct Tableau {
    /// Number of stages `S`; the slope at the step's end is slope `S`.
    pub(super) stages: usize,
    /// Stage times `cᵢ` as fractions of the step.
    pub(super) c: [f64; MAX_SLOPES],
    /// The stages' rows `aᵢ` (row 0 unused).
    pub(super) a: [Terms; MAX_SLOPES],
    /// The propagated solution's row.
    pub(super) b: Terms,
    /// The error estimate, and its rows (`e`, or `e5` then `e3`).
    pub(super) estimate: Estimate,
    pub(super) error: [Terms; 2],
    /// Order of the propagated solution (Hairer's initial-step heuristic).
    pub(super) order: i32,
    /// The controller's exponent, `1 / (q̂ + 1)`.
    pub(super) exponent: f64,
    /// Smallest factor by which one step may shrink the next.
    pub(super) min_factor: f64,
    /// Largest factor by which one step may grow the next.
    pub(super) max_factor: f64,
    /// The dense output's extra stages: number, time fractions and rows.
    pub(super) extras: usize,
    pub(super) extra_c: [f64; MAX_EXTRAS],
    pub(super) extra: [Terms; MAX_EXTRAS],
    /// The rows of the interpolant's coefficients `r₅, r₆, …`: number and
    /// rows.
    pub(super) dense_rows: usize,
    pub(super) d: [Terms; MAX_DENSE_ROWS],
}

/// The most extra stages of a dense output (DOP853's).
const MAX_EXTRAS: usize = 3;
/// The most rows `d` of a dense output (DOP853's `r₅…r₈`).
const MAX_DENSE_ROWS: usize = 4;

impl Tableau {
    /// `pair` padded to [`MAX_SLOPES`] slopes, its zero weights left out.
    pub(super) fn of<const S: usize, const T: usize>(pair: &EmbeddedPair<S, T>) -> Self {
        let empty = Terms::of(&[0.0; 0]);
        let (estimate, error) = match &pair.estimate {
            ErrorEstimate::Embedded { e, e_new } => {
                (Estimate::Embedded { e_new: *e_new }, [Terms::of(e), empty])
            }
            ErrorEstimate::FifthAndThird { e5, e3 } => {
                (Estimate::FifthAndThird, [Terms::of(e5), Terms::of(e3)])
            }
        };
        let mut tableau = Self {
            stages: S,
            c: [0.0; MAX_SLOPES],
            a: [empty; MAX_SLOPES],
            b: Terms::of(&pair.b),
            estimate,
            error,
            order: pair.order,
            exponent: pair.exponent,
            min_factor: pair.min_factor,
            max_factor: pair.max_factor,
            extras: pair.dense.extra.len(),
            extra_c: [0.0; MAX_EXTRAS],
            extra: [empty; MAX_EXTRAS],
            dense_rows: pair.dense.d.len(),
            d: [empty; MAX_DENSE_ROWS],
        };
        for (i, row) in pair.a.iter().enumerate() {
            (tableau.c[i], tableau.a[i]) = (pair.c[i], Terms::of(row));
        }
        for (k, (c, row)) in pair.dense.extra.iter().enumerate() {
            (tableau.extra_c[k], tableau.extra[k]) = (*c, Terms::of(row));
        }
        for (k, row) in pair.dense.d.iter().enumerate() {
            tableau.d[k] = Terms::of(row);
        }
        tableau
    }
}
