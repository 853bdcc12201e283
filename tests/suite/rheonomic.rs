//! Prescribed motion: a bead and a pendulum carried round by a platform
//! turning at a set rate, `frame R = N.rotate_z(w * t)`. The positions
//! depend on `t`, but `t` cancels from the mass matrix and the energies
//! (the platform is symmetric about its axis), so the timeless API holds;
//! the forcing keeps the Coriolis and centrifugal terms of the moving frame.
//! The generated code is checked against the interpreter on d'Alembert's
//! route and on Lagrange's (with the explicit time derivatives).

use dalembert_codegen::testing::{Interpreter, Route, Sample};

dalembert::dalembert! {
    /// A bead sliding on a turning platform, a pendulum hanging from it.
    pub Carousel {
        parameters m, l, w, g;
        coordinates s, theta;
        frame R = N.rotate_z(w * t);
        point C = O + s * R.x;
        frame B = R.rotate_x(theta);
        particle bead { mass: m, at: C };
        body arm { mass: m, center: C - l * B.y, frame: B, inertia: [m*l^2/12, 0, m*l^2/12] };
        gravity -g * N.z;
    }
}

const CAROUSEL: &str = "pub Carousel {
    parameters m, l, w, g;
    coordinates s, theta;
    frame R = N.rotate_z(w * t);
    point C = O + s * R.x;
    frame B = R.rotate_x(theta);
    particle bead { mass: m, at: C };
    body arm { mass: m, center: C - l * B.y, frame: B, inertia: [m*l^2/12, 0, m*l^2/12] };
    gravity -g * N.z;
}";

fn close(what: &str, a: f64, b: f64) {
    assert!(
        (a - b).abs() <= 1e-10 * b.abs().max(1.0),
        "{what}: {a} vs {b}"
    );
}

#[test]
fn generated_code_agrees_with_both_routes() {
    for route in [Route::Dalembert, Route::Lagrange] {
        let interpreter = Interpreter::new(CAROUSEL, route).expect("a valid model");
        for seed in 0..10 {
            let sample = Sample::random(&interpreter, seed);
            let at = sample.values();
            let [m, l, w, g] = [0, 1, 2, 3].map(|i| sample.parameters[i]);
            let system = Carousel { m, l, w, g };
            let (q, qd) = ([sample.q[0], sample.q[1]], [sample.qd[0], sample.qd[1]]);
            let mass = system.mass_matrix(&q);
            let expected = interpreter.mass_matrix(&at);
            for (k, row) in expected.iter().enumerate() {
                for (j, value) in row.iter().enumerate() {
                    close(&format!("{route:?} M[{k}][{j}]"), mass[k][j], *value);
                }
            }
            let forcing = system.forcing(sample.t, &q, &qd, &[]);
            for (k, value) in interpreter.forcing(&at).iter().enumerate() {
                close(&format!("{route:?} f[{k}]"), forcing[k], *value);
            }
            close(
                "T",
                system.kinetic_energy(&q, &qd),
                interpreter.kinetic_energy(&at),
            );
            close(
                "V",
                system.potential_energy(&q),
                interpreter.potential_energy(&at),
            );
        }
    }
}

#[test]
fn the_bead_feels_the_centrifugal_force() {
    // At rest on the platform (ṡ = θ̇ = 0) with the arm level (θ = 0, its
    // centre at C − l R.y), the centrifugal force on the bead and on the
    // arm has the component m w² s along R.x each: f_s = 2 m w² s.
    let system = Carousel {
        m: 1.5,
        l: 0.4,
        w: 3.0,
        g: 9.81,
    };
    let forcing = system.forcing(0.7, &[0.2, 0.0], &[0.0, 0.0], &[]);
    close("f_s", forcing[0], 2.0 * 1.5 * 9.0 * 0.2);
}
