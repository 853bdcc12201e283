//! Charts of the chain benchmarks against the number of links, log scale,
//! for every tool, one SVG per family.
//!
//! By default: nanoseconds per call, from `docs/charts/chains.csv` (written
//! by `benches/chains_table.py` from the criterion medians and the peer
//! harness) to `docs/charts/chains_planar.svg` and
//! `docs/charts/chains_spatial.svg`. With the argument `throughput`:
//! simulated seconds per CPU second of fixed-step RK4, from
//! `docs/charts/throughput.csv` (BENCHMARKS.md, "Simulation throughput") to
//! `docs/charts/throughput_planar.svg` and `docs/charts/throughput_spatial.svg`.
//!
//! Run with `cargo run --example chain_chart [-- throughput]`.

use std::collections::BTreeMap;
use std::error::Error;
use std::path::Path;

use dalembert_lab::{Series, line_chart_log_y};

/// Points `(n, value)` per tool, in the CSV's order of tools.
type Tools = Vec<(String, Vec<(f64, f64)>)>;

/// What one family of charts shows.
struct Measure {
    /// `docs/charts/{name}.csv` in, `docs/charts/{name}_{family}.svg` out.
    name: &'static str,
    /// The title after the family's name.
    title: &'static str,
    /// The y axis.
    unit: &'static str,
}

const TIME_PER_CALL: Measure = Measure {
    name: "chains",
    title: "time per call (lower is better)",
    unit: "ns per call",
};

const THROUGHPUT: Measure = Measure {
    name: "throughput",
    title: "RK4 at h = 1 ms, simulated time per CPU time (higher is better)",
    unit: "simulated s per CPU s",
};

fn main() -> Result<(), Box<dyn Error>> {
    let measure = match std::env::args().nth(1).as_deref() {
        None => TIME_PER_CALL,
        Some("throughput") => THROUGHPUT,
        Some(other) => return Err(format!("unknown chart {other}: expected throughput").into()),
    };
    let text = std::fs::read_to_string(format!("docs/charts/{}.csv", measure.name))?;
    let mut families: BTreeMap<String, Tools> = BTreeMap::new();
    for line in text.lines().skip(1) {
        let fields: Vec<&str> = line.split(',').collect();
        let [family, n, tool, ns] = fields[..] else {
            return Err(format!("bad line: {line}").into());
        };
        let tools = families.entry(family.to_owned()).or_default();
        let point = (n.parse()?, ns.parse()?);
        match tools.iter_mut().find(|(name, _)| name == tool) {
            Some((_, points)) => points.push(point),
            None => tools.push((tool.to_owned(), vec![point])),
        }
    }
    for (family, tools) in &families {
        let series: Vec<Series<'_>> = tools
            .iter()
            .map(|(name, points)| Series { name, points })
            .collect();
        let path = format!("docs/charts/{}_{family}.svg", measure.name);
        line_chart_log_y(
            Path::new(&path),
            &format!("{family} chains: {}", measure.title),
            "number of links n",
            measure.unit,
            &series,
        )?;
        println!("wrote {path}");
    }
    Ok(())
}
