//! The models of `models/` and the files `build.rs` generated from them.

use std::path::Path;

/// A model file and its name (the file stem, also its module's name).
pub struct Model {
    pub name: String,
    pub source: String,
}

impl Model {
    /// Whether the model is small enough to snapshot in full: every model
    /// but the benchmark chains longer than two links and the branching
    /// trees of many links (`*_tree_N`).
    #[allow(dead_code)] // not every test file uses every helper
    pub fn is_small(&self) -> bool {
        let sized = self.name.contains("_chain_") || self.name.contains("_tree_");
        !sized || self.name.ends_with("_02")
    }

    /// The Rust source `build.rs` wrote for this model: what the crate
    /// compiles.
    #[allow(dead_code)] // not every test file uses every helper
    pub fn generated(&self) -> String {
        let path = Path::new(env!("OUT_DIR")).join(format!("{}.rs", self.name));
        std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
    }
}

/// Every `models/*.dal`, in file-name order (the order `build.rs` uses).
pub fn models() -> Vec<Model> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("models");
    let mut paths: Vec<_> = std::fs::read_dir(&dir)
        .expect("models/")
        .map(|entry| entry.expect("models/ entry").path())
        .filter(|path| path.extension().is_some_and(|x| x == "dal"))
        .collect();
    paths.sort();
    assert!(!paths.is_empty(), "no models in {}", dir.display());
    paths
        .into_iter()
        .map(|path| Model {
            name: path.file_stem().unwrap().to_string_lossy().into_owned(),
            source: std::fs::read_to_string(&path).expect("model"),
        })
        .collect()
}

/// Arithmetic operations in the body of `function` of generated `code`:
/// `+`, `-` (binary or unary), `*`, `/` tokens and sines and cosines (one
/// per `sin_cos` call, one per angle of a `sin_cos_all` call).
#[allow(dead_code)] // not every test file uses every helper
pub fn operations(code: &str, function: &str) -> Operations {
    let file = syn::parse_file(code).expect("generated code parses");
    let body = file
        .items
        .iter()
        .filter_map(|item| match item {
            syn::Item::Impl(block) if block.trait_.is_none() => Some(&block.items),
            _ => None,
        })
        .flatten()
        .find_map(|item| match item {
            syn::ImplItem::Fn(f) if f.sig.ident == function => Some(&f.block),
            _ => None,
        })
        .unwrap_or_else(|| panic!("no fn {function}"));
    let mut counts = Operations::default();
    count(quote_tokens(body), &mut counts);
    counts
}

fn quote_tokens(block: &syn::Block) -> proc_macro2::TokenStream {
    use quote::ToTokens;
    block.to_token_stream()
}

fn count(tokens: proc_macro2::TokenStream, counts: &mut Operations) {
    use proc_macro2::TokenTree;
    let mut tokens = tokens.into_iter();
    while let Some(token) = tokens.next() {
        match token {
            TokenTree::Ident(i) if i == "sin_cos_all" => {
                // `sin_cos_all([x1, x2, …])`: one sine and cosine per angle.
                if let Some(TokenTree::Group(call)) = tokens.next() {
                    counts.sin_cos += angles(call.stream());
                }
            }
            TokenTree::Group(g) => count(g.stream(), counts),
            TokenTree::Punct(p) => match p.as_char() {
                '+' | '-' => counts.add += 1,
                '*' => counts.mul += 1,
                '/' => counts.div += 1,
                _ => {}
            },
            TokenTree::Ident(i) if i == "sin_cos" => counts.sin_cos += 1,
            _ => {}
        }
    }
}

/// The number of elements of the one array literal in `arguments`.
fn angles(arguments: proc_macro2::TokenStream) -> usize {
    use proc_macro2::TokenTree;
    match arguments.into_iter().next() {
        Some(TokenTree::Group(array)) => {
            let mut elements = 0;
            let mut empty = true;
            for token in array.stream() {
                match token {
                    TokenTree::Punct(p) if p.as_char() == ',' => empty = true,
                    _ if empty => (elements, empty) = (elements + 1, false),
                    _ => {}
                }
            }
            elements
        }
        _ => 0,
    }
}

/// Operation counts of one function, as [`operations`] counts them.
#[derive(Default)]
pub struct Operations {
    pub add: usize,
    pub mul: usize,
    pub div: usize,
    pub sin_cos: usize,
}

impl std::fmt::Display for Operations {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "add/sub/neg {:5}  mul {:5}  div {:3}  sin_cos {:2}  total {:5}",
            self.add,
            self.mul,
            self.div,
            self.sin_cos,
            self.add + self.mul + self.div
        )
    }
}
