//! Loops over the pairs of joints of a tree, which the generated code of a
//! large tree calls where the same dot products unrolled for every pair
//! would be code that the processor streams from memory:
//!
//! * the inertia and gravity terms of the partials `∂τ/∂q`, `∂τ/∂v` of its
//!   inverse dynamics, pair of joints by pair of joints, added at run time
//!   to the rows that the generated `accelerations_jacobian` then solves: a
//!   loop over the tree's links and their ancestors reading seven spatial
//!   vectors a link (Carpentier and Mansard's recursion, see the engine's
//!   `tree_partials`), [`add_tree_pairs`];
//! * its mass matrix by composite rigid bodies, two spatial vectors a speed
//!   (see the engine's `tree_mass`), [`tree_mass_matrix`], and the
//!   armatures on its diagonal, [`add_to_diagonal`].

/// One link of the tree: where its pairs go. An index `usize::MAX` is
/// none (the root's parent, a column that is not solved).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TreeLink {
    /// The parent's index among the links (parents before children).
    pub parent: usize,
    /// The index of the link of its joint's first speed: its own for a
    /// joint of one speed; a joint of several speeds (spherical, free) is
    /// as many links, each the parent of the next, sharing one frame.
    pub joint: usize,
    /// The row of the link's speed.
    pub row: usize,
    /// The column of `∂τ/∂q` by the link's speed.
    pub by_q: usize,
    /// The column of `∂τ/∂v` by the link's speed.
    pub by_v: usize,
    /// Where the link's subtree ends among the links (depth-first: its
    /// subtree is the links from it to before `end`).
    pub end: usize,
}

/// `a · b`, six entries.
#[inline]
fn dot(a: &[f64; 6], b: &[f64; 6]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3] + a[4] * b[4] + a[5] * b[5]
}

/// `row[c] += value`, if there is such an entry.
#[inline]
fn add<const C: usize>(row: &mut [f64; C], c: usize, value: f64) {
    if let Some(entry) = row.get_mut(c) {
        *entry += value;
    }
}

/// Link `k` and its ancestors, from `k` to the root.
fn lineage<'a, const L: usize>(
    vectors: &'a [[[f64; 6]; 8]; L],
    links: &'a [TreeLink; L],
    k: usize,
) -> impl Iterator<Item = (&'a [[f64; 6]; 8], &'a TreeLink)> {
    let mut j = k;
    core::iter::from_fn(move || {
        let here = (vectors.get(j)?, links.get(j)?);
        j = here.1.parent;
        Some(here)
    })
}

/// Adds, for every link `i` and each `j` of it and its ancestors, with
/// `vectors[k] = [Sₖ, Ψ̇ₖ, Ψ̈ₖ, Ψ̇ₖ + Φₖ, yₖ, zₖ, wₖ, uₖ]` (motions and
/// forces in one frame):
///
/// ```text
/// ∂τᵢ/∂qⱼ += yᵢ · Ψ̈ⱼ + zᵢ · Ψ̇ⱼ        ∂τᵢ/∂q̇ⱼ += zᵢ · Sⱼ + yᵢ · (Ψ̇ⱼ + Φⱼ)
/// ∂τⱼ/∂qᵢ += Sⱼ · wᵢ   (j ≠ i)      ∂τⱼ/∂q̇ᵢ += Sⱼ · uᵢ   (j ≠ i)
/// ```
///
/// the second row the first's with `i` and `j` exchanged where both are
/// speeds of one joint (each of its columns turns with the others), into
/// `rows[row of τ][column of the variable]` as `links` places them. Link
/// `i`'s own row is found once and its entries added one by one (each gets
/// at most one value from the pairs); the ancestors' rows, one entry pair
/// each, in a second walk up the tree. A column that is not solved gets no
/// dot product; a link whose `Sⱼ` is a unit vector and `Ψ̇ⱼ` zero (a root
/// joint's column in the recursion's frame, as a free base's are) has
/// its products by `Sⱼ` read as one entry and those by `Ψ̇ⱼ` left out:
/// the same values, about a third of the operations of its pairs.
pub fn add_tree_pairs<const C: usize, const N: usize, const L: usize>(
    mut rows: [&mut [f64; C]; N],
    vectors: &[[[f64; 6]; 8]; L],
    links: &[TreeLink; L],
) {
    let units: [Option<usize>; L] = core::array::from_fn(|k| vectors.get(k).and_then(unit_column));
    let unit = |k: usize| units.get(k).copied().flatten();
    for (i, (own, link)) in vectors.iter().zip(links).enumerate() {
        if let Some(row) = rows.get_mut(link.row) {
            let mut j = i;
            for (other, ancestor) in lineage(vectors, links, i) {
                add_ancestor_pair(row, ancestor, own, (other, unit(j)));
                j = ancestor.parent;
            }
        }
        let [.., w, u] = own;
        let mut j = link.parent;
        for (other, ancestor) in lineage(vectors, links, link.parent) {
            if let Some(row) = rows.get_mut(ancestor.row) {
                match (ancestor.joint == link.joint, unit(j)) {
                    (true, _) => add_ancestor_pair(row, link, other, (own, unit(i))),
                    (false, Some(k)) => {
                        add(row, link.by_q, w[k]);
                        add(row, link.by_v, u[k]);
                    }
                    (false, None) => {
                        if link.by_q < C {
                            add(row, link.by_q, dot(&other[0], w));
                        }
                        add(row, link.by_v, dot(&other[0], u));
                    }
                }
            }
            j = ancestor.parent;
        }
    }
}

/// The entry `k` where `S` of `link` (`[S, Ψ̇, ..]`) is one and every
/// other entry zero, if it is a unit vector and `Ψ̇` is zero.
#[inline]
fn unit_column(link: &[[f64; 6]; 8]) -> Option<usize> {
    let [s, rate, ..] = link;
    if rate.iter().any(|&x| x != 0.0) {
        return None;
    }
    unit_entry(s)
}

/// The entry `k` where `s` is one and every other entry zero, if `s` is
/// such a unit vector.
#[inline]
pub(super) fn unit_entry(s: &[f64; 6]) -> Option<usize> {
    let k = s.iter().position(|&x| x == 1.0)?;
    let rest_zero = s.iter().enumerate().all(|(m, &x)| m == k || x == 0.0);
    rest_zero.then_some(k)
}

/// Adds to `row` at the columns of `columns` (link `j`) the pair
/// `(∂τᵢ/∂qⱼ, ∂τᵢ/∂q̇ⱼ)` of the link of `own` (`i`) and `other` (`j`, an
/// ancestor of `i`, `i` itself or a speed of its joint):
/// `yᵢ · Ψ̈ⱼ + zᵢ · Ψ̇ⱼ` and `zᵢ · Sⱼ + yᵢ · (Ψ̇ⱼ + Φⱼ)`; where `unit` is
/// `Some(k)` (`Sⱼ` the unit vector along entry `k`, `Ψ̇ⱼ` zero),
/// `yᵢ · Ψ̈ⱼ` and `zᵢ[k] + yᵢ · (Ψ̇ⱼ + Φⱼ)`.
#[inline(always)]
fn add_ancestor_pair<const C: usize>(
    row: &mut [f64; C],
    columns: &TreeLink,
    own: &[[f64; 6]; 8],
    (other, unit): (&[[f64; 6]; 8], Option<usize>),
) {
    let [.., y, z, _, _] = own;
    let [s, rate, second_rate, driven, ..] = other;
    if columns.by_q < C {
        let by_q = match unit {
            Some(_) => dot(y, second_rate),
            None => dot(y, second_rate) + dot(z, rate),
        };
        add(row, columns.by_q, by_q);
    }
    let by_v = match unit.and_then(|k| z.get(k)) {
        Some(z_k) => z_k + dot(y, driven),
        None => dot(z, s) + dot(y, driven),
    };
    add(row, columns.by_v, by_v);
}

/// One speed of a tree for [`tree_mass_matrix`], the speeds depth-first
/// (each subtree's together, after its joint's).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TreeSpeed {
    /// One past the last of the speeds of its subtree (itself, its
    /// joint's later speeds and its descendants').
    pub end: usize,
    /// The row and column of the speed in `M`.
    pub speed: usize,
}

/// The mass matrix of a tree by composite rigid bodies: with
/// `vectors[k] = [Sₖ, Fₖ]` (speed `k`'s motion subspace column and the
/// momentum `Iᶜₖ Sₖ` of the subtree it moves at unit rate, in one frame
/// about one point),
///
/// ```text
/// Mᵢⱼ = Mⱼᵢ = Sᵢ · Fⱼ    for j from i to before speeds[i].end,
/// ```
///
/// at the rows and columns that `speeds` gives; zero elsewhere. Each `i`
/// runs over a contiguous range of `Fⱼ` with its `Sᵢ` at hand.
pub fn tree_mass_matrix<const N: usize, const L: usize>(
    vectors: &[[[f64; 6]; 2]; L],
    speeds: &[TreeSpeed; L],
) -> [[f64; N]; N] {
    let mut m = [[0.0; N]; N];
    for (i, ([s, _], own)) in vectors.iter().zip(speeds).enumerate() {
        let moved = vectors.get(i..own.end).unwrap_or_default();
        for ([_, force], other) in moved.iter().zip(speeds.get(i..).unwrap_or_default()) {
            let value = dot(s, force);
            for (r, c) in [(own.speed, other.speed), (other.speed, own.speed)] {
                if let Some(entry) = m.get_mut(r).and_then(|row| row.get_mut(c)) {
                    *entry = value;
                }
            }
        }
    }
    m
}

/// Adds each `(k, a)` of `terms` to `m[k][k]` (the armatures of a `M`
/// that [`tree_mass_matrix`] computed, which knows only the links'
/// inertias); an index outside `m` is skipped.
pub fn add_to_diagonal<const N: usize, const K: usize>(
    m: &mut [[f64; N]; N],
    terms: [(usize, f64); K],
) {
    for (k, a) in terms {
        if let Some(entry) = m.get_mut(k).and_then(|row| row.get_mut(k)) {
            *entry += a;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{TreeLink, TreeSpeed, add_to_diagonal, add_tree_pairs, tree_mass_matrix};

    /// A unit vector along entry `k` times `x`.
    fn along(k: usize, x: f64) -> [f64; 6] {
        let mut v = [0.0; 6];
        v[k] = x;
        v
    }

    /// Link 0 the root and link 1 its child, rows in the reverse order
    /// (speed 1 first), each link's columns `(by_q, by_v)` as `columns`.
    fn chain_of_two(columns: [(usize, usize); 2]) -> [TreeLink; 2] {
        let [(q0, v0), (q1, v1)] = columns;
        [
            TreeLink {
                parent: usize::MAX,
                joint: 0,
                row: 1,
                by_q: q0,
                by_v: v0,
                end: 2,
            },
            TreeLink {
                parent: 0,
                joint: 1,
                row: 0,
                by_q: q1,
                by_v: v1,
                end: 2,
            },
        ]
    }

    #[test]
    fn a_chain_of_two_gets_each_pair_once_and_skips_columns_not_solved() {
        // Link 0 the root, link 1 its child; rows in the reverse order
        // (speed 1 first); columns: ∂/∂q₁, ∂/∂v₀, ∂/∂v₁ (∂/∂q₀ not solved).
        let links = chain_of_two([(usize::MAX, 1), (0, 2)]);
        // [S, Ψ̇, Ψ̈, Ψ̇ + Φ, y, z, w, u], each along one entry so that each
        // dot product is one product of the two scales or zero (one-speed
        // joints: Ψ̇ + Φ = 2 Ψ̇).
        let vectors = [
            [
                along(0, 1.0),
                along(1, 2.0),
                along(2, 3.0),
                along(1, 4.0),
                along(1, 5.0),
                along(0, 7.0),
                along(3, 11.0),
                along(4, 13.0),
            ],
            [
                along(3, 17.0),
                along(4, 19.0),
                along(5, 23.0),
                along(4, 38.0),
                along(5, 29.0),
                along(4, 31.0),
                along(0, 37.0),
                along(0, 41.0),
            ],
        ];
        let (mut first, mut second) = ([100.0; 3], [200.0; 3]);
        add_tree_pairs([&mut first, &mut second], &vectors, &links);
        // Row 1 (τ₀): ∂τ₀/∂v₀ = z₀·S₀ + y₀·(Ψ̇₀ + Φ₀) = 7 + 5·4; ∂τ₀/∂q₁ = S₀·w₁
        // = 37, ∂τ₀/∂v₁ = S₀·u₁ = 41 (j = 0 ≺ i = 1); ∂τ₀/∂q₀ not solved.
        assert_eq!(second, [200.0 + 37.0, 200.0 + 27.0, 200.0 + 41.0]);
        // Row 0 (τ₁): ∂τ₁/∂q₁ = y₁·Ψ̈₁ + z₁·Ψ̇₁ = 29·23 + 31·19,
        // ∂τ₁/∂v₁ = z₁·S₁ + y₁·(Ψ̇₁ + Φ₁) = 0, ∂τ₁/∂v₀ = z₁·S₀ + y₁·(Ψ̇₀ + Φ₀) = 0.
        assert_eq!(first, [100.0 + 29.0 * 23.0 + 31.0 * 19.0, 100.0, 100.0]);
    }

    /// A chain of two whose root's `S₀` is a unit vector with `Ψ̇₀ = 0`
    /// (a root's column in its own axes), its pairs read `S₀`'s entry:
    /// the same sums as the dot products over all six entries give.
    #[test]
    fn a_root_column_along_one_axis_gets_the_same_pairs_as_the_dot_products() {
        let links = chain_of_two([(0, 1), (2, 3)]);
        let filled = |seed: f64| -> [f64; 6] { core::array::from_fn(|k| seed + k as f64 / 8.0) };
        let mut root = [0.0; 6].map(|_| [0.0; 6]);
        root[0] = along(2, 1.0);
        for (k, v) in root.iter_mut().enumerate().skip(2) {
            *v = filled(k as f64);
        }
        let child: [[f64; 6]; 8] = core::array::from_fn(|k| filled(0.5 + k as f64));
        let mut root_vectors = [[0.0; 6]; 8];
        root_vectors[..6].copy_from_slice(&root);
        root_vectors[6] = filled(9.0);
        root_vectors[7] = filled(10.0);
        let vectors = [root_vectors, child];
        let (mut first, mut second) = ([0.0; 4], [0.0; 4]);
        add_tree_pairs([&mut first, &mut second], &vectors, &links);
        let dot = |a: &[f64; 6], b: &[f64; 6]| -> f64 { a.iter().zip(b).map(|(x, y)| x * y).sum() };
        let pair = |own: &[[f64; 6]; 8], other: &[[f64; 6]; 8]| {
            let ([s, rate, second_rate, driven], [y, z]) = (
                [&other[0], &other[1], &other[2], &other[3]],
                [&own[4], &own[5]],
            );
            (
                dot(y, second_rate) + dot(z, rate),
                dot(z, s) + dot(y, driven),
            )
        };
        let [
            (root_q, root_v),
            (child_root_q, child_root_v),
            (child_q, child_v),
        ] = [
            pair(&vectors[0], &vectors[0]),
            pair(&vectors[1], &vectors[0]),
            pair(&vectors[1], &vectors[1]),
        ];
        let (w, u) = (&vectors[1][6], &vectors[1][7]);
        let expected_root_row = [
            root_q,
            root_v,
            dot(&vectors[0][0], w),
            dot(&vectors[0][0], u),
        ];
        let expected_child_row = [child_root_q, child_root_v, child_q, child_v];
        for (got, expected) in [(second, expected_root_row), (first, expected_child_row)] {
            for (g, e) in got.iter().zip(expected) {
                assert!(
                    (g - e).abs() <= 1e-12 * e.abs().max(1.0),
                    "{got:?} against {expected:?}"
                );
            }
        }
        assert!(first.iter().chain(&second).all(|&x| x != 0.0));
    }

    #[test]
    fn armatures_add_to_their_diagonal_entries_and_up() {
        let mut m = [[1.0, 2.0], [2.0, 5.0]];
        add_to_diagonal(&mut m, [(1, 0.25), (0, 0.5), (1, 0.125), (7, 9.0)]);
        assert_eq!(m, [[1.5, 2.0], [2.0, 5.375]]);
    }

    #[test]
    fn a_tree_of_three_gets_its_ancestors_pairs_both_ways_and_zero_between_branches() {
        // Speed 0 the root with two children, speeds 2 and 1 (rows of `M`
        // in another order than the table's), depth-first.
        let speeds = [
            TreeSpeed { end: 3, speed: 0 },
            TreeSpeed { end: 2, speed: 2 },
            TreeSpeed { end: 3, speed: 1 },
        ];
        // [S, F]: S₀ along entry 0, S of speed 2 along 4, of speed 1
        // along 1; each F with a share along the others, so that a pair
        // taken wrongly (between the branches) shows.
        let vectors = [
            [along(0, 2.0), along(0, 3.0)],
            [along(4, 5.0), [7.0, 0.0, 0.0, 0.0, 17.0, 0.0]],
            [along(1, 11.0), [19.0, 13.0, 0.0, 0.0, 29.0, 0.0]],
        ];
        let m: [[f64; 3]; 3] = tree_mass_matrix(&vectors, &speeds);
        // M₀₀ = S₀·F₀ = 6; M₂₂ = 5·17, M₀₂ = S₀·F₂ = 2·7; M₁₁ = 11·13,
        // M₀₁ = 2·19; M₁₂ = 0 (two branches, though S₂·F₁ = 5·29).
        assert_eq!(
            m,
            [[6.0, 38.0, 14.0], [38.0, 143.0, 0.0], [14.0, 0.0, 85.0]]
        );
    }
}
