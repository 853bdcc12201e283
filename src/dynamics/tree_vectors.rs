//! The recursion over the links of a large tree that its generated
//! `accelerations_jacobian` runs at run time, in a loop: Carpentier and
//! Mansard's recursion in the axes of `N` (the engine's `tree_partials`
//! derives the same formulas symbolically), one step outwards and one
//! inwards a link, from each link's placement in its parent, joint axis,
//! speed and inertia. A first pass at `q̈ = 0` gives the mass matrix (by
//! composite rigid bodies) and the tree's share of the forcing, which the
//! generated code solves for `q̈`; a second adds what `q̈` changes and
//! gives the seven spatial vectors of each link that
//! [`add_tree_pairs`](super::pairs::add_tree_pairs) pairs. Where the same steps
//! unrolled for every link would be code that the processor streams from
//! memory, this loop stays in its cache. Each link's steps run on its own
//! structures (array of structures), whose pairs of components LLVM packs
//! into SSE2 registers; the same steps for two links at once, one a lane,
//! were no faster (BENCHMARKS.md, "lanes across links"): the loops' time
//! is spread over the loads, stores and copies of a link's working set
//! more than over its arithmetic.
//!
//! Spatial vectors are in `N`'s axes at `N`'s origin: `(ω, v)` for a
//! motion, `(n, f)` for a force. `N` here is the frame of the links'
//! states, which the engine takes, for a tree whose one root is a free or
//! spherical joint, as the root link's axes at its origin at the state (an
//! inertial frame that coincides with the link at that instant; gravity
//! given in it): the pairs are dot products, the same in any frame, and
//! the root's columns are then unit vectors, whose pairs
//! [`add_tree_pairs`](super::pairs::add_tree_pairs) and
//! [`TreeRecursion::mass_and_bias`] read as entries.
//!
//! A joint of several speeds (spherical, free) is as many links, one a
//! speed, each the parent of the next ([`TreeLink::joint`] names the
//! first): the first is placed in the joint's parent, the others at the
//! first's frame; the last carries the link's inertia. Every column's
//! rates `Ψ̇`, `Ψ̈` are taken from the joint's parent, and `Φ = v × S`
//! (`v` the twist of the joint's last link) from the link's own twist.

use super::pairs::{TreeLink, unit_entry};

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
    /// The link's mass.
    pub mass: f64,
    /// The link's first moment about its origin, in its axes.
    pub moment: Vec3,
    /// The link's inertia tensor about its origin, in its axes.
    pub inertia: Mat3,
}

/// The recursion over a tree's links in its two passes around the solve
/// of `M q̈ = f`: [`TreeRecursion::sweep`] outwards and inwards at `q̈ = 0`,
/// which gives `M` and the tree's share of `f`
/// ([`TreeRecursion::mass_and_bias`]); then, with the solved `q̈`,
/// [`TreeRecursion::link_vectors`] adds what the accelerations change and
/// writes the vectors that [`add_tree_pairs`](super::pairs::add_tree_pairs) pairs.
pub struct TreeRecursion<const L: usize> {
    moving: [Moving; L],
    subtrees: [Subtree; L],
    /// `yⱼ = Iᶜⱼ Sⱼ`: the momentum of the subtree of `j` moved by its joint
    /// at unit rate.
    unit_momenta: [Spatial; L],
    /// The base's acceleration, `(0, −g)`.
    base: Spatial,
}

impl<const L: usize> Default for TreeRecursion<L> {
    /// Zeros, for [`TreeRecursion::sweep`] to fill in place (a recursion
    /// returned by value would be copied: kilobytes).
    #[inline]
    fn default() -> Self {
        TreeRecursion {
            moving: [Moving::ZERO; L],
            subtrees: [Subtree::ZERO; L],
            unit_momenta: [Spatial::ZERO; L],
            base: Spatial::ZERO,
        }
    }
}

impl<const L: usize> TreeRecursion<L> {
    /// Both sweeps over the tree whose links are `states` (parents before
    /// children, placed by `links`' parents) under gravity `gravity` (in
    /// `N`'s axes), at `q̈ = 0`: each link's placement, `Sⱼ`, `Ψ̇ⱼ`, twist,
    /// the share `v_λ × Ψ̇ⱼ` of `Ψ̈ⱼ` (the rest waits for the accelerations,
    /// [`TreeRecursion::link_vectors`]) and acceleration (the base at `−g`),
    /// and each subtree's `Iᶜⱼ`, `İᶜⱼ`, `hᶜⱼ`, inertia force `Fⱼ` and
    /// `yⱼ = Iᶜⱼ Sⱼ`.
    pub fn sweep(&mut self, states: &[LinkState; L], links: &[TreeLink; L], gravity: &Vec3) {
        self.base = Spatial {
            angular: [0.0; 3],
            linear: [-gravity[0], -gravity[1], -gravity[2]],
        };
        outwards(states, links, &self.base, &mut self.moving);
        inwards(states, links, &self.moving, &mut self.subtrees);
        for ((y, link), subtree) in self
            .unit_momenta
            .iter_mut()
            .zip(&self.moving)
            .zip(&self.subtrees)
        {
            *y = subtree.inertia.times(&link.subspace);
        }
    }

    /// The mass matrix and the inertia and gravity terms of `τ` at
    /// `q̈ = 0`, at the rows that `links` gives (by composite rigid bodies):
    ///
    /// ```text
    /// Mᵢⱼ = Mⱼᵢ = Sᵢ · Iᶜⱼ Sⱼ   for i an ancestor of j or j itself
    /// τ⁰ⱼ = Sⱼ · Fⱼ
    /// ```
    ///
    /// zero between branches. Only `M[row of j][row of i]` is written, `j`
    /// the descendant: the other half stays zero. The links depth-first,
    /// each `i` runs over the contiguous range of its subtree's `yⱼ` with
    /// its `Sᵢ` at hand.
    pub fn mass_and_bias<const N: usize>(
        &self,
        links: &[TreeLink; L],
    ) -> ([[f64; N]; N], [f64; N]) {
        let (mut mass, mut bias) = ([[0.0; N]; N], [0.0; N]);
        for (i, ((link, moving), subtree)) in links
            .iter()
            .zip(&self.moving)
            .zip(&self.subtrees)
            .enumerate()
        {
            let s = &moving.subspace;
            // `S · x` of a unit `S` is an entry of `x`: the same value.
            let unit = unit_entry(&s.flat());
            let project = |x: &Spatial| match unit {
                Some(k) => x.flat()[k],
                None => dot6(s, x),
            };
            put(&mut bias, link.row, project(&subtree.force));
            let below = links.get(i..link.end).unwrap_or_default();
            let momenta = self.unit_momenta.get(i..link.end).unwrap_or_default();
            for (other, y) in below.iter().zip(momenta) {
                if let Some(row) = mass.get_mut(other.row) {
                    put(row, link.row, project(y));
                }
            }
        }
        (mass, bias)
    }

    /// Writes into `vectors` `[Sⱼ, Ψ̇ⱼ, Ψ̈ⱼ, Ψ̇ⱼ + Φⱼ, yⱼ, zⱼ, wⱼ, uⱼ]` of
    /// every link `j` at the accelerations `accelerations` (by the rows
    /// that `links` gives), each `(angular, linear)`:
    ///
    /// ```text
    /// Ψ̇ⱼ = v_λ × Sⱼ                Ψ̈ⱼ = a_λ × Sⱼ + v_λ × Ψ̇ⱼ      Φⱼ = vⱼ × Sⱼ
    /// vⱼ = v_λ + Sⱼ q̇ⱼ             aⱼ = a_λ + Sⱼ q̈ⱼ + Ψ̇ⱼ q̇ⱼ   (the base at −g)
    /// yⱼ = Iᶜⱼ Sⱼ                  zⱼ = İᶜⱼ Sⱼ − Sⱼ ×* hᶜⱼ
    /// uⱼ = İᶜⱼ Sⱼ + Sⱼ ×* hᶜⱼ + Iᶜⱼ (Ψ̇ⱼ + Φⱼ)
    /// wⱼ = Sⱼ ×* Fⱼ + Iᶜⱼ Ψ̈ⱼ + İᶜⱼ Ψ̇ⱼ + Ψ̇ⱼ ×* hᶜⱼ
    /// ```
    ///
    /// with `Iᶜⱼ`, its rate `İᶜⱼ`, the momentum `hᶜⱼ` and the inertia force
    /// `Fⱼ` summed over the subtree of `j`, and `λ` the parent of `j`'s
    /// joint (`Φⱼ = Ψ̇ⱼ` for a joint of one speed). `Ψ̈ⱼ`'s first term is
    /// taken here, at `a_λ = a⁰_λ + Δa_λ` (the sweep's acceleration and the
    /// share that `q̈` moves, `Δaⱼ = Δa_λ + Sⱼ q̈ⱼ`), and the accelerations
    /// add `Σₖ Iₖ Δaₖ = Iᶜⱼ Δa_λ + Σₘ yₘ q̈ₘ` (`k`, `m` over the subtree of
    /// `j`) to `Fⱼ`.
    pub fn link_vectors<const N: usize>(
        &mut self,
        links: &[TreeLink; L],
        accelerations: &[f64; N],
        vectors: &mut [[[f64; 6]; 8]; L],
    ) {
        let mut moved = [Spatial::ZERO; L];
        let mut pushed = [Spatial::ZERO; L];
        let mut driven = [Spatial::ZERO; L];
        for (j, (link, y)) in links.iter().zip(&self.unit_momenta).enumerate() {
            let (done, rest) = self.moving.split_at_mut(j);
            let above = moved.get(link.parent).copied().unwrap_or(Spatial::ZERO);
            let joint_parent = links.get(link.joint).map_or(usize::MAX, |l| l.parent);
            let parent = match (moved.get(joint_parent), done.get(joint_parent)) {
                (Some(moved), Some(parent)) => parent.acceleration.add(moved),
                _ => self.base,
            };
            let qdd = accelerations.get(link.row).copied().unwrap_or_default();
            if let (Some(moving), Some(moved), Some(pushed), Some(driven)) = (
                rest.first_mut(),
                moved.get_mut(j),
                pushed.get_mut(j),
                driven.get_mut(j),
            ) {
                moving.second_rate = moving
                    .second_rate
                    .add(&motion_cross(&parent, &moving.subspace));
                *moved = above.add(&moving.subspace.scale(qdd));
                *pushed = above;
                *driven = y.scale(qdd);
            }
        }
        for (j, link) in links.iter().enumerate().rev() {
            let (before, rest) = driven.split_at_mut(j);
            if let (Some(parent), Some(this)) = (before.get_mut(link.parent), rest.first()) {
                *parent = parent.add(this);
            }
        }
        for (j, (((vectors, moving), (subtree, y)), (driven, pushed))) in vectors
            .iter_mut()
            .zip(&self.moving)
            .zip(self.subtrees.iter_mut().zip(&self.unit_momenta))
            .zip(driven.iter().zip(&pushed))
            .enumerate()
        {
            subtree.force = subtree
                .force
                .add(&subtree.inertia.times(pushed))
                .add(driven);
            let through_link = match joint_twist(links, &self.moving, j) {
                Some(twist) => motion_cross(twist, &moving.subspace),
                None => moving.rate,
            };
            *vectors = link_vectors(moving, subtree, y, &moving.rate.add(&through_link));
        }
    }
}

/// The twist of link `j`'s joint, that of its last speed's link, if the
/// joint has several speeds; `None` for a joint of one speed (whose
/// `Φ = Ψ̇`).
#[inline(always)]
fn joint_twist<'a, const L: usize>(
    links: &[TreeLink; L],
    moving: &'a [Moving; L],
    j: usize,
) -> Option<&'a Spatial> {
    let joint = links.get(j)?.joint;
    let mut last = j;
    while links.get(last + 1).is_some_and(|l| l.joint == joint) {
        last += 1;
    }
    (joint != j || last != j).then(|| moving.get(last).map(|m| &m.twist))?
}

/// Whether `link`, the `j`-th, is the child of the link just before it
/// (true of the first, a root): then the outward sweep hands the parent's
/// values over in a local rather than through the array just written, whose
/// load, of a store not yet complete and in other pieces, waits for it.
#[inline(always)]
fn follows_its_parent(link: &TreeLink, j: usize) -> bool {
    link.parent == j.wrapping_sub(1)
}

/// `values[i] = value`, if there is such an entry.
#[inline(always)]
fn put<const N: usize>(values: &mut [f64; N], i: usize, value: f64) {
    if let Some(entry) = values.get_mut(i) {
        *entry = value;
    }
}

/// `a · b` of a motion and a force.
#[inline(always)]
fn dot6(a: &Spatial, b: &Spatial) -> f64 {
    dot(&a.angular, &b.angular) + dot(&a.linear, &b.linear)
}

/// `[S, Ψ̇, Ψ̈, Ψ̇ + Φ, y, z, w, u]` of a link from its outward step, its
/// subtree's composites, `y` and `Ψ̇ + Φ`.
#[inline(always)]
fn link_vectors(link: &Moving, subtree: &Subtree, y: &Spatial, driven: &Spatial) -> [[f64; 6]; 8] {
    let (s, rate) = (&link.subspace, &link.rate);
    let turned = subtree.rate_times(s);
    let carried = force_cross(s, &subtree.momentum);
    let z = turned.sub(&carried);
    let u = turned.add(&carried).add(&subtree.inertia.times(driven));
    let w = force_cross(s, &subtree.force)
        .add(&subtree.inertia.times(&link.second_rate))
        .add(&subtree.rate_times(rate))
        .add(&force_cross(rate, &subtree.momentum));
    [
        s.flat(),
        rate.flat(),
        link.second_rate.flat(),
        driven.flat(),
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
/// subspace `S`, its rates `Ψ̇`, `Ψ̈` (only `v_λ × Ψ̇` of it until
/// [`TreeRecursion::link_vectors`]), twist and acceleration at `q̈ = 0`.
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

/// Every link outwards from the base (at rest, accelerating at `base`) at
/// `q̈ = 0`, into `moving`.
fn outwards<const L: usize>(
    states: &[LinkState; L],
    links: &[TreeLink; L],
    base: &Spatial,
    moving: &mut [Moving; L],
) {
    let base = Moving {
        rotation: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        acceleration: *base,
        ..Moving::ZERO
    };
    let mut previous = base;
    for (j, (state, link)) in states.iter().zip(links).enumerate() {
        let parent = if follows_its_parent(link, j) {
            &previous
        } else {
            moving.get(link.parent).unwrap_or(&base)
        };
        previous = match link.joint == j {
            true => step_outwards(parent, parent, state),
            false => {
                let joint_parent = links.get(link.joint).map_or(usize::MAX, |l| l.parent);
                step_outwards(parent, moving.get(joint_parent).unwrap_or(&base), state)
            }
        };
        if let Some(this) = moving.get_mut(j) {
            *this = previous;
        }
    }
}

/// The link of `state` from its parent's `parent`, the rates of its
/// column from the twist of its joint's parent, `joint_parent` (the
/// parent itself for a joint's first speed).
#[inline(always)]
fn step_outwards(parent: &Moving, joint_parent: &Moving, state: &LinkState) -> Moving {
    let rotation = mat_mul(&parent.rotation, &state.rotation);
    let origin = add3(&parent.origin, &mat_vec(&parent.rotation, &state.offset));
    let subspace = subspace(&rotation, &origin, &state.axis);
    let v = &joint_parent.twist;
    let rate = motion_cross(v, &subspace);
    let second_rate = motion_cross(v, &rate);
    Moving {
        rotation,
        origin,
        subspace,
        rate,
        second_rate,
        twist: parent.twist.add(&subspace.scale(state.speed)),
        acceleration: parent.acceleration.add(&rate.scale(state.speed)),
    }
}

/// `S` in `N` of a joint whose subspace in its link's axes at its origin is
/// `(e, b)`, the link at `rotation` and `origin`: `(R e, o × R e + R b)`,
/// without the products by the zero half of a turn (`b = 0`) or a slide
/// (`e = 0`).
#[inline(always)]
fn subspace(rotation: &Mat3, origin: &Vec3, axis: &[f64; 6]) -> Spatial {
    let [a0, a1, a2, b0, b1, b2] = *axis;
    let (e, b) = ([a0, a1, a2], [b0, b1, b2]);
    if b == [0.0; 3] {
        let angular = mat_vec(rotation, &e);
        Spatial {
            angular,
            linear: cross(origin, &angular),
        }
    } else if e == [0.0; 3] {
        Spatial {
            angular: [0.0; 3],
            linear: mat_vec(rotation, &b),
        }
    } else {
        let angular = mat_vec(rotation, &e);
        Spatial {
            angular,
            linear: add3(&cross(origin, &angular), &mat_vec(rotation, &b)),
        }
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
    if state.mass == 0.0 && state.moment == [0.0; 3] && state.inertia == [[0.0; 3]; 3] {
        // A joint's speed before its last (or a massless link).
        return Subtree::ZERO;
    }
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

/// `R K Rᵀ` of a symmetric `K`; of a diagonal one (principal axes, most
/// links) as `Σₖ Kₖₖ rₖ rₖᵀ` over the columns `rₖ` of `R`, without the
/// products by its zeros.
#[inline(always)]
fn rotated(r: &Mat3, k: &Mat3) -> Mat3 {
    let rk = if k[0][1] == 0.0 && k[0][2] == 0.0 && k[1][2] == 0.0 {
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

/// `m + x 1`.
#[inline(always)]
fn plus_diagonal(mut m: Mat3, x: f64) -> Mat3 {
    for (i, row) in m.iter_mut().enumerate() {
        row[i] += x;
    }
    m
}

impl Spatial {
    /// Zero, as a constant: arrays of it are set to zero in place, where
    /// arrays of `Default::default()` were each element copied in.
    const ZERO: Spatial = Spatial {
        angular: [0.0; 3],
        linear: [0.0; 3],
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

impl Moving {
    const ZERO: Moving = Moving {
        rotation: [[0.0; 3]; 3],
        origin: [0.0; 3],
        subspace: Spatial::ZERO,
        rate: Spatial::ZERO,
        second_rate: Spatial::ZERO,
        twist: Spatial::ZERO,
        acceleration: Spatial::ZERO,
    };
}

impl Subtree {
    const ZERO: Subtree = Subtree {
        inertia: Inertia {
            mass: 0.0,
            moment: [0.0; 3],
            tensor: [[0.0; 3]; 3],
        },
        moment_rate: [0.0; 3],
        inertia_rate: [[0.0; 3]; 3],
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
    use super::{LinkState, Mat3, TreeRecursion, Vec3, rotated, subspace};
    use crate::dynamics::pairs::{TreeLink, add_tree_pairs};

    const NONE: usize = usize::MAX;
    /// The masses and lengths of a double pendulum in the plane `z = 0`,
    /// each mass at the tip of its link, and gravity along `−y`.
    const M1: f64 = 1.5;
    const M2: f64 = 0.7;
    const L1: f64 = 0.8;
    const L2: f64 = 0.6;
    const G: f64 = 9.81;

    /// The pendulum's links, their speeds' rows reversed (as the generated
    /// code eliminates a chain), columns `∂/∂q₀, ∂/∂q₁, ∂/∂v₀, ∂/∂v₁`.
    const LINKS: [TreeLink; 2] = [
        TreeLink {
            parent: NONE,
            joint: 0,
            row: 1,
            by_q: 0,
            by_v: 2,
            end: 2,
        },
        TreeLink {
            parent: 0,
            joint: 1,
            row: 0,
            by_q: 1,
            by_v: 3,
            end: 2,
        },
    ];

    /// A link turning about `z` by `angle` at `offset` from its parent's
    /// origin, with its mass `mass` a point at `(length, 0, 0)` in its axes.
    fn turning(angle: f64, offset: f64, speed: f64, mass: f64, length: f64) -> LinkState {
        let (s, c) = angle.sin_cos();
        let l2 = mass * length * length;
        LinkState {
            rotation: [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]],
            offset: [offset, 0.0, 0.0],
            axis: [0.0, 0.0, 1.0, 0.0, 0.0, 0.0],
            speed,
            mass,
            moment: [mass * length, 0.0, 0.0],
            inertia: [[0.0, 0.0, 0.0], [0.0, l2, 0.0], [0.0, 0.0, l2]],
        }
    }

    fn states(q: [f64; 2], v: [f64; 2]) -> [LinkState; 2] {
        [
            turning(q[0], 0.0, v[0], M1, L1),
            turning(q[1], L1, v[1], M2, L2),
        ]
    }

    /// The textbook `M(q)` and `τ(q, q̇, q̈) = M q̈ + C q̇ + G` of the double
    /// pendulum (angles from `x`, the second relative to the first).
    fn closed_form(q: [f64; 2], v: [f64; 2], a: [f64; 2]) -> ([[f64; 2]; 2], [f64; 2]) {
        let (s2, c2) = q[1].sin_cos();
        let c12 = (q[0] + q[1]).cos();
        let m11 = M1 * L1 * L1 + M2 * (L1 * L1 + L2 * L2 + 2.0 * L1 * L2 * c2);
        let m12 = M2 * (L2 * L2 + L1 * L2 * c2);
        let m22 = M2 * L2 * L2;
        let h = M2 * L1 * L2 * s2;
        let tau = [
            m11 * a[0] + m12 * a[1] - h * (2.0 * v[0] * v[1] + v[1] * v[1])
                + (M1 + M2) * G * L1 * q[0].cos()
                + M2 * G * L2 * c12,
            m12 * a[0] + m22 * a[1] + h * v[0] * v[0] + M2 * G * L2 * c12,
        ];
        ([[m11, m12], [m12, m22]], tau)
    }

    fn close(got: f64, want: f64, tolerance: f64) -> bool {
        (got - want).abs() <= tolerance * want.abs().max(1.0)
    }

    #[test]
    fn the_first_pass_gives_the_double_pendulums_mass_matrix_and_bias_at_its_rows() {
        let (q, v) = ([0.4, -1.1], [0.9, -0.3]);
        let mut tree = TreeRecursion::default();
        tree.sweep(&states(q, v), &LINKS, &[0.0, -G, 0.0]);
        let (mass, bias): ([[f64; 2]; 2], [f64; 2]) = tree.mass_and_bias(&LINKS);
        let (m, tau) = closed_form(q, v, [0.0; 2]);
        // Rows reversed: row 0 is speed 1; `M₀₁` at the row of speed 1,
        // the descendant, and the other half zero.
        for (i, j) in [(0, 0), (0, 1), (1, 1)] {
            assert!(close(mass[1 - j][1 - i], m[i][j], 1e-14), "M{i}{j}");
        }
        assert_eq!(mass[1][0], 0.0);
        assert!(close(bias[1], tau[0], 1e-14) && close(bias[0], tau[1], 1e-14));
    }

    /// A body of mass `mass` sliding along `x` of its parent's axes, its
    /// origin at `offset` (`x` the slide), its mass a point at `(0, 0.2, 0)`.
    fn sliding(offset: [f64; 3], mass: f64) -> LinkState {
        let d = 0.2;
        LinkState {
            rotation: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            offset,
            axis: [0.0, 0.0, 0.0, 1.0, 0.0, 0.0],
            speed: 0.5,
            mass,
            moment: [0.0, mass * d, 0.0],
            inertia: [
                [mass * d * d, 0.0, 0.0],
                [0.0, 0.0, 0.0],
                [0.0, 0.0, mass * d * d],
            ],
        }
    }

    #[test]
    fn two_branches_couple_through_their_common_root_only() {
        // A carriage sliding along `x` carrying two sliders along `x`, each
        // on its own branch (parents: none, 0, 0; depth-first, subtrees
        // 0..3, 1..2, 2..3), gravity along `−x`: M is the masses moved by
        // each pair of speeds, and zero between the branches.
        let (m0, m1, m2) = (2.0, 0.7, 1.3);
        let link = |parent: usize, row: usize, end: usize| TreeLink {
            parent,
            joint: row,
            row,
            by_q: NONE,
            by_v: NONE,
            end,
        };
        let links = [link(NONE, 0, 3), link(0, 1, 2), link(0, 2, 3)];
        let states = [
            sliding([0.4, 0.0, 0.0], m0),
            sliding([-0.3, 0.5, 0.0], m1),
            sliding([0.9, -0.2, 0.1], m2),
        ];
        let mut tree = TreeRecursion::default();
        tree.sweep(&states, &links, &[-G, 0.0, 0.0]);
        let (mass, bias): ([[f64; 3]; 3], [f64; 3]) = tree.mass_and_bias(&links);
        let total = m0 + m1 + m2;
        let want = [[total, 0.0, 0.0], [m1, m1, 0.0], [m2, 0.0, m2]];
        for (got, want) in mass.iter().flatten().zip(want.iter().flatten()) {
            assert!(close(*got, *want, 1e-15), "{mass:?}");
        }
        for (got, want) in bias.iter().zip([total * G, m1 * G, m2 * G]) {
            assert!(close(*got, want, 1e-15), "{bias:?}");
        }
    }

    #[test]
    fn the_second_pass_pairs_to_the_central_differences_of_the_closed_form() {
        let (q, v, a) = ([0.4, -1.1], [0.9, -0.3], [-2.0, 1.3]);
        let mut tree = TreeRecursion::default();
        tree.sweep(&states(q, v), &LINKS, &[0.0, -G, 0.0]);
        let mut vectors = [[[0.0; 6]; 8]; 2];
        tree.link_vectors(&LINKS, &[a[1], a[0]], &mut vectors);
        let (mut row0, mut row1) = ([0.0; 4], [0.0; 4]);
        add_tree_pairs([&mut row0, &mut row1], &vectors, &LINKS);
        let h = 1e-6;
        for (k, column) in [(0, 0), (1, 1)] {
            let (mut plus, mut minus) = (q, q);
            plus[k] += h;
            minus[k] -= h;
            let by_q = [0, 1].map(|i| {
                (closed_form(plus, v, a).1[i] - closed_form(minus, v, a).1[i]) / (2.0 * h)
            });
            let (mut plus, mut minus) = (v, v);
            plus[k] += h;
            minus[k] -= h;
            let by_v = [0, 1].map(|i| {
                (closed_form(q, plus, a).1[i] - closed_form(q, minus, a).1[i]) / (2.0 * h)
            });
            // Speed 0's row is 1, speed 1's is 0.
            for (i, row) in [(0, &row1), (1, &row0)] {
                assert!(close(row[column], by_q[i], 1e-7), "∂τ{i}/∂q{k}");
                assert!(close(row[column + 2], by_v[i], 1e-7), "∂τ{i}/∂v{k}");
            }
        }
    }

    /// The rotation by `angle` about the unit `axis` (Rodrigues).
    fn turn(axis: Vec3, angle: f64) -> Mat3 {
        let (s, c) = angle.sin_cos();
        let [x, y, z] = axis;
        let k = [[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]];
        std::array::from_fn(|i| {
            std::array::from_fn(|j| {
                let kk: f64 = (0..3).map(|m| k[i][m] * k[m][j]).sum();
                f64::from(u8::from(i == j)) + s * k[i][j] + (1.0 - c) * kk
            })
        })
    }

    fn unit(v: Vec3) -> Vec3 {
        let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
        v.map(|x| x / norm)
    }

    /// A link's orientation, turned about no coordinate axis.
    fn orientation() -> Mat3 {
        turn(unit([0.3, -0.8, 0.5]), 0.9)
    }

    /// A free body (its six speeds: velocity then angular velocity in its
    /// axes, one link each) carrying a pendulum, at body placement
    /// `(rotation, position)`, pendulum angle `angle` and speeds `v`.
    fn floating(rotation: Mat3, position: Vec3, angle: f64, v: &[f64; 7]) -> [LinkState; 7] {
        let identity = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let (mass, center) = (2.5, [0.1, -0.2, 0.05]);
        std::array::from_fn(|k| match k {
            6 => turning(angle, 0.3, v[6], M2, L2),
            _ => {
                let mut axis = [0.0; 6];
                axis[if k < 3 { k + 3 } else { k - 3 }] = 1.0;
                let (rotation, offset) = match k {
                    0 => (rotation, position),
                    _ => (identity, [0.0; 3]),
                };
                let carries = k == 5;
                let c = center.map(|x| if carries { mass * x } else { 0.0 });
                let inertia = [[0.3, 0.01, 0.0], [0.01, 0.2, -0.02], [0.0, -0.02, 0.4]];
                LinkState {
                    rotation,
                    offset,
                    axis,
                    speed: v[k],
                    mass: if carries { mass } else { 0.0 },
                    moment: c,
                    inertia: inertia.map(|row| row.map(|x| if carries { x } else { 0.0 })),
                }
            }
        })
    }

    #[test]
    fn a_free_joints_pairs_are_the_central_differences_along_its_tangent_directions() {
        // Links 0–5 the free joint's speeds (joint 0), each the parent of
        // the next; link 6 the pendulum on the body. Rows in speed order;
        // columns ∂/∂δ₀…δ₆, then ∂/∂v₀…v₆.
        let links: [TreeLink; 7] = std::array::from_fn(|k| TreeLink {
            parent: k.wrapping_sub(1),
            joint: if k < 6 { 0 } else { 6 },
            row: k,
            by_q: k,
            by_v: 7 + k,
            end: 7,
        });
        let gravity = [0.0, 0.0, -G];
        let rotation = orientation();
        let (position, angle) = ([0.4, -0.3, 1.2], 0.7);
        let v = [0.3, -0.5, 0.8, 1.1, -0.7, 0.4, -1.3];
        let a = [0.2, 0.9, -0.4, -1.0, 0.6, 0.3, 1.5];
        // τ = M q̈ + τ⁰ by the first pass.
        let tau = |states: &[LinkState; 7]| -> [f64; 7] {
            let mut tree = TreeRecursion::default();
            tree.sweep(states, &links, &gravity);
            let (m, bias): ([[f64; 7]; 7], [f64; 7]) = tree.mass_and_bias(&links);
            std::array::from_fn(|i| {
                let lower: f64 = (0..7).map(|j| (m[i][j] + m[j][i]) * a[j]).sum();
                bias[i] + lower - m[i][i] * a[i]
            })
        };
        let mut tree = TreeRecursion::default();
        tree.sweep(&floating(rotation, position, angle, &v), &links, &gravity);
        let mut vectors = [[[0.0; 6]; 8]; 7];
        tree.link_vectors(&links, &a, &mut vectors);
        let mut rows = [[0.0; 14]; 7];
        let [r0, r1, r2, r3, r4, r5, r6] = &mut rows;
        add_tree_pairs([r0, r1, r2, r3, r4, r5, r6], &vectors, &links);
        let h = 1e-6;
        // The body moved along its k-th axis (k < 3) or turned about it.
        let moved = |k: usize, d: f64| -> [LinkState; 7] {
            let (mut r, mut p, mut angle) = (rotation, position, angle);
            match k {
                0..3 => p = std::array::from_fn(|i| p[i] + d * rotation[i][k]),
                3..6 => {
                    let mut axis = [0.0; 3];
                    axis[k - 3] = 1.0;
                    let turned = turn(axis, d);
                    r = std::array::from_fn(|i| {
                        std::array::from_fn(|j| (0..3).map(|m| rotation[i][m] * turned[m][j]).sum())
                    });
                }
                _ => angle += d,
            }
            floating(r, p, angle, &v)
        };
        let sped = |k: usize, d: f64| -> [LinkState; 7] {
            let mut w = v;
            w[k] += d;
            floating(rotation, position, angle, &w)
        };
        for k in 0..7 {
            let by_q = tau(&moved(k, h)).map(|x| x / (2.0 * h));
            let by_q_minus = tau(&moved(k, -h)).map(|x| x / (2.0 * h));
            let by_v = tau(&sped(k, h)).map(|x| x / (2.0 * h));
            let by_v_minus = tau(&sped(k, -h)).map(|x| x / (2.0 * h));
            for i in 0..7 {
                let (want_q, want_v) = (by_q[i] - by_q_minus[i], by_v[i] - by_v_minus[i]);
                assert!(
                    close(rows[i][k], want_q, 1e-7),
                    "∂τ{i}/∂δ{k}: {} against {want_q}",
                    rows[i][k]
                );
                assert!(
                    close(rows[i][7 + k], want_v, 1e-7),
                    "∂τ{i}/∂v{k}: {} against {want_v}",
                    rows[i][7 + k]
                );
            }
        }
    }

    #[test]
    fn a_rotated_tensor_is_the_triple_product_diagonal_or_not() {
        let r = orientation();
        let diagonal = [[0.4, 0.0, 0.0], [0.0, 0.25, 0.0], [0.0, 0.0, 0.1]];
        let full = [[0.4, 0.03, -0.02], [0.03, 0.25, 0.05], [-0.02, 0.05, 0.1]];
        for k in [diagonal, full] {
            let got = rotated(&r, &k);
            for (i, row) in got.iter().enumerate() {
                for (j, entry) in row.iter().enumerate() {
                    let want: f64 = (0..3)
                        .flat_map(|a| (0..3).map(move |b| (a, b)))
                        .map(|(a, b)| r[i][a] * k[a][b] * r[j][b])
                        .sum();
                    assert!(
                        close(*entry, want, 1e-15),
                        "({i}, {j}): {entry} against {want}"
                    );
                }
            }
        }
    }

    /// The motion of the point of the link at `N`'s origin, and of its
    /// axes, as the joint of axis `axis` (in the link's axes) moves by
    /// `±h` from the link at `rotation`, `origin`, by central differences:
    /// `(ω, v)` at `N`'s origin.
    fn moved_by_central_differences(rotation: &Mat3, origin: &Vec3, axis: &[f64; 6]) -> [f64; 6] {
        let h = 1e-6;
        let rotate = |m: &Mat3, x: &Vec3| -> Vec3 {
            std::array::from_fn(|i| (0..3).map(|j| m[i][j] * x[j]).sum())
        };
        let (e, b) = ([axis[0], axis[1], axis[2]], [axis[3], axis[4], axis[5]]);
        let (e_n, b_n) = (rotate(rotation, &e), rotate(rotation, &b));
        let norm = e_n.iter().map(|x| x * x).sum::<f64>().sqrt();
        // The point at `N`'s origin, turned about the line through `origin`
        // along `e_n` by `norm · t` and slid along `b_n` by `t`.
        let point = |t: f64| -> Vec3 {
            let r = if norm == 0.0 {
                turn([0.0, 0.0, 1.0], 0.0)
            } else {
                turn(e_n.map(|x| x / norm), norm * t)
            };
            let away = rotate(&r, &origin.map(|x| -x));
            std::array::from_fn(|i| origin[i] + away[i] + b_n[i] * t)
        };
        let (plus, minus) = (point(h), point(-h));
        let v: Vec3 = std::array::from_fn(|i| (plus[i] - minus[i]) / (2.0 * h));
        [e_n[0], e_n[1], e_n[2], v[0], v[1], v[2]]
    }

    #[test]
    fn a_joints_subspace_in_n_moves_the_point_at_ns_origin_as_its_motion_does() {
        let (rotation, origin) = (orientation(), [0.7, -0.2, 1.1]);
        let turning = [0.0, 0.0, 1.0, 0.0, 0.0, 0.0];
        let sliding = [0.0, 0.0, 0.0, 0.6, 0.0, 0.8];
        let screwing = [0.0, 1.0, 0.0, 0.0, 0.3, 0.0];
        for axis in [turning, sliding, screwing] {
            let got = subspace(&rotation, &origin, &axis).flat();
            let want = moved_by_central_differences(&rotation, &origin, &axis);
            for (g, w) in got.iter().zip(want) {
                assert!(close(*g, w, 1e-8), "{axis:?}: {got:?} against {want:?}");
            }
        }
    }
}
