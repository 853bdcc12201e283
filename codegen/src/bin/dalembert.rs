//! `dalembert`: the equations, generated code and diagnostics of a `.dal`
//! model from the command line.
//!
//! ```text
//! dalembert eom MODEL.dal [--latex | --latex-inline | --markdown]
//!                                     the equations of motion, as in the seed document
//! dalembert generate MODEL.dal        the generated Rust source
//! dalembert check MODEL.dal           the errors the dalembert! macro would report
//! dalembert chain FAMILY N [SPELLING] the .dal text of a benchmark chain (planar or spatial;
//!                                     spelled joints, symbolic or seed)
//! dalembert urdf ROBOT.urdf [--floating] [--name NAME] [--damping]
//!                                     the .dal model of a URDF robot
//! ```
//!
//! Exit status: 0 on success, 1 if the model has errors or cannot be read,
//! 2 on a usage error. Arguments are parsed by hand: the codegen crate is
//! compiled by every user of the macro, and a CLI framework would slow that
//! build for a three-command tool.

#![warn(missing_docs, rust_2018_idioms, unused_qualifications)]

use std::ffi::OsString;
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

use dalembert_codegen::testing::{Family, Spelling};
use dalembert_codegen::{BuildError, ModelFile, Severity, Style, Urdf};

const USAGE: &str = "\
Usage: dalembert <COMMAND> MODEL.dal

Commands:
  eom MODEL.dal [--latex | --latex-inline | --markdown]
                            print the equations of motion: Unicode text, a LaTeX
                            align* environment, its bare rows, or Markdown
  generate MODEL.dal        print the generated Rust source
  check MODEL.dal           report the errors the dalembert! macro would report
  chain FAMILY N [SPELLING] print the .dal text of the planar or spatial chain of N links,
                            spelled `joints` (default), `symbolic` or `seed`
  urdf ROBOT.urdf [--floating] [--name NAME] [--damping]
                            print the .dal model of a URDF robot (--damping: joint
                            damping as a dissipation function)
  help                      print this help

Options:
  -h, --help                print this help
  -V, --version             print the version";

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
    },
    Chain {
        family: Family,
        links: usize,
        spelling: Spelling,
    },
    Urdf {
        robot: PathBuf,
        options: UrdfOptions,
    },
    Help,
    Version,
}

fn main() -> ExitCode {
    match parse(std::env::args_os().skip(1)) {
        Ok(command) => run(command),
        Err(message) => {
            eprintln!("error: {message}\n\n{USAGE}");
            ExitCode::from(2)
        }
    }
}

/// The options of `urdf`.
#[derive(Debug, Default, PartialEq)]
struct UrdfOptions {
    floating: bool,
    name: Option<String>,
    damping: bool,
}

/// The command in `args` (without the program name), or what is wrong.
fn parse(args: impl IntoIterator<Item = OsString>) -> Result<Command, String> {
    let mut args = args.into_iter().peekable();
    if args.peek().is_some_and(|a| a == "urdf") {
        return parse_urdf(args.skip(1));
    }
    let mut positional = Vec::new();
    let mut style: Option<(&'static str, Style)> = None;
    for arg in args {
        match arg.to_str() {
            Some("-h" | "--help") => return Ok(Command::Help),
            Some("-V" | "--version") => return Ok(Command::Version),
            Some(flag @ ("--latex" | "--latex-inline" | "--markdown")) => {
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
            Some(flag) if flag.starts_with('-') => {
                return Err(format!("unknown option `{flag}`"));
            }
            _ => positional.push(arg),
        }
    }
    let mut positional = positional.into_iter();
    let Some(name) = positional.next() else {
        return Err("missing command".into());
    };
    let name = name.to_string_lossy().into_owned();
    // The command is known before its model file is asked for, so that a
    // misspelt command is reported as one.
    let command: fn(PathBuf, Style) -> Command = match name.as_str() {
        "chain" => return parse_chain(positional),
        "help" => return Ok(Command::Help),
        "eom" => |model, style| Command::Eom { model, style },
        "generate" => |model, _| Command::Generate { model },
        "check" => |model, _| Command::Check { model },
        _ => {
            return Err(format!(
                "unknown command `{name}`: expected `eom`, `generate`, `check`, `chain` or `urdf`"
            ));
        }
    };
    let model = PathBuf::from(
        positional
            .next()
            .ok_or_else(|| format!("`{name}` needs a model file"))?,
    );
    if let Some(extra) = positional.next() {
        return Err(format!("unexpected argument `{}`", extra.to_string_lossy()));
    }
    match style {
        Some((flag, _)) if name != "eom" => Err(format!("`{flag}` applies to `eom`, not `{name}`")),
        _ => Ok(command(model, style.map_or(Style::Unicode, |(_, s)| s))),
    }
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

/// The arguments of `urdf ROBOT.urdf [--floating] [--name NAME] [--damping]`.
fn parse_urdf(args: impl Iterator<Item = OsString>) -> Result<Command, String> {
    let mut options = UrdfOptions::default();
    let mut robot = None;
    let mut args = args.peekable();
    while let Some(arg) = args.next() {
        match arg.to_str() {
            Some("-h" | "--help") => return Ok(Command::Help),
            Some("--floating") => options.floating = true,
            Some("--damping") => options.damping = true,
            Some("--name") => {
                let name = args.next().ok_or("`--name` needs a struct name")?;
                options.name = Some(name.to_string_lossy().into_owned());
            }
            Some(flag) if flag.starts_with('-') => {
                return Err(format!("unknown option `{flag}` of `urdf`"));
            }
            _ if robot.is_some() => {
                return Err(format!("unexpected argument `{}`", arg.to_string_lossy()));
            }
            _ => robot = Some(PathBuf::from(arg)),
        }
    }
    let robot = robot.ok_or("`urdf` needs a URDF file")?;
    Ok(Command::Urdf { robot, options })
}

/// The `.dal` model of the URDF robot at `robot`; its warnings go to
/// stderr.
fn urdf(robot: &PathBuf, options: UrdfOptions) -> Result<String, BuildError> {
    let mut urdf = Urdf::read(robot)?
        .floating(options.floating)
        .damping(options.damping);
    if let Some(name) = options.name {
        urdf = urdf.name(name);
    }
    let imported = urdf.import()?;
    for warning in &imported.warnings {
        eprintln!("{warning}\n");
    }
    Ok(imported.model)
}

/// Runs `command`, printing its result to stdout and errors to stderr.
fn run(command: Command) -> ExitCode {
    let output = match command {
        Command::Help => Ok(USAGE.to_owned()),
        Command::Version => Ok(format!("dalembert {}", env!("CARGO_PKG_VERSION"))),
        Command::Eom { model, style } => ModelFile::read(model).and_then(|m| m.equations(style)),
        Command::Generate { model } => ModelFile::read(model).and_then(|m| m.generate()),
        Command::Check { model } => ModelFile::read(&model)
            .and_then(|m| m.check())
            .map(|()| format!("{}: ok", model.display())),
        Command::Chain {
            family,
            links,
            spelling,
        } => Ok(dalembert_codegen::testing::chain_spelled(
            family, links, spelling,
        )),
        Command::Urdf { robot, options } => urdf(&robot, options),
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
        assert_eq!(parse_str(&["check", "m.dal"]), Ok(Command::Check { model }));
        assert_eq!(parse_str(&["check", "--help"]), Ok(Command::Help));
        assert_eq!(parse_str(&["help"]), Ok(Command::Help));
        assert_eq!(
            parse_str(&["urdf", "r.urdf", "--name", "Arm", "--damping"]),
            Ok(Command::Urdf {
                robot: PathBuf::from("r.urdf"),
                options: UrdfOptions {
                    floating: false,
                    name: Some("Arm".into()),
                    damping: true
                }
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
            &["urdf", "r.urdf", "--latex"],
            &["urdf", "r.urdf", "s.urdf"],
        ] {
            assert!(parse_str(args).is_err(), "{args:?}");
        }
    }
}
