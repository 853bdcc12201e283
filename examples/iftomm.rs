//! The IFToMM benchmark problems A01 (simple pendulum in Cartesian
//! coordinates), A02 (N-four-bar mechanism, N = 2, 10 and 40), A03 (Andrews'
//! squeezer) and A04 (Bricard's overconstrained mechanism), each simulated
//! over the benchmark's duration with the rank-revealing and the sparse
//! constraint solvers (RK4 and DOP853, projected after every step) and with
//! the index-3 augmented Lagrangian method (and, on A02, the Runge–Kutta
//! methods again with the energy held after each projection): energy
//! drift, largest constraint residual and the error of the benchmark's
//! reference point against an independent reference, then a work-precision
//! chart per benchmark (error of the reference point at the final time
//! against median thread CPU time, one line per method).
//!
//! ```text
//! cargo run --release --example iftomm [-- --out DIR] [--repeats N]
//! ```
//!
//! Charts and CSVs go to `DIR` (default `docs/charts`).
//!
//! The independent references: A01 is the same pendulum in its angle (one
//! coordinate, no constraint); A02 is the one-coordinate parallelogram
//! motion (every crank parallel, couplers level), which the mechanism
//! follows from its symmetric start; both are integrated by DOP853 at
//! `1e-13`. A03's reference is its loops written as coordinate equations
//! (a model independent of the `closure` statements simulated), by DOP853 at
//! `1e-13` with projection, checked against RK4 at `h = 1e-7 s`. A04 has no
//! reduced form here: its reference is DOP853 at `1e-13` with projection,
//! checked against RK4 at `h = 1e-4 s` with projection.

use std::error::Error;
use std::f64::consts::FRAC_PI_2;
use std::path::{Path, PathBuf};

use clap::{Arg, Command, value_parser};
use dalembert::constrained::{ConstraintSolver, constraint_drift};
use dalembert::integrate::{
    Adaptive, AdaptiveOptions, AugmentedLagrangian, AugmentedLagrangianSettings, ExplicitPair,
    Integration, Rk4,
};
use dalembert::{
    Constrained, ConstrainedSystem, IntegrationError, Solution, Stabilisation, State,
    Unconstrained, energy,
};
use dalembert_fixtures::cpu_time::thread_time;
use dalembert_fixtures::iftomm::{
    ANDREWS, ANDREWS_EQUATIONS, AnglePendulum, Bricard, CartesianPendulum, FourBars2, FourBars10,
    FourBars40, Parallelogram, andrews_start, four_bar_start,
};
use dalembert_lab::{Accuracy, WorkPoint, measure, to_csv, work_precision_chart};

/// Projection after every step of the Runge–Kutta methods.
const PROJECTION: Stabilisation = Stabilisation::Projection {
    tolerance: 1e-12,
    max_iterations: 10,
};

/// One integration, reporting every state to the observer it is given.
type ObservedRun<'a, const NQ: usize> = dyn FnMut(&mut dyn FnMut(&State<NQ, NQ>)) -> Result<Solution<NQ, NQ>, IntegrationError<NQ>>
    + 'a;

/// A benchmark: its name, file stem, duration and the reference point's
/// position at the final time from the independent reference.
struct Benchmark {
    name: &'static str,
    stem: &'static str,
    duration: f64,
    reference: [f64; 2],
}

fn main() -> Result<(), Box<dyn Error>> {
    let options = Command::new("iftomm")
        .about("The IFToMM benchmarks A01 to A04: accuracy, drift and work-precision charts")
        .arg(
            Arg::new("out")
                .long("out")
                .value_parser(value_parser!(PathBuf))
                .default_value(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/charts")),
        )
        .arg(
            Arg::new("repeats")
                .long("repeats")
                .value_parser(value_parser!(usize))
                .default_value("3"),
        )
        .get_matches();
    let out = options
        .get_one::<PathBuf>("out")
        .cloned()
        .unwrap_or_default();
    let repeats = options.get_one::<usize>("repeats").copied().unwrap_or(3);
    std::fs::create_dir_all(&out)?;
    pendulum(&out, repeats)?;
    four_bars(&out, repeats)?;
    andrews(&out, repeats)?;
    bricard(&out, repeats)?;
    Ok(())
}

/// A01: 1 kg on a 1 m massless rod, at rest with the rod horizontal
/// (`x = 1 m`), 2000 s.
fn pendulum(out: &Path, repeats: usize) -> Result<(), Box<dyn Error>> {
    let system = CartesianPendulum {
        m: 1.0,
        l: 1.0,
        g: 9.81,
    };
    let angle = AnglePendulum {
        m: 1.0,
        l: 1.0,
        g: 9.81,
    };
    let duration = 2000.0;
    let theta = tight(
        &Unconstrained::without_inputs(&angle),
        State {
            t: 0.0,
            q: [0.0],
            v: [0.0],
        },
        duration,
        1e-13,
    )?;
    let benchmark = Benchmark {
        name: "A01 simple pendulum (Cartesian coordinates)",
        stem: "iftomm_a01",
        duration,
        reference: [theta.q[0].cos(), theta.q[0].sin()],
    };
    let start = State {
        t: 0.0,
        q: [1.0, 0.0],
        v: [0.0, 0.0],
    };
    let point = |s: &State<2, 2>| s.q;
    run(
        out,
        repeats,
        &benchmark,
        &system,
        start,
        point,
        &Settings {
            steps: &[2e-3, 1e-3, 5e-4],
            tolerances: &[1e-8, 1e-10, 1e-12],
            alf_steps: &[1e-3, 5e-4, 2.5e-4],
            solvers: DENSE,
            energy_held: false,
        },
    )
}

/// A02: unit rods, cranks upright, the tip `B0` of the first crank moving
/// at 1 m/s along `x`, 20 s; N = 2 and N = 10.
fn four_bars(out: &Path, repeats: usize) -> Result<(), Box<dyn Error>> {
    let (m, l, g) = (1.0, 1.0, 9.81);
    let two = FourBars2 { m, L: l, g };
    four_bar(
        out,
        repeats,
        "A02 two four-bars",
        "iftomm_a02_n2",
        2.0,
        &two,
    )?;
    let ten = FourBars10 { m, L: l, g };
    four_bar(
        out,
        repeats,
        "A02 ten four-bars",
        "iftomm_a02_n10",
        10.0,
        &ten,
    )?;
    let forty = FourBars40 { m, L: l, g };
    four_bar(
        out,
        repeats,
        "A02 forty four-bars",
        "iftomm_a02_n40",
        40.0,
        &forty,
    )
}

/// One A02 mechanism of `n` windows, against the parallelogram motion.
fn four_bar<S, const NQ: usize, const NC: usize>(
    out: &Path,
    repeats: usize,
    name: &'static str,
    stem: &'static str,
    n: f64,
    system: &S,
) -> Result<(), Box<dyn Error>>
where
    S: ConstrainedSystem<NQ, NQ, 0, NC>,
{
    let duration = 20.0;
    let reduced = Parallelogram {
        m: 1.0,
        L: 1.0,
        g: 9.81,
        n,
    };
    let upright = State {
        t: 0.0,
        q: [FRAC_PI_2],
        v: [-1.0],
    };
    let phi = tight(
        &Unconstrained::without_inputs(&reduced),
        upright,
        duration,
        1e-13,
    )?;
    let benchmark = Benchmark {
        name,
        stem,
        duration,
        reference: [phi.q[0].cos(), phi.q[0].sin()],
    };
    // The dense solver costs the cube of the size: at N = 40 only the
    // sparse one, with coarser steps.
    let settings = if NQ > 50 {
        Settings {
            steps: &[2e-2, 1e-2, 5e-3],
            tolerances: &[1e-4, 1e-5, 1e-6, 1e-8, 1e-10],
            alf_steps: &[],
            solvers: SPARSE,
            energy_held: true,
        }
    } else {
        Settings {
            steps: &[2e-3, 1e-3, 5e-4],
            tolerances: &[1e-6, 1e-8, 1e-10],
            alf_steps: &[2e-3, 1e-3, 5e-4],
            solvers: BOTH,
            energy_held: true,
        }
    };
    run(
        out,
        repeats,
        &benchmark,
        system,
        four_bar_start(),
        crank_tip,
        &settings,
    )
}

/// A03: Andrews' squeezer with Hairer and Wanner's data, from rest, 0.03 s.
/// The reference point is the crank angle `beta` and the coupler angle
/// `Theta` (in rad).
fn andrews(out: &Path, repeats: usize) -> Result<(), Box<dyn Error>> {
    let duration = 0.03;
    let exact = Stabilisation::Projection {
        tolerance: 1e-14,
        max_iterations: 10,
    };
    let written = Constrained::without_inputs(&ANDREWS_EQUATIONS, exact);
    let reference = tight(&written, andrews_start(), duration, 1e-13)?;
    let check = Integration::new(&written, andrews_start(), duration, Rk4 { steps: 300_000 })
        .run()?
        .end;
    let largest = |a: &State<7, 7>, b: &State<7, 7>| {
        a.q.iter()
            .zip(&b.q)
            .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
    };
    println!(
        "A03 reference (coordinate equations): DOP853 (1e-13) and RK4 (h = 1e-7 s) differ by {:.1e} rad at most\n\
         A03 reference at 0.03 s: q = {:?}",
        largest(&reference, &check),
        reference.q
    );
    let benchmark = Benchmark {
        name: "A03 Andrews' squeezer",
        stem: "iftomm_a03",
        duration,
        reference: [reference.q[0], reference.q[1]],
    };
    run(
        out,
        repeats,
        &benchmark,
        &ANDREWS,
        andrews_start(),
        |s| [s.q[0], s.q[1]],
        &Settings {
            steps: &[2e-5, 1e-5, 5e-6],
            tolerances: &[1e-6, 1e-8, 1e-10],
            alf_steps: &[2e-5, 1e-5, 5e-6],
            solvers: DENSE,
            energy_held: false,
        },
    )
}

/// `B0`, the tip of the first crank (unit rods).
fn crank_tip<const NQ: usize>(s: &State<NQ, NQ>) -> [f64; 2] {
    [s.q[0].cos(), s.q[0].sin()]
}

/// A04: unit rods along the edges of a cube, at rest, 10 s. The reference
/// point is the tip of the third rod (its `x` and `y`).
fn bricard(out: &Path, repeats: usize) -> Result<(), Box<dyn Error>> {
    let system = Bricard {
        m: 1.0,
        L: 1.0,
        g: 9.81,
    };
    let duration = 10.0;
    let start = State {
        t: 0.0,
        q: [0.0; 5],
        v: [0.0; 5],
    };
    let exact = Stabilisation::Projection {
        tolerance: 1e-14,
        max_iterations: 10,
    };
    let dynamics = Constrained::without_inputs(&system, exact);
    let reference = tight(&dynamics, start, duration, 1e-13)?;
    let check = Integration::new(&dynamics, start, duration, Rk4 { steps: 100_000 })
        .run()?
        .end;
    let (p, c) = (third_rod_tip(&reference), third_rod_tip(&check));
    println!(
        "A04 reference: DOP853 (1e-13) and RK4 (h = 1e-4 s), both projected to 1e-14, differ by {:.1e} m at P3",
        (p[0] - c[0]).abs().max((p[1] - c[1]).abs())
    );
    let benchmark = Benchmark {
        name: "A04 Bricard's mechanism",
        stem: "iftomm_a04",
        duration,
        reference: p,
    };
    run(
        out,
        repeats,
        &benchmark,
        &system,
        start,
        third_rod_tip,
        &Settings {
            steps: &[2e-3, 1e-3, 5e-4],
            tolerances: &[1e-6, 1e-8, 1e-10],
            alf_steps: &[2e-3, 1e-3, 5e-4],
            solvers: DENSE,
            energy_held: false,
        },
    )
}

/// The tip `P3` of the third rod of Bricard's mechanism (unit rods): `x` and
/// `y` of `F1.x + F2.y + F3.z` with `F1 = Ry(q1)`, `F2 = F1 Rz(q2)`,
/// `F3 = F2 Rx(q3)`.
fn third_rod_tip(s: &State<5, 5>) -> [f64; 2] {
    let [(s1, c1), (s2, c2), (s3, c3)] = [s.q[0].sin_cos(), s.q[1].sin_cos(), s.q[2].sin_cos()];
    // F1.x = Ry(q1) x, F2.y = Ry(q1) Rz(q2) y, F3.z = Ry(q1) Rz(q2) (0, −s3, c3).
    let f1x = [c1, 0.0];
    let f2y = [-s2 * c1, c2];
    let f3z = [c1 * s2 * s3 + s1 * c3, -c2 * s3];
    [f1x[0] + f2y[0] + f3z[0], f1x[1] + f2y[1] + f3z[1]]
}

/// The end of an integration by DOP853 at `tolerance`.
fn tight<D, const NQ: usize, const NV: usize>(
    dynamics: &D,
    start: State<NQ, NV>,
    duration: f64,
    tolerance: f64,
) -> Result<State<NQ, NV>, IntegrationError<NQ>>
where
    D: dalembert::integrate::Dynamics<NQ, NV>,
{
    let options = AdaptiveOptions {
        max_steps: 100_000_000,
        ..AdaptiveOptions::with_tolerance(tolerance)
    };
    Ok(Integration::new(
        dynamics,
        start,
        duration,
        Adaptive {
            pair: ExplicitPair::Dop853,
            options,
        },
    )
    .run()?
    .end)
}

/// The methods' settings on one benchmark: RK4 steps, DOP853 tolerances
/// (each with every solver of `solvers`) and the augmented Lagrangian
/// method's steps; with `energy_held`, the Runge–Kutta lines run a second
/// time with the energy held after each projection
/// (`Stabilisation::EnergyProjection`, for conservative mechanisms only).
struct Settings<'a> {
    steps: &'a [f64],
    tolerances: &'a [f64],
    alf_steps: &'a [f64],
    solvers: &'a [(&'a str, ConstraintSolver)],
    energy_held: bool,
}

/// The constraint solvers of the Runge–Kutta lines, by the suffix of their
/// name.
const DENSE: &[(&str, ConstraintSolver)] = &[("", ConstraintSolver::RankRevealing)];
const SPARSE: &[(&str, ConstraintSolver)] = &[(" (sparse)", ConstraintSolver::Sparse)];
const BOTH: &[(&str, ConstraintSolver)] = &[
    ("", ConstraintSolver::RankRevealing),
    (" (sparse)", ConstraintSolver::Sparse),
];

/// Simulates `system` over the benchmark by every method at every setting,
/// prints energy drift, residual and reference-point error, and writes the
/// work-precision chart and CSV.
fn run<S, const NQ: usize, const NC: usize>(
    out: &Path,
    repeats: usize,
    benchmark: &Benchmark,
    system: &S,
    start: State<NQ, NQ>,
    point: impl Fn(&State<NQ, NQ>) -> [f64; 2] + Copy,
    settings: &Settings<'_>,
) -> Result<(), Box<dyn Error>>
where
    S: ConstrainedSystem<NQ, NQ, 0, NC>,
{
    println!("\n{} over {} s", benchmark.name, benchmark.duration);
    println!(
        "{:<32} {:>9} {:>11} {:>11} {:>11} {:>9}",
        "method", "setting", "energy", "residual", "ref. point", "time [s]"
    );
    let dynamics = Constrained::without_inputs(system, PROJECTION);
    let initial = energy(system, &start.q, &start.v);
    let duration = benchmark.duration;
    let judge = |s: &State<NQ, NQ>| {
        let p = point(s);
        Accuracy {
            error: (p[0] - benchmark.reference[0])
                .abs()
                .max((p[1] - benchmark.reference[1]).abs()),
            energy_error: (energy(system, &s.q, &s.v) - initial).abs(),
            drift: constraint_drift(system, s),
        }
    };
    let mut points: Vec<WorkPoint> = Vec::new();
    let mut record =
        |method: &str, setting: f64, run: &mut ObservedRun<'_, NQ>| -> Result<(), Box<dyn Error>> {
            // One observed run for the drift over the whole history, then the
            // timed repeats.
            let (mut drift, mut residual) = (0.0f64, 0.0f64);
            let observed = run(&mut |s| {
                drift = drift.max((energy(system, &s.q, &s.v) - initial).abs());
                residual = residual.max(constraint_drift(system, s));
            });
            if let Err(error) = observed {
                println!("{method:<32} {setting:>9.1e} failed: {error}");
                return Ok(());
            }
            let measured = measure(
                method,
                setting,
                repeats,
                thread_time,
                || run(&mut |_| {}),
                judge,
            )?;
            println!(
                "{method:<32} {setting:>9.1e} {drift:>11.2e} {residual:>11.2e} {:>11.2e} {:>9.4}",
                measured.accuracy.error, measured.seconds
            );
            points.push(measured);
            Ok(())
        };
    let held = Stabilisation::EnergyProjection {
        tolerance: 1e-12,
        max_iterations: 10,
        energy: initial,
    };
    let stabilisations = [("projection", PROJECTION), ("energy held", held)];
    let stabilisations = &stabilisations[..1 + usize::from(settings.energy_held)];
    for (&(suffix, solver), &(kept, stabilisation)) in settings
        .solvers
        .iter()
        .flat_map(|s| stabilisations.iter().map(move |k| (s, k)))
    {
        let dynamics = Constrained::without_inputs(system, stabilisation).with_solver(solver);
        for &h in settings.steps {
            let n = (duration / h).round() as u64;
            record(&format!("RK4 + {kept}{suffix}"), h, &mut |observer| {
                Integration::new(&dynamics, start, duration, Rk4 { steps: n })
                    .observe(observer)
                    .run()
            })?;
        }
        for &tolerance in settings.tolerances {
            let options = AdaptiveOptions {
                max_steps: 100_000_000,
                ..AdaptiveOptions::with_tolerance(tolerance)
            };
            record(
                &format!("DOP853 + {kept}{suffix}"),
                tolerance,
                &mut |observer| {
                    Integration::new(
                        &dynamics,
                        start,
                        duration,
                        Adaptive {
                            pair: ExplicitPair::Dop853,
                            options,
                        },
                    )
                    .observe(observer)
                    .run()
                },
            )?;
        }
    }
    for &h in settings.alf_steps {
        let n = (duration / h).round() as u64;
        record("augmented Lagrangian (index 3)", h, &mut |observer| {
            Integration::new(
                &dynamics,
                start,
                duration,
                AugmentedLagrangian {
                    steps: n,
                    settings: AugmentedLagrangianSettings::for_step(h),
                },
            )
            .observe(observer)
            .run()
        })?;
    }
    std::fs::write(out.join(format!("{}.csv", benchmark.stem)), to_csv(&points))?;
    let chart = out.join(format!("{}.svg", benchmark.stem));
    work_precision_chart(
        &chart,
        &format!("{}: reference point at {} s", benchmark.name, duration),
        &points,
        &[],
    )?;
    println!("wrote {}", chart.display());
    Ok(())
}
