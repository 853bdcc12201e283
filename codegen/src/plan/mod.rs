//! Planning: every choice of route between the derived equations and the
//! emitted code, made in one place by one cost model ([`cost`]: operation
//! counts, and the code's size where it streams from memory).
//!
//! For each generated function the plan says how it computes what it
//! returns: `M` unrolled or by the runtime's loop over a tree's pairs
//! ([`MassMatrix`]); the partials of the inverse dynamics symbolic, by the
//! world-frame recursion, or by that recursion's loops at run time
//! ([`Partials`]); `accelerations` by the unrolled `L D Lᵀ` factorisation
//! (in which order of elimination) or the articulated-body recursion
//! ([`solve`]); the Taylor series' program on the equations as derived or
//! with their angle sums recombined, and how many orders are unrolled
//! ([`Taylor`]); which form (DAG or compact) each result takes
//! ([`optimize`]); and when a long body declares its temporaries ahead.
//! [`plan`] drives the outputs and hands them their routes; the partials
//! of `τ` are derived by both candidate routes and measured in
//! [`partials`], which hands the outputs those of the route chosen (at the
//! first output that returns them). Emission then only writes code from
//! the plan. Every
//! threshold is a constant below, with what was measured to set it.

pub mod cost;
pub mod optimize;
pub mod partials;
pub mod solve;

use crate::emit::Target;
use crate::equations::Equations;
use crate::expr::{ExprId, Pool};
use crate::model::Model;
use crate::outputs::{self, Body, Function, NameList};
use crate::readable::ReadableForms;
use crate::series::Lowered;
use cost::operations;
use partials::TauPartials;
use solve::{Accelerations, Factorisation};

/// The fewest operations of an unrolled `M` (as [`operations`] counts
/// them in the pool) above which a tree's `mass_matrix` takes its pairs of
/// speeds in a loop at run time: the spatial chain of 30 (9703–10707 in
/// the three spellings), whose unrolled code streams from L2, gains; the
/// planar one of 30 (5181–6437, its planar zeros folded) and the spatial
/// one of 12 (1781–2040) lose (BENCHMARKS.md, "Large models: unrolled
/// against looped code", the subsection of 25 Nov 2026 on `mass_matrix`).
pub const MASS_PAIRS_LOOPED_ABOVE: usize = 8000;

/// The operations of unrolled partials of a tree past which their code
/// streams from L2 at about twice the time per byte (BENCHMARKS.md, "where
/// the jacobian's time goes"): the plan charges the operations past it
/// again at [`STREAMED_PERCENT`], and weighs them against the looped
/// route's, which computes the partials in loops at run time, link by link
/// and pair of joints by pair (its straight-line code and the loops'
/// operations, `cost::tree_loop_operations`). Floating bases take the
/// same routes since the recursion knows free and spherical joints: the
/// floating G1's code fell from 4.8 MB to 1.8 MB and its jacobian's
/// operations from 220 k to 192 k (docs/humanoid.md, which has the
/// timings).
pub const TREE_LOOPED_ABOVE: usize = 6000;

/// The charge, in percent of their count, of the unrolled partials'
/// operations past [`TREE_LOOPED_ABOVE`]. Set so that every route timed
/// before the looped route was charged its loops keeps its choice: the
/// floating Solo-12 (symbolic 16 640 operations, charged 32 600, against
/// 27 236 looped; they measured alike, 6.1 µs unrolled and 6.2–6.4 looped,
/// docs/humanoid.md), the panda (its unrolled recursion's 8 943 charged
/// 13 357 against 13 040 looped), the floating humanoids, the spatial
/// chains of 12 and 30 and the tree of 14 stay looped; ANYmal C (6 062
/// symbolic against 14 601 looped, at the old threshold's edge) and the
/// planar chain of 30 (its recursion 14 230 against 70 205) are unrolled.
pub const STREAMED_PERCENT: usize = 250;

/// The most columns of structural zeros between two runs of possibly
/// nonzero columns that a step of the jacobian's forward substitution
/// passes over rather than starting a run anew: four columns are one
/// operation of the runtime's lanes (`dalembert::__private::subtract_on_runs`).
pub const FILLED_GAP: usize = 4;

/// The rows of `accelerations_jacobian` a pass of its rows as adjoints
/// takes, as the plan charges them: two, the lanes of an SSE2 register
/// (the x86-64 baseline; `dalembert::__private::WEIGHT_LANES` is four on
/// a target with AVX).
pub const ADJOINT_LANES: usize = 2;

/// The most operations a row of `accelerations_jacobian` may cost by
/// adjoints ([`crate::outputs::Body::AdjointRows`]: row `i` is `μᵀ ∂τ/∂x`
/// at `μ = −M⁻¹ eᵢ`, one reverse sweep over `τ` for [`ADJOINT_LANES`]
/// rows in SIMD lanes, `⌈n/2⌉ · sweep / n` a row) for a fixed-base tree on
/// the loops' route (above [`TREE_LOOPED_ABOVE`]) to take them. The loops'
/// work is the same for every link whatever its geometry; the sweep,
/// unrolled with the model's constants folded, is shorter for simpler
/// links. Measured (28 Nov 2026, thread CPU time, both routes' code in one
/// binary, medians of 31 interleaved runs; the sweep's operations as
/// [`operations`] counts them), the rows in passes of two lanes against
/// the loops: the panda (5 passes of a 2964-operation sweep, 1647 a row)
/// 0.75 of the loops' time, the branching tree of 14 (7 of 3665, 1833 a
/// row) 0.90, the spatial chain of 16 (8 of 3897, 1949 a row) 0.87 and
/// of 20 (10 of 4994, 2497 a row) 0.95, for 30 % more code; the spatial
/// chain of 12 (6 of 2809, 1405 a row) took 0.87 of its time in passes
/// of four lanes.
pub const ADJOINT_ROW_AT_MOST: usize = 2200;

/// Whether `accelerations_jacobian` of `model`, whose partials of `τ` are
/// `partials` (by the route the plan chose), takes its rows as adjoints in
/// lanes, the reverse sweep `sweep` (every entry of
/// `inverse_dynamics_adjoint`) [`ADJOINT_LANES`] rows a pass: a tree on a
/// fixed base (quaternion joints keep the loops) on the loops' route whose
/// rows cost at most [`ADJOINT_ROW_AT_MOST`] that way.
pub fn adjoint_rows(model: &Model, partials: &TauPartials, sweep: &[ExprId], pool: &Pool) -> bool {
    let nv = model.nv();
    model.balls.is_empty()
        && partials.route == Partials::Looped
        && nv.div_ceil(ADJOINT_LANES) * operations(pool, sweep) <= nv * ADJOINT_ROW_AT_MOST
}

/// The fewest coordinates for which `accelerations` may take the
/// articulated-body recursion: with one or two coordinates the
/// factorisation measured faster at any operation count.
pub const MIN_ARTICULATED: usize = 3;

/// The articulated-body recursion's operations, charged in percent of the
/// factorisation's: its sweeps run one link after another, where `M`'s
/// entries are independent of each other, and at 0.96 of the
/// factorisation's count the spatial chains of 12 ran 1.13–1.17 times as
/// long (BENCHMARKS.md, "The recursion's operations cost more").
pub const ARTICULATED_PERCENT: usize = 120;

/// [`ARTICULATED_PERCENT`] on a floating base (a free joint on `N`): its
/// tree's limbs are swept side by side, and the recursion ran its
/// operations a little faster than the factorisation, not slower. Measured
/// (thread CPU time, the median of 9 repeats over 1000 random states,
/// docs/humanoid.md, 28 Nov 2026) against the factorisation, at the count
/// ratio (recursion's / factorisation's operations) in brackets: dm_control's
/// humanoid 2.20 → 2.09 µs (1.01), the G1 3.38 → 3.00 (0.90), Talos 3.21 →
/// 2.78 (0.89), the floating Solo-12 0.90 → 0.95 (1.12); the time ratios
/// are 0.94–0.97 of the count ratios, so the recursion wins below 0.95.
pub const FLOATING_ARTICULATED_PERCENT: usize = 95;

/// [`ARTICULATED_PERCENT`] for `accelerations_x4` (four states at once,
/// one in each SIMD lane). The scalar factorisation's substitutions and
/// rows are vectorised by the compiler two entries at a time, which the
/// lanes, already full, cannot be: over the lanes the factorisation gains
/// less and the recursion wins sooner. With `wide::f64x4` on the default
/// x86-64 target, the spatial chain of 12 (the recursion at 96 % of the
/// factorisation's count) ran 0.62 of the scalar call by the factorisation
/// and 0.55 by the recursion; the chain of 6 (128 %) 0.53 and 0.82.
pub const LANES_ARTICULATED_PERCENT: usize = 100;

/// Most monomials a result may expand to for its compact form to be
/// offered ([`optimize`]); a larger one keeps its DAG form. Set with the
/// first optimisation pass (`ae08658`), with no measurement recorded: it
/// bounds the work of an expansion, whose monomials grow combinatorially
/// with a tree's depth.
pub const COMPACT_FORM_BUDGET: usize = 200;

/// Most monomials an entry of `M` or `f` may expand to for its angle sums
/// to be recombined in the Taylor series' program (`sin a cos b − cos a
/// sin b = sin(a − b)`: one `sin_cos` recurrence of the difference instead
/// of four Cauchy products and two sums, ≈ 5 % a step on seed example 1);
/// a larger entry is lowered as derived. The same bound as
/// [`COMPACT_FORM_BUDGET`], for the same reason (`727610e`).
pub const RECOMBINATION_BUDGET: usize = 200;

/// The orders of `taylor_coefficients` emitted one by one, each with its
/// own copy of the recurrences (a constant order, so sums of compile-time
/// length); higher orders run in a loop. The runtime's Taylor integrator
/// uses up to 31 (`dalembert::integrate::MAX_ORDER`).
pub const UNROLLED_ORDERS: usize = 31;

/// The most temporaries a body binds each with its own `let`. Each `let`
/// opens a lexical scope nested in the one before, and with full debug
/// information rustc recurses once per scope: a body of a few thousand
/// (the `inverse_dynamics_jacobian` of a 7-joint arm on a free flyer)
/// overflowed its stack in a default `dev` build. Above it, the
/// temporaries are declared ahead, [`DECLARED_TOGETHER`] to a `let`, and
/// each is assigned where it would have been bound (the same code once
/// optimised).
pub const DECLARED_AHEAD_ABOVE: usize = 1000;

/// How many temporaries one `let` declares ahead.
pub const DECLARED_TOGETHER: usize = 64;

/// How `mass_matrix` computes `M`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MassMatrix {
    /// Every entry in straight-line code.
    Unrolled,
    /// Each speed's vectors in straight-line code and their dot products
    /// by the runtime's loop over the tree (an unrolled `M` where the
    /// model is no tree).
    Looped,
}

/// How the partials of the inverse dynamics are computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Partials {
    /// `τ` differentiated symbolically.
    Symbolic,
    /// The world-frame recursion's partials, unrolled.
    Recursive,
    /// The world-frame recursion, its inertia and gravity terms in loops
    /// at run time.
    Looped,
}

/// The Taylor series' program of `taylor_coefficients`.
pub struct Taylor {
    /// `M`, `f` (and `A`, `b`) lowered to series.
    pub lowered: Lowered,
    /// The orders emitted one by one before the loop.
    pub unrolled_orders: usize,
}

/// What to emit for one system and how.
pub struct Plan {
    /// The functions, each with its route ([`Body`]), their results in the
    /// forms chosen.
    pub functions: Vec<Function>,
    /// The constants naming their entries.
    pub constants: Vec<NameList>,
    /// `M`'s unrolled factorisation; `None` for a system with constraints
    /// or no coordinates, or a crate without the runtime.
    pub factorisation: Option<Factorisation>,
    /// The route of `accelerations`; `None` where there is no such
    /// method.
    pub accelerations: Option<Accelerations>,
    /// The route of `accelerations_x4`, which may differ from that of
    /// `accelerations` ([`LANES_ARTICULATED_PERCENT`]); `None` where
    /// there is no `accelerations`.
    pub accelerations_x4: Option<Accelerations>,
    /// The program of `taylor_coefficients`, if it is emitted.
    pub taylor: Option<Taylor>,
}

/// The plan of every function to emit for `target` (the standard ones,
/// then those the model's `outputs` ask for), their results optimised.
pub fn plan(
    model: &Model,
    equations: &Equations,
    pool: &mut Pool,
    forms: &mut ReadableForms,
    target: Target,
) -> Plan {
    let mass = mass_matrix(equations, pool, target);
    let mut functions = outputs::standard(model, equations, pool, mass);
    // A looped `M`'s vectors are new expressions, optimised as the outputs are.
    if let Some(mass) = functions
        .first_mut()
        .filter(|f| matches!(f.body, Body::MassPairs(_)))
    {
        optimize::optimize_functions(std::slice::from_mut(mass), pool, forms);
    }
    let mut requested = outputs::requested(model, equations, pool);
    optimize::optimize_functions(&mut requested.functions, pool, forms);
    functions.extend(requested.functions);
    let runtime = target == Target::Std;
    let factorisation = runtime
        .then(|| solve::factorisation(model, pool, equations))
        .flatten();
    let routes = factorisation
        .as_ref()
        .map(|f| solve::accelerations(model, pool, equations, f));
    Plan {
        functions,
        constants: requested.constants,
        factorisation,
        accelerations: routes.map(|r| r.scalar),
        accelerations_x4: routes.map(|r| r.lanes),
        taylor: None,
    }
}

impl Plan {
    /// Plans the program of `taylor_coefficients`, if it is emitted (for a
    /// crate with the runtime, a system with a factorisation or
    /// constraints). It runs last, after the docs are rendered: the
    /// program's new nodes come after every node the other functions and
    /// the docs read, whose ids (which order sums and products, and so the
    /// code) are then as without it.
    pub fn plan_taylor(
        &mut self,
        model: &Model,
        pool: &mut Pool,
        forms: &mut ReadableForms,
        equations: &Equations,
        target: Target,
    ) {
        let constrained = !equations.constraint_jacobian.is_empty();
        let solvable = self.factorisation.is_some() || constrained;
        if target == Target::Std
            && solvable
            && self.functions.iter().any(|f| f.body == Body::Taylor)
        {
            self.taylor = Some(Taylor {
                lowered: taylor_program(pool, forms, model.nq(), equations),
                unrolled_orders: UNROLLED_ORDERS,
            });
        }
    }
}

/// [`MassMatrix::Looped`] for a crate with the runtime and an unrolled `M`
/// costing more than [`MASS_PAIRS_LOOPED_ABOVE`] operations (armatures are
/// added to the looped `M`'s diagonal after the runtime's loop).
fn mass_matrix(equations: &Equations, pool: &Pool, target: Target) -> MassMatrix {
    let entries: Vec<ExprId> = equations.mass_matrix.iter().flatten().copied().collect();
    let looped = target == Target::Std && operations(pool, &entries) > MASS_PAIRS_LOOPED_ABOVE;
    match looped {
        true => MassMatrix::Looped,
        false => MassMatrix::Unrolled,
    }
}

/// The equations lowered to series as derived, or with their angle sums
/// recombined (within [`RECOMBINATION_BUDGET`]) when that takes fewer
/// recurrences (the work of each order). Both are lowered over `pool`
/// (the recurrences are counted on the programs); the other's nodes are
/// never emitted.
fn taylor_program(
    pool: &mut Pool,
    forms: &mut ReadableForms,
    nq: usize,
    equations: &Equations,
) -> Lowered {
    let derived = Lowered::derived(pool, nq, equations);
    let recombined = Lowered::recombined(pool, forms, nq, equations, RECOMBINATION_BUDGET);
    if recombined.recurrences() < derived.recurrences() {
        recombined
    } else {
        derived
    }
}
