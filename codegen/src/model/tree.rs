//! The kinematic tree of a model, when it is one.
//!
//! A model is a tree of joints when every coordinate moves exactly one
//! subtree rigidly, about or along one constant axis of its parent:
//!
//! * a frame rotated from its parent by a constant angle is fixed in its
//!   parent's link (a welded frame); one rotated by a bare coordinate `q`
//!   about its constant axis starts a new link: a **revolute** joint;
//! * a point is fixed in a link when it is located from a point of that link
//!   by constant components along frames fixed in it; a point located from a
//!   point `J` of the parent link by constant components along the frames of
//!   a child link is fixed in that child, whose joint then sits at `J`
//!   (every point of the child must agree on it);
//! * a point located by `q * d` along a constant direction `d` of the link of
//!   its base point is fixed in a new link: a **prismatic** joint, whose
//!   other points and children follow from it;
//! * a body whose frame starts a child link and whose centre is fixed in the
//!   parent link sits on that child's joint (a massless frame between, as in
//!   seed example 2, is a link of its own).
//! * a frame turned by a quaternion joint starts a **spherical** link, placed
//!   like a revolute one; a **free** joint's link hangs from the ground at its
//!   origin point, which its three position coordinates move.
//!
//! Both spellings meet here: `joint` statements make exactly such frames
//! and points, and so do `frame B2 = B1.rotate_z(q2); point P2 = P1 - L * B2.y`.
//! Anything else (a coordinate in a point's position other than a slide, a
//! frame turned by an expression of several coordinates or of time, a point
//! offset along a frame that moves relative to its base point's link, a
//! coordinate that no joint moves) leaves the model without a tree, and the
//! equations take the general route. Seed example 1's absolute angles are
//! such a model: `B2 = N.rotate_z(θ₂)` turns relative to `N`, but `G2` is
//! placed from `P1`, which moves with `B1`.

use super::{FrameId, Model, NEWTONIAN, PointId, Vector};
use crate::expr::{Node, Pool, Sym, SymKinds};

/// How a joint moves its child link.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum JointKind {
    /// A rotation by the coordinate about a constant unit axis through the
    /// joint's origin.
    Revolute,
    /// A translation by the coordinate along a constant direction.
    Prismatic,
    /// A rotation by a unit quaternion about the joint's origin, with the
    /// angular velocity in the link's axes as its three speeds.
    Spherical,
    /// A spherical joint whose origin also moves, with its velocity in the
    /// link's axes as three more speeds (first): a floating base, on `N`.
    Free,
}

impl JointKind {
    /// Whether the joint turns its link (the link's axes are its own).
    pub fn turns(self) -> bool {
        self != JointKind::Prismatic
    }
}

/// A link: the rigid subtree beyond one joint.
pub struct Link {
    /// The parent link; `None` for a joint on the ground (`N`).
    pub parent: Option<usize>,
    /// How the joint moves the link.
    pub kind: JointKind,
    /// The joint's coordinate index (a quaternion joint's first).
    pub coordinate: usize,
    /// The quaternion joint of [`Model::balls`] for spherical and free
    /// joints.
    pub ball: Option<usize>,
    /// The frame whose axes are the link's: the frame a revolute or
    /// quaternion joint turns, the parent link's frame for a prismatic joint.
    pub frame: FrameId,
    /// Revolute: the unit axis, along `frame`'s axes (the same in the frame
    /// it is turned from). Prismatic: the constant direction the coordinate
    /// slides along, along frames fixed in the parent link.
    pub axis: Vector,
    /// From the parent link's origin to the joint's (at `q = 0` for a
    /// slide), along frames fixed in the parent link.
    pub offset: Vector,
}

/// Where something is fixed: a link (`None` for the ground) and the offset
/// from the link's origin, along frames fixed in the link.
#[derive(Clone, Debug, Default)]
pub struct Attachment {
    /// The link, `None` for the ground.
    pub link: Option<usize>,
    /// From the link's origin, along frames fixed in the link.
    pub offset: Vector,
}

/// The kinematic tree of a model.
pub struct Tree {
    /// The links, parents before children.
    pub links: Vec<Link>,
    /// Where each point of [`Model::points`] is fixed.
    pub points: Vec<Attachment>,
    /// The link each frame of [`Model::frames`] is fixed in.
    pub frames: Vec<Option<usize>>,
    /// Where each body of [`Model::bodies`] is fixed (its centre's offset).
    pub bodies: Vec<Attachment>,
}

impl Tree {
    /// The tree of `model`, or `None` if it is not one (see the module
    /// docs).
    pub fn of(model: &Model, pool: &mut Pool) -> Option<Tree> {
        let mut builder = Builder::new(model);
        builder.frames(model, pool)?;
        for (i, point) in model.points.iter().enumerate().skip(1) {
            let (base, offset) = point.placement.as_ref()?;
            let free = model
                .balls
                .iter()
                .find(|b| b.origin == PointId(i) && b.translation.is_some());
            let attachment = match free {
                Some(ball) => builder.free_origin(pool, ball.frame, *base, offset)?,
                None => builder.point(pool, *base, offset)?,
            };
            debug_assert_eq!(builder.points.len(), i);
            builder.points.push(attachment);
        }
        let bodies = model
            .bodies
            .iter()
            .map(|body| builder.body(pool, body.center, body.frame))
            .collect::<Option<Vec<_>>>()?;
        builder.finish(bodies)
    }
}

/// A link while the points are read: its parent is known once a point
/// places its joint.
struct Draft {
    /// `None` until placed; then the parent link (`None` for the ground).
    parent: Option<Option<usize>>,
    kind: JointKind,
    coordinate: usize,
    ball: Option<usize>,
    frame: FrameId,
    axis: Vector,
    offset: Vector,
    /// The frame whose axes the parent link must have (revolute joints).
    parent_orientation: FrameId,
}

struct Builder {
    links: Vec<Draft>,
    /// For each frame, the frame that starts its link's axes (`N` or a
    /// frame turned by a coordinate).
    orientation: Vec<FrameId>,
    /// The link each coordinate moves.
    moved_by: Vec<Option<usize>>,
    points: Vec<Attachment>,
}

impl Builder {
    fn new(model: &Model) -> Builder {
        Builder {
            links: Vec::new(),
            orientation: Vec::with_capacity(model.frames.len()),
            moved_by: vec![None; model.nq()],
            points: vec![Attachment::default()],
        }
    }

    /// Frames turned by constants join their parent's link; frames turned
    /// by a bare coordinate start a revolute link.
    fn frames(&mut self, model: &Model, pool: &Pool) -> Option<()> {
        self.orientation.push(NEWTONIAN);
        for (f, frame) in model.frames.iter().enumerate().skip(1) {
            let placement = frame.placement.as_ref()?;
            let frame = FrameId(f);
            if let Some(b) = placement.ball {
                let ball = &model.balls[b];
                let mut coordinates = ball.quaternion.to_vec();
                coordinates.extend(ball.translation.iter().flat_map(|(p, _)| *p));
                for &k in &coordinates {
                    self.claim(k)?;
                }
                self.links.push(Draft {
                    parent: None,
                    kind: match ball.translation {
                        Some(_) => JointKind::Free,
                        None => JointKind::Spherical,
                    },
                    coordinate: ball.quaternion[0],
                    ball: Some(b),
                    frame,
                    axis: Vector::default(),
                    offset: Vector::default(),
                    parent_orientation: self.orientation[placement.parent.0],
                });
                self.orientation.push(frame);
                continue;
            }
            let kinds = pool.kinds(placement.angle);
            if SymKinds::PARAM.contains(kinds) {
                self.orientation.push(self.orientation[placement.parent.0]);
                continue;
            }
            let Node::Sym(Sym::Coord(k)) = pool.node(placement.angle) else {
                return None;
            };
            self.claim(*k as usize)?;
            self.links.push(Draft {
                parent: None,
                kind: JointKind::Revolute,
                coordinate: *k as usize,
                ball: None,
                frame,
                axis: Vector {
                    parts: vec![(frame, placement.axis)],
                },
                offset: Vector::default(),
                parent_orientation: self.orientation[placement.parent.0],
            });
            self.orientation.push(frame);
        }
        Some(())
    }

    /// Marks coordinate `k` as moving the next link; `None` if another
    /// joint moves it already.
    fn claim(&mut self, k: usize) -> Option<()> {
        match self.moved_by[k] {
            Some(_) => None,
            None => {
                self.moved_by[k] = Some(self.links.len());
                Some(())
            }
        }
    }

    /// The frame starting the axes of `link`.
    fn orientation_of(&self, link: Option<usize>) -> FrameId {
        match link {
            None => NEWTONIAN,
            Some(l) => self.orientation[self.links[l].frame.0],
        }
    }

    /// The turning link starting at `frame`, if `frame` starts one.
    fn link_started_by(&self, frame: FrameId) -> Option<usize> {
        self.links
            .iter()
            .position(|l| l.kind.turns() && l.frame == frame)
    }

    /// The origin of the free joint turning `frame`: the point `base +
    /// offset`, where `offset` holds the joint's position; the joint sits on
    /// the ground (`base` is fixed in `N`, as the language checks).
    fn free_origin(
        &mut self,
        pool: &mut Pool,
        frame: FrameId,
        base: PointId,
        offset: &Vector,
    ) -> Option<Attachment> {
        let at = self.points.get(base.0)?.clone();
        let link = self.link_started_by(frame)?;
        if at.link.is_some() {
            return None;
        }
        let draft = &mut self.links[link];
        draft.parent = Some(None);
        draft.offset = at.offset.add(offset, pool);
        Some(Attachment {
            link: Some(link),
            offset: Vector::default(),
        })
    }

    /// Where the point `base + offset` is fixed.
    fn point(&mut self, pool: &mut Pool, base: PointId, offset: &Vector) -> Option<Attachment> {
        let Attachment {
            mut link,
            offset: mut from_origin,
        } = self.points.get(base.0)?.clone();
        let (constant, slide) = split_slide(pool, offset)?;
        let here = self.orientation_of(link);
        let (mut same, mut other) = (Vector::default(), Vector::default());
        let mut child = None;
        for (frame, components) in constant.parts {
            let part = Vector {
                parts: vec![(frame, components)],
            };
            let orientation = self.orientation[frame.0];
            if orientation == here {
                same = same.add(&part, pool);
            } else if child.is_none_or(|c| c == orientation) {
                child = Some(orientation);
                other = other.add(&part, pool);
            } else {
                return None;
            }
        }
        from_origin = from_origin.add(&same, pool);
        // A slide along the base link's axes comes before the child's
        // joint, one along the child's axes after it.
        let slide_first = slide.as_ref().is_some_and(|(_, direction)| {
            direction
                .parts
                .iter()
                .all(|(f, _)| self.orientation[f.0] == here)
        });
        if let (false, None, Some((_, direction))) = (slide_first, child, &slide) {
            // A slide along a child's axes from a point of its joint.
            child = direction.parts.first().map(|(f, _)| self.orientation[f.0]);
        }
        if slide_first {
            let (k, direction) = slide.clone()?;
            (link, from_origin) = self.slide(pool, link, k, direction, from_origin)?;
        }
        if let Some(orientation) = child {
            let child = self.link_started_by(orientation)?;
            self.place(pool, child, link, from_origin)?;
            (link, from_origin) = (Some(child), other);
        }
        if let (false, Some((k, direction))) = (slide_first, slide) {
            let here = self.orientation_of(link);
            if direction
                .parts
                .iter()
                .any(|(f, _)| self.orientation[f.0] != here)
            {
                return None;
            }
            (link, from_origin) = self.slide(pool, link, k, direction, from_origin)?;
        }
        Some(Attachment {
            link,
            offset: from_origin,
        })
    }

    /// The link and offset of a point `from_origin` from the origin of
    /// `link`, then slid by coordinate `k` along `direction`.
    fn slide(
        &mut self,
        pool: &mut Pool,
        link: Option<usize>,
        k: usize,
        direction: Vector,
        from_origin: Vector,
    ) -> Option<(Option<usize>, Vector)> {
        let slider = self.slider(pool, link, k, direction, &from_origin)?;
        let offset = difference(pool, &from_origin, &self.links[slider].offset);
        Some((Some(slider), offset))
    }

    /// The prismatic link of coordinate `k` sliding along `direction` from
    /// `parent`, made at `origin` if it is new.
    fn slider(
        &mut self,
        pool: &mut Pool,
        parent: Option<usize>,
        k: usize,
        direction: Vector,
        origin: &Vector,
    ) -> Option<usize> {
        if let Some(l) = self.moved_by[k] {
            let existing = &self.links[l];
            let same_direction = difference(pool, &existing.axis, &direction)
                .parts
                .is_empty();
            return (existing.kind == JointKind::Prismatic
                && existing.parent == Some(parent)
                && same_direction)
                .then_some(l);
        }
        self.claim(k)?;
        let frame = match parent {
            None => NEWTONIAN,
            Some(p) => self.links[p].frame,
        };
        self.links.push(Draft {
            parent: Some(parent),
            kind: JointKind::Prismatic,
            coordinate: k,
            ball: None,
            frame,
            axis: direction,
            offset: origin.clone(),
            parent_orientation: self.orientation_of(parent),
        });
        Some(self.links.len() - 1)
    }

    /// Puts the joint of revolute link `child` at `offset` from the origin
    /// of `parent`, or checks that it is there already.
    fn place(
        &mut self,
        pool: &mut Pool,
        child: usize,
        parent: Option<usize>,
        offset: Vector,
    ) -> Option<()> {
        let wanted = self.links[child].parent_orientation;
        let (parent, offset) = self.hang(pool, wanted, parent, offset)?;
        let draft = &mut self.links[child];
        match draft.parent {
            None => {
                draft.parent = Some(parent);
                draft.offset = offset;
                Some(())
            }
            Some(placed) => {
                let moved = difference(pool, &draft.offset, &offset);
                (placed == parent && moved.parts.is_empty()).then_some(())
            }
        }
    }

    /// The link with the axes `wanted` that the point at `offset` from the
    /// origin of `parent` is fixed in, placing joints on the way. A revolute
    /// joint's origin lies on its axis, so it is fixed in its parent link and
    /// in its own: when a point of `parent` carries a link that turns from
    /// other axes, the point is the origin of the joint that turns those axes
    /// (two or three axes through one point, as in a robot's shoulder or
    /// wrist; `place` checks it against every other point of that joint).
    fn hang(
        &mut self,
        pool: &mut Pool,
        wanted: FrameId,
        parent: Option<usize>,
        offset: Vector,
    ) -> Option<(Option<usize>, Vector)> {
        if self.orientation_of(parent) == wanted {
            return Some((parent, offset));
        }
        let between = self.link_started_by(wanted)?;
        self.place(pool, between, parent, offset)?;
        Some((Some(between), Vector::default()))
    }

    /// Where a body with centre `center` turning with `frame` is fixed.
    fn body(&mut self, pool: &mut Pool, center: PointId, frame: FrameId) -> Option<Attachment> {
        let at = self.points.get(center.0)?.clone();
        let orientation = self.orientation[frame.0];
        if orientation == self.orientation_of(at.link) {
            return Some(at);
        }
        let child = self.link_started_by(orientation)?;
        self.place(pool, child, at.link, at.offset)?;
        Some(Attachment {
            link: Some(child),
            offset: Vector::default(),
        })
    }

    /// The tree, links sorted parents first, once every coordinate moves a
    /// link; unplaced revolute joints (frames that carry no point) sit at
    /// their parent link's origin.
    fn finish(mut self, bodies: Vec<Attachment>) -> Option<Tree> {
        if self.moved_by.iter().any(Option::is_none) {
            return None;
        }
        for l in 0..self.links.len() {
            if self.links[l].parent.is_none() {
                let orientation = self.links[l].parent_orientation;
                let parent = match orientation {
                    NEWTONIAN => None,
                    frame => Some(self.link_started_by(frame)?),
                };
                self.links[l].parent = Some(parent);
            }
        }
        let depth = |links: &[Draft], mut l: usize| {
            let mut d = 0;
            while let Some(Some(p)) = links[l].parent {
                l = p;
                d += 1;
                if d > links.len() {
                    return None;
                }
            }
            Some(d)
        };
        let depths = (0..self.links.len())
            .map(|l| depth(&self.links, l))
            .collect::<Option<Vec<_>>>()?;
        let mut order: Vec<usize> = (0..self.links.len()).collect();
        order.sort_by_key(|&l| depths[l]);
        let mut new_index = vec![0; order.len()];
        for (new, &old) in order.iter().enumerate() {
            new_index[old] = new;
        }
        let renumber = |link: Option<usize>| link.map(|l| new_index[l]);
        let frames = self
            .orientation
            .iter()
            .map(|&o| match o {
                NEWTONIAN => None,
                frame => renumber(self.link_started_by(frame)),
            })
            .collect();
        let mut drafts: Vec<Option<Draft>> = self.links.into_iter().map(Some).collect();
        let links = order
            .iter()
            .map(|&old| {
                let d = drafts[old].take().expect("each link is taken once");
                Link {
                    parent: renumber(d.parent.flatten()),
                    kind: d.kind,
                    coordinate: d.coordinate,
                    ball: d.ball,
                    frame: d.frame,
                    axis: d.axis,
                    offset: d.offset,
                }
            })
            .collect();
        let attach = |a: Attachment| Attachment {
            link: renumber(a.link),
            offset: a.offset,
        };
        Some(Tree {
            links,
            points: self.points.into_iter().map(attach).collect(),
            frames,
            bodies: bodies.into_iter().map(attach).collect(),
        })
    }
}

/// `a − b`.
fn difference(pool: &mut Pool, a: &Vector, b: &Vector) -> Vector {
    let minus_b = b.neg(pool);
    a.add(&minus_b, pool)
}

/// `offset` split into its constant part and a slide `q * d` along a
/// constant direction `d` of one coordinate `q`, if any; `None` if it
/// depends on anything else, or on a coordinate otherwise.
fn split_slide(pool: &mut Pool, offset: &Vector) -> Option<(Vector, Option<(usize, Vector)>)> {
    let mut coordinate = None;
    for (_, components) in &offset.parts {
        for &c in components {
            for sym in pool.free_symbols(c) {
                match sym {
                    Sym::Param(_) => {}
                    Sym::Coord(k) if coordinate.is_none_or(|q| q == k) => coordinate = Some(k),
                    _ => return None,
                }
            }
        }
    }
    let Some(k) = coordinate else {
        return Some((offset.clone(), None));
    };
    let q = pool.sym(Sym::Coord(k));
    let mut constant = Vector::default();
    let mut direction = Vector::default();
    for (frame, components) in &offset.parts {
        let d = components.map(|c| pool.diff(c, Sym::Coord(k)));
        let rest = [0, 1, 2].map(|i| {
            let slide = pool.mul(q, d[i]);
            pool.sub(components[i], slide)
        });
        if d.iter()
            .chain(&rest)
            .any(|&x| !SymKinds::PARAM.contains(pool.kinds(x)))
        {
            return None;
        }
        constant = constant.add(
            &Vector {
                parts: vec![(*frame, rest)],
            },
            pool,
        );
        direction = direction.add(
            &Vector {
                parts: vec![(*frame, d)],
            },
            pool,
        );
    }
    Some((constant, Some((k as usize, direction))))
}

#[cfg(test)]
mod tests;
