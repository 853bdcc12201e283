//! The interpreter: the derived equations of a system evaluated
//! numerically, beside the generator (as `pest_vm` beside
//! `pest_generator`). It evaluates the symbolic DAG before optimisation and
//! emission, so comparing it with the emitted code checks the optimiser and
//! the emitter, and its [`Route::Lagrange`] derives `M` and `f` another way,
//! which checks the d'Alembert assembly.

use crate::equations::{Equations, lagrange};
use crate::expr::{Env, ExprId, Pool, Sym};
use crate::model::Model;

/// Which derivation of `M` and `f` an [`Interpreter`] evaluates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Route {
    /// d'Alembert's principle, as the generator derives them.
    Dalembert,
    /// Lagrange's equations: `M` as the Hessian of `T` in the speeds and
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
        // xorshift64 from a scrambled seed: small, fast and deterministic.
        let mut x = seed
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407)
            | 1;
        let mut draw = |n: usize, low: f64, width: f64| -> Vec<f64> {
            (0..n)
                .map(|_| {
                    x ^= x << 13;
                    x ^= x >> 7;
                    x ^= x << 17;
                    low + width * ((x >> 11) as f64 / (1u64 << 53) as f64)
                })
                .collect()
        };
        Sample {
            parameters: draw(interpreter.np(), 0.5, 1.0),
            t: draw(1, 0.0, 3.0)[0],
            q: draw(interpreter.nq(), -3.0, 6.0),
            qd: draw(interpreter.nq(), -2.0, 4.0),
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

/// A system's equations, ready to evaluate at any [`Values`].
pub struct Interpreter {
    model: Model,
    pool: Pool,
    equations: Equations,
}

impl Interpreter {
    /// Parses, checks and derives the system in `source` (the text of a
    /// `.dal` file) along `route`; the same errors as [`check`](crate::check).
    pub fn new(source: &str, route: Route) -> syn::Result<Interpreter> {
        let (mut model, mut pool, mut equations) = crate::derive_unoptimised(crate::lex(source)?)?;
        // The same checks as the generator, on the optimised equations; the
        // interpreter evaluates the unoptimised ones.
        let mut optimised = equations.clone();
        crate::optimize::optimize(&mut optimised, &mut pool);
        model.pool = pool;
        crate::check_equations(&model, &optimised)?;
        let mut pool = std::mem::take(&mut model.pool);
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
        Ok(Interpreter {
            model,
            pool,
            equations,
        })
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
