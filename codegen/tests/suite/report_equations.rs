//! The printed equations of three textbook systems, as a student would
//! paste them into a report: a heavy top in Z-X-Z Euler angles, an Atwood
//! machine with a massive pulley and a pendulum whose pivot is shaken in
//! time. Their Unicode text is kept as snapshots; their LaTeX (`--latex`,
//! one `align*`; `--latex-inline`, the bare rows; `--markdown`, `math`
//! blocks) is checked by a small structural parser of LaTeX math below
//! (balanced groups, matched environments and `\left`/`\right`, known
//! commands with their arguments, one `&` a row), and compiled by a TeX
//! engine where one is installed (`pdflatex`, `lualatex`, `xelatex` or
//! `tectonic` on the `PATH`); the test says which, or that it found none.

use std::path::Path;
use std::process::Command;

use dalembert_codegen::{Style, equations};

const HEAVY_TOP: &str = "
/// A symmetric heavy top on a fixed point, Z-X-Z Euler angles.
pub HeavyTop {
    parameters m, l, g, I1c, I3;
    coordinates psi, theta, phi;
    frame A = N.rotate_z(psi);
    frame B = A.rotate_x(theta);
    frame C = B.rotate_z(phi);
    body top { mass: m, center: O + l * C.z, frame: C, inertia: [I1c, I1c, I3] };
    gravity -g * N.z;
}";

const ATWOOD: &str = "
/// An Atwood machine whose pulley (a disc of radius r) has inertia.
pub Atwood {
    parameters m_A, m_B, m_p, r, g;
    coordinates y;
    frame P = N.rotate_z(y / r);
    point A = O - (2 + y) * N.y + r * N.x;
    point B = O - (2 - y) * N.y - r * N.x;
    particle a { mass: m_A, at: A };
    particle b { mass: m_B, at: B };
    body pulley { mass: m_p, center: O, frame: P, inertia: [0, 0, m_p*r^2/2] };
    gravity -g * N.y;
}";

const SHAKEN_PENDULUM: &str = "
/// A pendulum whose pivot is shaken horizontally, `x = A sin(w t)`.
pub ShakenPendulum {
    parameters m, l, g, A, w;
    coordinates theta;
    frame B = N.rotate_z(theta);
    point P = O + A * sin(w * t) * N.x;
    particle bob { mass: m, at: P - l * B.y };
    gravity -g * N.y;
}";

/// The shaken pendulum spelled with the pivot a coordinate and a rheonomic
/// constraint: the constrained coordinate's rates take dots too.
const DRIVEN_PIVOT: &str = "
pub DrivenPivot {
    parameters m, l, g, A, w;
    coordinates xp, theta;
    frame B = N.rotate_z(theta);
    point P = O + xp * N.x;
    particle bob { mass: m, at: P - l * B.y };
    gravity -g * N.y;
    constraint xp == A * sin(w * t);
}";

const SYSTEMS: [(&str, &str); 4] = [
    ("heavy_top", HEAVY_TOP),
    ("atwood", ATWOOD),
    ("shaken_pendulum", SHAKEN_PENDULUM),
    ("driven_pivot", DRIVEN_PIVOT),
];

fn render(source: &str, style: Style) -> String {
    equations(source, style).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn printed_equations_are_kept_as_snapshots() {
    for (name, source) in SYSTEMS {
        insta::assert_snapshot!(name, render(source, Style::Unicode));
    }
}

#[test]
fn the_tops_forcing_collects_its_inertias_and_names_are_typeset_alike() {
    let text = render(HEAVY_TOP, Style::Unicode);
    assert!(
        text.contains("f₁ = I₃ sin θ θ̇ φ̇ + 2 (I₃ − I_1c − m ℓ²) cos θ sin θ ψ̇ θ̇"),
        "{text}"
    );
    assert!(text.contains("M₂₂ = I_1c + m ℓ²"), "{text}");
    let latex = render(HEAVY_TOP, Style::Latex);
    assert!(
        latex.contains("I_{1c}") && !latex.contains("\\mathrm{I1c}"),
        "{latex}"
    );
    assert!(
        latex.contains("2 \\left(I_{3} - I_{1c} - m \\ell^{2}\\right)"),
        "{latex}"
    );
    let atwood = render(ATWOOD, Style::Unicode);
    assert!(atwood.contains("f₁ = (m_A − m_B) g"), "{atwood}");
    assert!(
        atwood.contains("T = ½ (m_A + m_B + ½ m_p) y\u{307}²"),
        "{atwood}"
    );
}

#[test]
fn every_rate_is_dotted_constrained_coordinates_included() {
    let text = render(DRIVEN_PIVOT, Style::Unicode);
    assert!(text.contains("x\u{308}_p = −A w² sin(w t)"), "{text}");
    assert!(text.contains("½ m x\u{307}_p²"), "{text}");
    assert!(!text.contains("d(xp)") && !text.contains("/dt"), "{text}");
    let latex = render(DRIVEN_PIVOT, Style::Latex);
    assert!(latex.contains("\\ddot{x}_{p}"), "{latex}");
}

#[test]
fn latex_is_one_align_environment_and_inline_rows_are_bare() {
    let mut checked = 0;
    for (name, source) in SYSTEMS {
        let document = render(source, Style::Latex);
        let body = math_of_comments(&document);
        assert_eq!(body.matches("\\begin{align*}").count(), 1, "{name}");
        assert!(body.trim_end().ends_with("\\end{align*}"), "{name}");
        check_latex(&body).unwrap_or_else(|e| panic!("{name}: {e}\n{body}"));
        let inline = render(source, Style::LatexInline);
        assert!(!inline.contains("\\begin"), "{name}: {inline}");
        let rows = math_of_comments(&inline);
        let wrapped = format!(
            "\\begin{{aligned}}\n{}\n\\end{{aligned}}",
            rows.trim_end().trim_end_matches("\\\\")
        );
        check_latex(&wrapped).unwrap_or_else(|e| panic!("{name} inline: {e}\n{wrapped}"));
        let markdown = render(source, Style::Markdown);
        assert!(
            markdown.starts_with("### Equations of motion of "),
            "{name}"
        );
        let blocks: Vec<&str> = markdown.split("```math\n").skip(1).collect();
        assert!(!blocks.is_empty(), "{name}: {markdown}");
        for block in blocks {
            let math = block.split("```").next().unwrap_or_default();
            check_latex(math).unwrap_or_else(|e| panic!("{name} markdown: {e}\n{math}"));
        }
        checked += 1;
    }
    assert_eq!(checked, SYSTEMS.len());
}

#[test]
fn latex_compiles_where_a_tex_engine_is_installed() {
    let engines = ["pdflatex", "lualatex", "xelatex", "tectonic"];
    let Some(engine) = engines.iter().find(|e| on_path(e)) else {
        println!(
            "skipped: no TeX engine ({}) on the PATH; the LaTeX is checked by the \
             structural parser of `latex_is_one_align_environment_and_inline_rows_are_bare`",
            engines.join(", ")
        );
        return;
    };
    println!("compiling with {engine}");
    let directory = std::env::temp_dir().join(format!("dalembert-latex-{}", std::process::id()));
    std::fs::create_dir_all(&directory).expect("a temporary directory");
    for (name, source) in SYSTEMS {
        let document = format!(
            "\\documentclass{{article}}\n\\usepackage{{amsmath}}\n\\begin{{document}}\n{}\n\\end{{document}}\n",
            render(source, Style::Latex)
        );
        let file = directory.join(format!("{name}.tex"));
        std::fs::write(&file, document).expect("writes");
        let mut command = Command::new(engine);
        if *engine != "tectonic" {
            command
                .arg("-interaction=nonstopmode")
                .arg("-halt-on-error");
        }
        let output = command
            .arg(&file)
            .current_dir(&directory)
            .output()
            .expect("runs");
        assert!(
            output.status.success(),
            "{engine} on {name}:\n{}",
            String::from_utf8_lossy(&output.stdout)
        );
    }
}

fn on_path(program: &str) -> bool {
    std::env::var_os("PATH").is_some_and(|paths| {
        std::env::split_paths(&paths).any(|dir| Path::new(&dir).join(program).is_file())
    })
}

/// `text` without its `%` comment lines.
fn math_of_comments(text: &str) -> String {
    text.lines()
        .filter(|line| !line.starts_with('%'))
        .collect::<Vec<_>>()
        .join("\n")
}

/// The commands the printers may write, with the number of brace groups
/// each takes.
const COMMANDS: &[(&str, usize)] = &[
    ("frac", 2),
    ("dot", 1),
    ("ddot", 1),
    ("sqrt", 1),
    ("mathrm", 1),
    ("text", 1),
    ("intertext", 1),
    ("begin", 1),
    ("end", 1),
    ("left", 0),
    ("right", 0),
    ("sin", 0),
    ("cos", 0),
    ("tan", 0),
    ("exp", 0),
    ("ln", 0),
    ("dots", 0),
    ("cdot", 0),
    ("ell", 0),
    ("alpha", 0),
    ("beta", 0),
    ("gamma", 0),
    ("delta", 0),
    ("epsilon", 0),
    ("theta", 0),
    ("lambda", 0),
    ("mu", 0),
    ("phi", 0),
    ("psi", 0),
    ("omega", 0),
    ("Omega", 0),
    ("rho", 0),
    ("sigma", 0),
    ("tau", 0),
];

/// A structural check of LaTeX math as the printers write it: every
/// command known and given its groups, braces balanced, `\begin`/`\end`
/// and `\left`/`\right` matched, `^` and `_` followed by an operand, and
/// in an alignment one `&` in each row (a `\intertext` line aside).
fn check_latex(text: &str) -> Result<(), String> {
    let chars: Vec<char> = text.chars().collect();
    let (mut i, mut depth, mut lefts) = (0, 0i32, 0i32);
    let mut environments: Vec<String> = Vec::new();
    let mut pending_groups: Vec<(String, usize)> = Vec::new();
    let mut row_ampersands = 0;
    let mut row_is_text = false;
    let mut rows = 0;
    while i < chars.len() {
        let c = chars[i];
        match c {
            '\\' => {
                let start = i + 1;
                let mut end = start;
                while end < chars.len() && chars[end].is_ascii_alphabetic() {
                    end += 1;
                }
                if end == start {
                    // `\\` ends a row; `\{`, `\,` and friends are symbols.
                    if chars.get(start) == Some(&'\\') && depth == 0 {
                        let in_alignment = environments.last().is_some();
                        if in_alignment && !row_is_text && row_ampersands != 1 {
                            return Err(format!("a row with {row_ampersands} `&` before {i}"));
                        }
                        row_ampersands = 0;
                        row_is_text = false;
                        rows += 1;
                    }
                    i = start + 1;
                    continue;
                }
                let name: String = chars[start..end].iter().collect();
                let Some(&(_, groups)) = COMMANDS.iter().find(|(n, _)| *n == name) else {
                    return Err(format!("unknown command \\{name}"));
                };
                i = end;
                match name.as_str() {
                    "left" => lefts += 1,
                    "right" => lefts -= 1,
                    "intertext" => {
                        if row_ampersands != 0 {
                            return Err("\\intertext inside a row".into());
                        }
                        row_is_text = true;
                    }
                    "begin" | "end" => {
                        let environment = group_at(&chars, i)?;
                        let open_row = environments.last().is_some() && !row_is_text;
                        if name == "end" && open_row && row_ampersands != 1 {
                            return Err(format!("a last row with {row_ampersands} `&`"));
                        }
                        if name == "begin" {
                            environments.push(environment);
                        } else if environments.pop().as_deref() != Some(environment.as_str()) {
                            return Err(format!("\\end{{{environment}}} without its \\begin"));
                        }
                        if !["align*", "aligned"]
                            .contains(&environments.last().map_or("align*", |e| e.as_str()))
                        {
                            return Err("an environment other than align* or aligned".into());
                        }
                    }
                    _ => {}
                }
                if groups > 0 {
                    pending_groups.push((name, groups));
                    if chars.get(i) != Some(&'{') {
                        return Err(format!(
                            "\\{} without its argument",
                            pending_groups.last().unwrap().0
                        ));
                    }
                }
                continue;
            }
            '{' => {
                depth += 1;
            }
            '}' => {
                depth -= 1;
                if depth < 0 {
                    return Err(format!("an unopened `}}` at {i}"));
                }
                if let Some((name, left)) = pending_groups.last_mut() {
                    *left -= 1;
                    if *left == 0 {
                        pending_groups.pop();
                    } else if chars.get(i + 1) != Some(&'{') {
                        return Err(format!("\\{name} without all its arguments"));
                    }
                }
            }
            '&' if depth == 0 => row_ampersands += 1,
            '^' | '_' => match chars.get(i + 1) {
                Some(&n) if n == '{' || n == '\\' || n.is_alphanumeric() => {}
                other => return Err(format!("`{c}` followed by {other:?}")),
            },
            _ => {}
        }
        i += 1;
    }
    if depth != 0 || lefts != 0 || !environments.is_empty() {
        return Err(format!(
            "unbalanced: braces {depth}, \\left − \\right {lefts}, open {environments:?}"
        ));
    }
    if rows == 0 && row_ampersands == 0 {
        return Err("no row".into());
    }
    Ok(())
}

/// The brace group starting at `i`, without its braces.
fn group_at(chars: &[char], i: usize) -> Result<String, String> {
    if chars.get(i) != Some(&'{') {
        return Err("an environment without its name".into());
    }
    let close = chars[i..]
        .iter()
        .position(|&c| c == '}')
        .ok_or("an unclosed environment name")?;
    Ok(chars[i + 1..i + close].iter().collect())
}

#[test]
fn the_parser_refuses_broken_latex() {
    for broken in [
        "\\begin{aligned}\na &= b \\\\\nc = d\n\\end{aligned}",
        "\\begin{aligned}\na &= \\frac{1}2 b\n\\end{aligned}",
        "\\begin{aligned}\na &= \\left(b\n\\end{aligned}",
        "\\begin{aligned}\na &= \\unknown{b}\n\\end{aligned}",
        "\\begin{aligned}\na &= {b\n\\end{aligned}",
        "\\begin{align*}\na &= b\n\\end{aligned}",
    ] {
        assert!(check_latex(broken).is_err(), "{broken}");
    }
    assert_eq!(
        check_latex("\\begin{aligned}\na &= \\frac{1}{2} b^{2}\n\\end{aligned}"),
        Ok(())
    );
}
