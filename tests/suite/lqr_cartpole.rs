//! LQR balancing of the cart-pole from its generated `linearize`: the gain
//! from the linearisation at the upright, the nonlinear model released
//! 0.3 rad off and simulated under `F = −K x` comes back to rest upright.

use dalembert::{State, Unconstrained, integrate};
use dalembert_fixtures::cart_pole::{
    CART_POLE, INPUT_WEIGHT, RELEASE_ANGLE, STATE_WEIGHTS, feedback,
};
use dalembert_lab::lqr;

#[test]
fn the_closed_loop_returns_to_upright() {
    let (a, b) = CART_POLE
        .linearize(0.0, &[0.0; 2], &[0.0; 2], &[0.0])
        .expect("the upright is regular");
    let (gain, _) = lqr(&a, &b, &STATE_WEIGHTS, &INPUT_WEIGHT).expect("stabilisable");
    let controlled = Unconstrained::new(&CART_POLE, |_, q: &[f64; 2], v: &[f64; 2]| {
        feedback(&gain, q, v)
    });
    let start = State {
        t: 0.0,
        q: [0.0, RELEASE_ANGLE],
        v: [0.0; 2],
    };
    let mut largest_force = 0.0_f64;
    let end =
        integrate::Integration::new(&controlled, start, 10.0, integrate::Rk4 { steps: 10_000 })
            .observe(|s| {
                largest_force = largest_force.max(feedback(&gain, &s.q, &s.v)[0].abs());
            })
            .run()
            .expect("integrates")
            .end;
    let distance = end
        .q
        .iter()
        .chain(&end.v)
        .fold(0.0_f64, |m, x| m.max(x.abs()));
    assert!(distance < 1e-3, "not at rest upright after 10 s: {end:?}");
    assert!(
        largest_force > 1.0,
        "the controller acted ({largest_force} N)"
    );
    // Without the controller, the pole falls.
    let falling = integrate::Integration::new(
        &Unconstrained::new(&CART_POLE, |_, _: &[f64; 2], _: &[f64; 2]| [0.0]),
        start,
        2.0,
        integrate::Rk4 { steps: 2_000 },
    )
    .run()
    .expect("integrates")
    .end;
    assert!(falling.q[1].abs() > 1.0, "the open loop falls: {falling:?}");
}
