//! The seven spatial vectors of each link of a tree that
//! [`add_tree_pairs`](super::add_tree_pairs) pairs, computed at run time by
//! a loop over the links: Carpentier and Mansard's recursion in the axes of
//! `N` (the engine's `tree_partials` derives the same formulas
//! symbolically), one step outwards and one inwards a link, from each
//! link's placement in its parent, joint axis, speed, acceleration and
//! inertia. Where the same steps unrolled for every link would be code that
//! the processor streams from memory, this loop stays in its cache.
//!
//! Spatial vectors are in `N`'s axes at `N`'s origin: `(ω, v)` for a
//! motion, `(n, f)` for a force.

use super::pairs::TreeLink;

type Vec3 = [f64; 3];
type Mat3 = [[f64; 3]; 3];

/// One link of a tree at a state, as the generated
/// `accelerations_jacobian` computes it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LinkState {
    /// Maps the link's components to its parent's.
    pub rotation: Mat3,
    /// From the parent's origin to the link's, in the parent's axes.
    pub offset: Vec3,
    /// The joint's motion subspace in the link's axes at its origin:
    /// `(e, 0)` for a turn about the unit axis `e`, `(0, e)` for a slide.
    pub axis: [f64; 6],
    /// The joint's speed `q̇`.
    pub speed: f64,
    /// The joint's acceleration `q̈`.
    pub acceleration: f64,
    /// The link's mass.
    pub mass: f64,
    /// The link's first moment about its origin, in its axes.
    pub moment: Vec3,
    /// The link's inertia tensor about its origin, in its axes.
    pub inertia: Mat3,
}

/// Writes into `vectors` `[Sⱼ, Ψ̇ⱼ, Ψ̈ⱼ, yⱼ, zⱼ, wⱼ, uⱼ]` of every link `j` of the tree whose
/// links are `states` (parents before children, placed by `links`' parents)
/// under gravity `gravity` (in `N`'s axes), each `(angular, linear)`:
///
/// ```text
/// Sⱼ = (R a, o × R a + R b)   for the axis (a, b) in the link's axes
/// Ψ̇ⱼ = v_λ × Sⱼ               Ψ̈ⱼ = a_λ × Sⱼ + v_λ × Ψ̇ⱼ
/// vⱼ = v_λ + Sⱼ q̇ⱼ             aⱼ = a_λ + Sⱼ q̈ⱼ + Ψ̇ⱼ q̇ⱼ   (the base at −g)
/// yⱼ = Iᶜⱼ Sⱼ                  zⱼ = İᶜⱼ Sⱼ − Sⱼ ×* hᶜⱼ
/// uⱼ = İᶜⱼ Sⱼ + Sⱼ ×* hᶜⱼ + 2 Iᶜⱼ Ψ̇ⱼ
/// wⱼ = Sⱼ ×* Fⱼ + Iᶜⱼ Ψ̈ⱼ + İᶜⱼ Ψ̇ⱼ + Ψ̇ⱼ ×* hᶜⱼ
/// ```
///
/// with `Iᶜⱼ`, its rate `İᶜⱼ`, the momentum `hᶜⱼ` and the inertia force
/// `Fⱼ` summed over the subtree of `j`.
pub fn tree_link_vectors<const L: usize>(
    states: &[LinkState; L],
    links: &[TreeLink; L],
    gravity: &Vec3,
    vectors: &mut [[[f64; 6]; 7]; L],
) {
    let mut moving = [Moving::ZERO; L];
    let mut subtrees = [Subtree::ZERO; L];
    outwards(states, links, gravity, &mut moving, &mut subtrees);
    inwards(links, &moving, &mut subtrees, vectors);
}

/// `[S, Ψ̇, Ψ̈, y, z, w, u]` of a link from its outward step and its
/// subtree's composites.
#[inline(always)]
fn link_vectors(link: &Moving, subtree: &Subtree) -> [[f64; 6]; 7] {
    let (s, rate) = (&link.subspace, &link.rate);
    let turned = subtree.rate_times(s);
    let carried = force_cross(s, &subtree.momentum);
    let pushed = subtree.inertia.times(rate);
    let y = subtree.inertia.times(s);
    let z = turned.sub(&carried);
    let u = turned.add(&carried).add(&pushed).add(&pushed);
    let w = force_cross(s, &subtree.force)
        .add(&subtree.inertia.times(&link.second_rate))
        .add(&subtree.rate_times(rate))
        .add(&force_cross(rate, &subtree.momentum));
    [
        s.flat(),
        rate.flat(),
        link.second_rate.flat(),
        y.flat(),
        z.flat(),
        w.flat(),
        u.flat(),
    ]
}

/// A spatial vector: `(ω, v)` of a motion, `(n, f)` of a force.
#[derive(Clone, Copy)]
struct Spatial {
    angular: Vec3,
    linear: Vec3,
}

/// The outward step's state of one link: placement in `N`, motion
/// subspace `S`, its rates `Ψ̇`, `Ψ̈`, twist and acceleration.
#[derive(Clone, Copy)]
struct Moving {
    rotation: Mat3,
    origin: Vec3,
    subspace: Spatial,
    rate: Spatial,
    second_rate: Spatial,
    twist: Spatial,
    acceleration: Spatial,
}

/// A spatial inertia about `N`'s origin: mass `m`, first moment `c`,
/// inertia tensor `K`.
#[derive(Clone, Copy)]
struct Inertia {
    mass: f64,
    moment: Vec3,
    tensor: Mat3,
}

/// A subtree's composites: inertia, its rate `(ċ, K̇)`, momentum and
/// inertia force.
#[derive(Clone, Copy)]
struct Subtree {
    inertia: Inertia,
    moment_rate: Vec3,
    inertia_rate: Mat3,
    momentum: Spatial,
    force: Spatial,
}

/// Every link outwards from the base (at rest, accelerating at `−g`), into
/// `moving`, and its own inertia in `N` with rate, momentum and force into
/// `subtrees` on the way: the outward steps depend on each other, the own
/// inertias do not and fill the time the steps wait.
fn outwards<const L: usize>(
    states: &[LinkState; L],
    links: &[TreeLink; L],
    gravity: &Vec3,
    moving: &mut [Moving; L],
    subtrees: &mut [Subtree; L],
) {
    let base = Moving {
        rotation: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        acceleration: Spatial {
            angular: [0.0; 3],
            linear: [-gravity[0], -gravity[1], -gravity[2]],
        },
        ..Moving::ZERO
    };
    for (j, ((state, link), subtree)) in states.iter().zip(links).zip(subtrees).enumerate() {
        let (done, rest) = moving.split_at_mut(j);
        let parent = done.get(link.parent).unwrap_or(&base);
        if let Some(this) = rest.first_mut() {
            *this = step_outwards(parent, state);
            *subtree = own(state, this);
        }
    }
}

/// The link of `state` from its parent's `parent`.
#[inline(always)]
fn step_outwards(parent: &Moving, state: &LinkState) -> Moving {
    let rotation = turned(&parent.rotation, &state.rotation);
    let origin = add3(&parent.origin, &mat_vec(&parent.rotation, &state.offset));
    let [a0, a1, a2, b0, b1, b2] = state.axis;
    let angular = times_axis(&rotation, &[a0, a1, a2]);
    let moved = cross(&origin, &angular);
    let linear = if [b0, b1, b2] == [0.0; 3] {
        moved
    } else {
        add3(&moved, &times_axis(&rotation, &[b0, b1, b2]))
    };
    let subspace = Spatial { angular, linear };
    let (v, a) = (&parent.twist, &parent.acceleration);
    let rate = motion_cross(v, &subspace);
    let second_rate = motion_cross(a, &subspace).add(&motion_cross(v, &rate));
    Moving {
        rotation,
        origin,
        subspace,
        rate,
        second_rate,
        twist: v.add(&subspace.scale(state.speed)),
        acceleration: a
            .add(&subspace.scale(state.acceleration))
            .add(&rate.scale(state.speed)),
    }
}

/// The composites of every subtree, leaves first, summed in `subtrees`
/// from the links' own, and each link's vectors into `vectors` as soon as
/// its subtree is complete (all its descendants come after it).
fn inwards<const L: usize>(
    links: &[TreeLink; L],
    moving: &[Moving; L],
    subtrees: &mut [Subtree; L],
    vectors: &mut [[[f64; 6]; 7]; L],
) {
    for (j, ((link, this), vectors)) in links.iter().zip(moving).zip(vectors).enumerate().rev() {
        let (before, rest) = subtrees.split_at_mut(j);
        if let Some(subtree) = rest.first() {
            *vectors = link_vectors(this, subtree);
            if let Some(parent) = before.get_mut(link.parent) {
                parent.add(subtree);
            }
        }
    }
}

/// The link of `state`'s own inertia in `N` at its placement and motion
/// `link`, with its rate, momentum and inertia force.
#[inline(always)]
fn own(state: &LinkState, link: &Moving) -> Subtree {
    let (rotation, origin, mass) = (&link.rotation, &link.origin, state.mass);
    let turned = mat_vec(rotation, &state.moment);
    let moment = add3(&turned, &vec3(|i| mass * origin[i]));
    let inertia = Inertia {
        mass,
        moment,
        tensor: shifted(&rotated(rotation, &state.inertia), mass, origin, &moment),
    };
    let Spatial {
        angular: w,
        linear: v,
    } = link.twist;
    // ċ = m v + ω × c; K̇ = A + Aᵀ + 2 (c·v) 1 − v cᵀ − c vᵀ with A = [ω]× K.
    let moment_rate = add3(&vec3(|i| mass * v[i]), &cross(&w, &moment));
    let t = mat3(|i, j| inertia.tensor[j][i]);
    let columns = [cross(&w, &t[0]), cross(&w, &t[1]), cross(&w, &t[2])];
    let inertia_rate = plus_diagonal(
        symmetric(|i, j| columns[j][i] + columns[i][j] - v[i] * moment[j] - moment[i] * v[j]),
        2.0 * dot(&moment, &v),
    );
    let momentum = inertia.times(&link.twist);
    let force = inertia
        .times(&link.acceleration)
        .add(&force_cross(&link.twist, &momentum));
    Subtree {
        inertia,
        moment_rate,
        inertia_rate,
        momentum,
        force,
    }
}

/// `R K Rᵀ` of a symmetric `K`; `R K` by scaling the columns of `R` where
/// `K` is diagonal (a body in its principal axes), 9 operations instead
/// of 45.
#[inline(always)]
fn rotated(r: &Mat3, k: &Mat3) -> Mat3 {
    let rk = if [k[0][1], k[0][2], k[1][2]] == [0.0; 3] {
        mat3(|i, j| r[i][j] * k[j][j])
    } else {
        mat_mul(r, k)
    };
    symmetric(|i, j| dot(&rk[i], &r[j]))
}

/// The tensor `k` about a body's point `d` (from `N`'s origin) moved to
/// `N`'s origin, for mass `m` and first moment `c` about `N`'s origin:
/// `K + (2 c·d − m|d|²) 1 − c dᵀ − d cᵀ + m d dᵀ`.
#[inline(always)]
fn shifted(k: &Mat3, m: f64, d: &Vec3, c: &Vec3) -> Mat3 {
    let md = vec3(|i| m * d[i]);
    let outer = symmetric(|i, j| k[i][j] - c[i] * d[j] - d[i] * c[j] + md[i] * d[j]);
    plus_diagonal(outer, 2.0 * dot(c, d) - dot(&md, d))
}

/// The parent's rotation `p` turned by the link's `r`: where `r` is a turn
/// about the link's `z` or `y` axis (as most joints'), by [`turn_about`],
/// 12 operations instead of 45.
#[inline(always)]
fn turned(p: &Mat3, r: &Mat3) -> Mat3 {
    if let Some(turned) = turn_about::<2, 0, 1>(p, r) {
        turned
    } else if let Some(turned) = turn_about::<1, 2, 0>(p, r) {
        turned
    } else {
        mat_mul(p, r)
    }
}

/// `p r` if `r` turns about the coordinate axis `K` (its row and column
/// `K` that axis, its entries `I, J` `[[c, −s], [s, c]]`, with `(K, I, J)`
/// a cyclic order): column `K` of `p` kept and the two others combined.
#[inline(always)]
fn turn_about<const K: usize, const I: usize, const J: usize>(p: &Mat3, r: &Mat3) -> Option<Mat3> {
    let (c, s) = (r[I][I], r[J][I]);
    let turns = r[K] == unit(K) && [r[I][K], r[J][K], r[J][J], r[I][J]] == [0.0, 0.0, c, -s];
    turns.then(|| {
        let mut turned = *p;
        for (row, p) in turned.iter_mut().zip(p) {
            row[I] = p[I] * c + p[J] * s;
            row[J] = p[J] * c - p[I] * s;
        }
        turned
    })
}

/// `m a`: a column of `m` where `a` is the `z` or `y` axis (most joints'
/// axis), no operation instead of 15.
#[inline(always)]
fn times_axis(m: &Mat3, a: &Vec3) -> Vec3 {
    if *a == unit(2) {
        column::<2>(m)
    } else if *a == unit(1) {
        column::<1>(m)
    } else {
        mat_vec(m, a)
    }
}

/// Column `K` of `m`.
#[inline(always)]
fn column<const K: usize>(m: &Mat3) -> Vec3 {
    vec3(|i| m[i][K])
}

/// The coordinate axis `k`.
#[inline(always)]
fn unit(k: usize) -> Vec3 {
    vec3(|i| if i == k { 1.0 } else { 0.0 })
}

/// `m + x 1`.
#[inline(always)]
fn plus_diagonal(mut m: Mat3, x: f64) -> Mat3 {
    for (i, row) in m.iter_mut().enumerate() {
        row[i] += x;
    }
    m
}

/// Zeros, constants rather than `Default` values: the arrays of links
/// start as one `memset` instead of a copy of a default value per link.
const ZERO3: Vec3 = [0.0; 3];

impl Spatial {
    const ZERO: Spatial = Spatial {
        angular: ZERO3,
        linear: ZERO3,
    };

    #[inline(always)]
    fn add(&self, other: &Spatial) -> Spatial {
        Spatial {
            angular: add3(&self.angular, &other.angular),
            linear: add3(&self.linear, &other.linear),
        }
    }

    #[inline(always)]
    fn sub(&self, other: &Spatial) -> Spatial {
        Spatial {
            angular: vec3(|i| self.angular[i] - other.angular[i]),
            linear: vec3(|i| self.linear[i] - other.linear[i]),
        }
    }

    #[inline(always)]
    fn scale(&self, s: f64) -> Spatial {
        Spatial {
            angular: vec3(|i| s * self.angular[i]),
            linear: vec3(|i| s * self.linear[i]),
        }
    }

    /// `(angular, linear)` as six entries.
    #[inline(always)]
    fn flat(&self) -> [f64; 6] {
        let ([a, b, c], [d, e, f]) = (self.angular, self.linear);
        [a, b, c, d, e, f]
    }
}

impl Moving {
    const ZERO: Moving = Moving {
        rotation: [ZERO3; 3],
        origin: ZERO3,
        subspace: Spatial::ZERO,
        rate: Spatial::ZERO,
        second_rate: Spatial::ZERO,
        twist: Spatial::ZERO,
        acceleration: Spatial::ZERO,
    };
}

impl Inertia {
    /// `I x = (K ω + c × v, m v − c × ω)`.
    #[inline(always)]
    fn times(&self, x: &Spatial) -> Spatial {
        let (w, v) = (&x.angular, &x.linear);
        let swung = cross(&self.moment, w);
        Spatial {
            angular: add3(&mat_vec(&self.tensor, w), &cross(&self.moment, v)),
            linear: vec3(|i| self.mass * v[i] - swung[i]),
        }
    }
}

impl Subtree {
    const ZERO: Subtree = Subtree {
        inertia: Inertia {
            mass: 0.0,
            moment: ZERO3,
            tensor: [ZERO3; 3],
        },
        moment_rate: ZERO3,
        inertia_rate: [ZERO3; 3],
        momentum: Spatial::ZERO,
        force: Spatial::ZERO,
    };

    /// `İ x = (K̇ ω + ċ × v, −ċ × ω)`.
    #[inline(always)]
    fn rate_times(&self, x: &Spatial) -> Spatial {
        Spatial {
            angular: add3(
                &mat_vec(&self.inertia_rate, &x.angular),
                &cross(&self.moment_rate, &x.linear),
            ),
            linear: cross(&x.angular, &self.moment_rate),
        }
    }

    /// Adds `other`'s composites.
    #[inline(always)]
    fn add(&mut self, other: &Subtree) {
        self.inertia.mass += other.inertia.mass;
        add_to(&mut self.inertia.moment, &other.inertia.moment);
        add_to(&mut self.moment_rate, &other.moment_rate);
        add_to(&mut self.momentum.angular, &other.momentum.angular);
        add_to(&mut self.momentum.linear, &other.momentum.linear);
        add_to(&mut self.force.angular, &other.force.angular);
        add_to(&mut self.force.linear, &other.force.linear);
        for i in 0..3 {
            add_to(&mut self.inertia.tensor[i], &other.inertia.tensor[i]);
            add_to(&mut self.inertia_rate[i], &other.inertia_rate[i]);
        }
    }
}

/// `a += b`.
#[inline(always)]
fn add_to(a: &mut Vec3, b: &Vec3) {
    for (a, b) in a.iter_mut().zip(b) {
        *a += b;
    }
}

/// `m₁ × m₂ = (ω₁ × ω₂, ω₁ × v₂ + v₁ × ω₂)`.
#[inline(always)]
fn motion_cross(a: &Spatial, b: &Spatial) -> Spatial {
    Spatial {
        angular: cross(&a.angular, &b.angular),
        linear: add3(&cross(&a.angular, &b.linear), &cross(&a.linear, &b.angular)),
    }
}

/// `m ×* f = (ω × n + v × f, ω × f)`.
#[inline(always)]
fn force_cross(m: &Spatial, f: &Spatial) -> Spatial {
    Spatial {
        angular: add3(&cross(&m.angular, &f.angular), &cross(&m.linear, &f.linear)),
        linear: cross(&m.angular, &f.linear),
    }
}

#[inline(always)]
fn cross(a: &Vec3, b: &Vec3) -> Vec3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

#[inline(always)]
fn dot(a: &Vec3, b: &Vec3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[inline(always)]
fn add3(a: &Vec3, b: &Vec3) -> Vec3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

#[inline(always)]
fn mat_vec(m: &Mat3, x: &Vec3) -> Vec3 {
    vec3(|i| dot(&m[i], x))
}

#[inline(always)]
fn mat_mul(a: &Mat3, b: &Mat3) -> Mat3 {
    mat3(|i, j| a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j])
}

/// `[f(0), f(1), f(2)]`.
#[inline(always)]
fn vec3(f: impl Fn(usize) -> f64) -> Vec3 {
    [f(0), f(1), f(2)]
}

/// The matrix of entries `f(i, j)`.
#[inline(always)]
fn mat3(f: impl Fn(usize, usize) -> f64) -> Mat3 {
    [
        [f(0, 0), f(0, 1), f(0, 2)],
        [f(1, 0), f(1, 1), f(1, 2)],
        [f(2, 0), f(2, 1), f(2, 2)],
    ]
}

/// The symmetric matrix of entries `f(i, j)` for `i ≤ j`.
#[inline(always)]
fn symmetric(f: impl Fn(usize, usize) -> f64) -> Mat3 {
    let [a, b, c] = [f(0, 0), f(0, 1), f(0, 2)];
    let [d, e, g] = [f(1, 1), f(1, 2), f(2, 2)];
    [[a, b, c], [b, d, e], [c, e, g]]
}

#[cfg(test)]
mod tests {
    use super::{mat_mul, mat_vec, rotated, times_axis, turned, unit};

    /// A rotation far from the axes, as a parent's.
    const PARENT: [[f64; 3]; 3] = [[0.36, 0.48, -0.8], [-0.8, 0.6, 0.0], [0.48, 0.64, 0.6]];

    #[test]
    fn the_cheaper_paths_give_the_general_products() {
        let (c, s) = (0.28, 0.96);
        let about_z = [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]];
        let about_y = [[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]];
        // About x: not taken by the cheaper path, the general product.
        let about_x = [[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]];
        for r in [about_z, about_y, about_x, PARENT] {
            let (fast, general) = (turned(&PARENT, &r), mat_mul(&PARENT, &r));
            for (a, b) in fast.iter().flatten().zip(general.iter().flatten()) {
                assert!((a - b).abs() < 1e-15, "{fast:?} against {general:?}");
            }
        }
        for a in [unit(0), unit(1), unit(2), [0.6, 0.0, 0.8]] {
            assert_eq!(times_axis(&PARENT, &a), mat_vec(&PARENT, &a));
        }
        let diagonal = [[0.1, 0.0, 0.0], [0.0, 0.2, 0.0], [0.0, 0.0, 0.3]];
        let general = mat_mul(&mat_mul(&PARENT, &diagonal), &transposed(&PARENT));
        let fast = rotated(&PARENT, &diagonal);
        for (a, b) in fast.iter().flatten().zip(general.iter().flatten()) {
            assert!((a - b).abs() < 1e-15, "{fast:?} against {general:?}");
        }
    }

    fn transposed(m: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
        [0, 1, 2].map(|i| [m[0][i], m[1][i], m[2][i]])
    }
}
