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
use crate::geometry::Values;
use crate::model::Model;

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
        let roots = function.roots();
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
