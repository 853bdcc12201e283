//! The derived equations in readable form, in the seed document's style:
//! doc-comment lines for the generated struct ([`equations_doc`]) and text
//! for a command-line tool ([`equations_text`]).
//!
//! Each entry is expanded and its trigonometric pairs recombined
//! ([`crate::readable`]); an entry too large for that is named in the rows and
//! noted as large in the listing. All entries share one budget of
//! monomials (each at most [`ENTRY_BUDGET`]), so the rendering of a 30-body
//! chain stays bounded in size and time.
//!
//! The readable forms come from the derivation's [`ReadableForms`], which
//! the optimiser filled first; `text` holds the Unicode and LaTeX printers.

mod collect;
pub mod text;

use std::collections::{HashMap, HashSet};

pub use text::Style;
use text::{Coefficient, SymbolNames, label, latex, linear_combination, unicode};

use crate::equations::Equations;
use crate::expr::{ExprId, Pool, Sym};
use crate::model::Model;
use crate::readable::{ReadableForms, term_count};

/// Most monomials one entry may show.
const ENTRY_BUDGET: usize = 100;

/// Most monomials the entries of one rendering may show together (about).
const DOCUMENT_BUDGET: usize = 3000;

/// Fewest monomials an entry may show however many entries there are.
const MIN_ENTRY_BUDGET: usize = 8;

/// How often entries that did not fit are retried with a larger share.
const BUDGET_ROUNDS: usize = 3;

/// Doc-comment lines (markdown, each as it appears after `///`) rendering
/// the equations of `model` and the same content as Unicode text (for
/// `NAME::EQUATIONS`), from one rendering: a heading, the form of the
/// equations, the equations row by row as `Σⱼ (Mₖⱼ) q̈ⱼ = fₖ (+ Σⱼ (aⱼₖ) λⱼ)`,
/// the constraint rows `A q̈ = b`, then every non-zero entry and the energies.
pub fn equations_doc(
    model: &Model,
    equations: &Equations,
    pool: &mut Pool,
    forms: &mut ReadableForms,
) -> (Vec<String>, String) {
    let document = Document::new(model, equations, pool, forms, Style::Unicode);
    let mut lines = vec![
        " # Equations of motion".to_string(),
        String::new(),
        format!(" {}", document.introduction("`")),
    ];
    for section in &document.sections {
        lines.push(String::new());
        if let Some(title) = &section.title {
            lines.extend([format!(" {title}:"), String::new()]);
        }
        lines.push(" ```text".to_string());
        lines.extend(
            section
                .equations
                .iter()
                .map(|(lhs, rhs)| format!(" {lhs} = {rhs}")),
        );
        lines.push(" ```".to_string());
    }
    (lines, document.text(model))
}

/// The content of [`equations_doc`] as text in `style`, for a command-line
/// tool: plain lines for Unicode, one `align*` environment for LaTeX, bare
/// rows for inline LaTeX, `math` blocks for Markdown (see [`Style`]).
pub fn equations_text(
    model: &Model,
    equations: &Equations,
    pool: &mut Pool,
    forms: &mut ReadableForms,
    style: Style,
) -> String {
    Document::new(model, equations, pool, forms, style).text(model)
}

/// A rendering independent of its output format.
struct Document {
    /// The layout of the rendering; the strings below are in its
    /// [notation](Style::math).
    style: Style,
    /// The form of the equations (`M(q) q̈ = f(t, q, q̇, u)`).
    form: String,
    /// Whether there are constraints.
    constrained: bool,
    /// Titled groups of equations, as `(lhs, rhs)`.
    sections: Vec<Section>,
}

/// A group of equations.
struct Section {
    title: Option<String>,
    equations: Vec<(String, String)>,
}

impl Document {
    /// Renders every part of `equations` in `style`.
    fn new(
        model: &Model,
        equations: &Equations,
        pool: &mut Pool,
        readable: &mut ReadableForms,
        style: Style,
    ) -> Document {
        let mut names = SymbolNames::new(&model.parameters, &model.coordinates, &model.inputs);
        let speeds_are_rates = pool.rates_are_speeds();
        if !speeds_are_rates {
            let speeds = model.speeds.iter();
            names = names.with_speeds(
                speeds.map(|s| (&s.name as &dyn std::fmt::Display, s.rate_of_coordinate)),
            );
        }
        let equations = &equations.ungrouped(pool);
        let forms = readable_forms(pool, readable, &entries(equations));
        let mut renderer = Renderer {
            pool,
            readable,
            names,
            style: style.math(),
            forms,
        };
        let constrained = !equations.constraint_jacobian.is_empty();
        let sections = [
            renderer.rows(equations),
            renderer.constraint_rows(equations),
            renderer.mass_matrix(&equations.mass_matrix),
            renderer.vector("Forcing", "f", &equations.forcing),
            renderer.matrix(
                "Constraint Jacobian (zero entries omitted)",
                "a",
                &equations.constraint_jacobian,
            ),
            renderer.vector("Constraint bias", "b", &equations.constraint_bias),
            renderer.energies(equations),
        ];
        Document {
            style,
            form: form(style.math(), constrained, speeds_are_rates),
            constrained,
            sections: sections
                .into_iter()
                .filter(|s| !s.equations.is_empty())
                .collect(),
        }
    }

    /// The sentence introducing the equations, the form between `quote`s.
    fn introduction(&self, quote: &str) -> String {
        let method = match self.constrained {
            false => "d'Alembert's principle",
            true => "d'Alembert's principle and Lagrange multipliers",
        };
        format!(
            "Derived with {method}, in the form {quote}{}{quote}:",
            self.form
        )
    }
}

/// Every expression a rendering shows, in the order it shows them.
fn entries(equations: &Equations) -> Vec<ExprId> {
    let matrices = equations
        .mass_matrix
        .iter()
        .chain(&equations.constraint_jacobian)
        .flatten();
    let vectors = equations.forcing.iter().chain(&equations.constraint_bias);
    let energies = [&equations.kinetic_energy, &equations.potential_energy];
    matrices.chain(vectors).chain(energies).copied().collect()
}

impl Document {
    /// The whole rendering as text in its layout (see [`Style`]).
    fn text(&self, model: &Model) -> String {
        let heading = format!("Equations of motion of {}", model.name);
        match self.style {
            Style::Unicode => self.plain(&heading),
            Style::Latex => self.align(&heading),
            Style::LatexInline => self.rows(&heading),
            Style::Markdown => self.markdown(&heading),
        }
    }

    /// Plain lines, `  lhs = rhs`, under each section's title.
    fn plain(&self, heading: &str) -> String {
        let mut out = format!("{heading}\n{}\n", self.introduction(""));
        for section in &self.sections {
            out.push('\n');
            if let Some(title) = &section.title {
                out.push_str(&format!("{title}:\n"));
            }
            for (lhs, rhs) in &section.equations {
                out.push_str(&format!("  {lhs} = {rhs}\n"));
            }
        }
        out
    }

    /// One `align*` environment, the titles as `\intertext` (between
    /// rows, so without a `\\` of their own), after the heading and form
    /// as `%` comments.
    fn align(&self, heading: &str) -> String {
        let mut lines: Vec<(bool, String)> = Vec::new();
        for section in &self.sections {
            if let Some(title) = &section.title {
                lines.push((true, format!("\\intertext{{{}:}}", latex_text(title))));
            }
            let rows = section
                .equations
                .iter()
                .map(|(l, r)| (false, format!("{l} &= {r}")));
            lines.extend(rows);
        }
        let mut body = String::new();
        for (i, (title, line)) in lines.iter().enumerate() {
            body.push_str(line);
            if i + 1 < lines.len() {
                body.push_str(if *title { "\n" } else { " \\\\\n" });
            }
        }
        format!(
            "% {heading}\n% {}\n\\begin{{align*}}\n{body}\n\\end{{align*}}\n",
            self.introduction("")
        )
    }

    /// The rows `lhs &= rhs \\` alone, the titles as `%` comments.
    fn rows(&self, heading: &str) -> String {
        let mut out = format!("% {heading}\n% {}\n", self.introduction(""));
        for section in &self.sections {
            if let Some(title) = &section.title {
                out.push_str(&format!("% {title}:\n"));
            }
            for (lhs, rhs) in &section.equations {
                out.push_str(&format!("{lhs} &= {rhs} \\\\\n"));
            }
        }
        out
    }

    /// Markdown: a heading, the introduction with the form in `$…$`, and
    /// each section's rows in a fenced `math` block.
    fn markdown(&self, heading: &str) -> String {
        let mut out = format!("### {heading}\n\n{}\n", self.introduction("$"));
        for section in &self.sections {
            out.push('\n');
            if let Some(title) = &section.title {
                out.push_str(&format!("{title}:\n\n"));
            }
            let rows: Vec<String> = section
                .equations
                .iter()
                .map(|(l, r)| format!("{l} &= {r}"))
                .collect();
            let body = rows.join(" \\\\\n");
            out.push_str(&format!(
                "```math\n\\begin{{aligned}}\n{body}\n\\end{{aligned}}\n```\n"
            ));
        }
        out
    }
}

/// `text` safe in LaTeX's text mode (`'` and letters pass; the characters
/// TeX reserves are escaped).
fn latex_text(text: &str) -> String {
    text.chars().fold(String::new(), |mut out, c| {
        match c {
            '&' | '%' | '$' | '#' | '_' | '{' | '}' => {
                out.push('\\');
                out.push(c);
            }
            _ => out.push(c),
        }
        out
    })
}

/// The form of the equations in the notation `style`: in `q̈` when every speed is its
/// coordinate's rate, else in the speeds `v` (`q̇ = N(q) v`).
fn form(style: Style, constrained: bool, speeds_are_rates: bool) -> String {
    let form = match (style, constrained) {
        (Style::Unicode, false) => "M(q) q̈ = f(t, q, q̇, u)",
        (Style::Unicode, true) => "M(q) q̈ = f(t, q, q̇, u) + A(q)ᵀ λ, A(q) q̈ = b(t, q, q̇)",
        (_, false) => "M(q) \\ddot{q} = f(t, q, \\dot{q}, u)",
        (_, true) => {
            "M(q) \\ddot{q} = f(t, q, \\dot{q}, u) + A(q)^{T} \\lambda, A(q) \\ddot{q} = b(t, q, \\dot{q})"
        }
    };
    match (speeds_are_rates, style) {
        (true, _) => form.to_string(),
        (false, Style::Unicode) => form.replace("q̈", "v̇").replace("q̇", "v") + " with q̇ = N(q) v",
        (false, _) => {
            form.replace("\\ddot{q}", "\\dot{v}")
                .replace("\\dot{q}", "v")
                + " \\text{ with } \\dot{q} = N(q) v"
        }
    }
}

/// The readable forms of `entries`, sharing [`DOCUMENT_BUDGET`]: every
/// entry first gets an equal share, then the entries that did not fit share
/// what the others left, for a few rounds. An entry that never fits maps to
/// the last budget it was given.
fn readable_forms(
    pool: &mut Pool,
    readable: &mut ReadableForms,
    entries: &[ExprId],
) -> HashMap<ExprId, Result<ExprId, usize>> {
    let mut forms = HashMap::new();
    let mut seen = HashSet::new();
    let mut pending: Vec<ExprId> = entries
        .iter()
        .copied()
        .filter(|&e| seen.insert(e))
        .collect();
    let mut budget = (DOCUMENT_BUDGET / pending.len().max(1)).clamp(MIN_ENTRY_BUDGET, ENTRY_BUDGET);
    let mut spent = 0;
    for _ in 0..BUDGET_ROUNDS {
        let mut failed = Vec::new();
        for e in pending {
            match readable.get(pool, e, budget) {
                Some(form) => {
                    spent += term_count(pool, form);
                    forms.insert(e, Ok(form));
                }
                None => {
                    forms.insert(e, Err(budget));
                    failed.push(e);
                }
            }
        }
        let share = DOCUMENT_BUDGET.saturating_sub(spent) / failed.len().max(1);
        if failed.is_empty() || share.min(ENTRY_BUDGET) <= budget {
            break;
        }
        (budget, pending) = (share.min(ENTRY_BUDGET), failed);
    }
    forms
}

/// Renders entries, computing each readable form once.
struct Renderer<'a> {
    pool: &'a mut Pool,
    /// The derivation's readable forms.
    readable: &'a mut ReadableForms,
    names: SymbolNames,
    style: Style,
    /// Readable forms by expression, or the budget they exceeded.
    forms: HashMap<ExprId, Result<ExprId, usize>>,
}

impl Renderer<'_> {
    /// The readable form of `e` with its parameter products collected
    /// ([`collect::collect_parameters`]), or the budget it exceeded.
    fn form(&mut self, e: ExprId) -> Result<ExprId, usize> {
        let form = match self.forms.get(&e) {
            Some(&form) => form,
            None => {
                let form = self
                    .readable
                    .get(self.pool, e, MIN_ENTRY_BUDGET)
                    .ok_or(MIN_ENTRY_BUDGET);
                self.forms.insert(e, form);
                form
            }
        };
        form.map(|form| collect::collect_parameters(self.pool, form))
    }

    /// `e` as a coefficient: its readable form, or the entry's label.
    fn coefficient(&mut self, e: ExprId, base: &str, indices: &[usize]) -> Coefficient {
        match self.form(e) {
            Ok(form) => Coefficient::Expr(form),
            Err(_) => Coefficient::Named(label(base, indices, self.style)),
        }
    }

    /// `e` in full, or a note that it is too large.
    fn entry(&mut self, e: ExprId) -> String {
        match self.form(e) {
            Ok(form) => match self.style {
                Style::Unicode => unicode(self.pool, form, &self.names),
                _ => latex(self.pool, form, &self.names),
            },
            Err(budget) => self.too_large(budget),
        }
    }

    /// The note standing for an entry past its budget.
    fn too_large(&self, budget: usize) -> String {
        let note = format!("(large: more than {budget} terms, see the generated code)");
        match self.style {
            Style::Unicode => note,
            _ => format!("\\text{{{note}}}"),
        }
    }

    /// `Σⱼ cⱼ vⱼ` with the leading part `leading`.
    fn combination(&self, leading: Option<&Coefficient>, terms: &[(Coefficient, Sym)]) -> String {
        linear_combination(self.pool, leading, terms, &self.names, self.style)
    }

    /// The equations of motion row by row: `Σⱼ (Mₖⱼ) q̈ⱼ = fₖ + Σⱼ (aⱼₖ) λⱼ`.
    fn rows(&mut self, equations: &Equations) -> Section {
        let mut rows = Vec::new();
        for (k, (row, &f)) in equations
            .mass_matrix
            .iter()
            .zip(&equations.forcing)
            .enumerate()
        {
            let inertia: Vec<(Coefficient, Sym)> = (0..row.len())
                .map(|j| (self.coefficient(row[j], "M", &[k + 1, j + 1]), accel(j)))
                .collect();
            let forcing = self.coefficient(f, "f", &[k + 1]);
            let reactions: Vec<(Coefficient, Sym)> = (0..equations.constraint_jacobian.len())
                .filter_map(|j| Some((*equations.constraint_jacobian[j].get(k)?, j)))
                .map(|(a, j)| (self.coefficient(a, "a", &[j + 1, k + 1]), multiplier(j)))
                .collect();
            rows.push((
                self.combination(None, &inertia),
                self.combination(Some(&forcing), &reactions),
            ));
        }
        Section {
            title: None,
            equations: rows,
        }
    }

    /// The constraints at the acceleration level: `Σⱼ (aₖⱼ) q̈ⱼ = bₖ`.
    fn constraint_rows(&mut self, equations: &Equations) -> Section {
        let mut rows = Vec::new();
        for (k, (row, &b)) in equations
            .constraint_jacobian
            .iter()
            .zip(&equations.constraint_bias)
            .enumerate()
        {
            let terms: Vec<(Coefficient, Sym)> = (0..row.len())
                .map(|j| (self.coefficient(row[j], "a", &[k + 1, j + 1]), accel(j)))
                .collect();
            let bias = self.coefficient(b, "b", &[k + 1]);
            rows.push((
                self.combination(None, &terms),
                self.combination(Some(&bias), &[]),
            ));
        }
        let title = "Constraints, differentiated twice (holonomic) or once (nonholonomic)";
        Section {
            title: Some(title.to_string()),
            equations: rows,
        }
    }

    /// The non-zero entries of the symmetric mass matrix on and above the
    /// diagonal.
    fn mass_matrix(&mut self, m: &[Vec<ExprId>]) -> Section {
        let upper: Vec<Vec<Option<ExprId>>> = m
            .iter()
            .enumerate()
            .map(|(k, row)| {
                row.iter()
                    .enumerate()
                    .map(|(j, &e)| (j >= k).then_some(e))
                    .collect()
            })
            .collect();
        let title = "Mass matrix (symmetric, zero entries omitted)";
        self.entries(title, "M", &upper)
    }

    /// The non-zero entries of a matrix.
    fn matrix(&mut self, title: &str, base: &str, m: &[Vec<ExprId>]) -> Section {
        let all: Vec<Vec<Option<ExprId>>> = m
            .iter()
            .map(|row| row.iter().copied().map(Some).collect())
            .collect();
        self.entries(title, base, &all)
    }

    /// The listed (`Some`), non-zero entries of a matrix as `Mₖⱼ = …`.
    fn entries(&mut self, title: &str, base: &str, m: &[Vec<Option<ExprId>>]) -> Section {
        let mut equations = Vec::new();
        for (k, row) in m.iter().enumerate() {
            for (j, &e) in row.iter().enumerate() {
                if let Some(e) = e.filter(|&e| !self.pool.is_zero(e)) {
                    equations.push((label(base, &[k + 1, j + 1], self.style), self.entry(e)));
                }
            }
        }
        Section {
            title: Some(title.to_string()),
            equations,
        }
    }

    /// Every entry of a vector as `fₖ = …`.
    fn vector(&mut self, title: &str, base: &str, v: &[ExprId]) -> Section {
        let equations = v
            .iter()
            .enumerate()
            .map(|(k, &e)| (label(base, &[k + 1], self.style), self.entry(e)))
            .collect();
        Section {
            title: Some(title.to_string()),
            equations,
        }
    }

    /// `T = …` and `V = …`.
    fn energies(&mut self, equations: &Equations) -> Section {
        let kinetic = self.entry(equations.kinetic_energy);
        let potential = self.entry(equations.potential_energy);
        let equations = vec![("T".to_string(), kinetic), ("V".to_string(), potential)];
        Section {
            title: Some("Kinetic and potential energy".to_string()),
            equations,
        }
    }
}

/// `q̈ⱼ`.
fn accel(j: usize) -> Sym {
    Sym::Accel(u32::try_from(j).unwrap_or(u32::MAX))
}

/// `λⱼ`.
fn multiplier(j: usize) -> Sym {
    Sym::Multiplier(u32::try_from(j).unwrap_or(u32::MAX))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::seeds::{CONSTRAINED_PENDULUM, DOUBLE_PENDULUM, ROTATING_BAR};

    /// The model, equations and pool of a system in the language.
    fn derive(source: &str) -> (Model, Equations, Pool) {
        let tokens: proc_macro2::TokenStream = source.parse().expect("tokens");
        let system = crate::language::parse_system(tokens).expect("a system");
        let (model, mut pool) = crate::model::resolve(&system).expect("a model");
        let equations = crate::equations::derive(&model, &mut pool);
        (model, equations, pool)
    }

    /// The rows of the first text block of a doc.
    fn rows(doc: &[String]) -> Vec<&str> {
        let start = doc
            .iter()
            .position(|l| l == " ```text")
            .expect("a text block")
            + 1;
        let end = start
            + doc[start..]
                .iter()
                .position(|l| l == " ```")
                .expect("closed");
        doc[start..end].iter().map(|l| l.trim_start()).collect()
    }

    #[test]
    fn double_pendulum_doc_in_the_seed_style() {
        let (model, equations, mut pool) = derive(DOUBLE_PENDULUM);
        let (doc, _) = equations_doc(&model, &equations, &mut pool, &mut ReadableForms::default());
        assert_eq!(doc[0], " # Equations of motion");
        assert!(doc[2].contains("`M(q) q̈ = f(t, q, q̇, u)`"), "{}", doc[2]);
        assert_eq!(
            rows(&doc),
            [
                "(4/3 m L²) θ̈₁ + (½ m L² cos(θ₂ − θ₁)) θ̈₂ = ½ m L² sin(θ₂ − θ₁) θ̇₂² − 3/2 m L g sin θ₁",
                "(½ m L² cos(θ₂ − θ₁)) θ̈₁ + (⅓ m L²) θ̈₂ = −½ m L² sin(θ₂ − θ₁) θ̇₁² − ½ m L g sin θ₂",
            ]
        );
        for line in [
            " M₁₂ = ½ m L² cos(θ₂ − θ₁)",
            " V = −3/2 m L g cos θ₁ − ½ m L g cos θ₂",
        ] {
            assert!(doc.iter().any(|l| l == line), "{line} missing");
        }
        assert!(
            !doc.iter().any(|l| l.starts_with(" M₂₁")),
            "the lower triangle is listed"
        );
        let fences = doc.iter().filter(|l| l.starts_with(" ```")).count();
        assert_eq!(fences % 2, 0);
        assert!(doc.iter().all(|l| l.is_empty() || l.starts_with(' ')));
    }

    #[test]
    fn rotating_bar_rows_match_the_seed() {
        let (model, equations, mut pool) = derive(ROTATING_BAR);
        let (doc, _) = equations_doc(&model, &equations, &mut pool, &mut ReadableForms::default());
        assert_eq!(
            rows(&doc),
            [
                "(m d² + 1/12 m ℓ² cos²θ) φ̈ = ⅙ m ℓ² cos θ sin θ φ̇ θ̇ + M_φ",
                "(1/12 m ℓ²) θ̈ = −1/12 m ℓ² cos θ sin θ φ̇² + M_θ",
            ]
        );
    }

    #[test]
    fn constrained_pendulum_has_multipliers_and_constraint_rows() {
        let (model, equations, mut pool) = derive(CONSTRAINED_PENDULUM);
        let (doc, _) = equations_doc(&model, &equations, &mut pool, &mut ReadableForms::default());
        assert!(doc[2].contains("A(q)ᵀ λ"), "{}", doc[2]);
        assert_eq!(
            rows(&doc),
            [
                "m x\u{308} = λ₁",
                "m y\u{308} = −m g + λ₂",
                "(1/12 m ℓ²) θ̈ = M − (½ ℓ cos θ) λ₁ − (½ ℓ sin θ) λ₂"
            ]
        );
        for line in [
            " x\u{308} − (½ ℓ cos θ) θ̈ = −½ ℓ sin θ θ̇²",
            " a₂₃ = −½ ℓ sin θ",
            " b₂ = ½ ℓ cos θ θ̇²",
        ] {
            assert!(doc.iter().any(|l| l == line), "{line} missing");
        }
        assert!(
            !doc.iter().any(|l| l.starts_with(" a₁₂")),
            "zero entries are listed"
        );
        let latex = equations_text(
            &model,
            &equations,
            &mut pool,
            &mut ReadableForms::default(),
            Style::Latex,
        );
        assert!(latex.starts_with("% Equations of motion of ConstrainedPendulum\n"));
        for line in [
            "m \\ddot{x} &= \\lambda_{1} \\\\",
            "(\\frac{1}{12} m \\ell^{2}) \\ddot{\\theta} &= M - (\\frac{1}{2} \\ell \\cos \\theta) \\lambda_{1} \
             - (\\frac{1}{2} \\ell \\sin \\theta) \\lambda_{2} \\\\",
        ] {
            assert!(
                latex.lines().any(|l| l == line),
                "{line} missing from\n{latex}"
            );
        }
        assert_eq!(
            latex.matches("\\begin{aligned}").count(),
            latex.matches("\\end{aligned}").count()
        );
    }

    #[test]
    fn unicode_text_for_the_command_line() {
        let (model, equations, mut pool) = derive(DOUBLE_PENDULUM);
        let text = equations_text(
            &model,
            &equations,
            &mut pool,
            &mut ReadableForms::default(),
            Style::Unicode,
        );
        assert!(text.starts_with(
            "Equations of motion of DoublePendulum\nDerived with d'Alembert's principle"
        ));
        assert!(text.contains("\n  M₁₁ = 4/3 m L²\n"), "{text}");
        assert!(!text.contains('`') && !text.contains("```"));
    }

    /// A planar chain of `n` links, angles absolute or relative to the
    /// previous link.
    fn chain(n: usize, relative: bool) -> String {
        let coordinates: Vec<String> = (1..=n).map(|i| format!("q{i}")).collect();
        let mut s = format!(
            "pub Chain {{ parameters m, L, g; coordinates {};",
            coordinates.join(", ")
        );
        for i in 1..=n {
            let parent = if relative && i > 1 {
                format!("B{}", i - 1)
            } else {
                "N".to_string()
            };
            let base = if i > 1 {
                format!("P{}", i - 1)
            } else {
                "O".to_string()
            };
            s += &format!(
                "frame B{i} = {parent}.rotate_z(q{i}); point P{i} = {base} - L * B{i}.y; \
                 point G{i} = {base} - L/2 * B{i}.y; \
                 body link{i} {{ mass: m, center: G{i}, frame: B{i}, inertia: [0, 0, m*L^2/12] }};"
            );
        }
        s + "gravity -g * N.y; }"
    }

    #[test]
    fn thirty_link_chains_stay_bounded() {
        for relative in [false, true] {
            let (model, equations, mut pool) = derive(&chain(30, relative));
            let (doc, _) =
                equations_doc(&model, &equations, &mut pool, &mut ReadableForms::default());
            let size: usize = doc.iter().map(String::len).sum();
            assert!(size < 400_000, "{size} bytes");
            let rows = rows(&doc);
            assert_eq!(rows.len(), 30);
            if relative {
                assert!(rows[0].starts_with("M₁₁ q̈₁ + M₁₂ q̈₂"), "{}", rows[0]);
                assert!(
                    doc.iter()
                        .any(|l| l == " M₁₁ = (large: more than 8 terms, see the generated code)")
                );
            } else {
                assert!(
                    rows[0].starts_with("(88/3 m L²) q̈₁ + (57/2 m L² cos(q₂ − q₁)) q̈₂"),
                    "{}",
                    rows[0]
                );
            }
        }
    }
}
