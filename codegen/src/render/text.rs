//! Printers of readable expressions in the seed document's notation, as
//! Unicode text (`½ m L² cos(θ₂ − θ₁) θ̇₂²`) or LaTeX
//! (`\frac{1}{2} m L^{2} \cos(\theta_{2} - \theta_{1}) \dot{\theta}_{2}^{2}`).
//!
//! One walker prints both, driven by a [`Notation`] table. Conventions:
//!
//! * names that spell a Greek letter print as the letter (`theta1` → `θ₁`,
//!   `Omega` → `Ω`, `l` → `ℓ` as in the seed); trailing digits become a
//!   subscript and `_` starts one (`M_phi` → `M_φ`); speeds are dotted
//!   (`θ̇₁`), accelerations double-dotted (`θ̈₁`), a stem of several letters
//!   takes Leibniz's notation instead (`d(FL_HFE)/dt`), multipliers are
//!   `λ₁…`;
//! * coefficients are fractions (`½`, `3/2`), products are juxtaposed with
//!   spaces, factors ordered parameters, inputs, `t`, coordinates, functions,
//!   speeds, accelerations, multipliers, then negative powers; integer
//!   powers are superscripts, negative ones included (`g L⁻¹`);
//! * terms with more speeds come first, then positive before negative
//!   ones; `sin θ₁` takes no parentheses, `sin(θ₂ − θ₁)` does, and a
//!   difference is oriented so that its highest-indexed symbol is positive
//!   (`cos(θ₂ − θ₁)`; for `sin` the sign moves to the term).
//!
//! Printing is bounded: nesting deeper than [`MAX_DEPTH`] or output longer
//! than [`MAX_LEN`] is cut off with an ellipsis, so no input can make the
//! printer overflow the stack or run for long.

use std::cmp::Reverse;
use std::fmt::Display;

use crate::expr::{ExprId, Func, Node, Number, Pool, Rational, Sym, SymKinds};
use crate::readable::factors;

/// Numerators and denominators below this are written as fractions
/// (`1/12`, `4/3`); larger ones as decimals.
const READABLE_FRACTION: i128 = 10_000;

/// Deepest nesting of parentheses and calls printed in full.
const MAX_DEPTH: usize = 64;

/// Longest output, in bytes, printed in full.
const MAX_LEN: usize = 1 << 20;

/// The notation to print in, and for a whole rendering its layout.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Style {
    /// Unicode text: `½ m L² cos(θ₂ − θ₁)`.
    Unicode,
    /// LaTeX math: `\frac{1}{2} m L^{2} \cos(\theta_{2} - \theta_{1})`; a
    /// rendering is one complete `align*` environment (amsmath), its
    /// sections' titles as `\intertext`.
    Latex,
    /// LaTeX math; a rendering is the bare rows `lhs &= rhs \\` to paste
    /// into an environment of one's own, its titles as `%` comments.
    LatexInline,
    /// LaTeX math; a rendering is Markdown for a README: a heading, the
    /// form in `$…$`, and each section in a fenced `math` block
    /// (`aligned`), as GitHub and most Markdown renderers show it.
    Markdown,
}

impl Style {
    /// The notation of the expressions: Unicode, or LaTeX for every
    /// LaTeX layout.
    pub fn math(self) -> Style {
        match self {
            Style::Unicode => Style::Unicode,
            Style::Latex | Style::LatexInline | Style::Markdown => Style::Latex,
        }
    }
}

/// `e` in Unicode text (see the module docs).
pub fn unicode(pool: &Pool, e: ExprId, names: &SymbolNames) -> String {
    expression(pool, e, names, Style::Unicode)
}

/// `e` in LaTeX (see the module docs).
pub fn latex(pool: &Pool, e: ExprId, names: &SymbolNames) -> String {
    expression(pool, e, names, Style::Latex)
}

/// `e` in `style`.
fn expression(pool: &Pool, e: ExprId, names: &SymbolNames, style: Style) -> String {
    let mut walker = Walker::new(pool, names, style);
    walker.expr(e);
    walker.out
}

/// A coefficient in a [`linear_combination`].
#[derive(Clone, Debug, PartialEq)]
pub enum Coefficient {
    /// A (readable) expression.
    Expr(ExprId),
    /// An expression too large to show, printed as this label (`M₁₂`).
    Named(String),
}

/// `leading + Σ cᵢ vᵢ` in the seed's style: `(½ m L² cos(θ₂ − θ₁)) θ̈₂`,
/// `m ẍ`, `θ̈`, `− (½ ℓ cos θ) λ₁`; zero coefficients are left out, and an
/// empty combination is `0`.
pub fn linear_combination(
    pool: &Pool,
    leading: Option<&Coefficient>,
    terms: &[(Coefficient, Sym)],
    names: &SymbolNames,
    style: Style,
) -> String {
    let mut walker = Walker::new(pool, names, style);
    if let Some(leading) = leading {
        walker.coefficient_alone(leading);
    }
    for (c, variable) in terms {
        walker.scaled_variable(c, *variable);
    }
    if walker.out.is_empty() {
        walker.out.push('0');
    }
    walker.out
}

/// `base` with 1-based `indices` as a subscript: `M₁₂`, `M_{12}`; indices
/// past 9 are separated by commas (`M₁₀,₁₁`).
pub fn label(base: &str, indices: &[usize], style: Style) -> String {
    let separator = if indices.iter().any(|&i| i > 9) {
        ","
    } else {
        ""
    };
    let digits: Vec<String> = indices.iter().map(usize::to_string).collect();
    let mut out = base.to_string();
    (style.notation().subscript)(&mut out, &digits.join(separator));
    out
}

/// How symbols are named: the identifiers of a model's parameters,
/// coordinates and inputs, read as described in the module docs.
#[derive(Clone, Debug)]
pub struct SymbolNames {
    parameters: Vec<Name>,
    coordinates: Vec<Name>,
    inputs: Vec<Name>,
    /// Speeds that are not their coordinate's rate, by index: each speed's
    /// name and dots (empty when every speed is `q̇ᵢ`).
    speeds: Vec<(Name, usize)>,
}

impl SymbolNames {
    /// Names from the identifiers as written (raw `r#` prefixes dropped).
    pub fn new(
        parameters: &[impl Display],
        coordinates: &[impl Display],
        inputs: &[impl Display],
    ) -> SymbolNames {
        SymbolNames {
            parameters: parameters
                .iter()
                .map(|id| Name::parse(&id.to_string()))
                .collect(),
            coordinates: coordinates
                .iter()
                .map(|id| Name::parse(&id.to_string()))
                .collect(),
            inputs: inputs
                .iter()
                .map(|id| Name::parse(&id.to_string()))
                .collect(),
            speeds: Vec::new(),
        }
    }

    /// The names of the speeds, as `(name, whether it is the rate of the
    /// coordinate called name)`, for systems with speeds of their own.
    pub fn with_speeds<'a>(
        mut self,
        speeds: impl IntoIterator<Item = (&'a dyn Display, bool)>,
    ) -> SymbolNames {
        self.speeds = speeds
            .into_iter()
            .map(|(id, rate)| (Name::parse(&id.to_string()), usize::from(rate)))
            .collect();
        self
    }

    /// The name of `sym` and its number of dots; symbols past the lists
    /// get `p₇`, `q₇`, `u₇`.
    fn of(&self, sym: Sym) -> (Name, usize) {
        let lookup = |list: &[Name], i: u32, fallback: &str| {
            let i = i as usize;
            list.get(i)
                .cloned()
                .unwrap_or_else(|| Name::indexed(Word::text(fallback), i))
        };
        match sym {
            Sym::Time => (Name::plain(Word::text("t")), 0),
            Sym::Param(i) => (lookup(&self.parameters, i, "p"), 0),
            Sym::Input(i) => (lookup(&self.inputs, i, "u"), 0),
            Sym::Coord(i) => (lookup(&self.coordinates, i, "q"), 0),
            Sym::Speed(i) | Sym::Accel(i) if !self.speeds.is_empty() => {
                let (name, dots) = self.speeds[i as usize].clone();
                (name, dots + usize::from(matches!(sym, Sym::Accel(_))))
            }
            Sym::Speed(i) => (lookup(&self.coordinates, i, "q"), 1),
            Sym::Accel(i) => (lookup(&self.coordinates, i, "q"), 2),
            Sym::Multiplier(i) => (Name::indexed(Word::Letter(&LAMBDA), i as usize), 0),
        }
    }
}

/// A letter with a Unicode and a LaTeX form.
#[derive(Debug, PartialEq, Eq)]
struct Letter {
    /// The spelling in identifiers.
    spelled: &'static str,
    unicode: &'static str,
    latex: &'static str,
}

/// The letter spelled `spelled`.
const fn letter(spelled: &'static str, unicode: &'static str, latex: &'static str) -> Letter {
    Letter {
        spelled,
        unicode,
        latex,
    }
}

/// `λ`, for multipliers.
const LAMBDA: Letter = letter("lambda", "λ", "\\lambda");

/// Letters spelled out in identifiers: Greek (capitals only where they
/// differ from Latin ones) and the seed's `ℓ`.
const LETTERS: &[Letter] = &[
    letter("alpha", "α", "\\alpha"),
    letter("beta", "β", "\\beta"),
    letter("gamma", "γ", "\\gamma"),
    letter("delta", "δ", "\\delta"),
    letter("epsilon", "ε", "\\epsilon"),
    letter("zeta", "ζ", "\\zeta"),
    letter("eta", "η", "\\eta"),
    letter("theta", "θ", "\\theta"),
    letter("iota", "ι", "\\iota"),
    letter("kappa", "κ", "\\kappa"),
    LAMBDA,
    letter("mu", "μ", "\\mu"),
    letter("nu", "ν", "\\nu"),
    letter("xi", "ξ", "\\xi"),
    letter("omicron", "ο", "o"),
    letter("pi", "π", "\\pi"),
    letter("rho", "ρ", "\\rho"),
    letter("sigma", "σ", "\\sigma"),
    letter("tau", "τ", "\\tau"),
    letter("upsilon", "υ", "\\upsilon"),
    letter("phi", "φ", "\\phi"),
    letter("chi", "χ", "\\chi"),
    letter("psi", "ψ", "\\psi"),
    letter("omega", "ω", "\\omega"),
    letter("Gamma", "Γ", "\\Gamma"),
    letter("Delta", "Δ", "\\Delta"),
    letter("Theta", "Θ", "\\Theta"),
    letter("Lambda", "Λ", "\\Lambda"),
    letter("Xi", "Ξ", "\\Xi"),
    letter("Pi", "Π", "\\Pi"),
    letter("Sigma", "Σ", "\\Sigma"),
    letter("Upsilon", "Υ", "\\Upsilon"),
    letter("Phi", "Φ", "\\Phi"),
    letter("Psi", "Ψ", "\\Psi"),
    letter("Omega", "Ω", "\\Omega"),
    letter("l", "ℓ", "\\ell"),
];

/// A part of a name: a spelled-out letter or text as written.
#[derive(Clone, Debug, PartialEq, Eq)]
enum Word {
    Letter(&'static Letter),
    Text(String),
}

impl Word {
    /// The word `s`: a letter if it spells one.
    fn of(s: &str) -> Word {
        match LETTERS.iter().find(|l| l.spelled == s) {
            Some(letter) => Word::Letter(letter),
            None => Word::text(s),
        }
    }

    /// `s` as written.
    fn text(s: &str) -> Word {
        Word::Text(s.to_string())
    }

    /// Whether the word is text of more than one letter (`mass`, `FL`),
    /// which reads as a product of letters where a letter would not.
    fn is_several_letters(&self) -> bool {
        matches!(self, Word::Text(t) if t.chars().count() > 1)
    }
}

/// An identifier read as `stem_label123`: a stem, an optional word
/// subscript and optional subscript digits.
#[derive(Clone, Debug, PartialEq, Eq)]
struct Name {
    stem: Word,
    label: Option<Word>,
    digits: String,
}

impl Name {
    /// `stem` alone.
    fn plain(stem: Word) -> Name {
        Name {
            stem,
            label: None,
            digits: String::new(),
        }
    }

    /// `stem` with the 1-based index `i + 1`.
    fn indexed(stem: Word, i: usize) -> Name {
        Name {
            stem,
            label: None,
            digits: (i + 1).to_string(),
        }
    }

    /// Reads an identifier: trailing digits (after an optional `_`) are
    /// the index, a `_` inside splits stem and label, and a short name
    /// that spells no letter is a letter with a subscript (`I1c` → `I_{1c}`,
    /// `xp` → `x_p`, as `m_B` → `m_B`: see [`Name::short`]).
    fn parse(ident: &str) -> Name {
        let ident = ident.strip_prefix("r#").unwrap_or(ident);
        let body = ident.trim_end_matches(|c: char| c.is_ascii_digit());
        let digits = ident[body.len()..].to_string();
        let body = match digits.is_empty() {
            true => body,
            false => body.strip_suffix('_').unwrap_or(body),
        };
        match body.split_once('_') {
            _ if body.is_empty() => Name::plain(Word::text(ident)),
            Some((stem, label)) if !stem.is_empty() && !label.is_empty() => Name {
                stem: Word::of(stem),
                label: Some(Word::of(label)),
                digits,
            },
            _ => Name::short(body, &digits).unwrap_or(Name {
                stem: Word::of(body),
                label: None,
                digits,
            }),
        }
    }

    /// `body` (with the index `digits`) read as a letter and a subscript,
    /// when it spells no letter of its own and the subscript is one
    /// character, or two with a digit, a capital or axes (`xyz`): the usual
    /// reading of `xp`, `mp`, `I1c`, `IA` or `Ixy` in mechanics, and the
    /// one whose rate takes dots (`ẋ_p`). Words (`mass`, `arm`) stay words.
    fn short(body: &str, digits: &str) -> Option<Name> {
        let mut chars = body.chars();
        let first = chars.next().filter(char::is_ascii_alphabetic)?;
        let rest = chars.as_str();
        let spells_a_letter = LETTERS.iter().any(|l| l.spelled == body);
        let subscript = match rest.chars().count() {
            1 => true,
            2 => {
                rest.chars()
                    .any(|c| c.is_ascii_digit() || c.is_ascii_uppercase())
                    || rest.chars().all(|c| "xyz".contains(c))
            }
            _ => false,
        };
        if !subscript || spells_a_letter {
            return None;
        }
        Some(Name {
            stem: Word::of(&first.to_string()),
            label: Some(Word::text(rest)),
            digits: digits.to_string(),
        })
    }

    /// Whether its rate is written in Leibniz's notation (a stem of
    /// several letters, see [`unicode_name`]).
    fn is_leibniz(&self, dots: usize) -> bool {
        dots > 0 && self.stem.is_several_letters()
    }
}

/// The longest subscript a short name is read with ([`Name::short`]).
const SHORT_SUBSCRIPT: usize = 2;

/// How a function call is written.
enum Call {
    /// `name x` or `name(x + y)`; trigonometric powers go on the name.
    Operator(&'static str, &'static str),
    /// `open x close`, always delimited (`|x|`, `\sqrt{x}`).
    Enclosed(&'static str, &'static str),
}

/// Everything the walker writes differently per [`Style`].
struct Notation {
    minus: &'static str,
    ellipsis: &'static str,
    superscript: fn(&mut String, i32),
    subscript: fn(&mut String, &str),
    fraction: fn(&mut String, Rational),
    /// Writes a name differentiated 0, 1 or 2 times: its stem, dotted, then
    /// its word subscript (`_φ`, `_{\phi}`) and digits if any.
    name: fn(&mut String, &Name, usize),
    call: fn(Func) -> Call,
    /// What encloses a group (a collected sum).
    parentheses: (&'static str, &'static str),
    /// Between two factors when one is a name of several letters, which a
    /// plain space would read as a product of letters (`m ma`).
    word_times: &'static str,
    /// Whether the rates of stems of several letters take Leibniz's
    /// notation (see [`unicode_name`]).
    leibniz: bool,
}

impl Style {
    /// The notation table of this style.
    fn notation(self) -> &'static Notation {
        match self.math() {
            Style::Unicode => &UNICODE,
            _ => &LATEX,
        }
    }
}

/// Unicode text.
const UNICODE: Notation = Notation {
    minus: "−",
    ellipsis: "…",
    superscript: unicode_superscript,
    subscript: unicode_subscript,
    fraction: unicode_fraction,
    name: unicode_name,
    call: unicode_call,
    parentheses: ("(", ")"),
    word_times: "·",
    leibniz: true,
};

/// LaTeX math.
const LATEX: Notation = Notation {
    minus: "-",
    ellipsis: "\\dots",
    superscript: latex_superscript,
    subscript: latex_subscript,
    fraction: latex_fraction,
    name: latex_name,
    call: latex_call,
    parentheses: ("\\left(", "\\right)"),
    word_times: " ",
    leibniz: false,
};

/// `²`, `⁻¹`.
fn unicode_superscript(out: &mut String, n: i32) {
    let digits = n.to_string();
    out.extend(
        digits
            .chars()
            .map(|c| map_char(c, "-0123456789", "⁻⁰¹²³⁴⁵⁶⁷⁸⁹")),
    );
}

/// `₁₂`.
fn unicode_subscript(out: &mut String, digits: &str) {
    out.extend(
        digits
            .chars()
            .map(|c| map_char(c, "0123456789", "₀₁₂₃₄₅₆₇₈₉")),
    );
}

/// `½`, or `3/2` where there is no vulgar fraction.
fn unicode_fraction(out: &mut String, r: Rational) {
    match VULGAR.iter().find(|&&(n, d, _)| (n, d) == (r.num, r.den)) {
        Some((_, _, glyph)) => out.push_str(glyph),
        None => out.push_str(&format!("{}/{}", r.num, r.den)),
    }
}

/// `θ`, `m`, `mass`.
fn unicode_word(out: &mut String, word: &Word) {
    match word {
        Word::Letter(l) => out.push_str(l.unicode),
        Word::Text(t) => out.push_str(t),
    }
}

/// `θ₁`, `θ̇₁`, `θ̈₁` (combining dots after the stem); a stem of several
/// letters, where a combining dot would sit on its last letter alone
/// (`FL_HFE` read as `FL̈_HFE`), takes the rate in Leibniz's notation:
/// `d(FL_HFE)/dt`, `d²(FL_HFE)/dt²`.
fn unicode_name(out: &mut String, name: &Name, dots: usize) {
    if name.is_leibniz(dots) {
        let order = if dots == 1 { "" } else { "²" };
        out.push_str(&format!("d{order}("));
        unicode_name(out, name, 0);
        out.push_str(&format!(")/dt{order}"));
        return;
    }
    unicode_word(out, &name.stem);
    out.extend(["", "\u{307}", "\u{308}"].get(dots).copied());
    unicode_labelled(out, name.label.as_ref(), &name.digits);
}

/// `_φ₂`.
fn unicode_labelled(out: &mut String, label: Option<&Word>, digits: &str) {
    if let Some(label) = label {
        out.push('_');
        unicode_word(out, label);
    }
    unicode_subscript(out, digits);
}

/// `sin θ`, `√x`, `|x|`.
fn unicode_call(f: Func) -> Call {
    match f {
        Func::Sqrt => Call::Operator("√", ""),
        Func::Abs => Call::Enclosed("|", "|"),
        _ => Call::Operator(f.name(), " "),
    }
}

/// `^{2}`.
fn latex_superscript(out: &mut String, n: i32) {
    out.push_str(&format!("^{{{n}}}"));
}

/// `_{12}` (nothing for no digits).
fn latex_subscript(out: &mut String, digits: &str) {
    if !digits.is_empty() {
        out.push_str(&format!("_{{{digits}}}"));
    }
}

/// `\frac{1}{2}`.
fn latex_fraction(out: &mut String, r: Rational) {
    out.push_str(&format!("\\frac{{{}}}{{{}}}", r.num, r.den));
}

/// `\theta`, `m`, `\mathrm{mass}`.
fn latex_word(out: &mut String, word: &Word) {
    match word {
        Word::Letter(l) => out.push_str(l.latex),
        Word::Text(t) if t.chars().count() == 1 => out.push_str(t),
        Word::Text(t) => out.push_str(&format!("\\mathrm{{{}}}", t.replace('_', "\\_"))),
    }
}

/// A subscript word: [`latex_word`], but a short one (as [`Name::short`]
/// reads) in math italic like its stem, `I_{1c}`, `x_{p}`.
fn latex_label(out: &mut String, word: &Word) {
    match word {
        Word::Text(t) if t.chars().count() <= SHORT_SUBSCRIPT => out.push_str(t),
        _ => latex_word(out, word),
    }
}

/// `\theta_{1}`, `\dot{\theta}_{1}`, `\ddot{\theta}_{1}` (an accent is
/// centred over a stem of several letters, `\dot{\mathrm{FL}}`).
fn latex_name(out: &mut String, name: &Name, dots: usize) {
    let accent = ["", "\\dot{", "\\ddot{"].get(dots).copied().unwrap_or("");
    out.push_str(accent);
    latex_word(out, &name.stem);
    if !accent.is_empty() {
        out.push('}');
    }
    latex_labelled(out, name.label.as_ref(), &name.digits);
}

/// `_{\phi,2}`.
fn latex_labelled(out: &mut String, label: Option<&Word>, digits: &str) {
    let mut inner = String::new();
    if let Some(label) = label {
        latex_label(&mut inner, label);
        if !digits.is_empty() {
            inner.push(',');
        }
    }
    inner.push_str(digits);
    latex_subscript(out, &inner);
}

/// `\sin \theta`, `\sqrt{x}`, `\left|x\right|`.
fn latex_call(f: Func) -> Call {
    match f {
        Func::Sqrt => Call::Enclosed("\\sqrt{", "}"),
        Func::Abs => Call::Enclosed("\\left|", "\\right|"),
        Func::Sin => Call::Operator("\\sin", " "),
        Func::Cos => Call::Operator("\\cos", " "),
        Func::Tan => Call::Operator("\\tan", " "),
        Func::Exp => Call::Operator("\\exp", " "),
        Func::Ln => Call::Operator("\\ln", " "),
    }
}

/// Unicode vulgar fractions.
const VULGAR: &[(i128, i128, &str)] = &[
    (1, 2, "½"),
    (1, 3, "⅓"),
    (2, 3, "⅔"),
    (1, 4, "¼"),
    (3, 4, "¾"),
    (1, 5, "⅕"),
    (2, 5, "⅖"),
    (3, 5, "⅗"),
    (4, 5, "⅘"),
    (1, 6, "⅙"),
    (5, 6, "⅚"),
    (1, 7, "⅐"),
    (1, 8, "⅛"),
    (3, 8, "⅜"),
    (5, 8, "⅝"),
    (7, 8, "⅞"),
    (1, 9, "⅑"),
    (1, 10, "⅒"),
];

/// `c` mapped from `from` to the character at the same position in `to`
/// (itself if absent).
fn map_char(c: char, from: &str, to: &str) -> char {
    from.chars()
        .position(|x| x == c)
        .and_then(|i| to.chars().nth(i))
        .unwrap_or(c)
}

/// One factor of a printed monomial: `base^exp`, with the argument of an
/// odd or even function, or a sum, negated when `flipped`.
#[derive(Clone, Copy, Debug)]
struct Factor {
    base: ExprId,
    exp: i32,
    flipped: bool,
}

/// A monomial as printed: its signed coefficient (after moving the signs
/// of flipped odd functions into it) and its factors in print order.
#[derive(Clone, Debug)]
struct Term {
    coefficient: Number,
    factors: Vec<Factor>,
}

impl Term {
    /// The printed form of monomial `e`, negated if `negate`.
    fn of(pool: &Pool, e: ExprId, negate: bool) -> Term {
        let (c, rest) = pool.split_coefficient(e);
        let mut coefficient = if negate { -c } else { c };
        let mut factors: Vec<Factor> = factors(pool, rest)
            .into_iter()
            .map(|(base, exp)| {
                let (flipped, odd) = orientation(pool, base);
                if flipped && odd && exp % 2 != 0 {
                    coefficient = -coefficient;
                }
                Factor { base, exp, flipped }
            })
            .collect();
        factors.sort_by_key(|f| (f.exp < 0, factor_order(pool, f.base, f.exp)));
        // The pool holds `c − b` as `−(b − c)`: a negative term's sign goes
        // into its one sum of both signs, `+ ½ (c − b) m`, not `− ½ (b − c) m`.
        if coefficient.is_negative()
            && let [sum] = factors
                .iter_mut()
                .filter(|f| f.exp == 1 && has_both_signs(pool, f.base))
                .collect::<Vec<_>>()
                .as_mut_slice()
        {
            coefficient = -coefficient;
            sum.flipped = true;
        }
        Term {
            coefficient,
            factors,
        }
    }

    /// Total degree in speeds, accelerations and multipliers: such terms
    /// print first.
    fn rate_degree(&self, pool: &Pool) -> i64 {
        self.factors
            .iter()
            .filter(|f| factor_order(pool, f.base, f.exp).0 >= FactorClass::Speed)
            .map(|f| i64::from(f.exp))
            .sum()
    }

    /// The number of factors that are not parameters.
    fn varying_factors(&self, pool: &Pool) -> usize {
        self.factors
            .iter()
            .filter(|f| factor_order(pool, f.base, f.exp).0 != FactorClass::Param)
            .count()
    }
}

/// Whether `e` is a sum (or a group of one) with a positive and a
/// negative term.
fn has_both_signs(pool: &Pool, e: ExprId) -> bool {
    let terms = match pool.node(e) {
        Node::Add(terms) => terms,
        Node::Group(sum) => return has_both_signs(pool, *sum),
        _ => return false,
    };
    let negative = |&t: &ExprId| pool.split_coefficient(t).0.is_negative();
    terms.iter().any(negative) && !terms.iter().all(negative)
}

/// Whether the argument of `base`, an odd or even function, prints
/// negated, and whether the function is odd. The argument is negated when
/// the term holding its greatest symbol is negative, so `cos(θ₁ − θ₂)`
/// prints as `cos(θ₂ − θ₁)`.
fn orientation(pool: &Pool, base: ExprId) -> (bool, bool) {
    let (odd, arg) = match *pool.node(base) {
        Node::Func(Func::Sin | Func::Tan, arg) => (true, arg),
        Node::Func(Func::Cos, arg) => (false, arg),
        _ => return (false, false),
    };
    let terms: &[ExprId] = match pool.node(arg) {
        Node::Add(terms) => terms,
        _ => std::slice::from_ref(&arg),
    };
    let leading = terms
        .iter()
        .max_by_key(|&&t| (greatest_symbol(pool, t), Reverse(t)));
    let negative = leading.is_some_and(|&t| pool.split_coefficient(t).0.is_negative());
    (negative, odd)
}

/// The greatest symbol among the factors of monomial `t`, if any.
fn greatest_symbol(pool: &Pool, t: ExprId) -> Option<Sym> {
    let (_, rest) = pool.split_coefficient(t);
    factors(pool, rest)
        .into_iter()
        .filter_map(|(base, _)| match pool.node(base) {
            Node::Sym(s) => Some(*s),
            _ => None,
        })
        .max()
}

/// Print order of factors (after the sign of the exponent: divisors go
/// last): by class, then symbol, then id.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum FactorClass {
    Param,
    Input,
    Time,
    Coord,
    Composite,
    Speed,
    Accel,
    Multiplier,
}

/// The sort key of a factor `base^exp`: by class, parameters to the first
/// power before powers of parameters (so `m r²` and `m L²` print alike,
/// whatever the declaration order), then symbol, then id.
fn factor_order(pool: &Pool, base: ExprId, exp: i32) -> (FactorClass, bool, Option<Sym>, ExprId) {
    let Node::Sym(s) = *pool.node(base) else {
        // A collected sum of parameters leads the parameters.
        let parameters =
            matches!(pool.node(base), Node::Group(_)) && SymKinds::PARAM.contains(pool.kinds(base));
        let class = match parameters {
            true => FactorClass::Param,
            false => FactorClass::Composite,
        };
        return (class, false, None, base);
    };
    let class = match s {
        Sym::Param(_) => FactorClass::Param,
        Sym::Input(_) => FactorClass::Input,
        Sym::Time => FactorClass::Time,
        Sym::Coord(_) => FactorClass::Coord,
        Sym::Speed(_) => FactorClass::Speed,
        Sym::Accel(_) => FactorClass::Accel,
        Sym::Multiplier(_) => FactorClass::Multiplier,
    };
    let raised = class == FactorClass::Param && exp.abs() > 1;
    (class, raised, Some(s), base)
}

/// The printer: one pass over an expression tree, writing into `out`.
struct Walker<'a> {
    pool: &'a Pool,
    names: &'a SymbolNames,
    notation: &'static Notation,
    out: String,
    depth: usize,
    truncated: bool,
}

impl<'a> Walker<'a> {
    fn new(pool: &'a Pool, names: &'a SymbolNames, style: Style) -> Walker<'a> {
        Walker {
            pool,
            names,
            notation: style.notation(),
            out: String::new(),
            depth: 0,
            truncated: false,
        }
    }

    /// Whether to stop here: too deep or too long. Writes the ellipsis
    /// once.
    fn cut_off(&mut self) -> bool {
        if !self.truncated && (self.depth > MAX_DEPTH || self.out.len() > MAX_LEN) {
            self.out.push_str(self.notation.ellipsis);
            self.truncated = true;
        }
        self.truncated
    }

    /// Writes `e`, its terms negated if `negate`; `−s` for a sum `s` is
    /// written as the terms of `s` negated ([`Pool::negated_sum`]).
    fn expr_signed(&mut self, e: ExprId, negate: bool) {
        if self.cut_off() {
            return;
        }
        self.depth += 1;
        let (e, negate) = match self.pool.negated_sum(e) {
            Some(sum) => (sum, !negate),
            None => (e, negate),
        };
        let terms: &[ExprId] = match self.pool.node(e) {
            Node::Add(terms) => terms,
            _ => std::slice::from_ref(&e),
        };
        let mut printed: Vec<Term> = terms
            .iter()
            .map(|&t| Term::of(self.pool, t, negate))
            .collect();
        printed.sort_by_cached_key(|t| {
            (
                Reverse(t.rate_degree(self.pool)),
                t.coefficient.is_negative(),
                t.varying_factors(self.pool),
            )
        });
        for (i, term) in printed.iter().enumerate() {
            self.sign(term.coefficient.is_negative(), i == 0);
            self.magnitude(term);
        }
        self.depth -= 1;
    }

    /// Writes `e`.
    fn expr(&mut self, e: ExprId) {
        self.expr_signed(e, false);
    }

    /// Writes the sign before a term: `−x`, ` + x`, ` − x`.
    fn sign(&mut self, negative: bool, first: bool) {
        match (first, negative) {
            (true, false) => {}
            (true, true) => self.out.push_str(self.notation.minus),
            (false, false) => self.out.push_str(" + "),
            (false, true) => {
                self.out.push(' ');
                self.out.push_str(self.notation.minus);
                self.out.push(' ');
            }
        }
    }

    /// Writes `|c| · Π factors`.
    fn magnitude(&mut self, term: &Term) {
        let c = term.coefficient.abs();
        if term.factors.is_empty() || !c.is_one() {
            self.number(c);
        }
        for (i, factor) in term.factors.iter().enumerate() {
            let after_word = i > 0 && self.is_word(term.factors[i - 1]);
            if after_word || (i > 0 && self.is_word(*factor)) {
                self.out.push_str(self.notation.word_times);
            } else if i > 0 || !c.is_one() {
                self.out.push(' ');
            }
            self.factor(*factor);
        }
    }

    /// Whether `factor` is a symbol named by a word of several letters
    /// (not a Greek letter's name).
    fn is_word(&self, factor: Factor) -> bool {
        match *self.pool.node(factor.base) {
            Node::Sym(s) => self.names.of(s).0.stem.is_several_letters(),
            _ => false,
        }
    }

    /// Writes a non-negative number: `3`, `½`, `\frac{3}{2}`, `0.1`. A
    /// fraction of long numbers (the exact value of a decimal literal such
    /// as a robot's inertia, `751063428762144027/1000000000000000000`) is
    /// written as the nearest `f64`, the value the generated code uses.
    fn number(&mut self, n: Number) {
        match n.as_rational() {
            Some(r) if r.is_integer() => self.out.push_str(&n.to_string()),
            Some(r) if r.num.abs() < READABLE_FRACTION && r.den < READABLE_FRACTION => {
                (self.notation.fraction)(&mut self.out, r)
            }
            _ => self.out.push_str(&format!("{:?}", n.to_f64())),
        }
    }

    /// Writes one factor `base^exp`; a rate in Leibniz's notation raised
    /// to a power is parenthesised (`(d(FL)/dt)²`, not `d(FL)/dt²`).
    fn factor(&mut self, Factor { base, exp, flipped }: Factor) {
        match *self.pool.node(base) {
            Node::Sym(s) => {
                let (name, dots) = self.names.of(s);
                let enclosed = exp != 1 && self.notation.leibniz && name.is_leibniz(dots);
                if enclosed {
                    self.out.push('(');
                }
                self.symbol(s);
                if enclosed {
                    self.out.push(')');
                }
                self.power(exp);
            }
            Node::Func(f, arg) => self.call(f, arg, exp, flipped),
            Node::Group(sum) => self.enclosed(self.notation.parentheses, sum, exp, flipped),
            _ => {
                self.parenthesised(base, flipped);
                self.power(exp);
            }
        }
    }

    /// Writes a superscript unless `exp` is one.
    fn power(&mut self, exp: i32) {
        if exp != 1 {
            (self.notation.superscript)(&mut self.out, exp);
        }
    }

    /// Writes `(e)`, negated if `negate`.
    fn parenthesised(&mut self, e: ExprId, negate: bool) {
        self.out.push('(');
        self.expr_signed(e, negate);
        self.out.push(')');
    }

    /// Writes a symbol's name.
    fn symbol(&mut self, s: Sym) {
        let (name, dots) = self.names.of(s);
        (self.notation.name)(&mut self.out, &name, dots);
    }

    /// Writes `f(arg)^exp`: `sin θ`, `sin²(θ₂ − θ₁)`, `(ln x)²`, `|x|⁻¹`.
    fn call(&mut self, f: Func, arg: ExprId, exp: i32, flipped: bool) {
        match (self.notation.call)(f) {
            Call::Enclosed(open, close) => self.enclosed((open, close), arg, exp, flipped),
            Call::Operator(name, gap)
                if exp > 0 && matches!(f, Func::Sin | Func::Cos | Func::Tan) =>
            {
                self.out.push_str(name);
                self.power(exp);
                // `sin²φ`: the superscript already separates.
                self.operand(arg, if exp == 1 { gap } else { "" }, flipped);
            }
            Call::Operator(name, gap) if exp == 1 => {
                self.out.push_str(name);
                self.operand(arg, gap, flipped);
            }
            Call::Operator(name, gap) => {
                self.out.push('(');
                self.out.push_str(name);
                self.operand(arg, gap, flipped);
                self.out.push(')');
                self.power(exp);
            }
        }
    }

    /// Writes `open arg close^exp`, the argument negated if `flipped`.
    fn enclosed(&mut self, (open, close): (&str, &str), arg: ExprId, exp: i32, flipped: bool) {
        self.out.push_str(open);
        self.expr_signed(arg, flipped);
        self.out.push_str(close);
        self.power(exp);
    }

    /// Writes the operand of an operator: `θ₁` after a gap if it is a
    /// symbol, else parenthesised.
    fn operand(&mut self, arg: ExprId, gap: &str, flipped: bool) {
        match *self.pool.node(arg) {
            Node::Sym(s) if !flipped => {
                self.out.push_str(gap);
                self.symbol(s);
            }
            _ => self.parenthesised(arg, flipped),
        }
    }

    /// Writes a coefficient standing alone, as the first part of a
    /// combination.
    fn coefficient_alone(&mut self, c: &Coefficient) {
        match c {
            Coefficient::Expr(e) if self.pool.is_zero(*e) => {}
            Coefficient::Expr(e) => self.expr(*e),
            Coefficient::Named(label) => self.out.push_str(label),
        }
    }

    /// Writes ` + c v` in the seed's style: the sign of a one-term
    /// coefficient pulled out, parentheses unless it is one symbol.
    fn scaled_variable(&mut self, c: &Coefficient, variable: Sym) {
        let first = self.out.is_empty();
        match c {
            Coefficient::Expr(e) if self.pool.is_zero(*e) => return,
            Coefficient::Expr(e)
                if matches!(self.pool.node(*e), Node::Add(_))
                    || self.pool.negated_sum(*e).is_some() =>
            {
                self.sign(false, first);
                self.parenthesised(*e, false);
            }
            Coefficient::Expr(e) => {
                let term = Term::of(self.pool, *e, false);
                self.sign(term.coefficient.is_negative(), first);
                self.bare_or_parenthesised(&term);
            }
            Coefficient::Named(label) => {
                self.sign(false, first);
                self.out.push_str(label);
            }
        }
        let after_sign = self.out.ends_with(' ') || self.out.ends_with(self.notation.minus);
        if !self.out.is_empty() && !after_sign {
            self.out.push(' ');
        }
        self.symbol(variable);
    }

    /// Writes a one-term coefficient's magnitude: nothing for 1, bare for
    /// one symbol (`m`), else in parentheses.
    fn bare_or_parenthesised(&mut self, term: &Term) {
        let unit = term.coefficient.abs().is_one();
        match term.factors.as_slice() {
            [] if unit => {}
            [Factor { base, exp: 1, .. }]
                if unit && matches!(self.pool.node(*base), Node::Sym(_)) =>
            {
                self.magnitude(term);
            }
            _ => {
                self.out.push('(');
                self.magnitude(term);
                self.out.push(')');
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::readable::readable;
    use crate::readable::tests::{Build, seed_double_pendulum, symbols};

    /// Names for `m, L, g, d, l`, `θ₁, θ₂` and the input `M_phi`.
    fn seed_names() -> SymbolNames {
        SymbolNames::new(
            &["m", "L", "g", "d", "l"],
            &["theta1", "theta2"],
            &["M_phi"],
        )
    }

    /// `sym` in both styles.
    fn both(names: &SymbolNames, sym: Sym) -> (String, String) {
        let mut p = Pool::new();
        let e = p.sym(sym);
        (unicode(&p, e, names), latex(&p, e, names))
    }

    #[test]
    fn names_spell_greek_letters_and_subscripts() {
        let names = SymbolNames::new(
            &[
                "m", "l", "M_phi", "omega", "mass", "Theta", "lambda", "alpha_2",
            ],
            &["theta1", "phi", "x12", "theta_2", "r#type", "v_max"],
            &["M_theta"],
        );
        let expected = [
            (Sym::Param(0), "m", "m"),
            (Sym::Param(1), "ℓ", "\\ell"),
            (Sym::Param(2), "M_φ", "M_{\\phi}"),
            (Sym::Param(3), "ω", "\\omega"),
            (Sym::Param(4), "mass", "\\mathrm{mass}"),
            (Sym::Param(5), "Θ", "\\Theta"),
            (Sym::Param(6), "λ", "\\lambda"),
            (Sym::Param(7), "α₂", "\\alpha_{2}"),
            (Sym::Coord(0), "θ₁", "\\theta_{1}"),
            (Sym::Coord(1), "φ", "\\phi"),
            (Sym::Coord(2), "x₁₂", "x_{12}"),
            (Sym::Coord(3), "θ₂", "\\theta_{2}"),
            (Sym::Coord(4), "type", "\\mathrm{type}"),
            (Sym::Coord(5), "v_max", "v_{\\mathrm{max}}"),
            (Sym::Input(0), "M_θ", "M_{\\theta}"),
            (Sym::Multiplier(1), "λ₂", "\\lambda_{2}"),
            (Sym::Time, "t", "t"),
            (Sym::Param(11), "p₁₂", "p_{12}"),
        ];
        for (sym, text, tex) in expected {
            assert_eq!(
                both(&names, sym),
                (text.to_string(), tex.to_string()),
                "{sym:?}"
            );
        }
    }

    #[test]
    fn speeds_and_accelerations_are_dotted() {
        let names = SymbolNames::new(&["m"], &["theta1", "x", "M_phi2"], &["u"]);
        assert_eq!(
            both(&names, Sym::Speed(0)),
            ("θ\u{307}₁".into(), "\\dot{\\theta}_{1}".into())
        );
        assert_eq!(
            both(&names, Sym::Accel(0)),
            ("θ\u{308}₁".into(), "\\ddot{\\theta}_{1}".into())
        );
        assert_eq!(
            both(&names, Sym::Accel(1)),
            ("x\u{308}".into(), "\\ddot{x}".into())
        );
        assert_eq!(
            both(&names, Sym::Speed(2)),
            ("M\u{307}_φ₂".into(), "\\dot{M}_{\\phi,2}".into())
        );
    }

    #[test]
    fn rates_of_names_of_several_letters_are_written_whole() {
        let names = SymbolNames::new(&["m"], &["FL_HFE", "panda_joint1"], &["u"]);
        assert_eq!(
            both(&names, Sym::Speed(0)),
            (
                "d(FL_HFE)/dt".into(),
                "\\dot{\\mathrm{FL}}_{\\mathrm{HFE}}".into()
            )
        );
        assert_eq!(
            both(&names, Sym::Accel(1)),
            (
                "d²(panda_joint₁)/dt²".into(),
                "\\ddot{\\mathrm{panda}}_{\\mathrm{joint},1}".into()
            )
        );
        assert_eq!(both(&names, Sym::Coord(0)).0, "FL_HFE");
    }

    #[test]
    fn short_names_are_a_letter_and_a_subscript_and_their_rates_are_dotted() {
        let names = SymbolNames::new(
            &["I1c", "m_B", "Ixx", "arm"],
            &["xp", "arm"],
            &[] as &[&str],
        );
        let expected = [
            (Sym::Param(0), "I_1c", "I_{1c}"),
            (Sym::Param(1), "m_B", "m_{B}"),
            (Sym::Param(2), "I_xx", "I_{xx}"),
            (Sym::Param(3), "arm", "\\mathrm{arm}"),
            (Sym::Speed(0), "x\u{307}_p", "\\dot{x}_{p}"),
            (Sym::Accel(0), "x\u{308}_p", "\\ddot{x}_{p}"),
        ];
        for (sym, text, tex) in expected {
            assert_eq!(
                both(&names, sym),
                (text.to_string(), tex.to_string()),
                "{sym:?}"
            );
        }
        // A rate in Leibniz's notation is parenthesised under a power.
        let mut p = Pool::new();
        let rate = p.sym(Sym::Speed(1));
        let e = p.powi(rate, 2);
        assert_eq!(unicode(&p, e, &names), "(d(arm)/dt)²");
    }

    #[test]
    fn powers_of_parameters_follow_and_words_are_multiplied_visibly() {
        let mut p = Pool::new();
        let names = SymbolNames::new(&["r", "m", "mass"], &["q"], &[] as &[&str]);
        let [r, m, ma] = [0, 1, 2].map(|i| p.sym(Sym::Param(i)));
        let r2 = p.powi(r, 2);
        let e = p.product([m, r2]);
        assert_eq!(unicode(&p, e, &names), "m r²", "declared r before m");
        let e = p.product([m, ma]);
        assert_eq!(unicode(&p, e, &names), "m·mass");
        assert_eq!(latex(&p, e, &names), "m \\mathrm{mass}");
    }

    #[test]
    fn seed_entries_print_as_in_the_seed() {
        let mut p = Pool::new();
        let s = symbols(&mut p);
        let names = seed_names();
        let (m12, f1) = seed_double_pendulum(&mut p, &s);
        let m12 = readable(&mut p, m12, 400).expect("small");
        assert_eq!(unicode(&p, m12, &names), "½ m L² cos(θ₂ − θ₁)");
        assert_eq!(
            latex(&p, m12, &names),
            "\\frac{1}{2} m L^{2} \\cos(\\theta_{2} - \\theta_{1})"
        );
        let f1 = readable(&mut p, f1, 400).expect("small");
        assert_eq!(
            unicode(&p, f1, &names),
            "½ m L² sin(θ₂ − θ₁) θ\u{307}₂² − 3/2 m L g sin θ₁"
        );
        // A negated sum prints as its terms negated, unexpanded or
        // expanded; the term with speeds still leads.
        let minus_f1 = p.neg(f1);
        assert_eq!(
            unicode(&p, minus_f1, &names),
            "−½ m L² sin(θ₂ − θ₁) θ\u{307}₂² + 3/2 m L g sin θ₁"
        );
        let minus_f1 = readable(&mut p, minus_f1, 400).expect("small");
        assert_eq!(
            unicode(&p, minus_f1, &names),
            "−½ m L² sin(θ₂ − θ₁) θ\u{307}₂² + 3/2 m L g sin θ₁"
        );
    }

    #[test]
    fn fractions_powers_and_calls() {
        let mut p = Pool::new();
        let s = symbols(&mut p);
        let names = seed_names();
        let [theta1, theta2] = s.q;
        let [third, eighth, twelfth, minus_four_thirds, minus_five_halves] =
            [(1, 3), (1, 8), (1, 12), (-4, 3), (-5, 2)].map(|(n, d)| p.num(n, d));
        let (inverse_l, sum, difference) = (
            p.pow(s.big_l, -1),
            p.plus(&[s.m, s.d]),
            p.minus(theta1, theta2),
        );
        let cases = [
            (p.prod(&[third, s.m]), "⅓ m", "\\frac{1}{3} m"),
            (p.prod(&[eighth, s.m]), "⅛ m", "\\frac{1}{8} m"),
            (p.prod(&[twelfth, s.m]), "1/12 m", "\\frac{1}{12} m"),
            (
                p.prod(&[minus_four_thirds, s.m]),
                "−4/3 m",
                "-\\frac{4}{3} m",
            ),
            (minus_five_halves, "−5/2", "-\\frac{5}{2}"),
            (p.prod(&[s.g, inverse_l]), "g L⁻¹", "g L^{-1}"),
            (p.sin_pow(theta1, 2), "sin²θ₁", "\\sin^{2}\\theta_{1}"),
            (
                p.cos_pow(theta1, -1),
                "(cos θ₁)⁻¹",
                "(\\cos \\theta_{1})^{-1}",
            ),
            (p.func(Func::Sqrt, s.big_l), "√L", "\\sqrt{L}"),
            (p.func(Func::Ln, s.big_l), "ln L", "\\ln L"),
            (
                p.func(Func::Abs, difference),
                "|θ₁ − θ₂|",
                "\\left|\\theta_{1} - \\theta_{2}\\right|",
            ),
            (p.pow(sum, -2), "(m + d)⁻²", "(m + d)^{-2}"),
            (
                p.sin_pow(difference, 3),
                "−sin³(θ₂ − θ₁)",
                "-\\sin^{3}(\\theta_{2} - \\theta_{1})",
            ),
        ];
        for (e, text, tex) in cases {
            assert_eq!(
                (
                    unicode(&p, e, &names).as_str(),
                    latex(&p, e, &names).as_str()
                ),
                (text, tex)
            );
        }
    }

    #[test]
    fn linear_combinations_in_the_seed_style() {
        // Seed 3: (1/12 m ℓ²) θ̈ = M − (ℓ/2 cos θ) λ₁ − (ℓ/2 sin θ) λ₂.
        let mut p = Pool::new();
        let s = symbols(&mut p);
        let names = SymbolNames::new(&["m", "L", "g", "d", "l"], &["theta", "x"], &["M"]);
        let theta = s.q[0];
        let input = p.sym(Sym::Input(0));
        let (half, minus_half, twelfth, l2) =
            (p.num(1, 2), p.num(-1, 2), p.num(1, 12), p.pow(s.l, 2));
        let (cos, sin) = (p.cos(theta), p.sin(theta));
        let (one, minus_one, zero, sum) = (p.one(), p.int(-1), p.zero(), p.plus(&[s.m, half]));
        let inertia = p.prod(&[twelfth, s.m, l2]);
        let a1 = p.prod(&[minus_half, s.l, cos]);
        let a2 = p.prod(&[minus_half, s.l, sin]);
        let lhs = [(Coefficient::Expr(inertia), Sym::Accel(0))];
        let rhs = [
            (Coefficient::Expr(a1), Sym::Multiplier(0)),
            (Coefficient::Expr(a2), Sym::Multiplier(1)),
        ];
        let leading = Coefficient::Expr(input);
        let show = |leading, terms: &[(Coefficient, Sym)], style| {
            linear_combination(&p, leading, terms, &names, style)
        };
        assert_eq!(show(None, &lhs, Style::Unicode), "(1/12 m ℓ²) θ\u{308}");
        assert_eq!(
            show(Some(&leading), &rhs, Style::Unicode),
            "M − (½ ℓ cos θ) λ₁ − (½ ℓ sin θ) λ₂"
        );
        assert_eq!(
            show(Some(&leading), &rhs, Style::Latex),
            "M - (\\frac{1}{2} \\ell \\cos \\theta) \\lambda_{1} - (\\frac{1}{2} \\ell \\sin \\theta) \\lambda_{2}"
        );
        // Unit and one-symbol coefficients go bare; sums keep parentheses.
        let terms = [
            (Coefficient::Expr(minus_one), Sym::Accel(1)),
            (Coefficient::Expr(s.m), Sym::Accel(0)),
            (Coefficient::Expr(zero), Sym::Accel(0)),
            (Coefficient::Expr(one), Sym::Multiplier(0)),
            (Coefficient::Expr(sum), Sym::Multiplier(1)),
            (Coefficient::Named("M₁₂".into()), Sym::Accel(1)),
        ];
        assert_eq!(
            show(None, &terms, Style::Unicode),
            "−x\u{308} + m θ\u{308} + λ₁ + (½ + m) λ₂ + M₁₂ x\u{308}"
        );
        assert_eq!(
            show(Some(&Coefficient::Expr(zero)), &[], Style::Unicode),
            "0"
        );
    }

    #[test]
    fn labels() {
        assert_eq!(label("M", &[1, 2], Style::Unicode), "M₁₂");
        assert_eq!(label("M", &[1, 2], Style::Latex), "M_{12}");
        assert_eq!(label("M", &[10, 11], Style::Unicode), "M₁₀,₁₁");
        assert_eq!(label("f", &[3], Style::Latex), "f_{3}");
    }

    #[test]
    fn deep_or_long_input_is_cut_off() {
        let mut p = Pool::new();
        let names = seed_names();
        let mut e = p.sym(Sym::Coord(0));
        for _ in 0..100_000 {
            e = p.sin(e);
        }
        let text = unicode(&p, e, &names);
        assert!(
            text.contains('…') && text.len() < 2_000,
            "{} bytes",
            text.len()
        );
        assert_eq!(
            text.matches('(').count(),
            text.matches(')').count(),
            "unbalanced: {text}"
        );
        assert!(latex(&p, e, &names).contains("\\dots"));
    }
}
