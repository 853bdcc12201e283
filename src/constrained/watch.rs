//! What a constrained integration watches after every step, so that it
//! never ends "successfully" off its constraints or on another branch of
//! its mechanism: the drift of every row at position and velocity level
//! against [`DriftLimits`], and, for the stabilisations that cannot cross
//! a singular position, how independent the rows still are
//! ([`constraint_conditioning`]).

use super::multipliers::DenseMetric;
use super::projection::checked;
use super::{ConstraintSolver, RANK_TOLERANCE};
use crate::dynamics::pivot_names;
use crate::integrate::{DriftLevel, Failure};
use crate::{ConstrainedSystem, DynamicsError, State};

/// The default largest drift of a constrained integration, at position
/// (`|φᵢ|`, in the row's units: metres, radians) and at velocity level
/// (`|ψᵢ|`, per second, relative to the row's speed when it exceeds one:
/// [`DriftLimits::velocity`]): `1e-6`. A run stabilised by projection holds
/// `1e-12` or so; Baumgarte's terms hold `1e-9` at ordinary steps and
/// gains; an unstabilised run of independent rows drifts by `1e-10` over
/// ten seconds of RK4 at `h = 1e-3 s`. What passes `1e-6` has left the
/// motion the model describes.
pub const DRIFT_LIMIT: f64 = 1e-6;

/// The relative singular value below which a constraint row counts as
/// barely independent of the others: `1e-3`. Measured by the pivoted
/// Cholesky factorisation of the (augmented) Schur complement
/// `S̄ = A M̄⁻¹ Aᵀ`, as the ratio `Lᵣᵣ / L₁₁` of the last pivot kept (above
/// [`RANK_TOLERANCE`]) to the first: an estimate of `σᵣ / σ₁`. Rows below
/// [`RANK_TOLERANCE`] (`σᵣ / σ₁ < 1e-6`) are dependent (redundant) and
/// solved as such; rows between the two are neither safely independent
/// (their multipliers and accelerations grow as `1/σ`) nor dependent, and
/// an integration that does not project reports them
/// ([`Failure::SingularPosition`]).
pub const BARELY_INDEPENDENT: f64 = 1e-3;

/// How far a constrained integration may drift off its constraints before
/// it stops with [`Failure::ConstraintDrift`], and how nearly dependent
/// its rows may become before a run that cannot cross singular positions
/// stops with [`Failure::SingularPosition`]. Set them with
/// [`Constrained::with_drift_limits`](crate::Constrained::with_drift_limits).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DriftLimits {
    /// The largest holonomic residual `|φᵢ(t, q)|` of any row. Under a
    /// projection the larger of this and the projection's own tolerance;
    /// under the augmented Lagrangian method, of this and its Newton
    /// tolerance.
    pub position: f64,
    /// The largest velocity form `|ψᵢ(t, q, v)|` of any row, relative to
    /// the speed of its terms `Σⱼ |Aᵢⱼ vⱼ|` when that exceeds one (a
    /// mechanism moving at metres per second keeps its velocity form to
    /// the same relative precision as one at rest keeps it absolutely).
    /// Under the augmented Lagrangian method, the larger of this and
    /// `1e-3`: its projection holds `ψ` only as far as its penalty allows
    /// near singular positions (`1.2e-5` in the IFToMM A02 mechanism at
    /// `h = 1e-3 s`), while its positions hold `φ` to its tolerance.
    pub velocity: f64,
    /// The smallest relative singular value of the independent rows, for
    /// the unstabilised and Baumgarte runs (see [`BARELY_INDEPENDENT`]);
    /// `0` never stops.
    pub conditioning: f64,
}

impl Default for DriftLimits {
    /// [`DRIFT_LIMIT`] at both levels and [`BARELY_INDEPENDENT`].
    fn default() -> Self {
        Self {
            position: DRIFT_LIMIT,
            velocity: DRIFT_LIMIT,
            conditioning: BARELY_INDEPENDENT,
        }
    }
}

impl DriftLimits {
    /// Nothing watched: the behaviour before the watch existed (a run may
    /// then end off its constraints or on another branch without error).
    pub const UNWATCHED: Self = Self {
        position: f64::INFINITY,
        velocity: f64::INFINITY,
        conditioning: 0.0,
    };

    /// Whether `state` is within these limits: its drift at position level
    /// (at most the larger of [`position`](Self::position) and the
    /// method's own precision `floor[0]`), then at velocity level (the
    /// larger of [`velocity`](Self::velocity) and `floor[1]`), then, unless
    /// the run `crosses` singular positions, the conditioning of its rows.
    /// A failure names the row, the value and the state's time.
    pub(crate) fn check<S, const NQ: usize, const NV: usize, const NU: usize, const NC: usize>(
        &self,
        system: &S,
        state: &State<NQ, NV>,
        floor: [f64; 2],
        crosses: bool,
    ) -> Result<(), Failure>
    where
        S: ConstrainedSystem<NQ, NV, NU, NC>,
    {
        let State { t, q, v } = state;
        let dynamics = |cause| Failure::Dynamics(cause);
        let residual = checked(system.constraint_residual(*t, q)).map_err(dynamics)?;
        let position = self.position.max(floor[0]);
        beyond(&residual, position, DriftLevel::Position, *t)?;
        let velocity = checked(system.constraint_velocity(*t, q, v)).map_err(dynamics)?;
        // Each row's scale: the speed of its terms, at least one.
        let jacobian = system.constraint_jacobian_at(*t, q);
        let scales: [f64; NC] = std::array::from_fn(|i| {
            let speed: f64 = jacobian[i].iter().zip(v).map(|(a, v)| (a * v).abs()).sum();
            speed.max(1.0)
        });
        let scaled: [f64; NC] = std::array::from_fn(|i| velocity[i] / scales[i]);
        let velocity_limit = self.velocity.max(floor[1]);
        if let Err(mut failure) = beyond(&scaled, velocity_limit, DriftLevel::Velocity, *t) {
            if let Failure::ConstraintDrift {
                row,
                residual,
                limit,
                ..
            } = &mut failure
            {
                (*residual, *limit) = (velocity[*row], velocity_limit * scales[*row]);
            }
            return Err(failure);
        }
        if crosses || self.conditioning <= 0.0 {
            return Ok(());
        }
        let conditioning = constraint_conditioning(system, *t, q).map_err(dynamics)?;
        match conditioning.weakest {
            Some(weakest) if weakest.singular_value < self.conditioning => {
                Err(Failure::SingularPosition {
                    row: weakest.row,
                    with: weakest.with,
                    singular_value: weakest.singular_value,
                    t: *t,
                })
            }
            _ => Ok(()),
        }
    }
}

/// The row of `values` furthest beyond `limit` (relative to it), as a
/// drift failure at level `level` and time `t`.
fn beyond<const NC: usize>(
    values: &[f64; NC],
    limit: f64,
    level: DriftLevel,
    t: f64,
) -> Result<(), Failure> {
    let worst = (0..NC).max_by(|&i, &j| values[i].abs().total_cmp(&values[j].abs()));
    match worst {
        Some(row) if values[row].abs() > limit => Err(Failure::ConstraintDrift {
            row,
            level,
            residual: values[row],
            limit,
            t,
        }),
        _ => Ok(()),
    }
}

/// How independent the constraint rows of a configuration are.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Conditioning {
    /// The number of independent rows (pivots of the Schur complement
    /// above [`RANK_TOLERANCE`] of the largest).
    pub rank: usize,
    /// The least independent of them, `None` if no row is independent.
    pub weakest: Option<WeakestRow>,
}

/// The least independent of the rows counted independent.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WeakestRow {
    /// Its index (declaration order).
    pub row: usize,
    /// The other independent row weighing most in its near-dependency
    /// (`row` itself when it is the only one).
    pub with: usize,
    /// Its relative singular value, estimated as [`BARELY_INDEPENDENT`]
    /// says: `1` for a single row, small near a singular position.
    pub singular_value: f64,
}

/// The rank of the constraint rows at `(t, q)` and their least independent row,
/// in the metric of the mass matrix (the rank-revealing solver's, so that
/// coordinates without inertia of their own are no error): below
/// [`BARELY_INDEPENDENT`] a configuration is near a singular position (a
/// four-bar folding flat, a slider-crank at a dead centre). Errors: a
/// non-finite mass matrix or Jacobian, a coordinate free to move without
/// inertia.
pub fn constraint_conditioning<
    S,
    const NQ: usize,
    const NV: usize,
    const NU: usize,
    const NC: usize,
>(
    system: &S,
    t: f64,
    q: &[f64; NQ],
) -> Result<Conditioning, DynamicsError>
where
    S: ConstrainedSystem<NQ, NV, NU, NC>,
{
    let mass = system.mass_matrix_at(t, q);
    let jacobian = system.constraint_jacobian_at(t, q);
    let names = pivot_names::<S, NQ, NV, NU>();
    let solver = ConstraintSolver::RankRevealing;
    let metric = DenseMetric::new(
        solver,
        RANK_TOLERANCE,
        &mass,
        &names,
        (&jacobian, &S::VANISHING_ROWS),
    )?;
    let schur = metric.schur();
    let weakest = schur.weakest().map(|(row, singular_value, dependency)| {
        let with = (0..NC)
            .filter(|&i| i != row && dependency[i] != 0.0)
            .max_by(|&i, &j| dependency[i].abs().total_cmp(&dependency[j].abs()))
            .unwrap_or(row);
        WeakestRow {
            row,
            with,
            singular_value,
        }
    });
    Ok(Conditioning {
        rank: schur.rank(),
        weakest,
    })
}
