//! The generated API of a system, listed for a person: the functions
//! emitted for it, read back from the emitted `impl` (so the list is what
//! was generated, whatever added it), and the `outputs` of the language
//! that the model did not ask for, each with the function it would add.
//! It ends the struct's docs and is what `dalembert check MODEL.dal --api`
//! prints, so that calling a function the model did not ask for (a bare
//! `no method named linearize`) has its fix written down.

use crate::model::{KINDS, Model, NEWTONIAN, ORIGIN, Subject, output_kind as kind};
use proc_macro2::{Delimiter, TokenStream, TokenTree};

/// One generated function: its name, its arguments' names and the first
/// sentence of its docs.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Entry {
    name: String,
    arguments: Vec<String>,
    summary: String,
}

impl Entry {
    /// `name(a, b)`.
    fn call(&self) -> String {
        format!("{}({})", self.name, self.arguments.join(", "))
    }
}

/// The functions a system has and the outputs it could ask for.
pub struct Api {
    functions: Vec<Entry>,
    /// Each output not asked for: as written in `outputs ...;` and the
    /// function it adds.
    others: Vec<(String, String)>,
}

impl Api {
    /// The API of `model` whose emitted items are `items` (the inherent
    /// `impl` or everything emitted for the system).
    pub fn of(model: &Model, items: &TokenStream) -> Api {
        let mut functions = Vec::new();
        public_functions(items.clone(), &mut functions);
        Api {
            functions,
            others: outputs_not_asked(model),
        }
    }

    /// The lines closing the struct's doc comment (Markdown).
    pub fn doc_lines(&self) -> Vec<String> {
        let mut lines = vec![
            String::new(),
            " # Generated functions".to_string(),
            String::new(),
        ];
        lines.extend(self.functions.iter().map(|f| {
            let summary = f.summary.trim();
            match summary.is_empty() {
                true => format!(" * `{}`", f.call()),
                false => format!(" * `{}`: {summary}", f.call()),
            }
        }));
        if !self.others.is_empty() {
            lines.push(String::new());
            lines.push(
                " Other functions are generated when the model asks for them with \
                 `outputs ...;` (P a named point, B a frame):"
                    .to_string(),
            );
            lines.push(String::new());
            lines.extend(
                self.others
                    .iter()
                    .map(|(written, adds)| format!(" * `outputs {written};` adds `{adds}`")),
            );
        }
        lines
    }

    /// The listing `dalembert check MODEL.dal --api` prints: one function
    /// a line, then the outputs that add the others.
    pub fn text(&self) -> String {
        let mut text = String::from("Generated functions:\n");
        for f in &self.functions {
            text.push_str(&format!("  {}", f.call()));
            if !f.summary.trim().is_empty() {
                text.push_str(&format!("  {}", f.summary.trim()));
            }
            text.push('\n');
        }
        if !self.others.is_empty() {
            text.push_str("Added by `outputs ...;` in the model (P a named point, B a frame):\n");
            for (written, adds) in &self.others {
                text.push_str(&format!("  outputs {written};  adds {adds}\n"));
            }
        }
        text
    }
}

/// The outputs of the language that `model` does not ask for, as written
/// and with the function each adds.
fn outputs_not_asked(model: &Model) -> Vec<(String, String)> {
    KINDS
        .iter()
        .filter(|(name, ..)| {
            let Some(this) = kind(name, Some(ORIGIN), Some(NEWTONIAN)) else {
                return false;
            };
            let this = std::mem::discriminant(&this);
            !model
                .outputs
                .iter()
                .any(|o| std::mem::discriminant(&o.kind) == this)
        })
        .map(|&(name, subject)| match subject {
            Subject::Point => (format!("{name}(P)"), format!("{name}_P")),
            Subject::Frame => (format!("{name}(B)"), format!("{name}_B")),
            // The one output whose function is not named after it.
            Subject::None if name == "taylor" => (name.into(), "taylor_coefficients".into()),
            Subject::None | Subject::Coordinates => (name.into(), name.into()),
        })
        .collect()
}

/// Collects the `pub fn`s of `tokens` (looking into `impl NAME { .. }`
/// blocks, not trait impls), each with the first sentence of the doc
/// attributes before it. A shallow walk over the token trees: the bodies
/// are never parsed.
fn public_functions(tokens: TokenStream, found: &mut Vec<Entry>) {
    let trees: Vec<TokenTree> = tokens.into_iter().collect();
    let mut docs: Vec<String> = Vec::new();
    for (i, tree) in trees.iter().enumerate() {
        let next = |k: usize| trees.get(i + k);
        match tree {
            TokenTree::Punct(p) if p.as_char() == '#' => {
                if let Some(TokenTree::Group(g)) = next(1) {
                    docs.extend(doc_text(g.stream()));
                }
            }
            TokenTree::Ident(word) if word == "impl" => {
                if let (Some(TokenTree::Ident(_)), Some(TokenTree::Group(body))) =
                    (next(1), next(2))
                {
                    if body.delimiter() == Delimiter::Brace {
                        public_functions(body.stream(), found);
                    }
                }
            }
            TokenTree::Ident(word) if word == "pub" => {
                if let (
                    Some(TokenTree::Ident(keyword)),
                    Some(TokenTree::Ident(name)),
                    Some(TokenTree::Group(arguments)),
                ) = (next(1), next(2), next(3))
                {
                    if keyword == "fn" {
                        found.push(Entry {
                            name: name.to_string(),
                            arguments: argument_names(arguments.stream()),
                            summary: first_sentence(&docs),
                        });
                    }
                }
                docs.clear();
            }
            TokenTree::Punct(p) if p.as_char() == ';' => docs.clear(),
            _ => {}
        }
    }
}

/// The first sentence of the first paragraph of `docs` (lines of a doc
/// comment), on one line.
fn first_sentence(docs: &[String]) -> String {
    let paragraph: Vec<&str> = docs
        .iter()
        .map(|line| line.trim())
        .take_while(|line| !line.is_empty())
        .collect();
    let text = paragraph.join(" ");
    match text.find(". ") {
        Some(end) => text[..=end].to_string(),
        None => text,
    }
}

/// The text of `doc = "..."`, if the attribute is one.
fn doc_text(attribute: TokenStream) -> Option<String> {
    let syn::Meta::NameValue(meta) = syn::parse2::<syn::Meta>(attribute).ok()? else {
        return None;
    };
    if !meta.path.is_ident("doc") {
        return None;
    }
    match meta.value {
        syn::Expr::Lit(syn::ExprLit {
            lit: syn::Lit::Str(text),
            ..
        }) => Some(text.value()),
        _ => None,
    }
}

/// The names of a function's arguments, `self` and leading underscores
/// left out: the first name of each comma-separated argument.
fn argument_names(arguments: TokenStream) -> Vec<String> {
    let mut names = Vec::new();
    let mut start = true;
    for tree in arguments {
        match &tree {
            TokenTree::Punct(p) if p.as_char() == ',' => start = true,
            TokenTree::Ident(name) if start => {
                let name = name.to_string();
                if name != "self" && name != "mut" {
                    names.push(name.trim_start_matches('_').to_string());
                }
                start = name == "mut";
            }
            TokenTree::Punct(p) if p.as_char() == '&' => {}
            _ => start = false,
        }
    }
    names
}

#[cfg(test)]
mod tests {
    use super::*;
    use quote::quote;

    #[test]
    fn reads_public_functions_with_their_first_doc_line() {
        let items = quote! {
            impl Pendulum {
                /// Number of coordinates.
                pub const NQ: usize = 1;
                /// The mass matrix.
                /// More.
                ///
                /// Other paragraph.
                #[inline]
                pub fn mass_matrix(&self, q: &[f64; 1]) -> [[f64; 1]; 1] { [[1.0]] }
                pub fn forcing(&self, t: f64, _q: &[f64; 1], mut qd: &[f64; 1]) -> f64 { 0.0 }
            }
            impl ::dalembert::MultibodySystem<1, 1, 0> for Pendulum {
                fn mass_matrix(&self) {}
            }
        };
        let mut found = Vec::new();
        public_functions(items, &mut found);
        let calls: Vec<String> = found.iter().map(Entry::call).collect();
        assert_eq!(calls, ["mass_matrix(q)", "forcing(t, q, qd)"]);
        assert_eq!(found[0].summary, "The mass matrix.");
        assert_eq!(found[1].summary, "");
    }
}
