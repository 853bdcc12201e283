//! The guide's build-script snippets (docs/getting-started.md) are this
//! crate's files, and the model they generate works with the runtime: the
//! route a user copies cannot rot.

use dalembert_build_example::pendulum::Pendulum;

/// The body of the fenced block of `language` that follows `after` in the
/// guide's chapter "Getting started".
fn guide_block(after: &str, language: &str) -> String {
    let chapter = include_str!("../../docs/getting-started.md");
    let section = chapter
        .find("## From a build script")
        .expect("the build-script section");
    let start = section
        + chapter[section..]
            .find(after)
            .expect("the snippet's first line");
    let fence = chapter[..start]
        .rfind(&format!("```{language}\n"))
        .expect("the snippet's opening fence");
    let body = &chapter[fence + language.len() + 4..];
    body[..body.find("```").expect("the snippet's closing fence")].to_string()
}

#[test]
fn the_build_script_and_the_library_are_the_guide_snippets() {
    let build = guide_block("// build.rs", "rust,ignore");
    assert_eq!(build, include_str!("../build.rs"));
    let library = guide_block("// src/lib.rs", "rust,ignore");
    assert_eq!(library, include_str!("../src/lib.rs"));
}

#[test]
fn the_manifest_has_the_guide_dependencies_with_this_checkout_s_paths() {
    let manifest = guide_block("[dependencies]", "toml")
        .replace("\"../dalembert/", "\"../")
        .replace("\"../dalembert\"", "\"..\"");
    assert!(
        include_str!("../Cargo.toml").contains(&manifest),
        "Cargo.toml lacks\n{manifest}"
    );
}

#[test]
fn the_generated_pendulum_swings_at_minus_g_over_l_sin_theta() {
    let pendulum = Pendulum {
        m: 2.0,
        l: 0.5,
        g: 9.81,
    };
    let [vdot] = dalembert::accelerations(&pendulum, 0.0, &[0.3], &[1.0], &[]).unwrap();
    assert!((vdot + 9.81 / 0.5 * 0.3f64.sin()).abs() < 1e-12);
}
