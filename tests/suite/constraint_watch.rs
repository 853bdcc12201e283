//! The constraint watch of every constrained integration: a start off the
//! constraints (at position or velocity level, time-dependent or not) is
//! refused by the runs that would carry the error along and corrected by
//! the projections; rows that are barely independent are reported, not
//! solved as independent; the limits are the user's to set. (The drift of
//! a redundant loop and the crossing of singular positions are in
//! `redundant_parallelogram` and `loop_rows`.)

use dalembert::constrained::{
    BARELY_INDEPENDENT, DRIFT_LIMIT, DriftLimits, constraint_conditioning, constraint_drift,
};
use dalembert::integrate::{
    Adaptive, AdaptiveOptions, AugmentedLagrangian, AugmentedLagrangianSettings, DriftLevel,
    ExplicitPair, Failure, Integration, Rk4,
};
use dalembert::{Constrained, Stabilisation, State};
use dalembert_fixtures::slider_crank::SEED_3;

dalembert::dalembert! {
    /// A particle whose `x` a drive prescribes, `x = a sin(w t)`: a
    /// rheonomic row.
    pub DrivenSlider {
        parameters m, a, w, g;
        coordinates x, y;
        particle p { mass: m, at: O + x * N.x + y * N.y };
        gravity -g * N.y;
        constraint x == a * sin(w * t);
    }
}

dalembert::dalembert! {
    /// A particle held in the plane `x = 0` twice over, by rows whose
    /// normals differ by the small angle `e`: independent, barely.
    pub NearlyParallel {
        parameters m, e, g;
        coordinates x, y, z;
        particle p { mass: m, at: O + x * N.x + y * N.y + z * N.z };
        gravity -g * N.z;
        constraint x == 0;
        constraint x + e * y == 0;
    }
}

const PROJECTION: Stabilisation = Stabilisation::Projection {
    tolerance: 1e-12,
    max_iterations: 5,
};

const BAUMGARTE: Stabilisation = Stabilisation::Baumgarte {
    alpha: 10.0,
    beta: 10.0,
};

/// The cause of a drift failure: row, level, value and time.
fn drift(cause: Failure) -> (usize, DriftLevel, f64, f64) {
    match cause {
        Failure::ConstraintDrift {
            row,
            level,
            residual,
            t,
            ..
        } => (row, level, residual, t),
        other => panic!("expected a drift failure, got {other:?}"),
    }
}

#[test]
fn a_start_off_the_velocity_form_is_refused_unless_projected() {
    // Seed example 3 assembled, then its x speed 1e-3 m/s off: the rows'
    // velocity form is −1e-3 on row 0.
    let mut start = SEED_3.assembled(0.4, 1.0);
    start.t = 2.0;
    start.v[0] += 1e-3;
    for stabilisation in [Stabilisation::None, BAUMGARTE] {
        let dynamics = Constrained::without_inputs(&SEED_3, stabilisation);
        let mut seen = 0;
        let error = Integration::new(&dynamics, start, 3.0, Rk4 { steps: 100 })
            .observe(|_| seen += 1)
            .run()
            .unwrap_err();
        let (row, level, residual, t) = drift(error.cause);
        assert_eq!((row, level, t), (0, DriftLevel::Velocity, 2.0), "{error}");
        assert!((residual.abs() - 1e-3).abs() < 1e-12, "{residual}");
        assert_eq!((error.t, error.q, seen), (2.0, start.q, 0));
        println!("{stabilisation:?}: {error}");
        let options = AdaptiveOptions::with_tolerance(1e-9);
        let error = Integration::new(
            &dynamics,
            start,
            3.0,
            Adaptive {
                pair: ExplicitPair::Dop853,
                options,
            },
        )
        .run()
        .unwrap_err();
        assert_eq!(drift(error.cause).3, 2.0);
    }
    // Projected, the start's error is removed by the first step's
    // projection and the run holds the constraints.
    let dynamics = Constrained::without_inputs(&SEED_3, PROJECTION);
    let mut worst = 0.0f64;
    Integration::new(&dynamics, start, 3.0, Rk4 { steps: 1000 })
        .observe(|s| {
            if s.t > 2.0 {
                let psi = SEED_3.constraint_velocity(s.t, &s.q, &s.v);
                worst = worst.max(psi[0].abs()).max(psi[1].abs());
            }
        })
        .run()
        .unwrap();
    assert!(worst < 1e-12, "{worst:e}");
}

#[test]
fn a_rheonomic_start_off_its_drive_is_refused() {
    let slider = DrivenSlider {
        m: 0.5,
        a: 0.2,
        w: 3.0,
        g: 9.81,
    };
    // At rest at t = 0, where the drive moves at a w = 0.6 m/s.
    let at_rest = State {
        t: 0.0,
        q: [0.0, 0.0],
        v: [0.0, 0.0],
    };
    let dynamics = Constrained::without_inputs(&slider, Stabilisation::None);
    let error = Integration::new(&dynamics, at_rest, 1.0, Rk4 { steps: 100 })
        .run()
        .unwrap_err();
    let (row, level, residual, t) = drift(error.cause);
    assert_eq!((row, level, t), (0, DriftLevel::Velocity, 0.0));
    assert!((residual.abs() - 0.6).abs() < 1e-12, "{residual}");
    // Off at position level: x = 0 at t = 0.5 s, where the drive is at
    // a sin(1.5).
    let late = State { t: 0.5, ..at_rest };
    let error = Integration::new(&dynamics, late, 1.0, Rk4 { steps: 100 })
        .run()
        .unwrap_err();
    let (row, level, residual, _) = drift(error.cause);
    assert_eq!((row, level), (0, DriftLevel::Position));
    assert!((residual.abs() - 0.2 * 1.5f64.sin()).abs() < 1e-12);
    // On the drive, the unstabilised run follows it within the limit.
    let on = State {
        t: 0.0,
        q: [0.0, 0.0],
        v: [0.6, 0.0],
    };
    let end = Integration::new(&dynamics, on, 1.0, Rk4 { steps: 1000 })
        .run()
        .unwrap()
        .end;
    assert!((end.q[0] - 0.2 * 3f64.sin()).abs() < 1e-9, "{end:?}");
    assert!((end.q[1] + 9.81 / 2.0).abs() < 1e-9, "{end:?}");
}

#[test]
fn barely_independent_rows_are_reported_not_solved_as_independent() {
    let e = 1e-4;
    let plane = NearlyParallel { m: 1.0, e, g: 9.81 };
    let q = [0.0, 0.0, 0.0];
    let conditioning = constraint_conditioning(&plane, 0.0, &q).unwrap();
    assert_eq!(conditioning.rank, 2);
    let weakest = conditioning.weakest.unwrap();
    // A = [[1, 0, 0], [1, e, 0]]: σ₂/σ₁ = e/2 to first order; the
    // estimate (the pivots of the augmented Schur complement) is √2 e.
    println!("{conditioning:?}");
    let estimate = weakest.singular_value;
    assert!(
        (estimate / (2f64.sqrt() * e) - 1.0).abs() < 1e-3,
        "{weakest:?}"
    );
    assert_eq!(weakest.row + weakest.with, 1, "rows 0 and 1: {weakest:?}");
    // Well apart, the rows are no concern.
    let apart = NearlyParallel { e: 1.0, ..plane };
    let singular_value = constraint_conditioning(&apart, 0.0, &q)
        .unwrap()
        .weakest
        .unwrap()
        .singular_value;
    assert!(singular_value > BARELY_INDEPENDENT, "{singular_value}");
    // An unstabilised run refuses to start there, naming both rows.
    let start = State {
        t: 0.0,
        q,
        v: [0.0; 3],
    };
    let dynamics = Constrained::without_inputs(&plane, Stabilisation::None);
    let error = Integration::new(&dynamics, start, 1.0, Rk4 { steps: 10 })
        .run()
        .unwrap_err();
    match error.cause {
        Failure::SingularPosition {
            row,
            with,
            singular_value,
            t,
        } => {
            assert_eq!((row + with, t), (1, 0.0), "{error}");
            assert_eq!(singular_value, weakest.singular_value);
        }
        other => panic!("{other:?}"),
    }
    assert!(error.to_string().contains("singular position"), "{error}");
    // The user may accept such rows by lowering the limit.
    let accepting = DriftLimits {
        conditioning: e / 10.0,
        ..DriftLimits::default()
    };
    let end = Integration::new(
        &dynamics.with_drift_limits(accepting),
        start,
        1.0,
        Rk4 { steps: 10 },
    )
    .run()
    .unwrap()
    .end;
    assert!((end.q[2] + 9.81 / 2.0).abs() < 1e-12, "{end:?}");
}

#[test]
fn the_limits_are_the_users_and_every_integrator_watches_them() {
    // Seed 3 started 1e-8 off its velocity form: within the default limit,
    // beyond a tighter one.
    let mut start = SEED_3.assembled(0.4, 1.0);
    start.v[0] += 1e-8;
    const { assert!(1e-8 < DRIFT_LIMIT) };
    let tight = DriftLimits {
        velocity: 1e-9,
        ..DriftLimits::default()
    };
    let lax = Constrained::without_inputs(&SEED_3, Stabilisation::None);
    Integration::new(&lax, start, 0.1, Rk4 { steps: 10 })
        .run()
        .unwrap();
    let strict = lax.with_drift_limits(tight);
    let failures = [
        Integration::new(&strict, start, 0.1, Rk4 { steps: 10 })
            .run()
            .map(|_| ()),
        Integration::new(&strict, start, 0.1, Adaptive::dopri5(1e-8))
            .run()
            .map(|_| ()),
    ];
    for failure in failures {
        let error = failure.unwrap_err();
        assert_eq!(drift(error.cause).1, DriftLevel::Velocity, "{error}");
    }
    // The augmented Lagrangian holds its own constraints: its drift is
    // watched too, against the larger of the limit and its tolerance.
    let assembled = SEED_3.assembled(0.4, 1.0);
    let mut worst = 0.0f64;
    Integration::new(
        &lax,
        assembled,
        1.0,
        AugmentedLagrangian {
            steps: 1000,
            settings: AugmentedLagrangianSettings::for_step(1e-3),
        },
    )
    .observe(|s| worst = worst.max(constraint_drift(&SEED_3, s)))
    .run()
    .unwrap();
    assert!(worst < DRIFT_LIMIT, "{worst:e}");
}
