//! Free and spherical joints checked against closed forms (Newton–Euler
//! for a free body, Euler's equations about a fixed point for a heavy top),
//! on both routes: the recursion over the tree and the general dot
//! products of partial velocities. (Speeds of a `speeds` statement are
//! checked end to end, in the project's `tests/suite/free_body.rs`.)

use crate::equations::{Equations, derive};
use crate::expr::Pool;
use crate::geometry::Values;
use crate::model::{Model, resolve};
use crate::random::Random;
use crate::rigid::{cross, mat_vec, quaternion_rotation as rotation, transpose_vec};

/// A free body, centred on its joint: `M = diag(m, m, m, I)` and
/// `f = (m Rᵀ g − m ω × v, −ω × I ω)`.
const FREE: &str = "pub Free {
    parameters m, I1, I2, I3, I12, g;
    joint free base { parent: N, child: B, at: O };
    body b { mass: m, center: base, frame: B, inertia: [I1, I2, I3, I12, 0, 0] };
    gravity -g * N.z;
}";

/// A heavy top on a spherical joint at `O`, its centre at `a B.z + c B.x`.
const TOP: &str = "pub Top {
    parameters m, I1, I2, I3, a, c, g;
    joint spherical ball { parent: N, child: B, at: O };
    body b { mass: m, center: ball + a * B.z + c * B.x, frame: B, inertia: [I1, I2, I3] };
    gravity -g * N.z;
}";

/// A free body off its joint's origin with loads everywhere, and a
/// pendulum on it: for the two routes against each other.
pub(super) const LOADED: &str = "pub Loaded {
    parameters m, a, b, g;
    coordinates s;
    inputs F, T;
    joint free base { parent: N, child: B, at: O + a * N.y };
    joint revolute J { parent: B, child: P, axis: y, coordinate: s, at: base + b * B.x };
    body hull { mass: m, center: base + a * B.x - b * B.z, frame: B, inertia: [m, 2 * m, 3 * m, m / 7, m / 5, -m / 9] };
    body arm { mass: m / 2, center: J - a * P.z, frame: P, inertia: [m / 3, m / 4, m / 5] };
    gravity -g * N.z + g / 4 * N.x;
    force F * N.x + F * B.y at J + a * B.z;
    torque T * B.z on B;
    torque T * P.y on P reacting B;
}";

/// A revolute link carrying a ball joint away from the root, with a body
/// on each side: a joint of several speeds inside the tree.
pub(super) const BALL_IN_CHAIN: &str = "pub BallInChain {
    parameters m, a, b, g;
    coordinates s;
    inputs T;
    joint revolute hinge { parent: N, child: A, axis: [1, 2, 2], coordinate: s, at: O };
    joint spherical ball { parent: A, child: B, at: hinge + a * A.x + b * A.z };
    body upper { mass: m, center: hinge + a / 2 * A.x, frame: A, inertia: [m / 3, m / 2, m / 5, m / 11, 0, m / 13] };
    body lower { mass: m / 3, center: ball - b * B.z + a * B.y, frame: B, inertia: [m / 4, m / 6, m / 7, 0, m / 17, m / 19] };
    gravity -g * N.z;
    torque T * A.x on A;
}";

fn derived(source: &str, recursive: bool) -> (Model, Pool, Equations) {
    let system = crate::language::parse_system(source.parse().expect("tokens")).expect("parses");
    let (mut model, mut pool) = resolve(&system).unwrap_or_else(|e| panic!("{e}"));
    assert!(model.tree.is_some(), "{} is a tree", model.name);
    if !recursive {
        model.tree = None;
    }
    let equations = derive(&model, &mut pool);
    (model, pool, equations)
}

/// A random state with unit quaternions at the given coordinate indices.
struct State {
    parameters: Vec<f64>,
    q: Vec<f64>,
    v: Vec<f64>,
    u: Vec<f64>,
}

impl State {
    fn random(model: &Model, seed: u64) -> State {
        let mut random = Random::new(seed);
        let mut draw = |n: usize, low: f64, high: f64| -> Vec<f64> {
            (0..n).map(|_| random.uniform(low, high)).collect()
        };
        let mut q = draw(model.nq(), -1.0, 1.0);
        for ball in &model.balls {
            let norm = ball
                .quaternion
                .iter()
                .map(|&i| q[i] * q[i])
                .sum::<f64>()
                .sqrt();
            ball.quaternion.iter().for_each(|&i| q[i] /= norm);
        }
        State {
            parameters: draw(model.parameters.len(), 0.5, 1.5),
            v: draw(model.nv(), -2.0, 2.0),
            u: draw(model.inputs.len(), -3.0, 3.0),
            q,
        }
    }

    fn values(&self) -> Values<'_> {
        Values {
            parameters: &self.parameters,
            t: 0.3,
            q: &self.q,
            qd: &self.v,
            u: &self.u,
        }
    }
}

fn assert_close(what: &str, got: f64, expected: f64) {
    assert!(
        (got - expected).abs() <= 1e-12 * expected.abs().max(1.0),
        "{what}: {got:e}, expected {expected:e}"
    );
}

/// The values of `M` and `f` at `state`.
fn evaluate(pool: &Pool, equations: &Equations, state: &State) -> (Vec<Vec<f64>>, Vec<f64>) {
    let at = state.values();
    let m = equations
        .mass_matrix
        .iter()
        .map(|row| pool.eval_many(row, &at))
        .collect();
    (m, pool.eval_many(&equations.forcing, &at))
}

#[test]
fn a_free_body_follows_newton_and_euler_in_its_own_axes() {
    for recursive in [true, false] {
        let (model, pool, equations) = derived(FREE, recursive);
        assert_eq!((model.nq(), model.nv()), (7, 6));
        for seed in 0..4 {
            let state = State::random(&model, seed);
            let [m, i1, i2, i3, i12, g] = state.parameters[..] else {
                unreachable!()
            };
            let inertia = [[i1, i12, 0.0], [i12, i2, 0.0], [0.0, 0.0, i3]];
            let r = rotation([state.q[3], state.q[4], state.q[5], state.q[6]]);
            let (v, w) = ([0, 1, 2].map(|i| state.v[i]), [3, 4, 5].map(|i| state.v[i]));
            let weight = transpose_vec(&r, [0.0, 0.0, -m * g]);
            let transport = cross(w, v);
            let gyroscopic = cross(w, mat_vec(&inertia, w));
            let expected_f: Vec<f64> = (0..3)
                .map(|i| weight[i] - m * transport[i])
                .chain((0..3).map(|i| -gyroscopic[i]))
                .collect();
            let (mass, forcing) = evaluate(&pool, &equations, &state);
            let name = format!("recursive {recursive}, seed {seed}");
            for k in 0..6 {
                for j in 0..6 {
                    let expected = match (k < 3, j < 3) {
                        (true, true) if k == j => m,
                        (false, false) => inertia[k - 3][j - 3],
                        _ => 0.0,
                    };
                    assert_close(&format!("{name}: M[{k}][{j}]"), mass[k][j], expected);
                }
                assert_close(&format!("{name}: f[{k}]"), forcing[k], expected_f[k]);
            }
        }
    }
}

#[test]
fn a_heavy_top_follows_euler_about_its_fixed_point() {
    for recursive in [true, false] {
        let (model, pool, equations) = derived(TOP, recursive);
        assert_eq!((model.nq(), model.nv()), (4, 3));
        for seed in 0..4 {
            let state = State::random(&model, seed);
            let [m, i1, i2, i3, a, c, g] = state.parameters[..] else {
                unreachable!()
            };
            // I_O = I_G + m (|r|² 1 − r rᵀ) for the centre r = (c, 0, a).
            let centre = [c, 0.0, a];
            let r2 = c * c + a * a;
            let central = [i1, i2, i3];
            let inertia = [0, 1, 2].map(|i| {
                [0, 1, 2].map(|j| {
                    let delta = if i == j { central[i] + m * r2 } else { 0.0 };
                    delta - m * centre[i] * centre[j]
                })
            });
            let r = rotation(state.q[..4].try_into().expect("four"));
            let w = [0, 1, 2].map(|i| state.v[i]);
            let weight = transpose_vec(&r, [0.0, 0.0, -m * g]);
            let moment = cross(centre, weight);
            let gyroscopic = cross(w, mat_vec(&inertia, w));
            let (mass, forcing) = evaluate(&pool, &equations, &state);
            let name = format!("recursive {recursive}, seed {seed}");
            for k in 0..3 {
                for j in 0..3 {
                    assert_close(&format!("{name}: M[{k}][{j}]"), mass[k][j], inertia[k][j]);
                }
                let expected = moment[k] - gyroscopic[k];
                assert_close(&format!("{name}: f[{k}]"), forcing[k], expected);
            }
        }
    }
}

#[test]
fn both_routes_agree_on_a_loaded_floating_tree() {
    let (model, recursive_pool, recursive) = derived(LOADED, true);
    let (_, general_pool, general) = derived(LOADED, false);
    assert_eq!((model.nq(), model.nv()), (8, 7));
    for seed in 0..4 {
        let state = State::random(&model, seed);
        let (m1, f1) = evaluate(&recursive_pool, &recursive, &state);
        let (m2, f2) = evaluate(&general_pool, &general, &state);
        for k in 0..7 {
            for j in 0..7 {
                assert_close(&format!("seed {seed}: M[{k}][{j}]"), m1[k][j], m2[k][j]);
            }
            assert_close(&format!("seed {seed}: f[{k}]"), f1[k], f2[k]);
        }
        // T = ½ vᵀ M v on both.
        let quadratic: f64 = (0..7)
            .flat_map(|k| (0..7).map(move |j| (k, j)))
            .map(|(k, j)| state.v[k] * m1[k][j] * state.v[j])
            .sum();
        let t = recursive_pool.eval(recursive.kinetic_energy, &state.values());
        assert_close(&format!("seed {seed}: 2T"), quadratic, 2.0 * t);
    }
}

/// The articulated-body recursion, which takes a joint of several speeds
/// as one-speed joints in series, solves `M v̇ = f` of the general route
/// for a free joint at the root and a ball joint inside the tree.
#[test]
fn the_articulated_recursion_solves_joints_of_several_speeds() {
    for source in [LOADED, BALL_IN_CHAIN] {
        let (model, recursive_pool, recursive) = derived(source, true);
        let (_, general_pool, general) = derived(source, false);
        let articulated = recursive.articulated.as_ref().expect("a tree");
        for seed in 0..4 {
            let state = State::random(&model, seed);
            let (m, f) = evaluate(&general_pool, &general, &state);
            let vdot = recursive_pool.eval_many(&articulated.accelerations, &state.values());
            let pivots = recursive_pool.eval_many(&articulated.pivots, &state.values());
            assert!(
                pivots.iter().all(|&p| p > 0.0),
                "{}: pivots {pivots:?}",
                model.name
            );
            for (k, (row, fk)) in m.iter().zip(&f).enumerate() {
                let mv: f64 = row.iter().zip(&vdot).map(|(a, b)| a * b).sum();
                assert_close(&format!("{}, seed {seed}: (M v̇)[{k}]", model.name), mv, *fk);
            }
        }
    }
}
