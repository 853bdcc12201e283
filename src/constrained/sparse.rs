//! The saddle-point system of a large mechanism with few couplings per row
//! (the N-four-bar mechanism, chains closed into loops): the augmented mass
//! matrix `M̄ = M + ρ AᵀA` factorised by a sparse `L D Lᵀ` in a minimum-degree
//! order, and the multipliers found by the method of multipliers, so that no
//! dense `A M̄⁻¹ Aᵀ` is ever formed.
//!
//! The nonzero structure of `M` and `A` is the same at every state of a
//! mechanism, so it is analysed once: an [`Analysis`] holds the positions of
//! the nonzeros, the elimination order, the pattern of `L` with its fill-in
//! and the list of updates of the factorisation, and each thread keeps the
//! analyses of the last few mechanisms it solved. A call then only checks
//! that its matrices have no nonzero outside the analysed pattern (counting
//! them), gathers the nonzeros and factorises at the cost of the nonzeros of
//! `L`. A matrix with a nonzero outside the pattern (an entry that was zero
//! by chance where the pattern was found) is analysed again with both
//! patterns. Unlike the dense solvers it keeps its work arrays on the heap
//! (a few allocations per call), which keeps the stack small for mechanisms
//! of a hundred coordinates.

use std::cell::RefCell;
use std::rc::Rc;

use super::multipliers::{CONSISTENCY_TOLERANCE, Dependents};
use crate::DynamicsError;
use crate::dynamics::RELATIVE_PIVOT_TOLERANCE;

/// The weight of `AᵀA` against `M` in [`ConstraintSolver::Sparse`]
/// (`ρ ‖A‖² ≈ STIFFNESS ‖M‖`): each multiplier iteration shrinks the
/// violation of a row by about `1 / (1 + STIFFNESS σ)`, `σ` the row's
/// weight in `A M⁻¹ Aᵀ` relative to the largest, at the price of about
/// `log10(STIFFNESS)` digits in the factorisation.
///
/// [`ConstraintSolver::Sparse`]: super::ConstraintSolver::Sparse
pub const STIFFNESS: f64 = 1e6;

/// The multiplier iteration stops once every row holds to this fraction of
/// the largest `Σⱼ |Aᵢⱼ xⱼ| + |cᵢ|` of any row.
const CONVERGED: f64 = 1e-13;

/// The multiplier iteration has stalled (at the rounding of the stiff
/// factorisation) when an iteration leaves more than this fraction of the
/// violation before it; a violation then left beyond
/// [`CONSISTENCY_TOLERANCE`] means contradictory rows.
const STALLED: f64 = 0.99;

/// At most this many multiplier iterations (rows close to dependent
/// converge slowly).
const MAX_ITERATIONS: usize = 100;

/// How many mechanisms' analyses a thread keeps.
const ANALYSES_KEPT: usize = 4;

thread_local! {
    /// The analyses of the mechanisms this thread solved last, the most
    /// recent first.
    static ANALYSES: RefCell<Vec<Rc<Analysis>>> = const { RefCell::new(Vec::new()) };
}

/// The structure of `M̄ = M + ρ AᵀA` for one mechanism: where the nonzeros
/// of `M` and `A` are, the elimination order, the pattern of `L` and where
/// each step of the factorisation writes.
///
/// The factor's values are stored in one array: the pivots `dₖ` at `k`, in
/// elimination order, then the entries of `L` column after column
/// (`n + e` for the `e`-th entry of `rows`).
struct Analysis {
    /// The number of coordinates.
    n: usize,
    /// The number of constraint rows.
    nc: usize,
    /// Every nonzero of `M`, as its index `i n + j` in the flattened matrix.
    mass_pattern: Vec<u32>,
    /// The nonzeros of `M` on and below the diagonal in elimination order,
    /// each as its flattened index and the slot of the factor it adds to.
    mass_slots: Vec<(u32, u32)>,
    /// Every nonzero of `A`, row after row, as its flattened index `i n + j`.
    jacobian_pattern: Vec<u32>,
    /// The columns of those nonzeros.
    columns: Vec<u32>,
    /// Row `i` of `A` is `columns[row_ends[i] - ..]`, from `row_ends[i - 1]`
    /// (`0` for row 0).
    row_ends: Vec<u32>,
    /// For each row of `A` and each pair `b ≤ a` of its nonzeros, the slot of
    /// the factor that `ρ Aᵢₐ Aᵢᵦ` adds to.
    normal_slots: Vec<u32>,
    /// The coordinate eliminated at each step.
    order: Vec<u32>,
    /// Column `k` of `L` has its entries at `column_ends[k - 1]..column_ends[k]`.
    column_ends: Vec<u32>,
    /// The row (in elimination order) of each entry of `L`, ascending in
    /// each column.
    rows: Vec<u32>,
    /// For each column `k` and each pair `b ≤ a` of its entries, the slot
    /// that `Lₐₖ Lᵦₖ dₖ` is taken from.
    update_slots: Vec<u32>,
}

impl Analysis {
    /// The structure of the `n × n` matrix `mass` and the `nc × n` matrix
    /// `jacobian` (both flattened row after row), with the nonzeros of
    /// `previous` (a structure of the same size) added.
    fn new(
        mass: &[f64],
        jacobian: &[f64],
        n: usize,
        nc: usize,
        previous: Option<&Analysis>,
    ) -> Self {
        let mut mass_nonzero: Vec<bool> = mass.iter().map(|&m| m != 0.0).collect();
        let mut jacobian_nonzero: Vec<bool> = jacobian.iter().map(|&a| a != 0.0).collect();
        if let Some(previous) = previous {
            for &e in &previous.mass_pattern {
                mass_nonzero[e as usize] = true;
            }
            for &e in &previous.jacobian_pattern {
                jacobian_nonzero[e as usize] = true;
            }
        }
        for i in 0..n {
            for j in 0..i {
                let either = mass_nonzero[i * n + j] || mass_nonzero[j * n + i];
                mass_nonzero[i * n + j] = either;
                mass_nonzero[j * n + i] = either;
            }
        }
        let mut coupled = mass_nonzero.clone();
        let jacobian_rows: Vec<Vec<usize>> = (0..nc)
            .map(|r| (0..n).filter(|&j| jacobian_nonzero[r * n + j]).collect())
            .collect();
        for row in &jacobian_rows {
            for &i in row {
                for &j in row {
                    coupled[i * n + j] = true;
                }
            }
        }
        let (order, eliminated_with) = minimum_degree_order(coupled, n);
        let mut position = vec![0; n];
        for (k, &p) in order.iter().enumerate() {
            position[p] = k;
        }
        let mut column_ends = Vec::with_capacity(n);
        let mut rows = Vec::new();
        for neighbours in &eliminated_with {
            let mut column: Vec<u32> = neighbours.iter().map(|&i| position[i] as u32).collect();
            column.sort_unstable();
            rows.extend(column);
            column_ends.push(rows.len() as u32);
        }
        let mut analysis = Analysis {
            n,
            nc,
            mass_pattern: Vec::new(),
            mass_slots: Vec::new(),
            jacobian_pattern: Vec::new(),
            columns: Vec::new(),
            row_ends: Vec::with_capacity(nc),
            normal_slots: Vec::new(),
            order: order.iter().map(|&p| p as u32).collect(),
            column_ends,
            rows,
            update_slots: Vec::new(),
        };
        for i in 0..n {
            for j in 0..n {
                if mass_nonzero[i * n + j] {
                    analysis.mass_pattern.push((i * n + j) as u32);
                    if position[i] >= position[j] {
                        let slot = analysis.slot(position[i], position[j]);
                        analysis.mass_slots.push(((i * n + j) as u32, slot));
                    }
                }
            }
        }
        for (r, row) in jacobian_rows.iter().enumerate() {
            for (a, &i) in row.iter().enumerate() {
                analysis.jacobian_pattern.push((r * n + i) as u32);
                analysis.columns.push(i as u32);
                for &j in &row[..=a] {
                    let (high, low) = (position[i].max(position[j]), position[i].min(position[j]));
                    let slot = analysis.slot(high, low);
                    analysis.normal_slots.push(slot);
                }
            }
            analysis.row_ends.push(analysis.columns.len() as u32);
        }
        for k in 0..n {
            let column = analysis.column(k);
            for a in column.clone() {
                for b in column.start..=a {
                    let (high, low) = (analysis.rows[a], analysis.rows[b]);
                    let slot = analysis.slot(high as usize, low as usize);
                    analysis.update_slots.push(slot);
                }
            }
        }
        analysis
    }

    /// The entries of column `k` of `L` (indices into `rows`).
    fn column(&self, k: usize) -> std::ops::Range<usize> {
        let start = if k == 0 { 0 } else { self.column_ends[k - 1] };
        start as usize..self.column_ends[k] as usize
    }

    /// The entries of row `i` of `A` (indices into `columns`).
    fn row(&self, i: usize) -> std::ops::Range<usize> {
        let start = if i == 0 { 0 } else { self.row_ends[i - 1] };
        start as usize..self.row_ends[i] as usize
    }

    /// The slot of the factor holding entry `(high, low)`, `high ≥ low`, in
    /// elimination order: the pivot if they are equal, else the entry of
    /// column `low` of `L` in row `high` (there by the fill-in).
    fn slot(&self, high: usize, low: usize) -> u32 {
        if high == low {
            return high as u32;
        }
        let entry = self
            .column(low)
            .find(|&e| self.rows[e] as usize == high)
            .expect("the analysis couples every pair it eliminates");
        (self.n + entry) as u32
    }

    /// Whether every nonzero of `mass` and `jacobian` (flattened, of a
    /// mechanism of this size, with `mass_nonzeros` and
    /// `jacobian_nonzeros` of them) is in this pattern.
    fn covers(
        &self,
        mass: &[f64],
        mass_nonzeros: usize,
        jacobian: &[f64],
        jacobian_nonzeros: usize,
    ) -> bool {
        let inside = |pattern: &[u32], values: &[f64]| {
            pattern
                .iter()
                .map(|&e| usize::from(values[e as usize] != 0.0))
                .sum::<usize>()
        };
        self.n * self.n == mass.len()
            && self.nc * self.n == jacobian.len()
            && inside(&self.mass_pattern, mass) == mass_nonzeros
            && inside(&self.jacobian_pattern, jacobian) == jacobian_nonzeros
    }
}

/// The elimination order of the symmetric pattern `coupled` (`n × n`,
/// flattened) that takes at every step the coordinate with the fewest
/// remaining couplings (the first of them), counting the fill-in of earlier
/// steps; with the coordinates still coupled to each one when it is
/// eliminated.
fn minimum_degree_order(mut coupled: Vec<bool>, n: usize) -> (Vec<usize>, Vec<Vec<usize>>) {
    let mut degree: Vec<usize> = (0..n)
        .map(|i| (0..n).filter(|&j| j != i && coupled[i * n + j]).count())
        .collect();
    let mut done = vec![false; n];
    let mut order = Vec::with_capacity(n);
    let mut eliminated_with = Vec::with_capacity(n);
    for _ in 0..n {
        let p = (0..n)
            .filter(|&i| !done[i])
            .min_by_key(|&i| degree[i])
            .unwrap_or(0);
        done[p] = true;
        let neighbours: Vec<usize> = (0..n).filter(|&i| !done[i] && coupled[p * n + i]).collect();
        for &i in &neighbours {
            degree[i] -= 1;
            for &j in &neighbours {
                if i != j && !coupled[i * n + j] {
                    coupled[i * n + j] = true;
                    degree[i] += 1;
                }
            }
        }
        order.push(p);
        eliminated_with.push(neighbours);
    }
    (order, eliminated_with)
}

/// The analysis of this thread whose pattern holds every nonzero of `mass`
/// and `jacobian` (flattened, `n` columns), or a new one (with the pattern
/// of the last analysis of the same size, so that entries zero by chance
/// are soon all in).
fn analysis_for(mass: &[f64], jacobian: &[f64], n: usize, nc: usize) -> Rc<Analysis> {
    let count = |values: &[f64]| values.iter().filter(|&&x| x != 0.0).count();
    let (mass_nonzeros, jacobian_nonzeros) = (count(mass), count(jacobian));
    ANALYSES.with_borrow_mut(|analyses| {
        let found = analyses
            .iter()
            .position(|a| a.covers(mass, mass_nonzeros, jacobian, jacobian_nonzeros));
        let analysis = match found {
            Some(i) => analyses.remove(i),
            None => {
                let previous = analyses
                    .iter()
                    .position(|a| a.n == n && a.nc == nc)
                    .map(|i| analyses.remove(i));
                Rc::new(Analysis::new(mass, jacobian, n, nc, previous.as_deref()))
            }
        };
        analyses.insert(0, Rc::clone(&analysis));
        analyses.truncate(ANALYSES_KEPT);
        analysis
    })
}

/// `M̄ = L D Lᵀ` with the structure of an [`Analysis`].
struct SparseFactor {
    analysis: Rc<Analysis>,
    /// The pivots then the entries of `L` (see [`Analysis`]).
    values: Vec<f64>,
}

impl SparseFactor {
    /// `M̄ = M + ρ AᵀA` from its scattered sum `values`, or the first
    /// coordinate (named from `names`) whose pivot is not safely positive.
    fn new(
        analysis: Rc<Analysis>,
        mut values: Vec<f64>,
        names: &[&'static str],
    ) -> Result<Self, DynamicsError> {
        let n = analysis.n;
        let largest = values[..n].iter().fold(0.0f64, |m, &d| m.max(d));
        let tolerance = RELATIVE_PIVOT_TOLERANCE * largest;
        let mut updates = analysis.update_slots.iter();
        for k in 0..n {
            let pivot = values[k];
            if pivot.is_nan() || pivot <= tolerance {
                let p = analysis.order[k] as usize;
                return Err(DynamicsError::SingularMassMatrix {
                    index: p,
                    coordinate: names[p],
                    pivot,
                    null_motion: crate::dynamics::NullMotion::default(),
                });
            }
            let column = analysis.column(k);
            for a in column.clone() {
                let la = values[n + a] / pivot;
                for b in column.start..=a {
                    if let Some(&slot) = updates.next() {
                        values[slot as usize] -= la * values[n + b];
                    }
                }
            }
            for l in &mut values[n + column.start..n + column.end] {
                *l /= pivot;
            }
        }
        Ok(SparseFactor { analysis, values })
    }

    /// `M̄⁻¹ b`.
    fn solve<const N: usize>(&self, b: [f64; N]) -> [f64; N] {
        let Analysis { order, rows, n, .. } = &*self.analysis;
        let (pivots, l) = self.values.split_at(*n);
        let mut y: [f64; N] = std::array::from_fn(|k| b[order[k] as usize]);
        for k in 0..N {
            let yk = y[k];
            for e in self.analysis.column(k) {
                y[rows[e] as usize] -= l[e] * yk;
            }
        }
        for (y, d) in y.iter_mut().zip(pivots) {
            *y /= d;
        }
        for k in (0..N).rev() {
            let correction: f64 = self
                .analysis
                .column(k)
                .map(|e| l[e] * y[rows[e] as usize])
                .sum();
            y[k] -= correction;
        }
        let mut x = [0.0; N];
        for (k, &p) in order.iter().enumerate() {
            x[p as usize] = y[k];
        }
        x
    }
}

/// The sparse counterpart of the dense metric: `M̄ = M + ρ AᵀA` factorised
/// once, for the accelerations and the projections.
pub(crate) struct SparseMetric<const NV: usize, const NC: usize> {
    factor: SparseFactor,
    /// The nonzeros of `A`, in the order of the analysis' `columns`.
    jacobian: Vec<f64>,
    penalty: f64,
}

impl<const NV: usize, const NC: usize> SparseMetric<NV, NC> {
    /// Factorises `M + ρ AᵀA` with `ρ ‖A‖² = STIFFNESS ‖M‖` (largest
    /// diagonal entries); fails as the dense metric does when an entry is not
    /// finite or `M̄` is not positive definite.
    pub(crate) fn new(
        mass: &[[f64; NV]; NV],
        names: &[&'static str; NV],
        jacobian: &[[f64; NV]; NC],
    ) -> Result<Self, DynamicsError> {
        let (mass, jacobian) = (mass.as_flattened(), jacobian.as_flattened());
        let analysis = analysis_for(mass, jacobian, NV, NC);
        let finite = |values: &[f64]| values.iter().all(|v| v.is_finite());
        let jacobian: Vec<f64> = analysis
            .jacobian_pattern
            .iter()
            .map(|&e| jacobian[e as usize])
            .collect();
        if !finite(&jacobian) {
            return Err(DynamicsError::NonFiniteConstraints);
        }
        let mut values = vec![0.0; NV + analysis.rows.len()];
        for &(entry, slot) in &analysis.mass_slots {
            values[slot as usize] += mass[entry as usize];
        }
        if !finite(&values) {
            return Err(DynamicsError::NonFiniteEquations);
        }
        let mut column_norms = [0.0f64; NV];
        for (&j, a) in analysis.columns.iter().zip(&jacobian) {
            column_norms[j as usize] += a * a;
        }
        let largest_mass = values[..NV].iter().fold(0.0f64, |m, &d| m.max(d));
        let largest_row = column_norms.iter().fold(0.0f64, |m, &c| m.max(c));
        let penalty = match (largest_mass > 0.0, largest_row > 0.0) {
            (_, false) => 0.0,
            (true, true) => STIFFNESS * largest_mass / largest_row,
            (false, true) => STIFFNESS / largest_row,
        };
        let mut slots = analysis.normal_slots.iter();
        for i in 0..NC {
            let row = &jacobian[analysis.row(i)];
            for (a, &ra) in row.iter().enumerate() {
                for &rb in &row[..=a] {
                    if let Some(&slot) = slots.next() {
                        values[slot as usize] += penalty * ra * rb;
                    }
                }
            }
        }
        Ok(SparseMetric {
            factor: SparseFactor::new(analysis, values, names)?,
            jacobian,
            penalty,
        })
    }

    /// The nonzero `(j, Aᵢⱼ)` of row `i`.
    fn row(&self, i: usize) -> impl Iterator<Item = (usize, f64)> + '_ {
        let entries = self.factor.analysis.row(i);
        self.factor.analysis.columns[entries.clone()]
            .iter()
            .zip(&self.jacobian[entries])
            .map(|(&j, &a)| (j as usize, a))
    }

    /// `f + Aᵀ μ`.
    fn plus_transpose_times(&self, f: &[f64; NV], mu: &[f64; NC]) -> [f64; NV] {
        let mut sum = *f;
        for (i, m) in mu.iter().enumerate() {
            for (j, a) in self.row(i) {
                sum[j] += a * m;
            }
        }
        sum
    }

    /// The `x` and the least-norm `λ` of `M x = f + Aᵀ λ`, `A x = c`, by
    /// the method of multipliers (see [`iterate`](Self::iterate)); fails if
    /// rows are left violated beyond [`CONSISTENCY_TOLERANCE`]
    /// (contradictory rows).
    pub(crate) fn solve(
        &self,
        f: &[f64; NV],
        c: &[f64; NC],
        dependents: Dependents,
    ) -> Result<([f64; NV], [f64; NC]), DynamicsError> {
        let solution = self.iterate(f, c);
        if dependents == Dependents::MustAgree
            && solution.mismatch > CONSISTENCY_TOLERANCE * solution.scale
        {
            let (row, with) = self.worst_rows(&solution.x, c);
            return Err(DynamicsError::InconsistentConstraints {
                row,
                with,
                mismatch: solution.mismatch,
            });
        }
        let lambda = std::array::from_fn(|i| solution.mu[i] - self.penalty * c[i]);
        Ok((solution.x, lambda))
    }

    /// The smallest correction in the metric of `M` with `A x = c` (as
    /// nearly as the rows allow: a projection iterates anyway).
    pub(crate) fn least_norm(&self, c: &[f64; NC]) -> [f64; NV] {
        self.iterate(&[0.0; NV], c).x
    }

    /// The method of multipliers: `M̄ xₖ = f + Aᵀ μₖ`,
    /// `μₖ₊₁ = μₖ + ρ (c − A xₖ)` from `μ₀ = ρ c`, so that `λ = μ − ρ c`
    /// stays in the range of `A` (the least-norm member of its family).
    /// Stops when the rows hold, or when the violation no longer shrinks
    /// (the rounding of the stiff factorisation, or rows that contradict),
    /// with the best iterate.
    fn iterate(&self, f: &[f64; NV], c: &[f64; NC]) -> Multipliers<NV, NC> {
        let mut mu: [f64; NC] = std::array::from_fn(|i| self.penalty * c[i]);
        let mut best: Option<Multipliers<NV, NC>> = None;
        for _ in 0..MAX_ITERATIONS {
            let x = self.factor.solve(self.plus_transpose_times(f, &mu));
            let (left, mismatch, scale) = self.left_over(&x, c);
            let current = Multipliers {
                x,
                mu,
                mismatch,
                scale,
            };
            match best {
                Some(previous) if mismatch.is_nan() || mismatch >= STALLED * previous.mismatch => {
                    return previous;
                }
                _ if mismatch <= CONVERGED * scale => return current,
                _ => {}
            }
            for (m, l) in mu.iter_mut().zip(&left) {
                *m += self.penalty * l;
            }
            best = Some(current);
        }
        best.unwrap_or(Multipliers {
            x: [0.0; NV],
            mu,
            mismatch: f64::INFINITY,
            scale: 0.0,
        })
    }

    /// What the rows leave undone at `x`, `c − A x`, with its largest
    /// magnitude and the scale it is measured against, the largest
    /// `Σⱼ |Aᵢⱼ xⱼ| + |cᵢ|`.
    fn left_over(&self, x: &[f64; NV], c: &[f64; NC]) -> ([f64; NC], f64, f64) {
        let (mut mismatch, mut scale) = (0.0f64, 0.0f64);
        let left = std::array::from_fn(|i| {
            let (mut sum, mut terms) = (0.0, 0.0);
            for (j, a) in self.row(i) {
                sum += a * x[j];
                terms += (a * x[j]).abs();
            }
            let left = c[i] - sum;
            mismatch = mismatch.max(left.abs());
            scale = scale.max(terms + c[i].abs());
            left
        });
        (left, mismatch, scale)
    }

    /// The rows most and second most violated at `x`.
    fn worst_rows(&self, x: &[f64; NV], c: &[f64; NC]) -> (usize, usize) {
        let (left, _, _) = self.left_over(x, c);
        let (mut worst, mut second) = (0, 0);
        for i in 0..NC {
            let violation = left[i].abs();
            if violation > left[worst].abs() {
                (worst, second) = (i, worst);
            } else if i != worst && (second == worst || violation > left[second].abs()) {
                second = i;
            }
        }
        (worst, second)
    }
}

/// An iterate of the method of multipliers and how far it is off: the
/// largest violation `|cᵢ − Aᵢ x|` and the scale it is measured against.
#[derive(Clone, Copy)]
struct Multipliers<const NV: usize, const NC: usize> {
    x: [f64; NV],
    mu: [f64; NC],
    mismatch: f64,
    scale: f64,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::constrained::ConstraintSolver;
    use crate::constrained::test_systems::{PointOnCircle, TiedMassless};

    /// An arrow matrix (first row and column full, diagonal elsewhere) in
    /// natural order fills in completely; the minimum-degree order leaves
    /// the full coordinate for the end and has no fill.
    #[test]
    fn an_arrow_matrix_is_solved_without_fill() {
        const N: usize = 6;
        let m: [[f64; N]; N] = std::array::from_fn(|i| {
            std::array::from_fn(|j| match (i, j) {
                _ if i == j => 4.0 + i as f64,
                (0, _) | (_, 0) => 1.0,
                _ => 0.0,
            })
        });
        let metric = SparseMetric::<N, 0>::new(&m, &["q"; N], &[]).unwrap();
        assert_eq!(metric.factor.analysis.rows.len(), N - 1, "no fill-in");
        let b = [1.0, -2.0, 3.0, 0.5, -1.5, 2.5];
        let x = metric.factor.solve(b);
        for i in 0..N {
            let mx: f64 = (0..N).map(|j| m[i][j] * x[j]).sum();
            assert!((mx - b[i]).abs() < 1e-14, "row {i}: {mx} vs {}", b[i]);
        }
    }

    /// The product `M x` of a dense matrix.
    fn times<const N: usize>(m: &[[f64; N]; N], x: &[f64; N]) -> [f64; N] {
        std::array::from_fn(|i| (0..N).map(|j| m[i][j] * x[j]).sum())
    }

    /// A mechanism's matrices with new values and the same nonzeros reuse
    /// its analysis; a nonzero outside the pattern (an entry that was zero
    /// by chance) brings a new analysis that also covers the old pattern.
    #[test]
    fn the_analysis_is_reused_until_a_nonzero_falls_outside_it() {
        let chain = |c: f64, k: f64| -> [[f64; 4]; 4] {
            [
                [2.0, c, 0.0, 0.0],
                [c, 3.0, 0.5, 0.0],
                [0.0, 0.5, 4.0, k],
                [0.0, 0.0, k, 5.0],
            ]
        };
        let jacobian = [[1.0, 0.0, 0.0, -1.0]];
        let names = ["a", "b", "c", "d"];
        let first = SparseMetric::new(&chain(0.3, 0.0), &names, &jacobian).unwrap();
        let same = SparseMetric::new(&chain(-0.7, 0.0), &names, &jacobian).unwrap();
        assert!(Rc::ptr_eq(&first.factor.analysis, &same.factor.analysis));
        let coupled = chain(-0.7, 0.9);
        let wider = SparseMetric::new(&coupled, &names, &jacobian).unwrap();
        assert!(!Rc::ptr_eq(&first.factor.analysis, &wider.factor.analysis));
        // The wider pattern holds the narrower one: no new analysis back.
        let back = SparseMetric::new(&chain(0.3, 0.0), &names, &jacobian).unwrap();
        assert!(Rc::ptr_eq(&wider.factor.analysis, &back.factor.analysis));
        // M̄ = M + ρ AᵀA solved exactly with the new coupling.
        let rho = wider.penalty;
        let mut augmented = coupled;
        for (i, j) in [(0, 0), (3, 3)] {
            augmented[i][j] += rho;
        }
        augmented[0][3] -= rho;
        augmented[3][0] -= rho;
        let b = [1.0, -2.0, 0.5, 3.0];
        let x = wider.factor.solve(b);
        let mx = times(&augmented, &x);
        for i in 0..4 {
            assert!((mx[i] - b[i]).abs() < 1e-9 * rho, "{mx:?} vs {b:?}");
        }
    }

    #[test]
    fn a_pendulum_and_a_redundant_row_agree_with_the_rank_revealing_solver() {
        let twice = PointOnCircle::<2> {
            m: 2.0,
            l: 0.5,
            g: 9.81,
        };
        for (q, v) in [([0.3, -0.4], [0.8, 0.6]), ([-0.5, 0.0], [0.0, 2.0])] {
            let dense = ConstraintSolver::RankRevealing
                .accelerations(&twice, 0.0, &q, &v, &[])
                .unwrap();
            let sparse = ConstraintSolver::Sparse
                .accelerations(&twice, 0.0, &q, &v, &[])
                .unwrap();
            for (a, b) in dense.0.iter().zip(&sparse.0) {
                assert!(
                    (a - b).abs() < 1e-10 * (1.0 + a.abs()),
                    "{dense:?} {sparse:?}"
                );
            }
            // The least-norm multipliers: the rod tension shared equally.
            for (a, b) in dense.1.iter().zip(&sparse.1) {
                assert!(
                    (a - b).abs() < 1e-9 * (1.0 + a.abs()),
                    "{dense:?} {sparse:?}"
                );
            }
        }
    }

    #[test]
    fn a_coordinate_without_inertia_tied_by_a_row_has_its_acceleration() {
        let system = TiedMassless {
            m: 2.0,
            g: 9.81,
            push: 5.0,
        };
        let (vdot, [lambda]) = ConstraintSolver::Sparse
            .accelerations(&system, 0.0, &[0.3, 0.3], &[1.0, 1.0], &[])
            .unwrap();
        let expected = system.push / system.m - system.g;
        assert!((vdot[0] - expected).abs() < 1e-9 && (vdot[1] - expected).abs() < 1e-9);
        assert!((lambda + system.push).abs() < 1e-8, "{lambda}");
    }

    #[test]
    fn contradictory_rows_are_named() {
        // x = 0 and 2x = 0 demanding different accelerations.
        let metric = SparseMetric::new(
            &[[1.0, 0.0], [0.0, 1.0]],
            &["x", "y"],
            &[[1.0, 0.0], [2.0, 0.0]],
        )
        .unwrap();
        let error = metric
            .solve(&[0.0, -9.81], &[0.0, 1.0], Dependents::MustAgree)
            .unwrap_err();
        assert!(
            matches!(error, DynamicsError::InconsistentConstraints { .. }),
            "{error:?}"
        );
    }
}
