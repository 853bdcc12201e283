//! The `dalembert!` macro and the build step produce the same code for the
//! same model: the items of `expand(model)` equal the items of the file
//! `build.rs` wrote. Both are printed with prettyplease before comparing, so
//! that token-level spelling the printer normalises (a raw or plain doc
//! string, a trailing comma) and the `@generated` header do not count. The
//! model's text (`SOURCE`) is the one thing that may be spelled apart: the
//! file's text for the build step, the tokens for an `expand` called outside
//! a macro; it must read as the same tokens.

use crate::common;

/// `file` with its `SOURCE` constant's text taken out, and that text.
fn without_source(mut file: syn::File) -> (syn::File, String) {
    let mut source = String::new();
    for item in &mut file.items {
        if let syn::Item::Impl(block) = item {
            for inner in &mut block.items {
                if let syn::ImplItem::Const(constant) = inner {
                    if constant.ident == "SOURCE" {
                        if let syn::Expr::Lit(syn::ExprLit {
                            lit: syn::Lit::Str(text),
                            ..
                        }) = &constant.expr
                        {
                            source = text.value();
                        }
                        constant.expr = syn::parse_quote!("");
                    }
                }
            }
        }
    }
    (file, source)
}

#[test]
fn macro_and_build_step_emit_the_same_items() {
    for model in common::models() {
        let input = model.source.parse().expect("model lexes");
        let expanded = dalembert_codegen::expand(input);
        let from_macro = syn::parse2::<syn::File>(expanded).expect("expansion parses");
        let from_build = syn::parse_file(&model.generated()).expect("generated file parses");
        let (from_macro, macro_source) = without_source(from_macro);
        let (from_build, build_source) = without_source(from_build);
        assert_eq!(
            build_source, model.source,
            "{}: the file's text",
            model.name
        );
        let tokens = |text: &str| {
            text.parse::<proc_macro2::TokenStream>()
                .unwrap()
                .to_string()
        };
        assert_eq!(
            tokens(&macro_source),
            tokens(&build_source),
            "{}: the macro's text reads as the file's tokens",
            model.name
        );
        assert!(
            !from_macro.items.is_empty(),
            "{}: empty expansion",
            model.name
        );
        assert_eq!(
            prettyplease::unparse(&from_macro),
            prettyplease::unparse(&from_build),
            "{}: macro and build step differ",
            model.name
        );
    }
}
