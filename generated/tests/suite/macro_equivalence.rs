//! The `dalembert!` macro and the build step produce the same code for the
//! same model: the items of `expand(model)` equal the items of the file
//! `build.rs` wrote. Both are printed with prettyplease before comparing, so
//! that token-level spelling the printer normalises (a raw or plain doc
//! string, a trailing comma) and the `@generated` header do not count.

use crate::common;

#[test]
fn macro_and_build_step_emit_the_same_items() {
    for model in common::models() {
        let input = model.source.parse().expect("model lexes");
        let expanded = dalembert_codegen::expand(input);
        let from_macro = syn::parse2::<syn::File>(expanded).expect("expansion parses");
        let from_build = syn::parse_file(&model.generated()).expect("generated file parses");
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
