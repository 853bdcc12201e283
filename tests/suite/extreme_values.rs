//! Generated functions and integrators on extreme but finite values:
//! masses of 1e-300 and 1e300 kg, lengths of 0, speeds of 1e150. Each
//! answer is finite or an error, never `Ok` holding a NaN or an infinity.

use dalembert::constrained::constrained_accelerations;
use dalembert::integrate::{Adaptive, AdaptiveOptions, ExplicitPair, Integration, Rk4};
use dalembert::{Constrained, Stabilisation, State, Unconstrained, accelerations};
use dalembert_fixtures::seeds::{ConstrainedPendulum, DoublePendulum};

const MASSES: [f64; 3] = [1e-300, 1.0, 1e300];
const LENGTHS: [f64; 3] = [0.0, 1e-300, 1.0];
const SPEEDS: [f64; 3] = [0.0, 1.0, 1e150];

/// Whether an `Ok` holds only finite numbers.
fn finite<T, E>(result: &Result<T, E>, values: impl Fn(&T) -> Vec<f64>) -> bool {
    match result {
        Ok(ok) => values(ok).iter().all(|x| x.is_finite()),
        Err(_) => true,
    }
}

#[test]
fn unconstrained_answers_are_finite_or_errors() {
    let (mut cases, mut errors) = (0, 0);
    for m in MASSES {
        for length in LENGTHS {
            for speed in SPEEDS {
                let pendulum = DoublePendulum {
                    m,
                    L: length,
                    g: 9.81,
                };
                let state = State {
                    t: 0.0,
                    q: [0.3, -0.4],
                    v: [speed, -speed],
                };
                let what = format!("m {m:e}, L {length:e}, speed {speed:e}");
                let vdot = accelerations(&pendulum, 0.0, &state.q, &state.v, &[]);
                assert!(finite(&vdot, |a| a.to_vec()), "{what}: {vdot:?}");
                let dynamics = Unconstrained::without_inputs(&pendulum);
                let fixed = Integration::new(&dynamics, state, 0.1, Rk4 { steps: 10 }).run();
                assert!(
                    finite(&fixed, |s| [s.end.q, s.end.v].concat()),
                    "{what}: RK4 {fixed:?}"
                );
                let options = AdaptiveOptions {
                    max_steps: 10_000,
                    ..AdaptiveOptions::with_tolerance(1e-8)
                };
                let pair = ExplicitPair::DormandPrince54;
                let adapted =
                    Integration::new(&dynamics, state, 0.1, Adaptive { pair, options }).run();
                assert!(
                    finite(&adapted, |s| [s.end.q, s.end.v].concat()),
                    "{what}: DOPRI5 {adapted:?}"
                );
                cases += 1;
                errors += usize::from(vdot.is_err()) + usize::from(fixed.is_err());
            }
        }
    }
    println!("{cases} cases, {errors} errors");
    assert_eq!(cases, 27);
    assert!(errors > 0, "the zero lengths are errors");
}

#[test]
fn constrained_answers_are_finite_or_errors() {
    let mut cases = 0;
    for m in MASSES {
        for l in LENGTHS {
            for speed in SPEEDS {
                let pendulum = ConstrainedPendulum { m, l, g: 9.81 };
                let (s, c) = 0.4f64.sin_cos();
                let state = State {
                    t: 0.0,
                    q: [l / 2.0 * s, -l / 2.0 * c, 0.4],
                    v: [l / 2.0 * c * speed, l / 2.0 * s * speed, speed],
                };
                let what = format!("m {m:e}, l {l:e}, speed {speed:e}");
                let solved = constrained_accelerations(&pendulum, 0.0, &state.q, &state.v, &[0.0]);
                assert!(
                    finite(&solved, |(a, lambda)| [a.to_vec(), lambda.to_vec()]
                        .concat()),
                    "{what}: {solved:?}"
                );
                for stabilisation in [
                    Stabilisation::None,
                    Stabilisation::Projection {
                        tolerance: 1e-12,
                        max_iterations: 5,
                    },
                ] {
                    let dynamics = Constrained::without_inputs(&pendulum, stabilisation);
                    let run = Integration::new(&dynamics, state, 0.1, Rk4 { steps: 10 }).run();
                    assert!(
                        finite(&run, |s| [s.end.q, s.end.v].concat()),
                        "{what}, {stabilisation:?}: {run:?}"
                    );
                }
                cases += 1;
            }
        }
    }
    assert_eq!(cases, 27);
}
