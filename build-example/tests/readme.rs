//! The README's build-script snippets are this crate's files, and the model
//! they generate works with the runtime: the route a user copies cannot rot.

use dalembert_build_example::pendulum::Pendulum;

/// The body of the fenced block of `language` that follows `after` in the
/// README.
fn readme_block(after: &str, language: &str) -> String {
    let readme = include_str!("../../README.md");
    let section = readme
        .find("## From a build script")
        .expect("the build-script section");
    let start = section
        + readme[section..]
            .find(after)
            .expect("the snippet's first line");
    let fence = readme[..start]
        .rfind(&format!("```{language}\n"))
        .expect("the snippet's opening fence");
    let body = &readme[fence + language.len() + 4..];
    body[..body.find("```").expect("the snippet's closing fence")].to_string()
}

#[test]
fn the_build_script_and_the_library_are_the_readme_snippets() {
    let build = readme_block("// build.rs", "rust,ignore");
    assert_eq!(build, include_str!("../build.rs"));
    let library = readme_block("// src/lib.rs", "rust,ignore");
    assert_eq!(library, include_str!("../src/lib.rs"));
}

#[test]
fn the_manifest_has_the_readme_dependencies_with_this_checkout_s_paths() {
    let manifest = readme_block("[dependencies]", "toml")
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
