//! `dalembert`: the equations, generated code and diagnostics of a `.dal`
//! model from the command line.
//!
//! ```text
//! dalembert eom MODEL.dal [--latex | --latex-inline | --markdown]
//!                                     the equations of motion, as in the seed document
//! dalembert generate MODEL.dal        the generated Rust source
//! dalembert check MODEL.dal [--stats] [--api] the errors the dalembert! macro would report
//!                                     (--stats: each generated function's estimated size;
//!                                     --api: the functions generated for the model)
//! dalembert chain FAMILY N [SPELLING] the .dal text of a benchmark chain (planar or spatial;
//!                                     spelled joints, symbolic or seed)
//! dalembert urdf ROBOT.urdf [--floating] [--name NAME] [--damping] [--outputs "LIST"]
//!                                     the .dal model of a URDF robot
//! dalembert mjcf MODEL.xml [--name NAME] [--outputs "LIST"]
//!                                     the .dal model of a MuJoCo model
//! ```
//!
//! `dalembert COMMAND --help` prints the command's own help.
//! Exit status: 0 on success, 1 if the model has errors or cannot be read,
//! 2 on a usage error (one line on stderr). Arguments are parsed by hand: the codegen crate is
//! compiled by every user of the macro, and a CLI framework would slow that
//! build for a three-command tool.

#![warn(missing_docs, rust_2018_idioms, unused_qualifications)]

use std::ffi::OsString;
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

use dalembert_codegen::chain::{Family, Spelling};
use dalembert_codegen::{BuildError, ImportOptions, Mjcf, ModelFile, Severity, Style, Urdf};

const USAGE: &str = "\
Usage: dalembert <COMMAND> MODEL.dal

Commands:
  eom MODEL.dal [--latex | --latex-inline | --markdown]
                            print the equations of motion: Unicode text, a LaTeX
                            align* environment, its bare rows, or Markdown
  generate MODEL.dal        print the generated Rust source
  check MODEL.dal [--stats] [--api]
                            report the errors the dalembert! macro would report
                            (--stats: and each generated function's estimated operations;
                            --api: and the functions generated for the model)
  chain FAMILY N [SPELLING] print the .dal text of the planar or spatial chain of N links,
                            spelled `joints` (default), `symbolic` or `seed`
  urdf ROBOT.urdf [--floating] [--name NAME] [--damping] [--outputs \"LIST\"]
                            print the .dal model of a URDF robot
  mjcf MODEL.xml [--name NAME] [--outputs \"LIST\"]
                            print the .dal model of a MuJoCo model (MJCF)
  help                      print this help

Options:
  -h, --help                print this help (after a command: the command's help)
  -V, --version             print the version";

/// A command's usage line and help, printed by `dalembert COMMAND --help`.
#[derive(Debug, PartialEq)]
struct Help {
    name: &'static str,
    usage: &'static str,
    text: &'static str,
}

impl Help {
    /// The full help: the usage line, then the text.
    fn full(&self) -> String {
        format!("Usage: {}\n\n{}", self.usage, self.text)
    }
}

/// The help of every command.
const COMMANDS: [Help; 6] = [
    Help {
        name: "eom",
        usage: "dalembert eom MODEL.dal [--latex | --latex-inline | --markdown]",
        text: "Prints the equations of motion of the model, M(q) and f, as in the seed document.

Options:
  --latex          a complete LaTeX align* environment instead of Unicode text
  --latex-inline   the LaTeX rows alone, to paste into an environment of your own
  --markdown       Markdown with math blocks, for a README
  -h, --help       print this help",
    },
    Help {
        name: "generate",
        usage: "dalembert generate MODEL.dal",
        text: "Prints the Rust source the build step generates for the model.

Options:
  -h, --help   print this help",
    },
    Help {
        name: "check",
        usage: "dalembert check MODEL.dal [--stats] [--api]",
        text: "Reports the errors the dalembert! macro would report for the model (exit status 1),
or prints `MODEL.dal: ok`.

Options:
  --stats      also print each generated function's estimated operation count (a model
               whose largest function exceeds the limit is refused: see docs/reliability.md)
  --api        also print the functions generated for the model, with their arguments,
               and the `outputs` that would add the others
  -h, --help   print this help",
    },
    Help {
        name: "chain",
        usage: "dalembert chain FAMILY N [SPELLING]",
        text:
            "Prints the .dal text of the benchmark chain of N links: FAMILY `planar` or `spatial`,
SPELLING `joints` (default), `symbolic` (symbolic parameters) or `seed` (frames and points).

Options:
  -h, --help   print this help",
    },
    Help {
        name: "urdf",
        usage: "dalembert urdf ROBOT.urdf [--floating] [--name NAME] [--damping] [--outputs \"LIST\"]",
        text: "Prints the .dal model of a URDF robot on stdout (nothing on stdout on an error).
Coordinates in Pinocchio's order: depth first from the root link, a link's child joints
sorted by name. Every link L has a frame `L` and a point `L_origin`.

Options:
  --name NAME        the struct's name (default: the robot's name in UpperCamelCase)
  --floating         a free joint `root_joint` between the ground and the root link
  --damping          each joint's <dynamics damping> as a dissipation function
  --outputs \"LIST\"   append `outputs LIST;` to the model, e.g.
                     --outputs \"jacobian(tool0_origin), rotation(tool0), linearize\"
  -h, --help         print this help",
    },
    Help {
        name: "mjcf",
        usage: "dalembert mjcf MODEL.xml [--name NAME] [--outputs \"LIST\"]",
        text: "Prints the MuJoCo model (MJCF) MODEL.xml, with the files it includes, as a model
in dalembert's language on stdout (nothing on stdout on an error): coordinates and speeds
in MuJoCo's order (qpos, qvel), free joints as (x, y, z, qx, qy, qz, qw) with speeds in
the body's axes, one input tau_<coordinate> per speed that is not a free joint's, gravity
from <option gravity>, joint springs, dampers and armature as MuJoCo applies them. Every
body B has a frame `B` and a point `B_origin`. Contacts, limits and actuators are left
out (see docs/mjcf.md).

Options:
  --name NAME        the struct's name (default: the model's name in UpperCamelCase)
  --outputs \"LIST\"   append `outputs LIST;` to the model
  -h, --help         print this help",
    },
];

/// A parsed command line.
#[derive(Debug, PartialEq)]
enum Command {
    Eom {
        model: PathBuf,
        style: Style,
    },
    Generate {
        model: PathBuf,
    },
    Check {
        model: PathBuf,
        stats: bool,
        api: bool,
    },
    Chain {
        family: Family,
        links: usize,
        spelling: Spelling,
    },
    Urdf {
        robot: PathBuf,
        options: ImportOptions,
    },
    Mjcf {
        model: PathBuf,
        options: ImportOptions,
    },
    /// The general help, or a command's.
    Help(Option<&'static Help>),
    Version,
}

fn main() -> ExitCode {
    match parse(std::env::args_os().skip(1)) {
        Ok(command) => run(command),
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::from(2)
        }
    }
}

/// The command in `args` (without the program name), or what is wrong,
/// on one line.
fn parse(args: impl IntoIterator<Item = OsString>) -> Result<Command, String> {
    let mut args = args.into_iter();
    let Some(first) = args.next() else {
        return Err(general_usage("missing command"));
    };
    let name = first.to_string_lossy().into_owned();
    match name.as_str() {
        "-h" | "--help" | "help" => return Ok(Command::Help(None)),
        "-V" | "--version" => return Ok(Command::Version),
        _ => {}
    }
    let Some(help) = COMMANDS.iter().find(|help| help.name == name) else {
        let what = if name.starts_with('-') {
            format!("unknown option `{name}`: expected a command first")
        } else {
            format!(
                "unknown command `{name}`: expected `eom`, `generate`, `check`, `chain`, `urdf` or `mjcf`"
            )
        };
        return Err(general_usage(&what));
    };
    let rest: Vec<OsString> = args.collect();
    if rest.iter().any(|a| a == "-h" || a == "--help") {
        return Ok(Command::Help(Some(help)));
    }
    let parsed = match help.name {
        "chain" => parse_chain(rest.into_iter()),
        "urdf" => parse_import(help.name, rest, &IMPORT_OPTIONS)
            .map(|(robot, options)| Command::Urdf { robot, options }),
        "mjcf" => parse_import(help.name, rest, &["--name", "--outputs"])
            .map(|(model, options)| Command::Mjcf { model, options }),
        _ => parse_model(help.name, rest),
    };
    parsed.map_err(|message| {
        format!(
            "{message}. Usage: {} (more: `dalembert {} --help`)",
            help.usage, help.name
        )
    })
}

/// `message` with the general usage, on one line.
fn general_usage(message: &str) -> String {
    format!("{message}. Usage: dalembert <COMMAND> [ARGS] (more: `dalembert --help`)")
}

/// The arguments of `eom`, `generate` and `check`: one model file, and
/// the format of `eom` (`--latex`, `--latex-inline`, `--markdown`) or
/// `--stats` for `check`.
fn parse_model(name: &str, args: Vec<OsString>) -> Result<Command, String> {
    let mut style: Option<(&'static str, Style)> = None;
    let (mut stats, mut api) = (false, false);
    let mut model = None;
    for arg in args {
        match arg.to_str() {
            Some(flag @ ("--latex" | "--latex-inline" | "--markdown")) if name == "eom" => {
                let chosen = match flag {
                    "--latex" => ("--latex", Style::Latex),
                    "--latex-inline" => ("--latex-inline", Style::LatexInline),
                    _ => ("--markdown", Style::Markdown),
                };
                if let Some((other, _)) = style.replace(chosen) {
                    return Err(format!(
                        "`{flag}` and `{other}` choose two formats: give one"
                    ));
                }
            }
            Some("--stats") if name == "check" => stats = true,
            Some("--api") if name == "check" => api = true,
            Some(flag) if flag.starts_with('-') => {
                return Err(format!("`{name}` takes no option `{flag}`"));
            }
            _ if model.is_some() => {
                return Err(format!("unexpected argument `{}`", arg.to_string_lossy()));
            }
            _ => model = Some(PathBuf::from(arg)),
        }
    }
    let model = model.ok_or_else(|| format!("`{name}` needs a model file"))?;
    Ok(match name {
        "eom" => Command::Eom {
            model,
            style: style.map_or(Style::Unicode, |(_, style)| style),
        },
        "generate" => Command::Generate { model },
        _ => Command::Check { model, stats, api },
    })
}

/// The arguments of `chain FAMILY N [SPELLING]`.
fn parse_chain(mut args: impl Iterator<Item = OsString>) -> Result<Command, String> {
    let (Some(family), Some(links), spelling, None) =
        (args.next(), args.next(), args.next(), args.next())
    else {
        return Err(
            "`chain` needs a family (`planar` or `spatial`), a number of links and optionally a spelling (`joints`, `symbolic` or `seed`)"
                .into(),
        );
    };
    let family = family.to_string_lossy();
    let family = Family::from_name(&family).ok_or_else(|| {
        format!("unknown chain family `{family}`: expected `planar` or `spatial`")
    })?;
    let spelling = match spelling {
        None => Spelling::Joints,
        Some(name) => {
            let name = name.to_string_lossy();
            Spelling::from_name(&name).ok_or_else(|| {
                format!("unknown spelling `{name}`: expected `joints`, `symbolic` or `seed`")
            })?
        }
    };
    match links.to_string_lossy().parse::<usize>() {
        Ok(links) if links > 0 => Ok(Command::Chain {
            family,
            links,
            spelling,
        }),
        _ => Err("the number of links must be a positive integer".into()),
    }
}

/// Every option an import command may take: `--name NAME`, `--floating`,
/// `--damping`, `--outputs "LIST"` (each importer takes those of them that
/// it lists in `takes`).
const IMPORT_OPTIONS: [&str; 4] = ["--name", "--floating", "--damping", "--outputs"];

/// The arguments of an import command `command FILE [OPTIONS]` taking the
/// options `takes` (of [`IMPORT_OPTIONS`]): the file and the options.
fn parse_import(
    command: &str,
    args: Vec<OsString>,
    takes: &[&str],
) -> Result<(PathBuf, ImportOptions), String> {
    let mut options = ImportOptions::new();
    let mut file = None;
    let mut args = args.into_iter();
    while let Some(arg) = args.next() {
        let Some(flag) = arg.to_str().filter(|a| a.starts_with('-')) else {
            if file.is_some() {
                return Err(format!("unexpected argument `{}`", arg.to_string_lossy()));
            }
            file = Some(PathBuf::from(arg));
            continue;
        };
        if !takes.contains(&flag) {
            return Err(if IMPORT_OPTIONS.contains(&flag) {
                format!("`{command}` does not take the option `{flag}`")
            } else {
                format!("unknown option `{flag}` of `{command}`")
            });
        }
        let mut value = |what: &str| {
            args.next()
                .map(|v| v.to_string_lossy().into_owned())
                .ok_or_else(|| format!("`{flag}` needs {what}"))
        };
        options = match flag {
            "--name" => options.name(value("a struct name")?),
            "--outputs" => options.outputs(value(
                "a list of outputs, such as \"jacobian(tool0_origin)\"",
            )?),
            "--floating" => options.floating(true),
            _ => options.damping(true),
        };
    }
    let file = file.ok_or_else(|| format!("`{command}` needs a file"))?;
    Ok((file, options))
}

/// The `.dal` model of the URDF robot at `robot`; its warnings go to
/// stderr.
fn urdf(robot: &PathBuf, options: ImportOptions) -> Result<String, BuildError> {
    let imported = Urdf::read(robot)?.options(options).import()?;
    for warning in &imported.warnings {
        eprintln!("{warning}\n");
    }
    Ok(imported.model)
}

/// The `.dal` model of the MuJoCo model at `model`.
fn mjcf(model: &PathBuf, options: ImportOptions) -> Result<String, BuildError> {
    Mjcf::read(model)?.options(options).model()
}

/// Runs `command`, printing its result to stdout and errors to stderr.
fn run(command: Command) -> ExitCode {
    let output = match command {
        Command::Help(None) => Ok(USAGE.to_owned()),
        Command::Help(Some(help)) => Ok(help.full()),
        Command::Version => Ok(format!("dalembert {}", env!("CARGO_PKG_VERSION"))),
        Command::Eom { model, style } => ModelFile::read(model).and_then(|m| m.equations(style)),
        Command::Generate { model } => ModelFile::read(model).and_then(|m| m.generate()),
        Command::Check { model, stats, api } => ModelFile::read(&model).and_then(|m| {
            m.check()?;
            let mut report = format!("{}: ok", model.display());
            if stats {
                let estimate = m.derivation_estimate()?;
                report.push_str(&format!(
                    "\nestimated derivation: {:.1e} units (limit {:.1e}), about {:.1} s",
                    estimate.units,
                    dalembert_codegen::DERIVATION_LIMIT,
                    estimate.seconds()
                ));
                let limit = dalembert_codegen::OPERATION_LIMIT;
                report.push_str(&format!(
                    "\nestimated operations per function (limit {limit}):"
                ));
                for s in &m.function_sizes()? {
                    report.push_str(&format!("\n{:>12}  {}", s.operations, s.name));
                }
            }
            if api {
                report.push('\n');
                report.push_str(m.api()?.trim_end());
            }
            Ok(report)
        }),
        Command::Chain {
            family,
            links,
            spelling,
        } => Ok(dalembert_codegen::chain::chain_spelled(
            family, links, spelling,
        )),
        Command::Urdf { robot, options } => urdf(&robot, options),
        Command::Mjcf { model, options } => mjcf(&model, options),
    };
    match output {
        Ok(text) => print(&text),
        Err(error) => report(&error),
    }
}

/// Prints `text` with exactly one final line break. A closed pipe (`| head`)
/// is not an error worth reporting.
fn print(text: &str) -> ExitCode {
    let mut out = std::io::stdout().lock();
    match writeln!(out, "{}", text.trim_end_matches('\n')) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: writing the output: {e}");
            ExitCode::FAILURE
        }
    }
}

/// Reports `error` on stderr, rustc style.
fn report(error: &BuildError) -> ExitCode {
    eprintln!("{error}");
    let count = error
        .diagnostics()
        .iter()
        .filter(|d| d.severity() == Severity::Error)
        .count();
    if count > 1 {
        eprintln!("\nerror: aborting due to {count} errors");
    }
    ExitCode::FAILURE
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse_str(args: &[&str]) -> Result<Command, String> {
        parse(args.iter().map(OsString::from))
    }

    #[test]
    fn parses_the_three_commands() {
        let model = PathBuf::from("m.dal");
        assert_eq!(
            parse_str(&["eom", "m.dal", "--latex"]),
            Ok(Command::Eom {
                model: model.clone(),
                style: Style::Latex
            })
        );
        assert_eq!(
            parse_str(&["eom", "m.dal"]),
            Ok(Command::Eom {
                model: model.clone(),
                style: Style::Unicode
            })
        );
        for (flag, style) in [
            ("--latex-inline", Style::LatexInline),
            ("--markdown", Style::Markdown),
        ] {
            let model = model.clone();
            assert_eq!(
                parse_str(&["eom", flag, "m.dal"]),
                Ok(Command::Eom { model, style })
            );
        }
        let both = parse_str(&["eom", "m.dal", "--latex", "--markdown"]);
        assert!(both.is_err_and(|e| e.contains("two formats")));
        assert_eq!(
            parse_str(&["generate", "m.dal"]),
            Ok(Command::Generate {
                model: model.clone()
            })
        );
        assert_eq!(
            parse_str(&["check", "m.dal", "--stats"]),
            Ok(Command::Check {
                model: model.clone(),
                stats: true,
                api: false
            })
        );
        assert_eq!(
            parse_str(&["check", "m.dal"]),
            Ok(Command::Check {
                model: model.clone(),
                stats: false,
                api: false
            })
        );
        assert_eq!(
            parse_str(&["check", "m.dal", "--api"]),
            Ok(Command::Check {
                model,
                stats: false,
                api: true
            })
        );
        assert_eq!(parse_str(&["help"]), Ok(Command::Help(None)));
        assert_eq!(
            parse_str(&[
                "urdf",
                "r.urdf",
                "--name",
                "Arm",
                "--damping",
                "--outputs",
                "linearize"
            ]),
            Ok(Command::Urdf {
                robot: PathBuf::from("r.urdf"),
                options: ImportOptions::new()
                    .name("Arm")
                    .damping(true)
                    .outputs("linearize")
            })
        );
        assert_eq!(
            parse_str(&[
                "mjcf",
                "m.xml",
                "--outputs",
                "inverse_dynamics",
                "--name",
                "M"
            ]),
            Ok(Command::Mjcf {
                model: PathBuf::from("m.xml"),
                options: ImportOptions::new().outputs("inverse_dynamics").name("M"),
            })
        );
        assert_eq!(
            parse_str(&["chain", "spatial", "12"]),
            Ok(Command::Chain {
                family: Family::Spatial,
                links: 12,
                spelling: Spelling::Joints,
            })
        );
        assert_eq!(
            parse_str(&["chain", "planar", "3", "seed"]),
            Ok(Command::Chain {
                family: Family::Planar,
                links: 3,
                spelling: Spelling::FramesAndPoints,
            })
        );
    }

    #[test]
    fn every_command_has_its_own_help() {
        for help in &COMMANDS {
            for args in [[help.name, "--help"], [help.name, "-h"]] {
                assert_eq!(parse_str(&args), Ok(Command::Help(Some(help))));
            }
            assert!(
                help.full()
                    .starts_with(&format!("Usage: dalembert {}", help.name))
            );
        }
    }

    #[test]
    fn an_import_refuses_an_option_it_does_not_take() {
        let args = ["m.xml", "--floating"].map(OsString::from).to_vec();
        let error = parse_import("mjcf", args, &["--name", "--outputs"]).unwrap_err();
        assert_eq!(error, "`mjcf` does not take the option `--floating`");
    }

    #[test]
    fn an_unknown_command_is_reported_as_one() {
        for args in [&["frobnicate"][..], &["frobnicate", "m.dal"]] {
            let error = parse_str(args).unwrap_err();
            assert!(error.starts_with("unknown command `frobnicate`"), "{error}");
        }
    }

    #[test]
    fn rejects_bad_usage() {
        for args in [
            &[][..],
            &["eom"],
            &["frobnicate", "m.dal"],
            &["check", "m.dal", "extra"],
            &["check", "m.dal", "--latex"],
            &["eom", "m.dal", "--unicode"],
            &["chain", "planar"],
            &["chain", "helical", "3"],
            &["chain", "planar", "0"],
            &["chain", "planar", "3", "4"],
            &["chain", "planar", "3", "seed", "5"],
            &["urdf"],
            &["urdf", "r.urdf", "--name"],
            &["urdf", "r.urdf", "--outputs"],
            &["urdf", "r.urdf", "--latex"],
            &["urdf", "r.urdf", "s.urdf"],
            &["mjcf"],
            &["mjcf", "m.xml", "--name"],
            &["mjcf", "m.xml", "--floating"],
            &["mjcf", "m.xml", "n.xml"],
        ] {
            assert!(parse_str(args).is_err(), "{args:?}");
        }
    }
}
