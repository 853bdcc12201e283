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
    let mut moving = [Moving::default(); L];
    outwards(states, links, gravity, &mut moving);
    let mut subtrees = [Subtree::default(); L];
    inwards(states, links, &moving, &mut subtrees);
    for ((vectors, link), subtree) in vectors.iter_mut().zip(&moving).zip(&subtrees) {
        *vectors = link_vectors(link, subtree);
    }
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
#[derive(Clone, Copy, Default)]
struct Spatial {
    angular: Vec3,
    linear: Vec3,
}

/// The outward step's state of one link: placement in `N`, motion
/// subspace `S`, its rates `Ψ̇`, `Ψ̈`, twist and acceleration.
#[derive(Clone, Copy, Default)]
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
#[derive(Clone, Copy, Default)]
struct Inertia {
    mass: f64,
    moment: Vec3,
    tensor: Mat3,
}

/// A subtree's composites: inertia, its rate `(ċ, K̇)`, momentum and
/// inertia force.
#[derive(Clone, Copy, Default)]
struct Subtree {
    inertia: Inertia,
    moment_rate: Vec3,
    inertia_rate: Mat3,
    momentum: Spatial,
    force: Spatial,
}

/// Every link outwards from the base (at rest, accelerating at `−g`), into
/// `moving`.
fn outwards<const L: usize>(
    states: &[LinkState; L],
    links: &[TreeLink; L],
    gravity: &Vec3,
    moving: &mut [Moving; L],
) {
    let base = Moving {
        rotation: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        acceleration: Spatial {
            angular: [0.0; 3],
            linear: [-gravity[0], -gravity[1], -gravity[2]],
        },
        ..Moving::default()
    };
    for (j, (state, link)) in states.iter().zip(links).enumerate() {
        let (done, rest) = moving.split_at_mut(j);
        let parent = done.get(link.parent).unwrap_or(&base);
        if let Some(this) = rest.first_mut() {
            *this = step_outwards(parent, state);
        }
    }
}

/// The link of `state` from its parent's `parent`.
#[inline(always)]
fn step_outwards(parent: &Moving, state: &LinkState) -> Moving {
    let rotation = mat_mul(&parent.rotation, &state.rotation);
    let origin = add3(&parent.origin, &mat_vec(&parent.rotation, &state.offset));
    let [a0, a1, a2, b0, b1, b2] = state.axis;
    let angular = mat_vec(&rotation, &[a0, a1, a2]);
    let linear = add3(
        &cross(&origin, &angular),
        &mat_vec(&rotation, &[b0, b1, b2]),
    );
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

/// The composites of every subtree into `subtrees`, leaves first.
fn inwards<const L: usize>(
    states: &[LinkState; L],
    links: &[TreeLink; L],
    moving: &[Moving; L],
    subtrees: &mut [Subtree; L],
) {
    for ((subtree, state), link) in subtrees.iter_mut().zip(states).zip(moving) {
        *subtree = own(state, link);
    }
    for (j, link) in links.iter().enumerate().rev() {
        let (before, rest) = subtrees.split_at_mut(j);
        if let (Some(parent), Some(this)) = (before.get_mut(link.parent), rest.first()) {
            parent.add(this);
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

/// `R K Rᵀ` of a symmetric `K`.
#[inline(always)]
fn rotated(r: &Mat3, k: &Mat3) -> Mat3 {
    let rk = mat_mul(r, k);
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

/// `m + x 1`.
#[inline(always)]
fn plus_diagonal(mut m: Mat3, x: f64) -> Mat3 {
    for (i, row) in m.iter_mut().enumerate() {
        row[i] += x;
    }
    m
}

impl Spatial {
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
