//! SVG line charts of trajectories and error histories.

use std::cmp::Ordering;
use std::fmt;
use std::ops::Range;
use std::path::{Path, PathBuf};

use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};
use plotters::prelude::*;

/// Width and height of a chart, in pixels.
const SIZE: (u32, u32) = (960, 600);
/// Fraction of the data range added as a margin above and below on the y axis.
const Y_PADDING: f64 = 0.05;
/// A data range narrower than this fraction of its magnitude is drawn as if
/// constant.
const DEGENERATE_WIDTH: f64 = 1e-12;

/// One named line of a chart.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Series<'a> {
    /// Name shown in the legend.
    pub name: &'a str,
    /// Points `(x, y)`, drawn in order.
    pub points: &'a [(f64, f64)],
}

/// A chart could not be drawn or written.
#[derive(Debug)]
pub struct ChartError {
    path: PathBuf,
    message: String,
}

impl fmt::Display for ChartError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "cannot draw the chart {}: {}",
            self.path.display(),
            self.message
        )
    }
}

impl std::error::Error for ChartError {}

/// Writes an SVG line chart of `series` to `path`, with linear axes.
///
/// Each series gets its own colour and a legend entry. Points with a
/// non-finite coordinate are left out. The axes span the data, the y axis
/// with a margin; a constant series is shown in a range of half its value
/// (at least `0.5`) on each side.
pub fn line_chart(
    path: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series<'_>],
) -> Result<(), ChartError> {
    let drawable = |&(x, y): &(f64, f64)| x.is_finite() && y.is_finite();
    let (x_range, y_range) = data_ranges(series, drawable);
    let x_range = widen_degenerate(x_range, linear_half_width);
    let y_range = pad(widen_degenerate(y_range, linear_half_width), Y_PADDING);
    let labels = Labels {
        title,
        x: x_label,
        y: y_label,
    };
    draw(
        path,
        labels,
        series,
        drawable,
        (x_range, y_range),
        Formats::default(),
    )
}

/// Like [`line_chart`], with a logarithmic y axis (for errors and energy
/// drift spanning decades).
///
/// Points with `y ≤ 0` cannot be shown on a log axis and are left out, as are
/// non-finite ones. A constant series is shown in a range of a decade on each
/// side.
pub fn line_chart_log_y(
    path: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series<'_>],
) -> Result<(), ChartError> {
    let drawable = |&(x, y): &(f64, f64)| x.is_finite() && y.is_finite() && y > 0.0;
    let (x_range, y_range) = data_ranges(series, drawable);
    let x_range = widen_degenerate(x_range, linear_half_width);
    let labels = Labels {
        title,
        x: x_label,
        y: y_label,
    };
    let formats = Formats {
        y: Some(&powers_of_ten),
        ..Formats::default()
    };
    draw(
        path,
        labels,
        series,
        drawable,
        (x_range, log_range(y_range)),
        formats,
    )
}

/// Like [`line_chart`], with both axes logarithmic (work-precision
/// diagrams: error against time), the legend in the lower left corner.
///
/// Points with `x ≤ 0` or `y ≤ 0` are left out, as are non-finite ones. A
/// constant coordinate is shown in a range of a decade on each side.
pub fn line_chart_log_log(
    path: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series<'_>],
) -> Result<(), ChartError> {
    let drawable = |&(x, y): &(f64, f64)| x.is_finite() && y.is_finite() && x > 0.0 && y > 0.0;
    let (x_range, y_range) = data_ranges(series, drawable);
    let labels = Labels {
        title,
        x: x_label,
        y: y_label,
    };
    // Fast and accurate is the empty corner of an error-against-cost chart.
    let formats = Formats {
        x: Some(&powers_of_ten),
        y: Some(&powers_of_ten),
        legend: SeriesLabelPosition::LowerLeft,
    };
    let ranges = (log_range(x_range), log_range(y_range));
    draw(path, labels, series, drawable, ranges, formats)
}

/// A log-scaled axis over the positive `range`, padded and widened to a
/// decade each side if degenerate.
fn log_range(
    range: Range<f64>,
) -> impl AsRangedCoord<Value = f64, CoordDescType: ValueFormatter<f64>> {
    let decades = range.start.log10()..range.end.log10();
    let decades = pad(widen_degenerate(decades, |_| 1.0), Y_PADDING);
    (10f64.powf(decades.start)..10f64.powf(decades.end)).log_scale()
}

/// A tick label of a log axis: `1e-6`.
fn powers_of_ten(value: &f64) -> String {
    format!("{value:.0e}")
}

/// Tick label formats of the two axes (plotters' own where `None`) and the
/// corner of the legend.
struct Formats<'a> {
    x: Option<&'a dyn Fn(&f64) -> String>,
    y: Option<&'a dyn Fn(&f64) -> String>,
    legend: SeriesLabelPosition,
}

impl Default for Formats<'_> {
    fn default() -> Self {
        Self {
            x: None,
            y: None,
            legend: SeriesLabelPosition::UpperRight,
        }
    }
}

/// The texts of a chart.
struct Labels<'a> {
    title: &'a str,
    x: &'a str,
    y: &'a str,
}

/// Draws the chart over the axes `(x_range, y_range)` with the tick labels
/// `formats`.
fn draw<X, Y>(
    path: &Path,
    labels: Labels<'_>,
    series: &[Series<'_>],
    drawable: impl Fn(&(f64, f64)) -> bool + Copy,
    (x_range, y_range): (X, Y),
    formats: Formats<'_>,
) -> Result<(), ChartError>
where
    X: AsRangedCoord<Value = f64>,
    X::CoordDescType: ValueFormatter<f64>,
    Y: AsRangedCoord<Value = f64>,
    Y::CoordDescType: ValueFormatter<f64>,
{
    let failed = |error: &dyn std::error::Error| ChartError {
        path: path.to_owned(),
        message: error.to_string(),
    };
    let root = SVGBackend::new(path, SIZE).into_drawing_area();
    root.fill(&WHITE).map_err(|e| failed(&e))?;
    let mut chart = ChartBuilder::on(&root)
        .caption(labels.title, ("sans-serif", 24))
        .margin(16)
        .x_label_area_size(48)
        .y_label_area_size(80)
        .build_cartesian_2d(x_range, y_range)
        .map_err(|e| failed(&e))?;
    let mut mesh = chart.configure_mesh();
    mesh.x_desc(labels.x).y_desc(labels.y);
    if let Some(format) = formats.x {
        mesh.x_label_formatter(format);
    }
    if let Some(format) = formats.y {
        mesh.y_label_formatter(format);
    }
    mesh.draw().map_err(|e| failed(&e))?;
    for (index, line) in series.iter().enumerate() {
        let style = Palette99::pick(index).stroke_width(2);
        let points = line.points.iter().copied().filter(drawable);
        chart
            .draw_series(LineSeries::new(points, style))
            .map_err(|e| failed(&e))?
            .label(line.name)
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], style));
    }
    chart
        .configure_series_labels()
        .position(formats.legend)
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()
        .map_err(|e| failed(&e))?;
    root.present().map_err(|e| failed(&e))
}

/// The x and y ranges of the drawable points; empty (`start > end`) when
/// there are none.
fn data_ranges(
    series: &[Series<'_>],
    drawable: impl Fn(&(f64, f64)) -> bool,
) -> (Range<f64>, Range<f64>) {
    let empty = (
        f64::INFINITY..f64::NEG_INFINITY,
        f64::INFINITY..f64::NEG_INFINITY,
    );
    series
        .iter()
        .flat_map(|line| line.points.iter())
        .filter(|p| drawable(p))
        .fold(empty, |(x, y), &(px, py)| {
            (
                x.start.min(px)..x.end.max(px),
                y.start.min(py)..y.end.max(py),
            )
        })
}

/// `range` if it has a drawable width; otherwise a range around its value
/// (around 0 when it is empty) reaching `half_width(value)` on each side.
fn widen_degenerate(range: Range<f64>, half_width: impl Fn(f64) -> f64) -> Range<f64> {
    let magnitude = range.start.abs().max(range.end.abs());
    let centre = match range.start.partial_cmp(&range.end) {
        None | Some(Ordering::Greater) => 0.0,
        _ if range.end - range.start > DEGENERATE_WIDTH * magnitude => return range,
        _ => 0.5 * (range.start + range.end),
    };
    let half = half_width(centre);
    centre - half..centre + half
}

/// Half the width of the range shown for a constant linear series.
fn linear_half_width(value: f64) -> f64 {
    0.5 * value.abs().max(1.0)
}

/// `range` widened by `fraction` of its length on both ends, unless that
/// overflows.
fn pad(range: Range<f64>, fraction: f64) -> Range<f64> {
    let margin = fraction * (range.end - range.start);
    let padded = range.start - margin..range.end + margin;
    if padded.start.is_finite() && padded.end.is_finite() {
        padded
    } else {
        range
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A scratch SVG path unique to this test process and `name`, removed on
    /// drop.
    struct ScratchFile(PathBuf);

    impl ScratchFile {
        fn new(name: &str) -> Self {
            let file = format!("dalembert-chart-{}-{name}.svg", std::process::id());
            Self(std::env::temp_dir().join(file))
        }

        fn contents(&self) -> String {
            std::fs::read_to_string(&self.0).unwrap()
        }
    }

    impl Drop for ScratchFile {
        fn drop(&mut self) {
            let _ = std::fs::remove_file(&self.0);
        }
    }

    fn sine_and_cosine() -> [Vec<(f64, f64)>; 2] {
        let times = (0..200).map(|i| f64::from(i) * 0.05);
        [
            times.clone().map(|t| (t, t.sin())).collect(),
            times.map(|t| (t, t.cos())).collect(),
        ]
    }

    #[test]
    fn line_chart_writes_title_axis_labels_legend_and_distinct_colours() {
        let file = ScratchFile::new("linear");
        let [sine, cosine] = sine_and_cosine();
        let series = [
            Series {
                name: "sine of t",
                points: &sine,
            },
            Series {
                name: "cosine of t",
                points: &cosine,
            },
        ];
        line_chart(&file.0, "Two waves", "time [s]", "angle [rad]", &series).unwrap();
        let svg = file.contents();
        for text in [
            "Two waves",
            "time [s]",
            "angle [rad]",
            "sine of t",
            "cosine of t",
        ] {
            assert!(svg.contains(text), "{text} missing from the SVG");
        }
        let [first, second] = [0, 1].map(|i| {
            let (r, g, b) = Palette99::pick(i).rgb();
            format!("#{r:02X}{g:02X}{b:02X}")
        });
        assert_ne!(first, second);
        assert!(
            svg.contains(&first) && svg.contains(&second),
            "series colours missing"
        );
    }

    #[test]
    fn constant_empty_and_non_finite_series_still_draw() {
        let file = ScratchFile::new("degenerate");
        let constant = [
            (0.0, 3.0),
            (1.0, 3.0),
            (f64::NAN, 1.0),
            (2.0, f64::INFINITY),
        ];
        let single_point = [(5.0, 0.0)];
        let cases: [&[Series<'_>]; 3] = [
            &[Series {
                name: "constant",
                points: &constant,
            }],
            &[Series {
                name: "one point",
                points: &single_point,
            }],
            &[Series {
                name: "nothing",
                points: &[],
            }],
        ];
        for series in cases {
            line_chart(&file.0, "Degenerate", "x", "y", series).unwrap();
            line_chart_log_y(&file.0, "Degenerate", "x", "y", series).unwrap();
            assert!(file.contents().contains(series[0].name));
        }
    }

    #[test]
    fn log_chart_labels_powers_of_ten_and_skips_non_positive_values() {
        let file = ScratchFile::new("log");
        let drift: Vec<(f64, f64)> = (0..50)
            .map(|i| (f64::from(i), 1e-12 * 10f64.powf(f64::from(i) / 7.0)))
            .chain([(50.0, 0.0), (51.0, -1.0)])
            .collect();
        let series = [Series {
            name: "energy drift",
            points: &drift,
        }];
        line_chart_log_y(&file.0, "Drift", "time [s]", "|ΔE| / E", &series).unwrap();
        let svg = file.contents();
        assert!(svg.contains("energy drift") && svg.contains("|ΔE| / E"));
        assert!(svg.contains("1e-10") && svg.contains("1e-6"), "{svg}");
    }

    #[test]
    fn log_log_chart_labels_both_axes_in_powers_of_ten() {
        let file = ScratchFile::new("log-log");
        let work: Vec<(f64, f64)> = (0..8)
            .map(|i| (1e-4 * 10f64.powi(i / 2), 1e-2 * 10f64.powi(-i)))
            .chain([(0.0, 1.0), (1.0, -1.0)])
            .collect();
        let series = [Series {
            name: "DOP853",
            points: &work,
        }];
        line_chart_log_log(&file.0, "Work", "CPU time [s]", "error", &series).unwrap();
        let svg = file.contents();
        assert!(svg.contains("DOP853") && svg.contains("CPU time [s]"));
        assert!(svg.contains("1e-3") && svg.contains("1e-8"), "{svg}");
    }

    #[test]
    fn unwritable_path_is_an_error_naming_it() {
        let path = Path::new("/nonexistent-dalembert-dir/chart.svg");
        let series = [Series {
            name: "s",
            points: &[(0.0, 1.0), (1.0, 2.0)],
        }];
        let error = line_chart(path, "t", "x", "y", &series).unwrap_err();
        assert!(
            error
                .to_string()
                .contains("/nonexistent-dalembert-dir/chart.svg"),
            "{error}"
        );
    }
}
