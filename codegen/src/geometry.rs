//! A model's named geometry evaluated numerically: where its points are
//! and how its frames and bodies turn at a configuration, from the engine's
//! own kinematics (the expressions the equations are derived from). This is
//! what an animation draws (`dalembert-lab`'s scenes); nothing of it enters
//! the generated code.

use crate::expr::{Env, ExprId, Pool, Sym};
use crate::kinematics::Kinematics;
use crate::model::{FrameId, NEWTONIAN, ORIGIN, PointId, Vector};

/// The values of every symbol of a system: parameters in declaration
/// order, time, coordinates, speeds and inputs. [`Geometry`] reads the
/// parameters, `t` and `q` only (the other slices may be empty).
#[derive(Clone, Copy, Debug)]
pub struct Values<'a> {
    /// One value per parameter.
    pub parameters: &'a [f64],
    /// Time `t`.
    pub t: f64,
    /// The coordinates `q`.
    pub q: &'a [f64],
    /// The speeds `q̇`.
    pub qd: &'a [f64],
    /// The inputs `u`.
    pub u: &'a [f64],
}

impl Env for Values<'_> {
    fn value(&self, sym: Sym) -> f64 {
        let at = |values: &[f64], i: u32| values[i as usize];
        match sym {
            Sym::Time => self.t,
            Sym::Param(i) => at(self.parameters, i),
            Sym::Coord(i) => at(self.q, i),
            Sym::Speed(i) => at(self.qd, i),
            Sym::Input(i) => at(self.u, i),
            // Neither appears in the equations evaluated here.
            Sym::Accel(_) | Sym::Multiplier(_) => f64::NAN,
        }
    }
}

/// Where the named parts of a system are at a configuration: the named
/// points (`O` first, then in declaration order, joint points included),
/// the named frames (`N` first), the bodies (at their centres, turned with
/// their frames) and the particles, evaluated from the engine's own
/// kinematics. Built by [`Geometry::new`].
pub struct Geometry {
    pool: Pool,
    points: Vec<String>,
    frames: Vec<String>,
    bodies: Vec<String>,
    particles: Vec<String>,
    segments: Vec<(usize, usize)>,
    /// Named points, then body centres, then particles: three expressions
    /// each, in `N`'s axes.
    positions: Vec<ExprId>,
    /// Named frames, then body frames: nine expressions each, row-major.
    rotations: Vec<ExprId>,
    /// Each body's mass and then its central inertia, row-major.
    mass_properties: Vec<ExprId>,
    /// The uniform gravity field in `N`'s axes (zero without a `gravity`
    /// statement).
    gravity: [ExprId; 3],
    name: String,
    np: usize,
    nq: usize,
}

impl Geometry {
    /// The named geometry of the system in `source` (the text of a `.dal`
    /// file, the language of `dalembert!`), for drawing it: where every
    /// named point is and how every named frame, body and particle sits,
    /// from the same kinematics the equations are derived from. The same
    /// errors as [`check`](crate::check) for the model's rules.
    pub fn new(source: &str) -> syn::Result<Geometry> {
        let system = crate::language::parse_system(crate::lex(source)?)?;
        let (model, mut pool) = crate::model::resolve(&system)?;
        let kinematics = Kinematics::new(&model, &mut pool);
        let names = &model.names;
        let point_ids: Vec<PointId> = [ORIGIN]
            .into_iter()
            .chain(names.points.iter().map(|(_, id)| *id))
            .collect();
        let frame_ids: Vec<FrameId> = [NEWTONIAN]
            .into_iter()
            .chain(names.frames.iter().map(|(_, id)| *id))
            .collect();
        let segments = point_ids
            .iter()
            .enumerate()
            .filter_map(|(i, p)| {
                let (base, offset) = model.points[p.0].placement.as_ref()?;
                let from = point_ids.iter().position(|q| q == base)?;
                (!offset.parts.is_empty() && from != i).then_some((from, i))
            })
            .collect();
        let centres = model.bodies.iter().map(|b| b.center);
        let particles = model.particles.iter().map(|p| p.at);
        let positions = point_ids
            .iter()
            .copied()
            .chain(centres)
            .chain(particles)
            .flat_map(|p| kinematics.position(p))
            .collect();
        let body_frames = model.bodies.iter().map(|b| b.frame);
        let all_frames: Vec<FrameId> = frame_ids.iter().copied().chain(body_frames).collect();
        let mut rotations = Vec::with_capacity(9 * all_frames.len());
        for frame in all_frames {
            let columns = [0, 1, 2].map(|axis| {
                let unit = Vector::unit(&pool, frame, axis);
                kinematics.express(&mut pool, &model, &unit, NEWTONIAN)
            });
            rotations.extend((0..3).flat_map(|row| columns.map(|column| column[row])));
        }
        let mass_properties = model
            .bodies
            .iter()
            .flat_map(|b| [b.mass].into_iter().chain(b.inertia.into_iter().flatten()))
            .collect();
        let gravity = model.gravity.as_ref().map_or([pool.zero(); 3], |g| {
            kinematics.express(&mut pool, &model, g, NEWTONIAN)
        });
        Ok(Geometry {
            name: model.name.to_string(),
            np: model.parameters.len(),
            nq: model.nq(),
            mass_properties,
            gravity,
            pool,
            points: [String::from("O")]
                .into_iter()
                .chain(names.points.iter().map(|(name, _)| name.to_string()))
                .collect(),
            frames: [String::from("N")]
                .into_iter()
                .chain(names.frames.iter().map(|(name, _)| name.to_string()))
                .collect(),
            bodies: names.bodies.iter().map(ToString::to_string).collect(),
            particles: names.particles.iter().map(ToString::to_string).collect(),
            segments,
            positions,
            rotations,
        })
    }

    /// The system's name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The number of parameters.
    pub fn np(&self) -> usize {
        self.np
    }

    /// The number of coordinates.
    pub fn nq(&self) -> usize {
        self.nq
    }

    /// The named points: `O`, then in declaration order.
    pub fn points(&self) -> &[String] {
        &self.points
    }

    /// The named frames: `N`, then in declaration order.
    pub fn frames(&self) -> &[String] {
        &self.frames
    }

    /// The bodies, in declaration order.
    pub fn bodies(&self) -> &[String] {
        &self.bodies
    }

    /// The particles, in declaration order.
    pub fn particles(&self) -> &[String] {
        &self.particles
    }

    /// `(i, j)` for every named point `j` located from named point `i`
    /// by a vector (`point P = Q ± vec`, a joint's point): indices into
    /// [`points`](Self::points).
    pub fn segments(&self) -> &[(usize, usize)] {
        &self.segments
    }

    /// Positions in `N`'s axes of the named points, then of the bodies'
    /// centres, then of the particles. Only the parameters, `t` and `q` of
    /// `at` are read (geometry depends on nothing else).
    ///
    /// # Panics
    ///
    /// If a slice of `at` is shorter than the system's count.
    pub fn positions(&self, at: &Values<'_>) -> Vec<[f64; 3]> {
        let values = self.pool.eval_many(&self.positions, at);
        values.chunks_exact(3).map(|r| [r[0], r[1], r[2]]).collect()
    }

    /// Rotation matrices of the named frames, then of the bodies' frames:
    /// each maps the frame's components to `N`'s (its columns are the
    /// frame's unit vectors in `N`'s axes). Panics as
    /// [`positions`](Self::positions).
    pub fn rotations(&self, at: &Values<'_>) -> Vec<[[f64; 3]; 3]> {
        let values = self.pool.eval_many(&self.rotations, at);
        values
            .chunks_exact(9)
            .map(|r| [[r[0], r[1], r[2]], [r[3], r[4], r[5]], [r[6], r[7], r[8]]])
            .collect()
    }

    /// Each body's mass and central inertia tensor in its frame's axes.
    /// Only the parameters of `at` are read.
    pub fn mass_properties(&self, at: &Values<'_>) -> Vec<(f64, [[f64; 3]; 3])> {
        let values = self.pool.eval_many(&self.mass_properties, at);
        values
            .chunks_exact(10)
            .map(|r| {
                (
                    r[0],
                    [[r[1], r[2], r[3]], [r[4], r[5], r[6]], [r[7], r[8], r[9]]],
                )
            })
            .collect()
    }

    /// The uniform gravity field in `N`'s axes (zero if the model has
    /// none). Only the parameters of `at` are read.
    pub fn gravity(&self, at: &Values<'_>) -> [f64; 3] {
        let values = self.pool.eval_many(&self.gravity, at);
        [values[0], values[1], values[2]]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A cart sliding by `s` along a turntable's `x` (turned by `a` about
    /// `N.z`), a bob on a stick of length `L` across it, and a user's force
    /// at an anonymous point: names, segments and positions by hand.
    const CART: &str = "
        Cart {
            parameters L;
            coordinates s, a;
            frame A = N.rotate_z(a);
            force 3 * N.x at O + L * N.y;
            joint prismatic S { parent: A, child: C, axis: x, coordinate: s, at: O };
            point Tip = S + L * C.y;
            particle bob { mass: 1, at: Tip };
            body cart { mass: 2, center: S + 0.5 * C.x, frame: C, inertia: [1, 2, 3] };
        }";

    #[test]
    fn names_segments_and_positions_of_a_jointed_model() {
        let geometry = Geometry::new(CART).unwrap();
        assert_eq!(geometry.name(), "Cart");
        assert_eq!((geometry.np(), geometry.nq()), (1, 2));
        assert_eq!(geometry.points(), ["O", "S", "Tip"]);
        assert_eq!(geometry.frames(), ["N", "A", "C"]);
        assert_eq!(geometry.bodies(), ["cart"]);
        assert_eq!(geometry.particles(), ["bob"]);
        assert_eq!(geometry.segments(), [(0, 1), (1, 2)]);
        let (l, s, a) = (0.7, 1.3, 0.4);
        let at = Values {
            parameters: &[l],
            t: 0.0,
            q: &[s, a],
            qd: &[],
            u: &[],
        };
        let (sin, cos) = f64::sin_cos(a);
        let slider = [s * cos, s * sin, 0.0];
        let tip = [slider[0] - l * sin, slider[1] + l * cos, 0.0];
        let centre = [slider[0] + 0.5 * cos, slider[1] + 0.5 * sin, 0.0];
        let expected = [[0.0; 3], slider, tip, centre, tip];
        assert_close(&geometry.positions(&at), &expected);
        let turn = [[cos, -sin, 0.0], [sin, cos, 0.0], [0.0, 0.0, 1.0]];
        let identity = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        // N, A, C, and the cart's frame C.
        let rotations = geometry.rotations(&at);
        assert_eq!(rotations.len(), 4);
        for (got, expected) in rotations.iter().zip([identity, turn, turn, turn]) {
            assert_close(got, &expected);
        }
        let mass_properties = geometry.mass_properties(&at);
        assert_eq!(
            mass_properties,
            [(2.0, [[1.0, 0.0, 0.0], [0.0, 2.0, 0.0], [0.0, 0.0, 3.0]])]
        );
        assert_eq!(geometry.gravity(&at), [0.0; 3], "no gravity statement");
    }

    #[test]
    fn gravity_in_the_newtonian_axes() {
        let source = CART.replace("coordinates s, a;", "coordinates s, a; gravity -L * N.y;");
        let geometry = Geometry::new(&source).unwrap();
        let at = Values {
            parameters: &[0.7],
            t: 0.0,
            q: &[1.3, 0.4],
            qd: &[],
            u: &[],
        };
        assert_close(&[geometry.gravity(&at)], &[[0.0, -0.7, 0.0]]);
    }

    fn assert_close(got: &[[f64; 3]], expected: &[[f64; 3]]) {
        assert_eq!(got.len(), expected.len());
        for (got, expected) in got.iter().zip(expected) {
            for i in 0..3 {
                assert!(
                    (got[i] - expected[i]).abs() < 1e-14,
                    "{got:?} ≠ {expected:?}"
                );
            }
        }
    }
}
