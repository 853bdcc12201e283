//! Work-precision diagrams and stability charts: for seed example 1 (the
//! chaotic double pendulum of the reference data), seed example 3 and the
//! slider-crank, every integrator over a sweep of tolerances or step sizes,
//! its final-state error against median thread CPU time (SVG, log-log) and a CSV
//! with the energy error, the constraint drift and the right-hand-side
//! evaluations; then the long-time energy drift, the stiff joint and the
//! sensitivity of the chaotic pendulum.
//!
//! ```text
//! cargo run --release --example work_precision [-- --out DIR] [--scipy CSV] [--repeats N] [--taylor]
//! ```
//!
//! `--taylor` runs only the charts with the Taylor integrator: seed example
//! 1 (chaotic), the same pendulum at 0.2 rad (regular), whose ratio of
//! DOP853's time to Taylor's at the final-state error 1e-12 it prints, and
//! seed example 3 (constrained: Taylor unstabilised and with projection).
//!
//! Output goes to `DIR` (default `target/charts`). `--scipy` adds the SciPy
//! `solve_ivp(DOP853)` line written by `scripts/scipy_baseline.sh` to the
//! seed-1 chart and prints the speed ratio at equal error (default:
//! `DIR/scipy_dop853.csv` if it exists).

use std::error::Error;
use std::path::{Path, PathBuf};

use clap::{Arg, Command, value_parser};
use dalembert::constrained::{DriftLimits, constraint_drift};
use dalembert::integrate::{self, AdaptiveOptions, Dynamics, ExplicitPair, GaussLegendre};
use dalembert::{
    Constrained, ConstrainedSystem, IntegrationError, Solution, Stabilisation, State, TaylorSystem,
    Unconstrained, energy,
};
use dalembert_fixtures::cpu_time::thread_time;
use dalembert_fixtures::seeds::{CHAOTIC, CHAOTIC_END, CHAOTIC_START};
use dalembert_fixtures::slider_crank::{CRANK_SPEED, SEED_3, SLIDER_CRANK};
use dalembert_fixtures::stability::{ON_AXIS, STIFF, STIFF_START, TOWARDS_AXIS, chaotic_reference};
use dalembert_generated::taylor_constrained_pendulum::TaylorConstrainedPendulum;
use dalembert_generated::taylor_double_pendulum::TaylorDoublePendulum;
use dalembert_lab::{
    Accuracy, Series, WorkPoint, line_chart_log_y, measure, seconds_at_error, state_error, to_csv,
    work_precision_chart,
};
use indicatif::{ProgressBar, ProgressStyle};

/// The error at which our DOP853 and SciPy's are compared.
const COMPARISON_ERROR: f64 = 1e-6;
/// The error at which our DOP853 and the Taylor integrator are compared.
const TAYLOR_COMPARISON_ERROR: f64 = 1e-12;
/// Where double precision meets the chaos of seed example 1 at t = 10: the
/// reference README's DOP853 at rtol = atol = 1e-14 is 3.3e-8 off.
const CHAOTIC_LIMIT: f64 = 3.3e-8;
/// Projection after every step, for the constrained systems.
const PROJECTION: Stabilisation = Stabilisation::Projection {
    tolerance: 1e-13,
    max_iterations: 8,
};

/// A method at one setting: how to run it once.
type Run<'a, const NQ: usize> =
    Box<dyn Fn() -> Result<Solution<NQ, NQ>, IntegrationError<NQ>> + 'a>;

fn main() -> Result<(), Box<dyn Error>> {
    let options = Command::new("work_precision")
        .about("Work-precision diagrams and stability charts of dalembert's integrators")
        .arg(
            Arg::new("out")
                .long("out")
                .value_parser(value_parser!(PathBuf))
                .default_value(concat!(env!("CARGO_MANIFEST_DIR"), "/target/charts")),
        )
        .arg(
            Arg::new("scipy")
                .long("scipy")
                .value_parser(value_parser!(PathBuf)),
        )
        .arg(
            Arg::new("repeats")
                .long("repeats")
                .value_parser(value_parser!(usize))
                .default_value("5"),
        )
        .arg(
            Arg::new("taylor")
                .long("taylor")
                .action(clap::ArgAction::SetTrue),
        )
        .get_matches();
    let out = options
        .get_one::<PathBuf>("out")
        .cloned()
        .unwrap_or_default();
    let repeats = options.get_one::<usize>("repeats").copied().unwrap_or(5);
    let scipy = options
        .get_one::<PathBuf>("scipy")
        .cloned()
        .unwrap_or_else(|| out.join("scipy_dop853.csv"));
    std::fs::create_dir_all(&out)?;

    chaotic_pendulum(&out, repeats, &scipy)?;
    regular_pendulum(&out, repeats)?;
    let pendulum = SEED_3;
    let start = pendulum.assembled(1.0, 2.0);
    let taylor_pendulum = TaylorConstrainedPendulum {
        m: pendulum.m,
        l: pendulum.l,
        g: pendulum.g,
    };
    constrained(
        ("seed example 3", "seed_3"),
        (&out, repeats),
        (&pendulum, Some(&taylor_pendulum)),
        start,
        10.0,
    )?;
    if options.get_flag("taylor") {
        return Ok(());
    }
    let crank = SLIDER_CRANK;
    let start = crank.assembled(0.0, CRANK_SPEED);
    constrained(
        ("slider-crank", "slider_crank"),
        (&out, repeats),
        (&crank, None::<&TaylorConstrainedPendulum>),
        start,
        2.0,
    )?;
    energy_drift(&out)?;
    stiff_joint(&out)?;
    sensitivity(&out)?;
    singular_mass_matrix();
    Ok(())
}

/// A progress bar over `total` items.
fn progress(title: &str, total: usize) -> ProgressBar {
    let bar = ProgressBar::new(total as u64);
    let style = ProgressStyle::with_template("{prefix:>16} [{bar:40}] {pos}/{len} {msg}")
        .unwrap_or_else(|_| ProgressStyle::default_bar());
    bar.set_style(style.progress_chars("=> "));
    bar.set_prefix(title.to_owned());
    bar
}

/// Measures every run of `runs`, showing progress, and keeps the points that
/// succeed (a failing setting — a step too large — is reported and skipped).
fn sweep<const NQ: usize>(
    title: &str,
    repeats: usize,
    runs: Vec<(String, f64, Run<'_, NQ>)>,
    judge: &dyn Fn(&State<NQ, NQ>) -> Accuracy,
) -> Vec<WorkPoint> {
    let bar = progress(title, runs.len());
    let mut points = Vec::with_capacity(runs.len());
    for (method, setting, run) in runs {
        bar.set_message(format!("{method} at {setting:e}"));
        match measure(&method, setting, repeats, thread_time, run, judge) {
            Ok(point) => points.push(point),
            Err(error) => bar.println(format!("{method} at {setting:e} failed: {error}")),
        }
        bar.inc(1);
    }
    bar.finish_with_message("done");
    points
}

/// A fixed-step method of the sweeps.
#[derive(Clone, Copy)]
enum FixedStep {
    Rk4,
    Gauss(GaussLegendre),
    Sdirk,
}

impl FixedStep {
    /// Its name in charts.
    fn name(self) -> &'static str {
        match self {
            Self::Rk4 => "RK4",
            Self::Gauss(GaussLegendre::Midpoint) => "implicit midpoint",
            Self::Gauss(GaussLegendre::Order4) => "Gauss 4",
            Self::Gauss(GaussLegendre::Order6) => "Gauss 6",
            Self::Sdirk => "SDIRK 3",
        }
    }

    /// Integrates `dynamics` from `start` to `t_end` in steps of about `h`.
    fn run<E: Dynamics<NQ, NQ>, const NQ: usize>(
        self,
        dynamics: &E,
        start: State<NQ, NQ>,
        t_end: f64,
        h: f64,
    ) -> Result<Solution<NQ, NQ>, IntegrationError<NQ>> {
        let steps = ((t_end - start.t) / h).round().max(1.0) as u64;
        match self {
            Self::Rk4 => {
                integrate::Integration::new(dynamics, start, t_end, integrate::Rk4 { steps }).run()
            }
            Self::Gauss(method) => integrate::Integration::new(
                dynamics,
                start,
                t_end,
                integrate::Gauss {
                    rule: method,
                    steps,
                },
            )
            .run(),
            Self::Sdirk => {
                integrate::Integration::new(dynamics, start, t_end, integrate::Sdirk { steps })
                    .run()
            }
        }
    }
}

/// The runs of `pairs` over `tolerances` and of `methods` over `steps`, each
/// name suffixed by `label`.
fn runs<'a, E: Dynamics<NQ, NQ>, const NQ: usize>(
    label: &str,
    dynamics: &'a E,
    (start, t_end): (State<NQ, NQ>, f64),
    pairs: &[(ExplicitPair, &[f64])],
    methods: &[(FixedStep, &[f64])],
) -> Vec<(String, f64, Run<'a, NQ>)> {
    let mut runs: Vec<(String, f64, Run<'a, NQ>)> = Vec::new();
    for &(pair, tolerances) in pairs {
        let name = match pair {
            ExplicitPair::DormandPrince54 => "DOPRI5",
            ExplicitPair::Dop853 => "DOP853",
        };
        for &tolerance in tolerances {
            let options = AdaptiveOptions::with_tolerance(tolerance);
            let run = move || {
                integrate::Integration::new(
                    dynamics,
                    start,
                    t_end,
                    integrate::Adaptive { pair, options },
                )
                .run()
            };
            runs.push((format!("{name}{label}"), tolerance, Box::new(run)));
        }
    }
    for &(method, steps) in methods {
        for &h in steps {
            let run = move || method.run(dynamics, start, t_end, h);
            runs.push((format!("{}{label}", method.name()), h, Box::new(run)));
        }
    }
    runs
}

/// The runs of the Taylor integrator over `tolerances`, its name suffixed
/// by `label`.
fn taylor_runs<'a, E: integrate::TaylorDynamics<NQ, NQ>, const NQ: usize>(
    label: &str,
    dynamics: &'a E,
    (start, t_end): (State<NQ, NQ>, f64),
    tolerances: &[f64],
) -> Vec<(String, f64, Run<'a, NQ>)> {
    tolerances
        .iter()
        .map(|&tolerance| {
            let options = integrate::Taylor::with_tolerance(tolerance);
            let run = move || integrate::Integration::new(dynamics, start, t_end, options).run();
            (
                format!("Taylor{label}"),
                tolerance,
                Box::new(run) as Run<'a, NQ>,
            )
        })
        .collect()
}

/// Seed example 1 at 0.2 rad to t = 10 s, a regular motion: DOPRI5, DOP853
/// and Taylor against the Taylor integrator at 1e-20 (checked against
/// DOP853 at 1e-16), and the ratio of DOP853's time to Taylor's at
/// [`TAYLOR_COMPARISON_ERROR`].
fn regular_pendulum(out: &Path, repeats: usize) -> Result<(), Box<dyn Error>> {
    let pendulum = TaylorDoublePendulum {
        m: 1.0,
        L: 1.0,
        g: 9.81,
    };
    let dynamics = Unconstrained::without_inputs(&pendulum);
    let start = State {
        t: 0.0,
        q: [0.2, 0.2],
        v: [0.0, 0.0],
    };
    let t_end = 10.0;
    let tight = integrate::Taylor::with_tolerance(1e-20);
    let reference = integrate::Integration::new(&dynamics, start, t_end, tight)
        .run()?
        .end;
    let check =
        integrate::Integration::new(&dynamics, start, t_end, integrate::Adaptive::dop853(1e-16))
            .run()?;
    println!(
        "seed example 1 at 0.2 rad: reference (Taylor 1e-20) vs DOP853 1e-16: {:.2e}",
        state_error(&check.end, &reference)
    );
    let initial_energy = energy(&pendulum, &start.q, &start.v);
    let judge = |end: &State<2, 2>| Accuracy {
        error: state_error(end, &reference),
        energy_error: ((energy(&pendulum, &end.q, &end.v) - initial_energy) / initial_energy).abs(),
        drift: 0.0,
    };
    let mut all = runs(
        "",
        &dynamics,
        (start, t_end),
        &[
            (ExplicitPair::DormandPrince54, &decades(6, 13)),
            (ExplicitPair::Dop853, &decades(6, 16)),
        ],
        &[],
    );
    all.extend(taylor_runs("", &dynamics, (start, t_end), &decades(6, 17)));
    let points = sweep("0.2 rad", repeats, all, &judge);
    write_work_precision(
        out,
        "regular_pendulum",
        "Seed example 1 at 0.2 rad (regular) to t = 10 s",
        &points,
        &[],
    )?;
    let error = TAYLOR_COMPARISON_ERROR;
    match (
        seconds_at_error(&points, "DOP853", error),
        seconds_at_error(&points, "Taylor", error),
    ) {
        (Some(dop853), Some(taylor)) => println!(
            "at final-state error {error:e} (0.2 rad): DOP853 {:.1} µs, Taylor {:.1} µs: {:.2}× fewer seconds",
            dop853 * 1e6,
            taylor * 1e6,
            dop853 / taylor
        ),
        _ => println!("DOP853 or Taylor does not bracket the error {error:e}"),
    }
    Ok(())
}

/// Tolerances `10⁻ᵃ … 10⁻ᵇ`, a decade apart.
fn decades(from: i32, to: i32) -> Vec<f64> {
    (from..=to).map(|k| 10f64.powi(-k)).collect()
}

/// Writes `points` as `DIR/wp_NAME.csv` and their chart as `DIR/wp_NAME.svg`.
fn write_work_precision(
    out: &Path,
    name: &str,
    title: &str,
    points: &[WorkPoint],
    extra: &[Series<'_>],
) -> Result<(), Box<dyn Error>> {
    std::fs::write(out.join(format!("wp_{name}.csv")), to_csv(points))?;
    let chart = out.join(format!("wp_{name}.svg"));
    work_precision_chart(&chart, title, points, extra)?;
    println!("wrote {}", chart.display());
    Ok(())
}

/// Seed example 1 from the chaotic reference: every method against the
/// 25-digit final state, with SciPy's DOP853 and the chaotic limit.
fn chaotic_pendulum(out: &Path, repeats: usize, scipy: &Path) -> Result<(), Box<dyn Error>> {
    let reference = chaotic_reference()?;
    let dynamics = Unconstrained::without_inputs(&CHAOTIC);
    let initial_energy = energy(&CHAOTIC, &CHAOTIC_START.q, &CHAOTIC_START.v);
    let judge = |end: &State<2, 2>| Accuracy {
        error: state_error(end, &reference),
        energy_error: ((energy(&CHAOTIC, &end.q, &end.v) - initial_energy) / initial_energy).abs(),
        drift: 0.0,
    };
    let tightest = integrate::Integration::new(
        &dynamics,
        CHAOTIC_START,
        CHAOTIC_END,
        integrate::Adaptive::dop853(1e-15),
    )
    .run()?;
    println!(
        "seed example 1: DOP853 at 1e-15 is {:.2e} from the 25-digit reference (chaotic limit ≈ {CHAOTIC_LIMIT:.1e})",
        state_error(&tightest.end, &reference)
    );
    let steps_rk4 = [1e-2, 5e-3, 2e-3, 1e-3, 5e-4, 2e-4, 1e-4];
    let steps_implicit = [2e-2, 1e-2, 5e-3, 2e-3, 1e-3, 5e-4];
    let steps_sdirk = [5e-3, 2e-3, 1e-3, 5e-4, 2e-4, 1e-4];
    let runs = runs(
        "",
        &dynamics,
        (CHAOTIC_START, CHAOTIC_END),
        &[
            (ExplicitPair::DormandPrince54, &decades(4, 14)),
            (ExplicitPair::Dop853, &decades(4, 15)),
        ],
        &[
            (FixedStep::Rk4, &steps_rk4),
            (FixedStep::Gauss(GaussLegendre::Order4), &steps_implicit),
            (FixedStep::Gauss(GaussLegendre::Order6), &steps_implicit),
            (FixedStep::Sdirk, &steps_sdirk),
        ],
    );
    let taylor_system = TaylorDoublePendulum {
        m: CHAOTIC.m,
        L: CHAOTIC.L,
        g: CHAOTIC.g,
    };
    let taylor_dynamics = Unconstrained::without_inputs(&taylor_system);
    let mut runs = runs;
    runs.extend(taylor_runs(
        "",
        &taylor_dynamics,
        (CHAOTIC_START, CHAOTIC_END),
        &decades(6, 16),
    ));
    let points = sweep("seed example 1", repeats, runs, &judge);
    let scipy_points = read_scipy(scipy);
    let scipy_line: Vec<(f64, f64)> = scipy_points
        .iter()
        .map(|p| (p.seconds, p.accuracy.error))
        .collect();
    let (fastest, slowest) = points
        .iter()
        .chain(&scipy_points)
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), p| {
            (lo.min(p.seconds), hi.max(p.seconds))
        });
    let limit = [(fastest, CHAOTIC_LIMIT), (slowest, CHAOTIC_LIMIT)];
    let mut extra = vec![Series {
        name: "chaotic limit of double precision (≈ 3e-8)",
        points: &limit,
    }];
    if !scipy_line.is_empty() {
        extra.push(Series {
            name: "SciPy solve_ivp DOP853 (lambdify, cse)",
            points: &scipy_line,
        });
    }
    write_work_precision(
        out,
        "seed_1",
        "Seed example 1, chaotic double pendulum to t = 10 s",
        &points,
        &extra,
    )?;
    report_comparison(&points, &scipy_points);
    Ok(())
}

/// Prints the time of our DOP853 and SciPy's at [`COMPARISON_ERROR`].
fn report_comparison(points: &[WorkPoint], scipy: &[WorkPoint]) {
    let ours = seconds_at_error(points, "DOP853", COMPARISON_ERROR);
    let theirs = seconds_at_error(scipy, "SciPy DOP853", COMPARISON_ERROR);
    match (ours, theirs) {
        (Some(ours), Some(theirs)) => println!(
            "at final-state error {COMPARISON_ERROR:e}: our DOP853 {:.3} ms, SciPy's {:.1} ms: {:.0}× faster",
            ours * 1e3,
            theirs * 1e3,
            theirs / ours
        ),
        (Some(ours), None) => println!(
            "at final-state error {COMPARISON_ERROR:e}: our DOP853 {:.3} ms (no SciPy figures: run scripts/scipy_baseline.sh)",
            ours * 1e3
        ),
        _ => println!("our DOP853 does not bracket the error {COMPARISON_ERROR:e}"),
    }
}

/// The SciPy points of `scripts/scipy_baseline.py`'s CSV (its columns
/// `method,rtol,seconds,rhs_evaluations,error`), or none if it is absent.
fn read_scipy(path: &Path) -> Vec<WorkPoint> {
    let Ok(text) = std::fs::read_to_string(path) else {
        return Vec::new();
    };
    text.lines()
        .skip(1)
        .filter_map(|line| {
            let fields: Vec<&str> = line.split(',').collect();
            let [_, setting, seconds, evaluations, error] = fields[..] else {
                return None;
            };
            Some(WorkPoint {
                method: "SciPy DOP853".to_owned(),
                setting: setting.parse().ok()?,
                seconds: seconds.parse().ok()?,
                rhs_evaluations: evaluations.parse().ok()?,
                accuracy: Accuracy {
                    error: error.parse().ok()?,
                    ..Accuracy::default()
                },
            })
        })
        .collect()
}

/// A constrained system: a reference by DOP853 at 1e-14 with projection,
/// checked against Gauss 6 with projection, then RK4 and DOP853 without
/// stabilisation, with Baumgarte's and with projection, and Gauss 6 with
/// projection.
fn constrained<S, T>(
    (title, name): (&str, &str),
    (out, repeats): (&Path, usize),
    (system, taylor): (&S, Option<&T>),
    start: State<3, 3>,
    t_end: f64,
) -> Result<(), Box<dyn Error>>
where
    S: ConstrainedSystem<3, 3, 1, 2>,
    T: ConstrainedSystem<3, 3, 1, 2> + TaylorSystem<3, 3, 1>,
{
    let inputs = |_: f64, _: &[f64; 3], _: &[f64; 3]| [0.0];
    let gain = 10.0;
    let modes = [
        ("", Stabilisation::None),
        (
            ", Baumgarte",
            Stabilisation::Baumgarte {
                alpha: gain,
                beta: gain,
            },
        ),
        (", projection", PROJECTION),
    ];
    // Unwatched: the drift of the unstabilised runs is part of what is charted.
    let dynamics = modes.map(|(_, mode)| {
        Constrained::new(system, inputs, mode).with_drift_limits(DriftLimits::UNWATCHED)
    });
    let projected = &dynamics[2];
    let tight = AdaptiveOptions::with_tolerance(1e-14);
    let reference = integrate::Integration::new(
        projected,
        start,
        t_end,
        integrate::Adaptive {
            pair: ExplicitPair::Dop853,
            options: tight,
        },
    )
    .run()?
    .end;
    let check = FixedStep::Gauss(GaussLegendre::Order6).run(projected, start, t_end, 1e-3)?;
    println!(
        "{title}: reference (DOP853 1e-14, projection) vs Gauss 6 h = 1e-3: {:.2e}",
        state_error(&check.end, &reference)
    );
    let initial_energy = energy(system, &start.q, &start.v);
    let judge = |end: &State<3, 3>| Accuracy {
        error: state_error(end, &reference),
        energy_error: ((energy(system, &end.q, &end.v) - initial_energy) / initial_energy).abs(),
        drift: constraint_drift(system, end),
    };
    let steps = [1e-2, 5e-3, 2e-3, 1e-3, 5e-4, 2e-4];
    let tolerances = decades(4, 13);
    let mut all = Vec::new();
    for ((label, _), dynamics) in modes.iter().zip(&dynamics) {
        let mut methods = vec![(FixedStep::Rk4, &steps[..])];
        if !label.is_empty() && label.contains("projection") {
            methods.push((FixedStep::Gauss(GaussLegendre::Order6), &steps[..]));
        }
        all.extend(runs(
            label,
            dynamics,
            (start, t_end),
            &[(ExplicitPair::Dop853, &tolerances)],
            &methods,
        ));
    }
    let taylor_modes = taylor.map(|taylor| {
        [modes[0], modes[2]].map(|(label, mode)| {
            let dynamics = Constrained::new(taylor, inputs, mode);
            (label, dynamics.with_drift_limits(DriftLimits::UNWATCHED))
        })
    });
    for (label, dynamics) in taylor_modes.iter().flatten() {
        all.extend(taylor_runs(
            label,
            dynamics,
            (start, t_end),
            &decades(6, 16),
        ));
    }
    let points = sweep(title, repeats, all, &judge);
    let chart_title = format!("{title} to t = {t_end} s: none / Baumgarte / projection");
    write_work_precision(out, name, &chart_title, &points, &[])
}

/// Relative energy error `|E(t) − E(0)| / |E(0)|` of the chaotic pendulum,
/// its largest value in each `window` seconds, over `horizon` seconds.
fn energy_history(
    horizon: f64,
    window: f64,
    integrate: impl FnOnce(&mut dyn FnMut(&State<2, 2>)) -> Result<(), IntegrationError<2>>,
) -> Result<Vec<(f64, f64)>, IntegrationError<2>> {
    let initial = energy(&CHAOTIC, &CHAOTIC_START.q, &CHAOTIC_START.v);
    let mut history = Vec::with_capacity((horizon / window) as usize + 1);
    let mut worst = 0.0f64;
    let mut window_end = window;
    let mut observe = |s: &State<2, 2>| {
        let error = ((energy(&CHAOTIC, &s.q, &s.v) - initial) / initial).abs();
        worst = worst.max(error);
        if s.t >= window_end {
            history.push((s.t, worst));
            worst = 0.0;
            window_end += window;
        }
    };
    integrate(&mut observe)?;
    Ok(history)
}

/// The long-time energy behaviour of RK4, DOP853 and Gauss 4 on the chaotic
/// pendulum over 10⁴ s, charted as `energy_drift.svg`.
fn energy_drift(out: &Path) -> Result<(), Box<dyn Error>> {
    const HORIZON: f64 = 1e4;
    let dynamics = Unconstrained::without_inputs(&CHAOTIC);
    let bar = progress("energy, 10⁴ s", 3);
    let rk4 = energy_history(HORIZON, 10.0, |observe| {
        integrate::Integration::new(
            &dynamics,
            CHAOTIC_START,
            CHAOTIC_START.t + 1e4,
            integrate::Rk4 { steps: 2_000_000 },
        )
        .observe(observe)
        .run()
        .map(drop)
    })?;
    bar.inc(1);
    let dop853 = energy_history(HORIZON, 10.0, |observe| {
        let options = AdaptiveOptions::with_tolerance(1e-8);
        integrate::Integration::new(
            &dynamics,
            CHAOTIC_START,
            HORIZON,
            integrate::Adaptive {
                pair: ExplicitPair::Dop853,
                options,
            },
        )
        .observe(observe)
        .run()
        .map(drop)
    })?;
    bar.inc(1);
    let gauss = energy_history(HORIZON, 10.0, |observe| {
        integrate::Integration::new(
            &dynamics,
            CHAOTIC_START,
            CHAOTIC_START.t + 1e4,
            integrate::Gauss {
                rule: GaussLegendre::Order4,
                steps: 1_000_000,
            },
        )
        .observe(observe)
        .run()
        .map(drop)
    })?;
    bar.finish();
    let series = [
        Series {
            name: "RK4, h = 5 ms",
            points: &rk4,
        },
        Series {
            name: "DOP853, tolerance 1e-8",
            points: &dop853,
        },
        Series {
            name: "Gauss 4 (symmetric), h = 10 ms",
            points: &gauss,
        },
    ];
    for line in &series {
        let first_tenth = line
            .points
            .iter()
            .take(line.points.len() / 10)
            .fold(0.0f64, |m, p| m.max(p.1));
        let all = line.points.iter().fold(0.0f64, |m, p| m.max(p.1));
        println!(
            "{}: max |ΔE|/E over the first 10³ s {first_tenth:.2e}, over 10⁴ s {all:.2e}",
            line.name
        );
    }
    let path = out.join("energy_drift.svg");
    line_chart_log_y(
        &path,
        "Chaotic double pendulum over 10⁴ s: energy error (largest per 10 s)",
        "time [s]",
        "|E(t) − E(0)| / |E(0)|",
        &series,
    )?;
    println!("wrote {}", path.display());
    Ok(())
}

/// The stiff joint (`k = 10⁶`) over 1 s: RK4 just above its stability limit,
/// DOP853 forced to tiny steps, the L-stable SDIRK at large steps; charted as
/// `stiff_joint.svg` (the spring's stretch `|θ₂ − θ₁|`).
fn stiff_joint(out: &Path) -> Result<(), Box<dyn Error>> {
    const DURATION: f64 = 1.0;
    let dynamics = Unconstrained::without_inputs(&STIFF);
    let stretch = |s: &State<2, 2>| (s.t, (s.q[1] - s.q[0]).abs());
    let mut rk4 = Vec::new();
    let rk4_end = integrate::Integration::new(
        &dynamics,
        STIFF_START,
        STIFF_START.t + 1.0,
        integrate::Rk4 { steps: 500 },
    )
    .observe(|s| rk4.push(stretch(s)))
    .run();
    let mut dop853 = Vec::new();
    let options = AdaptiveOptions::with_tolerance(1e-6);
    let explicit = integrate::Integration::new(
        &dynamics,
        STIFF_START,
        DURATION,
        integrate::Adaptive {
            pair: ExplicitPair::Dop853,
            options,
        },
    )
    .observe(|s| dop853.push(stretch(s)))
    .run()?;
    let mut sdirk = Vec::new();
    let implicit = integrate::Integration::new(
        &dynamics,
        STIFF_START,
        STIFF_START.t + 1.0,
        integrate::Sdirk { steps: 100 },
    )
    .observe(|s| sdirk.push(stretch(s)))
    .run()?;
    match rk4_end {
        Ok(end) => println!(
            "stiff joint: RK4 at h = 2 ms ends at stretch {:.3e}",
            (end.end.q[1] - end.end.q[0]).abs()
        ),
        Err(error) => println!("stiff joint: RK4 at h = 2 ms fails: {error}"),
    }
    println!(
        "stiff joint: DOP853 at 1e-6 takes {} steps ({} rejected, {} evaluations); SDIRK at h = 10 ms takes {} steps ({} evaluations); they end {:.2e} apart",
        explicit.statistics.accepted_steps,
        explicit.statistics.rejected_steps,
        explicit.statistics.rhs_evaluations,
        implicit.statistics.accepted_steps,
        implicit.statistics.rhs_evaluations,
        state_error(&explicit.end, &implicit.end),
    );
    let path = out.join("stiff_joint.svg");
    line_chart_log_y(
        &path,
        "Stiff joint (k = 1e6): spring stretch |θ₂ − θ₁|",
        "time [s]",
        "|θ₂ − θ₁| [rad]",
        &[
            Series {
                name: "RK4, h = 2 ms (unstable)",
                points: &rk4,
            },
            Series {
                name: "DOP853, tolerance 1e-6",
                points: &dop853,
            },
            Series {
                name: "SDIRK 3 (L-stable), h = 10 ms",
                points: &sdirk,
            },
        ],
    )?;
    println!("wrote {}", path.display());
    Ok(())
}

/// Two chaotic trajectories 1e-10 rad apart: their separation over 30 s,
/// charted as `separation.svg`.
fn sensitivity(out: &Path) -> Result<(), Box<dyn Error>> {
    let dynamics = Unconstrained::without_inputs(&CHAOTIC);
    let mut nudged = CHAOTIC_START;
    nudged.q[0] += 1e-10;
    let (h, steps) = (1e-3, 30_000);
    let mut first = Vec::with_capacity(steps + 1);
    integrate::Integration::new(
        &dynamics,
        CHAOTIC_START,
        CHAOTIC_START.t + steps as f64 * h,
        integrate::Gauss {
            rule: GaussLegendre::Order6,
            steps: steps as u64,
        },
    )
    .observe(|s| first.push(*s))
    .run()?;
    let mut separation = Vec::with_capacity(steps + 1);
    let mut index = 0;
    integrate::Integration::new(
        &dynamics,
        nudged,
        nudged.t + steps as f64 * h,
        integrate::Gauss {
            rule: GaussLegendre::Order6,
            steps: steps as u64,
        },
    )
    .observe(|s| {
        separation.push((s.t, state_error(s, &first[index])));
        index += 1;
    })
    .run()?;
    if let Some((t, _)) = separation.iter().find(|(_, d)| *d > 1e-3) {
        println!("sensitivity: trajectories 1e-10 apart separate beyond 1e-3 at t = {t:.2} s");
    }
    let path = out.join("separation.svg");
    line_chart_log_y(
        &path,
        "Chaotic double pendulum: two starts 1e-10 rad apart",
        "time [s]",
        "max |Δq|, |Δq̇|",
        &[Series {
            name: "separation (Gauss 6, h = 1 ms)",
            points: &separation,
        }],
    )?;
    println!("wrote {}", path.display());
    Ok(())
}

/// Seed example 2 with `d = 0` reaching its singular configuration: prints
/// how RK4, DOP853 and SDIRK stop there.
fn singular_mass_matrix() {
    let dynamics = Unconstrained::without_inputs(&ON_AXIS);
    let options = AdaptiveOptions::with_tolerance(1e-8);
    let outcomes = [
        (
            "RK4",
            integrate::Integration::new(
                &dynamics,
                TOWARDS_AXIS,
                TOWARDS_AXIS.t + 1.0,
                integrate::Rk4 { steps: 8 },
            )
            .run(),
        ),
        (
            "DOP853",
            integrate::Integration::new(
                &dynamics,
                TOWARDS_AXIS,
                0.5,
                integrate::Adaptive {
                    pair: ExplicitPair::Dop853,
                    options,
                },
            )
            .run(),
        ),
        (
            "SDIRK",
            integrate::Integration::new(
                &dynamics,
                TOWARDS_AXIS,
                TOWARDS_AXIS.t + 1.0,
                integrate::Sdirk { steps: 8 },
            )
            .run(),
        ),
    ];
    for (name, outcome) in outcomes {
        match outcome {
            Ok(solution) => println!("singular mass matrix: {name} passed it: {:?}", solution.end),
            Err(error) => println!("singular mass matrix: {name} stops: {error}"),
        }
    }
}
