//! The interpreter: the derived equations of a system evaluated
//! numerically, beside the generator (as `pest_vm` beside
//! `pest_generator`).
//!
//! * [`Route::Dalembert`] evaluates the equations exactly as
//!   `equations::derive` returns them, and the requested outputs built from
//!   those, before `optimize` and emission. The emitted code computes the
//!   optimised equations through the emitter's folding and sharing, so
//!   comparing the two checks the optimiser and the emitter.
//! * [`Route::Lagrange`] derives `M` and `f` another way, from the same
//!   (unoptimised) `T` and `V`; comparing it with the d'Alembert route
//!   checks the d'Alembert assembly. `T`, `V`, `A`, `b` and the outputs
//!   are the same on both routes.
//!
//! The generator's checks of the derived equations (`checks::after_derivation`) run
//! on the optimised equations, as when generating, so a model the
//! interpreter accepts is one the generator accepts.

use crate::equations::{Equations, lagrange};
use crate::expr::{Env, ExprId, Pool, Sym};
use crate::kinematics::Kinematics;
use crate::model::{FrameId, Model, NEWTONIAN, ORIGIN, PointId, Vector};

/// Which derivation of `M` and `f` an [`Interpreter`] evaluates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Route {
    /// d'Alembert's principle, as the generator derives them.
    Dalembert,
    /// Lagrange's equations (for systems whose speeds are the coordinates'
    /// rates): `M` as the Hessian of `T` in the speeds and
    /// `f` from the derivatives of `T`, `V` and the dissipation function,
    /// with the generalized forces through partial velocities taken another
    /// way. Energies and constraints are the same as on the other route.
    Lagrange,
}

/// The values of every symbol of a system: parameters in declaration
/// order, time, coordinates, speeds and inputs.
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

/// Owned values of every symbol, as [`Values`] borrows them: a sample
/// point for differential tests.
#[derive(Clone, Debug, PartialEq)]
pub struct Sample {
    /// One value per parameter.
    pub parameters: Vec<f64>,
    /// Time `t`.
    pub t: f64,
    /// The coordinates `q`.
    pub q: Vec<f64>,
    /// The speeds `q̇`.
    pub qd: Vec<f64>,
    /// The inputs `u`.
    pub u: Vec<f64>,
}

impl Sample {
    /// A reproducible random sample for `interpreter`'s system, from
    /// `seed`: parameters in `[0.5, 1.5)` (positive, as masses and
    /// lengths are), `t` in `[0, 3)`, coordinates in `[−3, 3)`, speeds in
    /// `[−2, 2)`, inputs in `[−5, 5)`.
    pub fn random(interpreter: &Interpreter, seed: u64) -> Sample {
        let mut random = crate::random::Random::new(seed);
        let mut draw = |n: usize, low: f64, width: f64| -> Vec<f64> {
            (0..n).map(|_| random.uniform(low, low + width)).collect()
        };
        Sample {
            parameters: draw(interpreter.np(), 0.5, 1.0),
            t: draw(1, 0.0, 3.0)[0],
            q: draw(interpreter.nq(), -3.0, 6.0),
            qd: draw(interpreter.nv(), -2.0, 4.0),
            u: draw(interpreter.nu(), -5.0, 10.0),
        }
    }

    /// The sample as [`Values`].
    pub fn values(&self) -> Values<'_> {
        Values {
            parameters: &self.parameters,
            t: self.t,
            q: &self.q,
            qd: &self.qd,
            u: &self.u,
        }
    }
}

/// [`Values`] and the speeds' rates `v̇`, for the outputs that read them.
struct WithRates<'a> {
    values: &'a Values<'a>,
    rates: &'a [f64],
}

impl Env for WithRates<'_> {
    fn value(&self, sym: Sym) -> f64 {
        match sym {
            Sym::Accel(i) => self.rates[i as usize],
            other => self.values.value(other),
        }
    }
}

/// A system's equations, ready to evaluate at any [`Values`].
pub struct Interpreter {
    model: Model,
    pool: Pool,
    equations: Equations,
    /// The functions the model's `outputs` statement asks for, unoptimised.
    outputs: Vec<crate::outputs::Function>,
}

impl Interpreter {
    /// Parses, checks and derives the system in `source` (the text of a
    /// `.dal` file) along `route`; the same errors as [`check`](crate::check).
    pub fn new(source: &str, route: Route) -> syn::Result<Interpreter> {
        let crate::Derivation {
            model,
            mut pool,
            mut equations,
            mut forms,
        } = crate::derive_unoptimised(crate::lex(source)?)?;
        // The same checks as the generator, on the optimised equations; the
        // interpreter evaluates the unoptimised ones.
        let mut optimised = equations.clone();
        crate::plan::optimize::optimize(&mut optimised, &mut pool, &mut forms);
        crate::checks::after_derivation(&model, &pool, &optimised)?;
        if route == Route::Lagrange && !pool.rates_are_speeds() {
            return Err(syn::Error::new(
                model.name.span(),
                "the Lagrange route needs every speed to be its coordinate's rate; this system \
                 has speeds of its own (a free or spherical joint)",
            ));
        }
        if route == Route::Lagrange {
            let (mass_matrix, forcing) = lagrange::lagrange(
                &model,
                &mut pool,
                equations.kinetic_energy,
                equations.potential_energy,
            );
            equations.mass_matrix = mass_matrix;
            equations.forcing = forcing;
        }
        let outputs = crate::outputs::requested(&model, &equations, &mut pool).functions;
        Ok(Interpreter {
            model,
            pool,
            equations,
            outputs,
        })
    }

    /// The value of the generated function `name` that the model's
    /// `outputs` statement asks for (`inverse_dynamics`, `position_P`,
    /// `regressor`, `base_parameters`, ...), its results flattened row by
    /// row, at `at` with the speeds' rates `rates` (read by
    /// `inverse_dynamics`, `acceleration_P` and `regressor`); `None` if the
    /// model does not ask for it. Panics as
    /// [`mass_matrix`](Self::mass_matrix).
    pub fn output(&self, name: &str, at: &Values<'_>, rates: &[f64]) -> Option<Vec<f64>> {
        let function = self.outputs.iter().find(|f| f.name == name)?;
        let roots: Vec<ExprId> = function
            .results
            .iter()
            .flat_map(|value| value.expressions.iter().copied())
            .collect();
        Some(
            self.pool
                .eval_many(&roots, &WithRates { values: at, rates }),
        )
    }

    /// The system's name.
    pub fn name(&self) -> String {
        self.model.name.to_string()
    }

    /// The number of parameters.
    pub fn np(&self) -> usize {
        self.model.parameters.len()
    }

    /// The number of coordinates.
    pub fn nq(&self) -> usize {
        self.model.nq()
    }

    /// The number of speeds.
    pub fn nv(&self) -> usize {
        self.model.nv()
    }

    /// The number of inputs.
    pub fn nu(&self) -> usize {
        self.model.inputs.len()
    }

    /// The number of constraints.
    pub fn nc(&self) -> usize {
        self.equations.constraint_jacobian.len()
    }

    /// `M(q)`, row by row.
    ///
    /// # Panics
    ///
    /// If a slice of `at` is shorter than the system's count.
    pub fn mass_matrix(&self, at: &Values<'_>) -> Vec<Vec<f64>> {
        self.matrix(&self.equations.mass_matrix, at)
    }

    /// `f(t, q, q̇, u)`. Panics as [`mass_matrix`](Self::mass_matrix).
    pub fn forcing(&self, at: &Values<'_>) -> Vec<f64> {
        self.pool.eval_many(&self.equations.forcing, at)
    }

    /// `q̈` by the articulated-body recursion (the d'Alembert route's, on
    /// either route), for kinematic trees without constraints; `None` for
    /// other systems. Panics as [`mass_matrix`](Self::mass_matrix).
    pub fn articulated_accelerations(&self, at: &Values<'_>) -> Option<Vec<f64>> {
        let articulated = self.equations.articulated.as_ref()?;
        Some(self.pool.eval_many(&articulated.accelerations, at))
    }

    /// `T(q, q̇)`. Panics as [`mass_matrix`](Self::mass_matrix).
    pub fn kinetic_energy(&self, at: &Values<'_>) -> f64 {
        self.pool.eval(self.equations.kinetic_energy, at)
    }

    /// `V(q)`. Panics as [`mass_matrix`](Self::mass_matrix).
    pub fn potential_energy(&self, at: &Values<'_>) -> f64 {
        self.pool.eval(self.equations.potential_energy, at)
    }

    /// `A(q)`, one row per constraint. Panics as
    /// [`mass_matrix`](Self::mass_matrix).
    pub fn constraint_jacobian(&self, at: &Values<'_>) -> Vec<Vec<f64>> {
        self.matrix(&self.equations.constraint_jacobian, at)
    }

    /// `b(t, q, q̇)` with `A q̈ = b`. Panics as
    /// [`mass_matrix`](Self::mass_matrix).
    pub fn constraint_bias(&self, at: &Values<'_>) -> Vec<f64> {
        self.pool.eval_many(&self.equations.constraint_bias, at)
    }

    /// The residuals of the constraints (0 for nonholonomic rows). Panics
    /// as [`mass_matrix`](Self::mass_matrix).
    pub fn constraint_residual(&self, at: &Values<'_>) -> Vec<f64> {
        self.pool.eval_many(&self.equations.constraint_residual, at)
    }

    /// The values of a matrix of expressions, in one pass.
    fn matrix(&self, rows: &[Vec<ExprId>], at: &Values<'_>) -> Vec<Vec<f64>> {
        let flat: Vec<ExprId> = rows.concat();
        let values = self.pool.eval_many(&flat, at);
        let width = rows.first().map_or(0, Vec::len);
        values.chunks(width.max(1)).map(<[f64]>::to_vec).collect()
    }
}

impl Interpreter {
    /// The named geometry of the system in `source` (the text of a `.dal`
    /// file), for drawing it: where every named point is and how every
    /// named frame, body and particle sits, from the same kinematics the
    /// equations are derived from. The same errors as
    /// [`check`](crate::check) for the model's rules.
    pub fn geometry(source: &str) -> syn::Result<Geometry> {
        Geometry::new(source)
    }
}

/// Where the named parts of a system are at a configuration: the named
/// points (`O` first, then in declaration order, joint points included),
/// the named frames (`N` first), the bodies (at their centres, turned with
/// their frames) and the particles, evaluated from the engine's own
/// kinematics. Built by [`Interpreter::geometry`].
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
    fn new(source: &str) -> syn::Result<Geometry> {
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
mod geometry_tests {
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
        let geometry = Interpreter::geometry(CART).unwrap();
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
        let geometry = Interpreter::geometry(&source).unwrap();
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
