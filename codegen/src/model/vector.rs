//! Vectors as the user writes them: sums of components along the unit
//! vectors of named frames (`L * B1.y - d * N.x`), kept per frame so that no
//! rotation is applied until kinematics needs one.

use crate::expr::{ExprId, Pool};

/// Index of a frame in [`super::Model::frames`]; `FrameId(0)` is `N`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct FrameId(pub usize);

/// The Newtonian frame `N`.
pub const NEWTONIAN: FrameId = FrameId(0);

/// A vector: components along the axes of one or more frames, at most one
/// entry per frame, in order of first appearance. The empty vector is zero.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Vector {
    /// `(frame, [x, y, z])`: the part of the vector measured in that frame.
    pub parts: Vec<(FrameId, [ExprId; 3])>,
}

impl Vector {
    /// The unit vector along axis `axis` (0, 1, 2 for x, y, z) of `frame`.
    pub fn unit(pool: &Pool, frame: FrameId, axis: usize) -> Vector {
        let mut components = [pool.zero(); 3];
        components[axis] = pool.one();
        Vector {
            parts: vec![(frame, components)],
        }
    }

    /// The vector of components `components` in `frame`'s axes.
    pub fn along(pool: &Pool, frame: FrameId, components: [ExprId; 3]) -> Vector {
        let mut vector = Vector {
            parts: vec![(frame, components)],
        };
        vector.drop_zero_parts(pool);
        vector
    }

    /// `self + other`.
    pub fn add(&self, other: &Vector, pool: &mut Pool) -> Vector {
        let mut sum = self.clone();
        for (frame, components) in &other.parts {
            match sum.parts.iter_mut().find(|(f, _)| f == frame) {
                Some((_, mine)) => {
                    for (a, b) in mine.iter_mut().zip(components) {
                        *a = pool.add(*a, *b);
                    }
                }
                None => sum.parts.push((*frame, *components)),
            }
        }
        sum.drop_zero_parts(pool);
        sum
    }

    /// `scale * self`.
    pub fn scale(&self, scale: ExprId, pool: &mut Pool) -> Vector {
        let mut scaled = Vector {
            parts: self
                .parts
                .iter()
                .map(|(frame, c)| (*frame, c.map(|x| pool.mul(scale, x))))
                .collect(),
        };
        scaled.drop_zero_parts(pool);
        scaled
    }

    /// `-self`.
    pub fn neg(&self, pool: &mut Pool) -> Vector {
        let minus_one = pool.int(-1);
        self.scale(minus_one, pool)
    }

    fn drop_zero_parts(&mut self, pool: &Pool) {
        self.parts
            .retain(|(_, c)| c.iter().any(|x| !pool.is_zero(*x)));
    }
}
