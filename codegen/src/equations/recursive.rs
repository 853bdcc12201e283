//! The inertia terms of a tree of revolute joints, by recursion over the
//! tree instead of by dot products of partial velocities: the composite-
//! rigid-body recursion for `M` and the Newton–Euler recursion for the
//! velocity- and gravity-dependent terms, on the same DAG.
//!
//! Both are d'Alembert's principle regrouped. For a revolute joint `k` with
//! unit axis `eₖ` through point `Jₖ`, the partial velocity of any point `P`
//! carried by the joint is `eₖ × (r_P − r_Jₖ)` and that of any frame it
//! carries is `eₖ`; so `Σᵢ (mᵢ a_Gᵢ · ∂v_Gᵢ/∂q̇ₖ + Mᵢ · ∂ωᵢ/∂q̇ₖ)` is `eₖ`
//! dotted with the moment about `Jₖ` of the inertia forces of everything
//! beyond joint `k`, which a sweep from the leaves to the root accumulates
//! in `O(n)`. Every vector lives in the axes of its own link, so a planar
//! chain meets only 2×2 rotations and its zeros fold away at construction.
//!
//! Canonical sums would flatten each step's running totals into the next
//! and spread every coefficient over their terms, making a step cost as
//! much as all before it; so each step's results are [`Pool::group`]ed.
//!
//! The recursion applies when the model is such a tree (see
//! [`JointTree::of`]); otherwise the general assembly runs.

use crate::expr::{ExprId, Node, Pool, Sym, SymKinds};
use crate::kinematics::{Mat3, Vec3, add3, axis_rotation, cross, dot, mat_vec, transpose_mul};
use crate::model::{FrameId, Model, NEWTONIAN, PointId, Vector, unit_axis};

/// A model whose frames are all children of revolute joints on single
/// coordinates, each joint located by a constant offset in its parent
/// link, and whose masses are fixed in links.
pub struct JointTree {
    /// The links, parents before children (the order of the joints).
    links: Vec<Link>,
    /// The bodies and particles, each fixed in one link.
    masses: Vec<Mass>,
    /// Gravity in `N`'s axes.
    gravity: Vec3,
}

/// A link: the frame beyond one joint.
struct Link {
    /// The parent link, `None` for a joint on `N`.
    parent: Option<usize>,
    /// The joint axis (0, 1, 2), an axis of both the parent and the link.
    axis: usize,
    /// The joint's coordinate index.
    coordinate: usize,
    /// From the parent's joint point (or `O`) to this joint's point, in the
    /// parent's axes.
    offset: Vec3,
}

/// A mass fixed in a link.
struct Mass {
    link: usize,
    mass: ExprId,
    /// From the link's joint point to the centre, in the link's axes.
    center: Vec3,
    /// Central inertia in the link's axes (zero for a particle).
    inertia: Mat3,
}

/// The velocity-independent recursion state of one link, in its axes.
struct Motion {
    omega: Vec3,
    /// Angular acceleration at `q̈ = 0`.
    alpha: Vec3,
    /// Acceleration of the joint point at `q̈ = 0`, gravity subtracted.
    accel: Vec3,
}

/// A subtree's mass, first moment and inertia about its joint point.
#[derive(Clone, Copy)]
struct Composite {
    mass: ExprId,
    moment: Vec3,
    inertia: Mat3,
}

impl JointTree {
    /// The tree of `model`, or `None` if the model is not one: a frame not
    /// made by a revolute joint on a bare coordinate, a joint point or mass
    /// not fixed in a link by a constant offset, a mass in `N`, gravity
    /// given in a moving frame.
    pub fn of(model: &Model, pool: &Pool) -> Option<JointTree> {
        if model.frames.len() != model.joints.len() + 1 || model.joints.len() != model.nq() {
            return None;
        }
        let mut link_of_frame = vec![None; model.frames.len()];
        let mut coordinate_used = vec![false; model.nq()];
        let mut links = Vec::with_capacity(model.joints.len());
        for joint in &model.joints {
            let placement = model.frames[joint.frame.0].placement.as_ref()?;
            let Node::Sym(Sym::Coord(k)) = pool.node(placement.angle) else {
                return None;
            };
            let coordinate = *k as usize;
            if std::mem::replace(&mut coordinate_used[coordinate], true) {
                return None;
            }
            let parent = match placement.parent {
                NEWTONIAN => None,
                frame => Some(link_of_frame[frame.0]?),
            };
            let (frame, offset) = located(model, pool, joint.point)?;
            if frame != parent {
                return None;
            }
            link_of_frame[joint.frame.0] = Some(links.len());
            links.push(Link {
                parent,
                axis: placement.principal_axis(pool)?,
                coordinate,
                offset,
            });
        }
        let mut masses = Vec::new();
        for body in &model.bodies {
            let link = link_of_frame[body.frame.0]?;
            let (frame, center) = attachment(model, pool, body.center)?;
            if frame != Some(link) {
                return None;
            }
            masses.push(Mass {
                link,
                mass: body.mass,
                center,
                inertia: body.inertia,
            });
        }
        for particle in &model.particles {
            let (link, center) = attachment(model, pool, particle.at)?;
            masses.push(Mass {
                link: link?,
                mass: particle.mass,
                center,
                inertia: [[pool.zero(); 3]; 3],
            });
        }
        let gravity = match &model.gravity {
            None => [pool.zero(); 3],
            Some(g) => constant_in(g, NEWTONIAN, pool)?,
        };
        Some(JointTree {
            links,
            masses,
            gravity,
        })
    }
}

/// The link a point is fixed in and its offset from that link's joint
/// point (`O` for `N`, link `None`), in the link's axes: a joint point
/// itself, or a point [`located`] from one.
fn attachment(model: &Model, pool: &Pool, point: PointId) -> Option<(Option<usize>, Vec3)> {
    match origin_of(model, point) {
        Some(link) => Some((link, [pool.zero(); 3])),
        None => located(model, pool, point),
    }
}

/// The link whose joint point `point` is placed from, and the offset, if
/// that offset is constant and along the link's own axes.
fn located(model: &Model, pool: &Pool, point: PointId) -> Option<(Option<usize>, Vec3)> {
    let (base, offset) = model.points[point.0].placement.as_ref()?;
    let link = origin_of(model, *base)?;
    let frame = link.map_or(NEWTONIAN, |l| model.joints[l].frame);
    Some((link, constant_in(offset, frame, pool)?))
}

/// `Some(link)` if `point` is the joint point of `link` (`Some(None)` for
/// `O`), `None` if it is no link's origin.
fn origin_of(model: &Model, point: PointId) -> Option<Option<usize>> {
    if point == crate::model::ORIGIN {
        return Some(None);
    }
    model.joints.iter().position(|j| j.point == point).map(Some)
}

/// The components of `v` if it lies along `frame`'s axes only and is
/// constant (numbers and parameters).
fn constant_in(v: &Vector, frame: FrameId, pool: &Pool) -> Option<Vec3> {
    let mut components = [pool.zero(); 3];
    for (f, c) in &v.parts {
        if *f != frame || c.iter().any(|&x| !SymKinds::PARAM.contains(pool.kinds(x))) {
            return None;
        }
        components = *c;
    }
    Some(components)
}

/// `M` and, per coordinate, the inertia and gravity terms that multiply no
/// `q̈`: `Σᵢ (mᵢ (a_bias − g) · vₖ + (I α_bias + ω × Iω) · ωₖ)`.
pub fn inertia_terms(tree: &JointTree, pool: &mut Pool) -> (Vec<Vec<ExprId>>, Vec<ExprId>) {
    let rotations: Vec<Mat3> = tree
        .links
        .iter()
        .map(|link| {
            let q = pool.sym(Sym::Coord(link.coordinate as u32));
            axis_rotation(pool, &unit_axis(pool, link.axis), q)
        })
        .collect();
    let mass_matrix = tree.mass_matrix(pool, &rotations);
    let bias = tree.bias(pool, &rotations);
    (mass_matrix, bias)
}

impl JointTree {
    /// `M` by composite rigid bodies: the subtree beyond joint `j` turning
    /// at unit rate about `eⱼ` has momentum `(eⱼ × hⱼ, Kⱼ eⱼ)` about `Jⱼ`;
    /// `Mₖⱼ` is its angular momentum about `Jₖ`, along `eₖ`, for every
    /// ancestor `k`.
    fn mass_matrix(&self, pool: &mut Pool, rotations: &[Mat3]) -> Vec<Vec<ExprId>> {
        let nq = self.links.len();
        let composites = self.composites(pool, rotations);
        let mut m = vec![vec![pool.zero(); nq]; nq];
        for (j, link) in self.links.iter().enumerate() {
            let e = unit(pool, link.axis);
            let linear = cross(pool, &e, &composites[j].moment);
            let mut linear = group3(pool, &linear);
            let angular = mat_vec(pool, &composites[j].inertia, &e);
            let mut angular = group3(pool, &angular);
            let column = link.coordinate;
            m[column][column] = angular[link.axis];
            let mut l = j;
            while let Some(p) = self.links[l].parent {
                linear = mat_vec(pool, &rotations[l], &linear);
                let rotated = mat_vec(pool, &rotations[l], &angular);
                let shift = cross(pool, &self.links[l].offset, &linear);
                linear = group3(pool, &linear);
                let sum = add3(pool, &rotated, &shift);
                angular = group3(pool, &sum);
                let row = self.links[p].coordinate;
                m[row][column] = angular[self.links[p].axis];
                m[column][row] = m[row][column];
                l = p;
            }
        }
        m
    }

    /// Mass, first moment and inertia of every subtree about its joint
    /// point, in its link's axes, leaves first.
    fn composites(&self, pool: &mut Pool, rotations: &[Mat3]) -> Vec<Composite> {
        let zero = pool.zero();
        let mut composites = vec![
            Composite {
                mass: zero,
                moment: [zero; 3],
                inertia: [[zero; 3]; 3],
            };
            self.links.len()
        ];
        for mass in &self.masses {
            let own = Composite {
                mass: mass.mass,
                moment: mass.center.map(|c| pool.mul(mass.mass, c)),
                inertia: mass.inertia,
            };
            let own = shifted(pool, &own, &mass.center, &own.moment);
            composites[mass.link] = combined(pool, &composites[mass.link], &own);
        }
        for l in (0..self.links.len()).rev() {
            let Some(p) = self.links[l].parent else {
                continue;
            };
            let c = grouped(pool, &composites[l]);
            let rotated = Composite {
                mass: c.mass,
                moment: mat_vec(pool, &rotations[l], &c.moment),
                inertia: rotate_tensor(pool, &rotations[l], &c.inertia),
            };
            let moved_moment = [0, 1, 2].map(|i| {
                let shift = pool.mul(c.mass, self.links[l].offset[i]);
                pool.add(rotated.moment[i], shift)
            });
            let moved = shifted(pool, &rotated, &self.links[l].offset, &moved_moment);
            composites[p] = combined(pool, &composites[p], &moved);
        }
        composites
    }

    /// The Newton–Euler sweeps: motions from the root out, then the moment
    /// about each joint point of the inertia forces beyond it (gravity as an
    /// upward acceleration of the base), along the joint axis.
    fn bias(&self, pool: &mut Pool, rotations: &[Mat3]) -> Vec<ExprId> {
        let motions = self.motions(pool, rotations);
        let zero = pool.zero();
        let mut force = vec![[zero; 3]; self.links.len()];
        let mut moment = vec![[zero; 3]; self.links.len()];
        for mass in &self.masses {
            let (f, n) = inertia_wrench(pool, mass, &motions[mass.link]);
            force[mass.link] = add3(pool, &force[mass.link], &f);
            moment[mass.link] = add3(pool, &moment[mass.link], &n);
        }
        let mut bias = vec![zero; self.links.len()];
        for l in (0..self.links.len()).rev() {
            let link = &self.links[l];
            bias[link.coordinate] = moment[l][link.axis];
            let Some(p) = link.parent else {
                continue;
            };
            let f = group3(pool, &force[l]);
            let f = mat_vec(pool, &rotations[l], &f);
            let n = group3(pool, &moment[l]);
            let n = mat_vec(pool, &rotations[l], &n);
            let lever = cross(pool, &link.offset, &f);
            force[p] = add3(pool, &force[p], &f);
            let n = add3(pool, &n, &lever);
            moment[p] = add3(pool, &moment[p], &n);
        }
        bias
    }

    /// `ω`, `α` and the joint point's acceleration of every link at
    /// `q̈ = 0`, each in its link's axes; the base accelerates at `−g`.
    fn motions(&self, pool: &mut Pool, rotations: &[Mat3]) -> Vec<Motion> {
        let zero = pool.zero();
        let base = Motion {
            omega: [zero; 3],
            alpha: [zero; 3],
            accel: self.gravity.map(|g| pool.neg(g)),
        };
        let mut motions: Vec<Motion> = Vec::with_capacity(self.links.len());
        for (l, link) in self.links.iter().enumerate() {
            let parent = link.parent.map_or(&base, |p| &motions[p]);
            let r = &rotations[l];
            let d = &link.offset;
            // a_J = a_p + α_p × d + ω_p × (ω_p × d), then into the link's axes.
            let tangential = cross(pool, &parent.alpha, d);
            let omega_d = cross(pool, &parent.omega, d);
            let centripetal = cross(pool, &parent.omega, &omega_d);
            let accel = add3(pool, &parent.accel, &tangential);
            let accel = add3(pool, &accel, &centripetal);
            let accel = transpose_mul(pool, r, &accel);
            // ω = Rᵀ ω_p + q̇ e;  α = Rᵀ α_p + (Rᵀ ω_p) × q̇ e.
            let qd = pool.sym(Sym::Speed(link.coordinate as u32));
            let mut spin = [zero; 3];
            spin[link.axis] = qd;
            let carried = transpose_mul(pool, r, &parent.omega);
            let omega = add3(pool, &carried, &spin);
            let alpha = transpose_mul(pool, r, &parent.alpha);
            let coriolis = cross(pool, &carried, &spin);
            let alpha = add3(pool, &alpha, &coriolis);
            motions.push(Motion {
                omega: group3(pool, &omega),
                alpha: group3(pool, &alpha),
                accel: group3(pool, &accel),
            });
        }
        motions
    }
}

/// The inertia force `m a_G` of a mass and its moment about the link's
/// joint point, `I α + ω × Iω + c × m a_G`, at `q̈ = 0`.
fn inertia_wrench(pool: &mut Pool, mass: &Mass, motion: &Motion) -> (Vec3, Vec3) {
    let c = &mass.center;
    let tangential = cross(pool, &motion.alpha, c);
    let omega_c = cross(pool, &motion.omega, c);
    let centripetal = cross(pool, &motion.omega, &omega_c);
    let a = add3(pool, &motion.accel, &tangential);
    let a = add3(pool, &a, &centripetal);
    let a = group3(pool, &a);
    let force = a.map(|x| pool.mul(mass.mass, x));
    let i_alpha = mat_vec(pool, &mass.inertia, &motion.alpha);
    let h = mat_vec(pool, &mass.inertia, &motion.omega);
    let gyroscopic = cross(pool, &motion.omega, &h);
    let lever = cross(pool, c, &force);
    let moment = add3(pool, &i_alpha, &gyroscopic);
    (force, add3(pool, &moment, &lever))
}

/// Each component as one operand ([`Pool::group`]).
fn group3(pool: &mut Pool, v: &Vec3) -> Vec3 {
    v.map(|x| pool.group(x))
}

/// A composite with every entry grouped.
fn grouped(pool: &mut Pool, c: &Composite) -> Composite {
    Composite {
        mass: c.mass,
        moment: group3(pool, &c.moment),
        inertia: c.inertia.map(|row| group3(pool, &row)),
    }
}

/// The unit vector along axis `axis`.
fn unit(pool: &Pool, axis: usize) -> Vec3 {
    let mut e = [pool.zero(); 3];
    e[axis] = pool.one();
    e
}

/// `a + b`, entry by entry.
fn combined(pool: &mut Pool, a: &Composite, b: &Composite) -> Composite {
    Composite {
        mass: pool.add(a.mass, b.mass),
        moment: add3(pool, &a.moment, &b.moment),
        inertia: [0, 1, 2].map(|i| [0, 1, 2].map(|j| pool.add(a.inertia[i][j], b.inertia[i][j]))),
    }
}

/// `c` (inertia about a point `A`, first moment `h` about `A`) moved to the
/// point `B = A − d`, where its first moment is `moved = h + m d`:
/// `K_B = K_A + m(|d|² 1 − d dᵀ) + 2(h·d) 1 − h dᵀ − d hᵀ`, with `h` the
/// moment about `A`. For a single mass about its centre, `h = 0` and `moved
/// = m d`: pass the centre as `d` and `m c` as `moved` (the parallel-axis
/// theorem).
fn shifted(pool: &mut Pool, c: &Composite, d: &Vec3, moved: &Vec3) -> Composite {
    // With h = moved − m d: K_B = K_A + (2 moved·d − m|d|²) 1 − moved dᵀ − d movedᵀ + m d dᵀ.
    let two = pool.int(2);
    let md = d.map(|x| pool.mul(c.mass, x));
    let moved_dot_d = dot(pool, moved, d);
    let twice = pool.mul(two, moved_dot_d);
    let m_dd = dot(pool, &md, d);
    let diagonal = pool.sub(twice, m_dd);
    let inertia = [0, 1, 2].map(|i| {
        [0, 1, 2].map(|j| {
            let outer = [
                pool.mul(moved[i], d[j]),
                pool.mul(d[i], moved[j]),
                pool.mul(md[i], d[j]),
            ];
            let minus = [pool.neg(outer[0]), pool.neg(outer[1]), outer[2]];
            let mut terms = vec![c.inertia[i][j]];
            terms.extend(minus);
            if i == j {
                terms.push(diagonal);
            }
            pool.sum(terms)
        })
    });
    Composite {
        mass: c.mass,
        moment: *moved,
        inertia,
    }
}

/// `R K Rᵀ`: a tensor given in a child's axes, in the parent's.
fn rotate_tensor(pool: &mut Pool, r: &Mat3, k: &Mat3) -> Mat3 {
    // Columns of R K, then the rows of (R K) Rᵀ as R times the rows of R K.
    let columns: [Vec3; 3] = [0, 1, 2].map(|j| mat_vec(pool, r, &[k[0][j], k[1][j], k[2][j]]));
    [0, 1, 2].map(|i| mat_vec(pool, r, &[columns[0][i], columns[1][i], columns[2][i]]))
}
