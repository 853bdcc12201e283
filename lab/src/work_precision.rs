//! The work-precision harness: what accuracy each integrator buys per unit
//! of time on a given system.
//!
//! A run is a closure that integrates the system once and returns its
//! [`Solution`]; [`measure`] times it (the median of several repeats on the
//! caller's clock: the thread's CPU time on a shared machine), counts its
//! right-hand-side evaluations and judges its final state against a
//! reference with a caller-supplied [`Accuracy`] function. The points of a
//! sweep go to a CSV ([`to_csv`]) and to a log-log chart of error against time
//! ([`work_precision_chart`]); [`seconds_at_error`] interpolates the time a
//! method needs for a given error, for comparisons at equal accuracy.

use std::fmt::Write as _;
use std::time::Duration;

use dalembert::{IntegrationError, Solution, State};

use crate::{ChartError, Series, line_chart_log_log};

/// How far a final state is from the truth.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Accuracy {
    /// Final-state error: the largest `|Δqᵢ|` or `|Δq̇ᵢ|` against the
    /// reference ([`state_error`]).
    pub error: f64,
    /// Relative energy error at the final time, `|E(T) − E(0)| / |E(0)|`
    /// (meaningful for conservative systems).
    pub energy_error: f64,
    /// Constraint drift at the final time (`0` for unconstrained systems).
    pub drift: f64,
}

/// One method at one setting, measured.
#[derive(Clone, Debug, PartialEq)]
pub struct WorkPoint {
    /// The method's name (one line of the chart).
    pub method: String,
    /// Its tolerance or step size.
    pub setting: f64,
    /// Median time of one integration on the caller's clock, in seconds.
    pub seconds: f64,
    /// Right-hand-side evaluations of one integration.
    pub rhs_evaluations: u64,
    /// Accuracy of the final state.
    pub accuracy: Accuracy,
}

/// The largest `|Δqᵢ|` or `|Δq̇ᵢ|` between two states.
pub fn state_error<const NQ: usize, const NV: usize>(
    state: &State<NQ, NV>,
    reference: &State<NQ, NV>,
) -> f64 {
    let coordinates = state.q.iter().zip(&reference.q);
    let speeds = state.v.iter().zip(&reference.v);
    coordinates
        .chain(speeds)
        .fold(0.0, |m, (a, b)| m.max((a - b).abs()))
}

/// Runs `run` `repeats` times (at least once) and returns its median time
/// on `clock` (any monotonic reading: the thread's CPU time, which another
/// process holding the core does not inflate, or `|| start.elapsed()` for
/// wall time), its work and the accuracy `judge` gives its final state.
///
/// Stops at the first run that fails.
pub fn measure<const NQ: usize, const NV: usize>(
    method: &str,
    setting: f64,
    repeats: usize,
    clock: impl Fn() -> Duration,
    mut run: impl FnMut() -> Result<Solution<NQ, NV>, IntegrationError<NQ>>,
    judge: impl Fn(&State<NQ, NV>) -> Accuracy,
) -> Result<WorkPoint, IntegrationError<NQ>> {
    let (first_time, solution) = timed(&clock, &mut run)?;
    let mut times = Vec::with_capacity(repeats.max(1));
    times.push(first_time);
    for _ in 1..repeats {
        times.push(timed(&clock, &mut run)?.0);
    }
    times.sort_by(f64::total_cmp);
    Ok(WorkPoint {
        method: method.to_owned(),
        setting,
        seconds: times[times.len() / 2],
        rhs_evaluations: solution.statistics.rhs_evaluations,
        accuracy: judge(&solution.end),
    })
}

/// One run of `run` and its time on `clock` in seconds.
fn timed<const NQ: usize, const NV: usize>(
    clock: &impl Fn() -> Duration,
    run: &mut impl FnMut() -> Result<Solution<NQ, NV>, IntegrationError<NQ>>,
) -> Result<(f64, Solution<NQ, NV>), IntegrationError<NQ>> {
    let start = clock();
    let solution = run()?;
    Ok(((clock() - start).as_secs_f64(), solution))
}

/// The points as CSV with a header:
/// `method,setting,seconds,rhs_evaluations,error,energy_error,drift`.
pub fn to_csv(points: &[WorkPoint]) -> String {
    let mut csv = String::from("method,setting,seconds,rhs_evaluations,error,energy_error,drift\n");
    for point in points {
        let Accuracy {
            error,
            energy_error,
            drift,
        } = point.accuracy;
        // Writing to a String cannot fail.
        let _ = writeln!(
            csv,
            "{},{:e},{:e},{},{:e},{:e},{:e}",
            point.method,
            point.setting,
            point.seconds,
            point.rhs_evaluations,
            error,
            energy_error,
            drift
        );
    }
    csv
}

/// The time `method` needs for the final-state error `error`, interpolated
/// log-log between the two of its points, in order of time, whose errors
/// bracket it; `None` if none do.
pub fn seconds_at_error(points: &[WorkPoint], method: &str, error: f64) -> Option<f64> {
    let mut line: Vec<(f64, f64)> = points
        .iter()
        .filter(|p| p.method == method && p.seconds > 0.0 && p.accuracy.error > 0.0)
        .map(|p| (p.seconds.ln(), p.accuracy.error.ln()))
        .collect();
    line.sort_by(|a, b| a.0.total_cmp(&b.0));
    let target = error.ln();
    line.windows(2).find_map(|pair| {
        let [(t0, e0), (t1, e1)] = [pair[0], pair[1]];
        let brackets = (e0 - target) * (e1 - target) <= 0.0 && e0 != e1;
        brackets.then(|| (t0 + (target - e0) / (e1 - e0) * (t1 - t0)).exp())
    })
}

/// The points of one method as `(seconds, error)`, in order of time: a line
/// of a work-precision chart.
pub fn work_line(points: &[WorkPoint], method: &str) -> Vec<(f64, f64)> {
    let mut line: Vec<(f64, f64)> = points
        .iter()
        .filter(|p| p.method == method)
        .map(|p| (p.seconds, p.accuracy.error))
        .collect();
    line.sort_by(|a, b| a.0.total_cmp(&b.0));
    line
}

/// Writes the log-log work-precision chart of `points` (final-state error
/// against median time, one line per method in order of first appearance)
/// to `path`, with `extra` lines (a baseline, a limit) after them.
pub fn work_precision_chart(
    path: &std::path::Path,
    title: &str,
    points: &[WorkPoint],
    extra: &[Series<'_>],
) -> Result<(), ChartError> {
    let mut methods: Vec<&str> = Vec::new();
    for point in points {
        if !methods.contains(&point.method.as_str()) {
            methods.push(&point.method);
        }
    }
    let lines: Vec<Vec<(f64, f64)>> = methods.iter().map(|m| work_line(points, m)).collect();
    let series: Vec<Series<'_>> = methods
        .iter()
        .zip(&lines)
        .map(|(name, points)| Series { name, points })
        .chain(extra.iter().copied())
        .collect();
    line_chart_log_log(
        path,
        title,
        "median time per integration [s]",
        "final-state error (max abs)",
        &series,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use dalembert::integrate::Statistics;

    fn point(method: &str, seconds: f64, error: f64) -> WorkPoint {
        WorkPoint {
            method: method.to_owned(),
            setting: 1e-6,
            seconds,
            rhs_evaluations: 10,
            accuracy: Accuracy {
                error,
                energy_error: 0.0,
                drift: 0.0,
            },
        }
    }

    #[test]
    fn state_error_is_the_largest_coordinate_or_speed_difference() {
        let a = State {
            t: 1.0,
            q: [1.0, 2.0],
            v: [0.0, -1.0],
        };
        let b = State {
            q: [1.5, 2.0],
            v: [0.0, 1.0],
            ..a
        };
        assert_eq!(state_error(&a, &b), 2.0);
    }

    #[test]
    fn seconds_at_error_interpolates_log_log_between_bracketing_points() {
        let points = [
            point("A", 1e-3, 1e-4),
            point("A", 1e-1, 1e-8),
            point("B", 1.0, 1e-6),
        ];
        let seconds = seconds_at_error(&points, "A", 1e-6).unwrap();
        assert!((seconds / 1e-2 - 1.0).abs() < 1e-12, "{seconds}");
        assert_eq!(seconds_at_error(&points, "A", 1e-10), None);
        assert_eq!(seconds_at_error(&points, "B", 1e-6), None);
    }

    #[test]
    fn measure_reports_the_median_time_the_work_and_the_judged_accuracy() {
        let end = State {
            t: 1.0,
            q: [0.5],
            v: [0.0],
        };
        let mut runs = 0;
        let run = || {
            runs += 1;
            Ok(Solution {
                end,
                statistics: Statistics {
                    rhs_evaluations: 42,
                    ..Statistics::default()
                },
            })
        };
        let judge = |s: &State<1, 1>| Accuracy {
            error: s.q[0],
            ..Accuracy::default()
        };
        let start = std::time::Instant::now();
        let point = measure("m", 0.1, 3, || start.elapsed(), run, judge).unwrap();
        assert_eq!(runs, 3);
        assert_eq!((point.rhs_evaluations, point.accuracy.error), (42, 0.5));
        let csv = to_csv(&[point]);
        assert!(csv.starts_with("method,setting,seconds,"), "{csv}");
        assert!(csv.lines().nth(1).unwrap().starts_with("m,1e-1,"), "{csv}");
    }
}
