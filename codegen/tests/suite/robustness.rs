//! The engine never panics and never hangs on bad input: property tests
//! over random token streams and random mutations of valid models (token
//! deletion, duplication, swap and replacement, extreme numbers, deep
//! nesting, huge exponents) run every front door — [`check`], [`generate`],
//! [`equations`] and [`expand`] — and require an answer within a time
//! limit: code for a valid model, spanned errors for an invalid one.
//!
//! The number of cases is fixed (`CASES` per property, from a fixed seed
//! unless `PROPTEST_RNG_SEED` says otherwise), so CI time is bounded;
//! `PROPTEST_CASES` raises it for a longer local run.

use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::mpsc;
use std::thread;
use std::time::Duration;

use dalembert_codegen::{Style, check, equations, expand, generate};
use proc_macro2::{Delimiter, Spacing, TokenStream, TokenTree};
use proptest::prelude::*;
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};

/// Cases per property in CI.
const CASES: u32 = 1000;

/// The most one input may take before the test reports a hang. Generous:
/// a debug build on a loaded CI machine is slow, a hang is forever.
const TIME_LIMIT: Duration = Duration::from_secs(20);

/// Valid models to mutate: the seed examples and systems that use the rest
/// of the language (joints, particles, forces, reacting torques, potentials,
/// dissipation, holonomic and nonholonomic constraints).
const MODELS: [&str; 5] = [
    include_str!("../../../generated/models/double_pendulum.dal"),
    include_str!("../../../generated/models/rotating_bar.dal"),
    include_str!("../../../generated/models/constrained_pendulum.dal"),
    "/// Everything at once.
    pub Gyro {
        parameters m, a, b, c, g, k, r;
        coordinates psi, th, ph, s;
        inputs Tq, Fx;
        frame A = N.rotate_z(psi);
        frame B = A.rotate_x(th);
        frame C = B.rotate_y(ph);
        point G = O + a * B.z + r * C.x;
        body rotor { mass: m, center: G, frame: C, inertia: [a*m, b*m, c*m, m*a*b/10, -m*c/7, m/5] };
        particle tip { mass: m/3, at: G + b * C.z - r * B.y + s * A.x };
        gravity -g * N.z;
        force Fx * N.x + k * dt(th) * A.y at G;
        torque Tq * B.y on C reacting A;
        potential k * th^2 / 2 + k * sin(ph)^2 + exp(-s^2) / sqrt(1 + abs(s));
        dissipation c * dt(psi)^2 / 2 + r * dt(ph) * dt(th);
        constraint dt(s) == r * cos(psi) * dt(ph);
    }",
    "pub Chain {
        parameters m1, m2, L1, L2, g;
        coordinates q1, q2, q3;
        joint revolute J1 { parent: N, child: L1f, axis: z, coordinate: q1, at: O };
        joint revolute J2 { parent: L1f, child: L2f, axis: y, coordinate: q2, at: J1 + L1 * L1f.x };
        joint prismatic J3 { parent: L2f, child: S, axis: x, coordinate: q3, at: J2 };
        body link1 { mass: m1, center: J1 + L1/2 * L1f.x, frame: L1f, inertia: [0, m1*L1^2/12, m1*L1^2/12] };
        body link2 { mass: m2, center: J2 + L2/2 * L2f.x, frame: L2f, inertia: [m2/100, m2*L2^2/12, m2*L2^2/12] };
        particle slider { mass: m2/2, at: J3 };
        gravity -g * N.z;
        constraint q3 - L1 * sin(q1) == L2 * sin(t);
    }",
];

/// Tokens that replace or join the tokens of a model: every keyword, names
/// of the models, functions, punctuation, unbalanced delimiters and
/// extreme numbers.
const VOCABULARY: &[&str] = &[
    "parameters",
    "coordinates",
    "inputs",
    "frame",
    "point",
    "body",
    "particle",
    "joint",
    "gravity",
    "force",
    "torque",
    "potential",
    "dissipation",
    "constraint",
    "at",
    "on",
    "reacting",
    "revolute",
    "prismatic",
    "mass",
    "center",
    "inertia",
    "parent",
    "child",
    "axis",
    "coordinate",
    "pub",
    "N",
    "O",
    "t",
    "x",
    "y",
    "z",
    "rotate_x",
    "rotate_z",
    "theta1",
    "phi",
    "m",
    "L",
    "g",
    "G",
    "B",
    "sin",
    "cos",
    "tan",
    "sqrt",
    "exp",
    "ln",
    "abs",
    "dt",
    "atan2",
    "(",
    ")",
    "[",
    "]",
    "{",
    "}",
    "( theta1 )",
    "[ 0 , 0 , 1 ]",
    "{ mass : m }",
    ";",
    ",",
    ":",
    ".",
    "=",
    "==",
    "+",
    "-",
    "*",
    "/",
    "^",
    "#",
    "!",
    "&",
    "0",
    "1",
    "-1",
    "2.5",
    "0.0",
    "1e308",
    "1e-308",
    "1e400",
    "2147483647",
    "-2147483648",
    "4294967296",
    "170141183460469231731687303715884105727",
    "2f64",
    "0x10",
    // Found by this sweep: a raw identifier as a coordinate panicked the
    // emitter (`r#m_dot`), keywords expanded to code rustc cannot parse.
    "r#m",
    "type",
    "self",
    "_",
    "\"text\"",
    "'c'",
    "///doc\n",
    "//comment\n",
];

/// Deterministic inputs worth checking on every run: the extremes the
/// strategies hit only by luck.
const EXTREMES: &[&str] = &[
    "potential theta1^2147483647;",
    "potential (theta1 + L)^2147483647;",
    "potential (theta1 + L)^-2147483648;",
    "potential theta1^-2147483648 * theta1^-2147483648;",
    "potential (theta1^65536)^65536;",
    "potential 2^2^2^2^2 * theta1;",
    "potential m * 0^-1;",
    "potential m * (L - L)^-1;",
    "potential 1e308 * 1e308 * theta1;",
    "potential 1e308 * 1e308 * theta1 - 1e308 * 1e308 * theta1;",
    "potential (1e308 * 10 - 1e308 * 10) * theta1;",
    "potential theta1 / (1e-308 / 1e308);",
    "potential exp(exp(exp(1e308))) * theta1;",
    "potential ln(0) * theta1;",
    "potential sqrt(-1) * theta1;",
    "potential tan(theta1)^40 / cos(theta1)^40;",
    "potential 170141183460469231731687303715884105727 * 170141183460469231731687303715884105727 * theta1;",
    "potential 1 / 170141183460469231731687303715884105727 / 170141183460469231731687303715884105727 * theta1;",
    // Found by this test: `-i128::MIN` overflowed in the emitter.
    "point Q = O - L / 170141183460469231731687303715884105727 * B1.y; particle q { mass: m, at: Q };",
    "potential -170141183460469231731687303715884105728 * theta1;",
    "gravity -1e308 * g * N.y; gravity -1e308 * g * N.y;",
    "constraint dt(theta1) * 0 == 0;",
    "constraint theta1 - theta1 + dt(theta1) - dt(theta1) == 0;",
    "constraint theta1 == theta1;",
    // Found by the acceptance sweep: these two panicked the emitter.
    "coordinates r#s; point S = O + r#s * N.x; particle ps { mass: m, at: S };",
    "joint spherical r#ball { parent: N, child: Bz, at: O }; body bz { mass: m, center: O + Bz.x, frame: Bz, inertia: [1, 1, 1] };",
    "body b2 { mass: m, center: G1, frame: B1, inertia: [0, 0, 0] };",
    "body b2 { mass: 1e-308, center: G1, frame: B1, inertia: [1e308, 1e308, 1e308, 1e308, 1e308, 1e308] };",
    "frame C = B1.rotate_x(1e308 * theta1); body c { mass: m, center: O, frame: C, inertia: [1, 2, 3] };",
];

/// Runs `job` on another thread and fails the test if it takes longer
/// than [`TIME_LIMIT`]. A panic in `job` is a test failure too.
fn within_time_limit<T: Send + 'static>(
    input: &str,
    job: impl FnOnce() -> T + Send + 'static,
) -> T {
    let (sender, receiver) = mpsc::channel();
    let worker = thread::spawn(move || {
        let _ = sender.send(job());
    });
    match receiver.recv_timeout(TIME_LIMIT) {
        Ok(value) => value,
        Err(mpsc::RecvTimeoutError::Timeout) => {
            panic!("no answer within {TIME_LIMIT:?} (a hang?) for:\n{input}")
        }
        Err(mpsc::RecvTimeoutError::Disconnected) => {
            let payload = worker
                .join()
                .expect_err("a worker that sent nothing panicked");
            std::panic::resume_unwind(payload)
        }
    }
}

/// Every front door on `source`: no panic, no hang, and consistent
/// answers — `generate` and `equations` succeed exactly when `check` does,
/// every error has a message, and `expand` of the tokens gives items or
/// `compile_error!`s.
/// Returns whether `source` is valid.
fn assert_answers(source: &str) -> bool {
    let owned = source.to_owned();
    within_time_limit(source, move || {
        let checked = check(&owned);
        let generated = generate(&owned);
        let rendered = equations(&owned, Style::Unicode);
        for error in [
            &checked.as_ref().err(),
            &generated.as_ref().err(),
            &rendered.as_ref().err(),
        ]
        .into_iter()
        .flatten()
        {
            assert!(
                error.into_iter().all(|e| !e.to_string().is_empty()),
                "an error without a message for:\n{owned}"
            );
        }
        assert_eq!(
            checked.is_ok(),
            generated.is_ok(),
            "check and generate disagree on:\n{owned}\ncheck: {checked:?}\ngenerate: {:?}",
            generated.as_ref().map(|_| "code")
        );
        assert_eq!(
            checked.is_ok(),
            rendered.is_ok(),
            "check and equations disagree on:\n{owned}"
        );
        if let Ok(tokens) = owned.parse::<TokenStream>() {
            let expanded = expand(tokens);
            assert!(!expanded.is_empty(), "an empty expansion of:\n{owned}");
            if checked.is_err() {
                assert!(
                    expanded.to_string().contains("compile_error"),
                    "an invalid model expanded without errors:\n{owned}"
                );
            }
        }
        checked.is_ok()
    })
}

/// The token texts of `source`, groups opened and closed as separate
/// tokens so that mutations can unbalance them, and joint punctuation
/// (`==`) kept as one token.
fn token_texts(source: &str) -> Vec<String> {
    fn flatten(stream: TokenStream, out: &mut Vec<String>, glue: &mut bool) {
        for token in stream {
            let text = match token {
                TokenTree::Group(group) => {
                    let (open, close) = match group.delimiter() {
                        Delimiter::Parenthesis => ("(", ")"),
                        Delimiter::Bracket => ("[", "]"),
                        Delimiter::Brace => ("{", "}"),
                        Delimiter::None => ("", ""),
                    };
                    out.push(open.to_owned());
                    flatten(group.stream(), out, glue);
                    close.to_owned()
                }
                TokenTree::Punct(punct) if *glue => {
                    *glue = punct.spacing() == Spacing::Joint;
                    if let Some(last) = out.last_mut() {
                        last.push(punct.as_char());
                    }
                    continue;
                }
                TokenTree::Punct(punct) => {
                    *glue = punct.spacing() == Spacing::Joint;
                    punct.to_string()
                }
                other => other.to_string(),
            };
            out.push(text);
        }
    }
    let mut out = Vec::new();
    flatten(
        source.parse().expect("the models lex"),
        &mut out,
        &mut false,
    );
    out
}

/// Numbers that replace the numbers of a model: such a model often stays
/// valid, so extreme values go through the whole pipeline.
const NUMBERS: &[&str] = &[
    "0",
    "1",
    "3",
    "0.5",
    "1e308",
    "1e-308",
    "1e-320",
    "2147483647",
    "4294967296",
    "170141183460469231731687303715884105727",
    "0.000000000000000000000000000000000000001",
];

/// Operators that replace the operators of a model.
const OPERATORS: &[&str] = &["+", "-", "*", "/", "^"];

/// One edit of a token list.
#[derive(Clone, Debug)]
enum Mutation {
    Delete(usize),
    Duplicate(usize),
    Swap(usize, usize),
    Replace(usize, &'static str),
    Insert(usize, &'static str),
    /// Replaces the `i`-th numeric literal (wrapping around).
    Number(usize, &'static str),
    /// Replaces the `i`-th arithmetic operator (wrapping around).
    Operator(usize, &'static str),
}

impl Mutation {
    /// Applies the edit; positions wrap around the list's length.
    fn apply(&self, tokens: &mut Vec<String>) {
        let len = tokens.len().max(1);
        match *self {
            Mutation::Delete(i) if !tokens.is_empty() => {
                tokens.remove(i % len);
            }
            Mutation::Duplicate(i) if !tokens.is_empty() => {
                let token = tokens[i % len].clone();
                tokens.insert(i % len, token);
            }
            Mutation::Swap(i, j) if !tokens.is_empty() => tokens.swap(i % len, j % len),
            Mutation::Replace(i, token) if !tokens.is_empty() => tokens[i % len] = token.to_owned(),
            Mutation::Insert(i, token) => tokens.insert(i % (tokens.len() + 1), token.to_owned()),
            Mutation::Number(i, number) => {
                replace_nth(tokens, i, number, |t| {
                    t.starts_with(|c: char| c.is_ascii_digit())
                });
            }
            Mutation::Operator(i, operator) => {
                replace_nth(tokens, i, operator, |t| OPERATORS.contains(&t));
            }
            _ => {}
        }
    }
}

/// Replaces the `i`-th token (wrapping around) that `select` picks, if any.
fn replace_nth(tokens: &mut [String], i: usize, by: &str, select: impl Fn(&str) -> bool) {
    let picked: Vec<usize> = (0..tokens.len()).filter(|&k| select(&tokens[k])).collect();
    if !picked.is_empty() {
        tokens[picked[i % picked.len()]] = by.to_owned();
    }
}

fn vocabulary_token() -> impl Strategy<Value = &'static str> {
    proptest::sample::select(VOCABULARY)
}

fn mutation() -> impl Strategy<Value = Mutation> {
    let position = 0..10_000usize;
    prop_oneof![
        position.clone().prop_map(Mutation::Delete),
        position.clone().prop_map(Mutation::Duplicate),
        (position.clone(), position.clone()).prop_map(|(i, j)| Mutation::Swap(i, j)),
        (position.clone(), vocabulary_token()).prop_map(|(i, t)| Mutation::Replace(i, t)),
        (position.clone(), vocabulary_token()).prop_map(|(i, t)| Mutation::Insert(i, t)),
        (position.clone(), proptest::sample::select(NUMBERS))
            .prop_map(|(i, n)| Mutation::Number(i, n)),
        (position, proptest::sample::select(OPERATORS)).prop_map(|(i, o)| Mutation::Operator(i, o)),
    ]
}

/// A model with one to five random edits.
fn mutated_model() -> impl Strategy<Value = String> {
    (0..MODELS.len(), proptest::collection::vec(mutation(), 1..6)).prop_map(|(model, edits)| {
        let mut tokens = token_texts(MODELS[model]);
        for edit in &edits {
            edit.apply(&mut tokens);
        }
        tokens.join(" ")
    })
}

/// Up to 60 random tokens, inside `pub S { ... }` or bare.
fn random_tokens() -> impl Strategy<Value = String> {
    (
        proptest::collection::vec(vocabulary_token(), 0..60),
        any::<bool>(),
    )
        .prop_map(|(tokens, wrapped)| {
            let body = tokens.join(" ");
            if wrapped {
                format!("pub S {{ {body} }}")
            } else {
                body
            }
        })
}

/// A proptest runner with [`CASES`] cases (or `PROPTEST_CASES`) from a
/// fixed seed (or `ROBUSTNESS_SEED`, a number), so that every CI run tries
/// the same inputs and a longer local run can try others.
fn runner() -> TestRunner {
    let variable = |name| std::env::var(name).ok().and_then(|v| v.parse::<u64>().ok());
    let config = Config {
        cases: variable("PROPTEST_CASES").map_or(CASES, |cases| cases as u32),
        failure_persistence: None,
        ..Config::default()
    };
    let rng = match variable("ROBUSTNESS_SEED") {
        Some(seed) => {
            let mut bytes = [0; 32];
            bytes[..8].copy_from_slice(&seed.to_le_bytes());
            TestRng::from_seed(RngAlgorithm::ChaCha, &bytes)
        }
        None => TestRng::deterministic_rng(RngAlgorithm::ChaCha),
    };
    TestRunner::new_with_rng(config, rng)
}

#[test]
fn mutated_models_get_an_answer() {
    let valid = AtomicU32::new(0);
    let mut runner = runner();
    runner
        .run(&mutated_model(), |source| {
            if assert_answers(&source) {
                valid.fetch_add(1, Ordering::Relaxed);
            }
            Ok(())
        })
        .unwrap_or_else(|failure| panic!("{failure}"));
    // Some mutations keep the model valid (a swapped `+`, a duplicated
    // statement separator...), so code generation is exercised too.
    let valid = valid.into_inner();
    eprintln!(
        "{valid} of {} mutated models were valid",
        runner.config().cases
    );
    assert!(
        valid * 50 >= runner.config().cases,
        "only {valid} valid models"
    );
}

#[test]
fn random_token_streams_get_an_answer() {
    runner()
        .run(&random_tokens(), |source| {
            assert_answers(&source);
            Ok(())
        })
        .unwrap_or_else(|failure| panic!("{failure}"));
}

#[test]
fn extreme_numbers_exponents_and_nesting_get_an_answer() {
    let base = MODELS[0].trim_end().trim_end_matches('}');
    for extra in EXTREMES {
        let source = format!("{base}    {extra}\n}}");
        assert_answers(&source);
    }
    for depth in [200, 255, 256, 257, 5000] {
        let nested = format!("{}theta1{}", "(".repeat(depth), ")".repeat(depth));
        assert_answers(&format!("{base}    potential {nested};\n}}"));
        let minus = format!("{}theta1", "-".repeat(depth));
        assert_answers(&format!("{base}    potential {minus};\n}}"));
    }
    // Found by this sweep: a long sum's syntax tree is as deep as it is long.
    for terms in [2049, 2050, 20_000] {
        let sum = vec!["theta1"; terms].join(" + ");
        assert_answers(&format!("{base}    potential {sum};\n}}"));
    }
}

#[test]
fn every_model_here_is_valid_also_as_spelt_by_the_mutator() {
    for model in MODELS {
        assert!(check(model).is_ok(), "{model}");
        let respelt = token_texts(model).join(" ");
        assert!(check(&respelt).is_ok(), "{respelt}");
    }
}
