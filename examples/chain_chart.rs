//! Charts of the chain benchmarks: nanoseconds per call against
//! the number of links, log scale, for every tool, one SVG per family.
//!
//! Reads `docs/charts/chains.csv` (written by `benches/chains_table.py`
//! from the criterion medians and the peer harness) and writes
//! `docs/charts/chains_planar.svg` and `docs/charts/chains_spatial.svg`.
//!
//! Run with `cargo run --example chain_chart`.

use std::collections::BTreeMap;
use std::error::Error;
use std::path::Path;

use dalembert_lab::{Series, line_chart_log_y};

/// Points `(n, ns per call)` per tool, in the CSV's order of tools.
type Tools = Vec<(String, Vec<(f64, f64)>)>;

fn main() -> Result<(), Box<dyn Error>> {
    let text = std::fs::read_to_string("docs/charts/chains.csv")?;
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
        let path = format!("docs/charts/chains_{family}.svg");
        line_chart_log_y(
            Path::new(&path),
            &format!("{family} chains: time per call (lower is better)"),
            "number of links n",
            "ns per call",
            &series,
        )?;
        println!("wrote {path}");
    }
    Ok(())
}
