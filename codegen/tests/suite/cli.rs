//! The `dalembert` command-line tool, run as a process: `eom` prints the
//! seed document's boxed results, `generate` the build step's output, and
//! `check` reports errors as the macro does, with exit status 1.

use std::path::{Path, PathBuf};
use std::process::Output;

fn seed_model(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../generated/models")
        .join(format!("{name}.dal"))
}

fn dalembert(args: &[&str]) -> Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_dalembert"))
        .args(args)
        .output()
        .expect("run dalembert")
}

/// Stdout of a successful run.
fn stdout_of(args: &[&str]) -> String {
    let out = dalembert(args);
    assert!(
        out.status.success(),
        "dalembert {args:?} failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).expect("UTF-8 output")
}

/// `dalembert eom` on a seed model.
fn eom(name: &str) -> String {
    stdout_of(&["eom", seed_model(name).to_str().unwrap()])
}

fn assert_lines(text: &str, expected: &[&str]) {
    for line in expected {
        assert!(
            text.lines().any(|l| l.trim() == *line),
            "missing line `{line}` in:\n{text}"
        );
    }
}

/// Seed example 1, boxed result:
/// (4/3 mL²) θ̈₁ + (½ mL² C₂₋₁) θ̈₂ − (½ mL² S₂₋₁) θ̇₂² + (3/2 mgL) S₁ = 0,
/// (½ mL² C₂₋₁) θ̈₁ + (⅓ mL²) θ̈₂ + (½ mL² S₂₋₁) θ̇₁² + (½ mgL) S₂ = 0.
#[test]
fn eom_double_pendulum_matches_the_seed() {
    assert_lines(
        &eom("double_pendulum"),
        &[
            "M₁₁ = 4/3 m L²",
            "M₁₂ = ½ m L² cos(θ₂ − θ₁)",
            "M₂₂ = ⅓ m L²",
            "f₁ = ½ m L² sin(θ₂ − θ₁) θ̇₂² − 3/2 m L g sin θ₁",
            "f₂ = −½ m L² sin(θ₂ − θ₁) θ̇₁² − ½ m L g sin θ₂",
        ],
    );
}

/// Seed example 2, boxed result:
/// (m d² + 1/12 mℓ² C²θ) φ̈ − (⅙ mℓ² Sθ Cθ) θ̇ φ̇ = M_φ,
/// (1/12 mℓ²) θ̈ + (1/12 mℓ² Sθ Cθ) φ̇² = M_θ.
#[test]
fn eom_rotating_bar_matches_the_seed() {
    assert_lines(
        &eom("rotating_bar"),
        &[
            "M₁₁ = m d² + 1/12 m ℓ² cos²θ",
            "M₂₂ = 1/12 m ℓ²",
            "f₁ = ⅙ m ℓ² cos θ sin θ φ̇ θ̇ + M_φ",
            "f₂ = −1/12 m ℓ² cos θ sin θ φ̇² + M_θ",
        ],
    );
}

/// Seed example 3, boxed result: m ẍ = λ₁, m ÿ = −mg + λ₂,
/// (1/12 mℓ²) θ̈ = M − (ℓ/2 Cθ) λ₁ − (ℓ/2 Sθ) λ₂, and the constraint
/// Jacobian of the generated API (`docs/language.md`). (Dots are combining characters: `x\u{308}`, not
/// the precomposed `ẍ`.)
#[test]
fn eom_constrained_pendulum_matches_the_seed() {
    assert_lines(
        &eom("constrained_pendulum"),
        &[
            "m x\u{308} = λ₁",
            "m y\u{308} = −m g + λ₂",
            "(1/12 m ℓ²) θ̈ = M − (½ ℓ cos θ) λ₁ − (½ ℓ sin θ) λ₂",
            "a₁₃ = −½ ℓ cos θ",
            "a₂₃ = −½ ℓ sin θ",
            "b₁ = −½ ℓ sin θ θ̇²",
            "b₂ = ½ ℓ cos θ θ̇²",
        ],
    );
}

#[test]
fn eom_latex() {
    let model = seed_model("double_pendulum");
    let text = stdout_of(&["eom", model.to_str().unwrap(), "--latex"]);
    assert!(
        text.contains(r"M_{12} &= \frac{1}{2} m L^{2} \cos(\theta_{2} - \theta_{1})"),
        "{text}"
    );
}

#[test]
fn generate_prints_the_build_step_output() {
    let model = seed_model("rotating_bar");
    let source = std::fs::read_to_string(&model).unwrap();
    let printed = stdout_of(&["generate", model.to_str().unwrap()]);
    assert_eq!(printed, dalembert_codegen::generate(&source).unwrap());
}

#[test]
fn check_accepts_the_seed_models() {
    for name in ["double_pendulum", "rotating_bar", "constrained_pendulum"] {
        let model = seed_model(name);
        let printed = stdout_of(&["check", model.to_str().unwrap()]);
        assert!(printed.ends_with(": ok\n"), "{printed}");
    }
}

#[test]
fn check_reports_errors_with_position_and_exit_status_1() {
    let path = Path::new(env!("CARGO_TARGET_TMPDIR")).join("cli_bad_model.dal");
    std::fs::write(
        &path,
        "pub Bad {\n    parameters m;\n    coordinates q;\n    frame B = N.rotate_z(qq);\n}\n",
    )
    .unwrap();
    let out = dalembert(&["check", path.to_str().unwrap()]);
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(out.stdout.is_empty());
    let expected = format!(
        " --> {}:4:26\n  |\n4 |     frame B = N.rotate_z(qq);\n  |                          ^^\n",
        path.display()
    );
    assert!(stderr.starts_with("error: unknown name `qq`"), "{stderr}");
    assert!(stderr.contains(&expected), "{stderr}");
}

#[test]
fn unreadable_model_exits_with_1() {
    let out = dalembert(&["eom", "no/such/model.dal"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("no/such/model.dal"));
}

#[test]
fn usage_errors_exit_with_2() {
    for args in [&[][..], &["frobnicate", "m.dal"], &["check"]] {
        let out = dalembert(args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert!(String::from_utf8_lossy(&out.stderr).contains("Usage: dalembert"));
    }
    assert!(stdout_of(&["--help"]).starts_with("Usage: dalembert"));
}
