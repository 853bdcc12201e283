//! Generated functions and the runtime's solvers allocate nothing: a
//! counting global allocator around calls of every generated function and
//! of `accelerations`, `constrained_accelerations`, `Rk4::step` (unconstrained
//! and constrained with projection), `energy`, the adaptive pairs and the
//! Taylor integrator finds no allocation.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

use dalembert::constrained::constrained_accelerations;
use dalembert::{
    Constrained, Stabilisation, State, Unconstrained, accelerations, energy, integrate,
};

use dalembert_fixtures::seeds::{ConstrainedPendulum, DoublePendulum, RotatingBar};

/// The system allocator, counting the allocations of the thread that
/// counts (the test harness's own threads are left alone).
struct Counting;

thread_local! {
    /// Allocations seen on this thread while counting, if counting.
    static ALLOCATIONS: Cell<Option<usize>> = const { Cell::new(None) };
}

// SAFETY: every call is forwarded unchanged to `System`; the counter is a
// thread-local `Cell` with a const initialiser, which never allocates.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count();
        // SAFETY: the caller upholds `GlobalAlloc::alloc`'s contract.
        unsafe { System.alloc(layout) }
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        count();
        // SAFETY: as for `alloc`.
        unsafe { System.alloc_zeroed(layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count();
        // SAFETY: as for `alloc`.
        unsafe { System.realloc(ptr, layout, new_size) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: as for `alloc`.
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

fn count() {
    // `try_with`: the thread-local may be gone while a thread exits.
    let _ = ALLOCATIONS.try_with(|n| n.set(n.get().map(|n| n + 1)));
}

/// The allocations `job` makes on this thread.
fn allocations<T>(job: impl FnOnce() -> T) -> (usize, T) {
    ALLOCATIONS.with(|n| n.set(Some(0)));
    let value = std::hint::black_box(job());
    let made = ALLOCATIONS.with(|n| n.replace(None)).unwrap_or(0);
    (made, value)
}

#[test]
fn the_counter_sees_an_allocation() {
    let (made, _) = allocations(|| Box::new(std::hint::black_box(1.0_f64)));
    assert_eq!(made, 1);
}

#[test]
fn generated_functions_and_solvers_allocate_nothing() {
    let pendulum = DoublePendulum {
        m: 1.0,
        L: 1.2,
        g: 9.81,
    };
    let bar = RotatingBar {
        m: 2.0,
        l: 0.7,
        d: 0.3,
    };
    let constrained = ConstrainedPendulum {
        m: 1.0,
        l: 2.0,
        g: 9.81,
    };
    let (q, qd) = ([0.3, -0.4], [0.5, 0.1]);
    // On the constraints: `x = l/2 sin θ`, `y = −l/2 cos θ`, and rates.
    let (theta, rate): (f64, f64) = (0.4, 0.2);
    let cq = [theta.sin(), -theta.cos(), theta];
    let cqd = [theta.cos() * rate, theta.sin() * rate, rate];
    let (made, _) = allocations(|| {
        (
            pendulum.mass_matrix(&q),
            pendulum.forcing(0.0, &q, &qd, &[]),
            pendulum.kinetic_energy(&q, &qd),
            pendulum.potential_energy(&q),
            bar.mass_matrix(&q),
            bar.forcing(0.0, &q, &qd, &[0.1, -0.2]),
            constrained.constraint_jacobian(&cq),
            constrained.constraint_bias(0.0, &cq, &cqd),
            constrained.constraint_residual(0.0, &cq),
            energy(&pendulum, &q, &qd),
        )
    });
    assert_eq!(made, 0, "the generated functions allocated");
    let (made, result) = allocations(|| {
        let a = accelerations(&pendulum, 0.0, &q, &qd, &[]).map(|_| ());
        let b = constrained_accelerations(&constrained, 0.0, &cq, &cqd, &[0.5]).map(|_| ());
        let state = State { t: 0.0, q, v: qd };
        let c = integrate::Rk4::step(&Unconstrained::without_inputs(&pendulum), &state, 1e-3)
            .map(|_| ());
        let start = State {
            t: 0.0,
            q: cq,
            v: cqd,
        };
        let projection = Stabilisation::Projection {
            tolerance: 1e-12,
            max_iterations: 10,
        };
        let d = integrate::Rk4::step(
            &Constrained::new(&constrained, |_, _, _| [0.5], projection),
            &start,
            1e-3,
        )
        .map(|_| ());
        (a, b, c.is_ok(), d.is_ok())
    });
    assert_eq!(made, 0, "the solvers allocated");
    assert!(
        result.0.is_ok() && result.1.is_ok() && result.2 && result.3,
        "{result:?}"
    );
}

#[test]
fn rank_revealing_solves_and_the_augmented_lagrangian_allocate_nothing() {
    use dalembert::constrained::ConstraintSolver;
    use dalembert::integrate::{AugmentedLagrangian, AugmentedLagrangianSettings, Integration};
    use dalembert_fixtures::iftomm::Bricard;

    // Bricard's mechanism: five closure rows of rank four.
    let bricard = Bricard {
        m: 1.0,
        L: 1.0,
        g: 9.81,
    };
    let start = State {
        t: 0.0,
        q: [0.0; 5],
        v: [0.0; 5],
    };
    let projection = Stabilisation::Projection {
        tolerance: 1e-12,
        max_iterations: 10,
    };
    let dynamics = Constrained::without_inputs(&bricard, projection);
    let (made, result) = allocations(|| {
        let solve = ConstraintSolver::RankRevealing
            .accelerations(&bricard, 0.0, &start.q, &start.v, &[])
            .is_ok();
        let step = integrate::Rk4::step(&dynamics, &start, 1e-3).is_ok();
        let settings = AugmentedLagrangianSettings::default();
        let alf = Integration::new(
            &dynamics,
            start,
            1e-2,
            AugmentedLagrangian {
                steps: 10,
                settings,
            },
        )
        .run()
        .is_ok();
        (solve, step, alf)
    });
    assert_eq!(
        made, 0,
        "the rank-revealing solver or the augmented Lagrangian allocated"
    );
    assert_eq!(result, (true, true, true));
}

#[test]
fn adaptive_pairs_dense_output_and_events_allocate_nothing() {
    let pendulum = DoublePendulum {
        m: 1.0,
        L: 1.2,
        g: 9.81,
    };
    let dynamics = Unconstrained::without_inputs(&pendulum);
    let start = State {
        t: 0.0,
        q: [0.3, -0.4],
        v: [0.5, 0.1],
    };
    let options = integrate::AdaptiveOptions::with_tolerance(1e-10);
    let pair = integrate::ExplicitPair::Dop853;
    let (made, result) = allocations(|| {
        let plain = integrate::Integration::new(
            &dynamics,
            start,
            1.0,
            integrate::Adaptive { pair, options },
        )
        .run();
        let mut middle = 0.0;
        let dense = integrate::Integration::new(
            &dynamics,
            start,
            1.0,
            integrate::Adaptive { pair, options },
        )
        .dense(|step| {
            middle += step.state_at(0.5 * (step.start().t + step.end().t)).q[0];
            std::ops::ControlFlow::Continue(())
        })
        .run();
        let upright = integrate::Event::record(
            |_, q: &[f64; 2], _: &[f64; 2]| q[0],
            integrate::Crossing::Either,
        );
        let mut crossings = 0;
        let events = integrate::Integration::new(
            &dynamics,
            start,
            1.0,
            integrate::Adaptive { pair, options },
        )
        .event(upright, |_| crossings += 1)
        .run();
        (plain.is_ok(), dense.is_ok(), events.is_ok(), crossings)
    });
    assert_eq!(made, 0, "the adaptive integrators allocated");
    assert!(result.0 && result.1 && result.2, "{result:?}");
    assert!(
        result.3 > 0,
        "the pendulum crosses θ₁ = 0 within 1 s: {result:?}"
    );
}

#[test]
fn the_taylor_integrator_its_polynomials_and_events_allocate_nothing() {
    let pendulum = dalembert_generated::taylor_double_pendulum::TaylorDoublePendulum {
        m: 1.0,
        L: 1.2,
        g: 9.81,
    };
    let dynamics = Unconstrained::without_inputs(&pendulum);
    let start = State {
        t: 0.0,
        q: [0.3, -0.4],
        v: [0.5, 0.1],
    };
    let options = integrate::Taylor::with_tolerance(1e-14);
    let (made, result) = allocations(|| {
        let plain = integrate::Integration::new(&dynamics, start, 1.0, options).run();
        let mut middle = 0.0;
        let dense = integrate::Integration::new(&dynamics, start, 1.0, options)
            .dense(|step| {
                middle += step.state_at(0.5 * (step.start().t + step.end().t)).q[0];
                std::ops::ControlFlow::Continue(())
            })
            .run();
        let upright = integrate::Event::record(
            |_, q: &[f64; 2], _: &[f64; 2]| q[0],
            integrate::Crossing::Either,
        );
        let mut crossings = 0;
        let events = integrate::Integration::new(&dynamics, start, 1.0, options)
            .event(upright, |_| crossings += 1)
            .run();
        (plain.is_ok(), dense.is_ok(), events.is_ok(), crossings)
    });
    assert_eq!(made, 0, "the Taylor integrator allocated");
    assert!(result.0 && result.1 && result.2, "{result:?}");
    assert!(
        result.3 > 0,
        "the pendulum crosses θ₁ = 0 within 1 s: {result:?}"
    );
}

/// `accelerations_x4` over lanes, on both routes of the solve (the unrolled
/// factorisation of seed example 1, the articulated-body recursion of the
/// chain of 30) and through the scalar call of a state that fails; the RK4
/// step of four states over it (`control::rk4_group_step_x4`).
#[test]
fn four_states_in_lanes_allocate_nothing() {
    use dalembert_generated::lanes::{double_pendulum, spatial_chain_30};
    let pendulum = double_pendulum::DoublePendulum {
        m: 1.0,
        L: 1.2,
        g: 9.81,
    };
    let chain = spatial_chain_30::SpatialChain30 {};
    let q = [[0.3, -0.4], [f64::NAN, 0.0], [0.1, 0.2], [1.0, 2.0]];
    let v = [[0.5, 0.1]; 4];
    let chain_q: [[f64; 30]; 4] =
        std::array::from_fn(|k| std::array::from_fn(|i| 0.1 * (i + k) as f64));
    let chain_v = [[0.2; 30]; 4];
    let states = std::array::from_fn(|k| dalembert::State {
        t: 0.0,
        q: chain_q[k],
        v: chain_v[k],
    });
    let (made, (a, b, c)) = allocations(|| {
        (
            pendulum.accelerations_x4([0.0; 4], &q, &v, &[[]; 4]),
            dalembert::accelerations_x4(&chain, [0.0; 4], &chain_q, &chain_v, &[[]; 4]),
            dalembert::control::rk4_group_step_x4(&chain, &states, &[[]; 4], 1e-3),
        )
    });
    assert_eq!(made, 0, "accelerations_x4 or rk4_group_step_x4 allocated");
    assert!(
        a[1].is_err() && a[0].is_ok() && b.iter().all(Result::is_ok) && c.iter().all(Result::is_ok),
        "{a:?} {b:?} {c:?}"
    );
}
