//! The `armature a on v;` statement: `a` added to `M`'s diagonal entry of
//! the speed `v` and `½ a v²` to the kinetic energy, on every route (the
//! derived `M`, Lagrange's Hessian of `T`, the articulated-body pivots),
//! and the errors of a target that is not a speed or a value that is not
//! constant.

use dalembert_codegen::testing::{Interpreter, Route, Values};

/// A pendulum on a hinge and a ball joint below it, with armatures.
const MODEL: &str = "
pub Rotors {
    coordinates q;
    joint revolute J { parent: N, child: A, axis: y, coordinate: q, at: O };
    joint spherical ball { parent: A, child: B, at: J - A.z };
    body a { mass: 2, center: J - 1/2 * A.z, frame: A, inertia: [1, 2, 3] };
    body b { mass: 1, center: ball - 1/2 * B.z, frame: B, inertia: [0.1, 0.2, 0.3] };
    gravity -9.81 * N.z;
    armature 0.25 on dt(q);
    armature 0.5 on ball_wx;
    armature 0.125 on ball_wx;
}";

fn without_armature() -> String {
    MODEL
        .lines()
        .filter(|l| !l.contains("armature"))
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn adds_to_the_diagonal_and_the_kinetic_energy() {
    let q = [0.3, 0.1, -0.2, 0.3, (1.0_f64 - 0.14).sqrt()];
    let v = [0.7, -1.1, 0.4, 0.9];
    let at = Values {
        parameters: &[],
        t: 0.0,
        q: &q,
        qd: &v,
        u: &[],
    };
    let with = Interpreter::new(MODEL, Route::Dalembert).unwrap();
    let without = Interpreter::new(&without_armature(), Route::Dalembert).unwrap();
    let (m, m0) = (with.mass_matrix(&at), without.mass_matrix(&at));
    let added = [0.25, 0.625, 0.0, 0.0];
    for i in 0..4 {
        for j in 0..4 {
            let expected = m0[i][j] + if i == j { added[i] } else { 0.0 };
            assert!((m[i][j] - expected).abs() < 1e-14, "M[{i}][{j}]");
        }
    }
    // The forcing is unchanged: a constant inertia on an independent speed
    // brings no velocity terms.
    for (f, f0) in with.forcing(&at).iter().zip(without.forcing(&at)) {
        assert!((f - f0).abs() < 1e-13);
    }
    let t = with.kinetic_energy(&at) - without.kinetic_energy(&at);
    let expected = 0.5 * (0.25 * v[0] * v[0] + 0.625 * v[1] * v[1]);
    assert!((t - expected).abs() < 1e-14, "{t} against {expected}");
    // The articulated-body recursion solves the same M.
    let qdd = with.articulated_accelerations(&at).expect("a tree");
    let f = with.forcing(&at);
    for i in 0..4 {
        let row: f64 = (0..4).map(|j| m[i][j] * qdd[j]).sum();
        assert!(
            (row - f[i]).abs() < 1e-12,
            "row {i}: {row} against {}",
            f[i]
        );
    }
}

#[test]
fn lagrange_takes_it_from_the_kinetic_energy() {
    let model = "
pub Rotor {
    coordinates q, s;
    frame A = N.rotate_z(q);
    point P = O + s * A.x;
    body a { mass: 2, center: P, frame: A, inertia: [1, 2, 3] };
    armature 0.5 on dt(s);
    armature 0.25 on dt(q);
}";
    let at = Values {
        parameters: &[],
        t: 0.0,
        q: &[0.4, 1.5],
        qd: &[0.3, -0.6],
        u: &[],
    };
    let dalembert = Interpreter::new(model, Route::Dalembert).unwrap();
    let lagrange = Interpreter::new(model, Route::Lagrange).unwrap();
    let (m, m_l) = (dalembert.mass_matrix(&at), lagrange.mass_matrix(&at));
    assert!((m[0][0] - (3.0 + 2.0 * 1.5 * 1.5 + 0.25)).abs() < 1e-14);
    assert!((m[1][1] - 2.5).abs() < 1e-14);
    for (row, row_l) in m.iter().zip(&m_l) {
        for (x, y) in row.iter().zip(row_l) {
            assert!((x - y).abs() < 1e-14);
        }
    }
    for (f, f_l) in dalembert.forcing(&at).iter().zip(lagrange.forcing(&at)) {
        assert!((f - f_l).abs() < 1e-13);
    }
}

#[test]
fn the_target_is_a_speed_and_the_value_a_constant() {
    let with = |statement: &str| {
        format!(
            "pub S {{ coordinates q; inputs u; frame A = N.rotate_z(q); \
             body a {{ mass: 1, center: O, frame: A, inertia: [1, 1, 1] }}; {statement} }}"
        )
    };
    dalembert_codegen::check(&with("armature 0.1 on dt(q);")).unwrap();
    let error = dalembert_codegen::check(&with("armature 0.1 on q;")).unwrap_err();
    assert!(
        error.to_string().contains("expected a speed after `on`"),
        "{error}"
    );
    let error = dalembert_codegen::check(&with("armature u on dt(q);")).unwrap_err();
    assert!(error.to_string().contains("parameters only"), "{error}");
    let error = dalembert_codegen::check(&with("armature 0.1 dt(q);")).unwrap_err();
    assert!(error.to_string().contains("`on` and a speed"), "{error}");
}

/// `source` (a model ending in `}`) with `statements` added before its end.
fn with_statements(source: &str, statements: &str) -> String {
    let end = source.rfind('}').expect("a system ends with `}`");
    format!("{}{statements}\n{}", &source[..end], &source[end..])
}

/// The looped tree routes take the armatures too: a large tree's
/// `mass_matrix` adds them to the diagonal that the runtime's pairs fill,
/// and its looped `accelerations_jacobian` to the diagonal entries of the
/// runtime's `M` that it factorises (neither loop of the runtime knows
/// them): the entries of the generated code, by name. The chain of 12,
/// whose rows are adjoints (as the chain of 16's), adds them to its own `M`.
#[test]
fn the_looped_tree_routes_add_the_armatures() {
    use dalembert_codegen::chain::{Family, chain};
    let armature = "    armature 0.25 on dt(q3);\n    armature 0.5 on dt(q7);";
    let large =
        dalembert_codegen::generate(&with_statements(&chain(Family::Spatial, 30), armature))
            .unwrap()
            .replace(char::is_whitespace, "");
    assert!(large.contains("dalembert::__private::tree_mass_matrix"));
    assert!(
        large.contains("dalembert::__private::add_to_diagonal(&mutm,[(2,0.25),(6,0.5)]);"),
        "the armatures after the pairs"
    );
    let outputs = format!("{armature}\n    outputs accelerations_jacobian;");
    let derivatives =
        dalembert_codegen::generate(&with_statements(&chain(Family::Spatial, 20), &outputs))
            .unwrap()
            .replace(char::is_whitespace, "");
    assert!(derivatives.contains("TreeRecursion::default()"));
    // Speed 2 (q3) and 6 (q7) are rows 17 and 13 of the reversed chain of
    // 20 (the chain of 12 takes its rows as adjoints: below).
    for (entry, value) in [
        (
            "m2_2=::dalembert::__private::matrix_entry(&mass,17,17)+",
            "0.25",
        ),
        (
            "m6_6=::dalembert::__private::matrix_entry(&mass,13,13)+",
            "0.5",
        ),
    ] {
        assert!(
            derivatives.contains(&format!("{entry}{value};")),
            "{entry}{value} in the looped accelerations_jacobian"
        );
    }
    assert!(derivatives.contains("m1_1=::dalembert::__private::matrix_entry(&mass,18,18);"));
    // The chain of 12 takes the jacobian's rows as adjoints
    // (`plan::ADJOINT_ROW_AT_MOST`), over its own unrolled `M`, whose
    // diagonal carries the armatures.
    let rows = dalembert_codegen::generate(&with_statements(&chain(Family::Spatial, 12), &outputs))
        .unwrap()
        .replace(char::is_whitespace, "");
    assert!(rows.contains("weight_lanes") && !rows.contains("TreeRecursion::default()"));
    assert!(
        rows.contains(",0.25+x") && rows.contains(",0.5+x"),
        "the armatures in M"
    );
}
