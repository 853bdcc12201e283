//! Scenes drawn from the model a generated system carries
//! (`Scene::of(&system)`, the macro's front door), and the energy plot of a
//! driven system: the energy change beside the inputs' work.

use dalembert::{Model, MultibodySystem, State, Unconstrained, energy, integrate};
use dalembert_fixtures::scene_page::embedded_data;
use dalembert_fixtures::seeds::{DoublePendulum, RotatingBar};
use dalembert_lab::{Recording, Scene, input_power};

/// Seed example 1 as the language reference writes it.
const DOUBLE_PENDULUM: &str = include_str!("../../../generated/models/double_pendulum.dal");

/// A made-up swing of `nq` coordinates, `samples` samples over 2 s.
fn swing(nq: usize, samples: usize) -> Recording {
    let mut recording = Recording::new();
    for i in 0..samples {
        let t = 2.0 * i as f64 / (samples - 1) as f64;
        let q: Vec<f64> = (0..nq).map(|k| (t + k as f64).sin()).collect();
        recording.push(t, &q, 1.0);
    }
    recording
}

#[test]
fn a_macro_system_carries_its_model_and_draws_as_its_pasted_text() {
    let pendulum = DoublePendulum {
        m: 1.5,
        L: 0.7,
        g: 9.81,
    };
    assert_eq!(pendulum.parameter_values(), [1.5, 0.7, 9.81]);
    assert_eq!(<DoublePendulum as Model<3>>::PARAMETERS, ["m", "L", "g"]);
    // The macro's text is its tokens: the same model, the same equations.
    let unicode = dalembert_codegen::Style::Unicode;
    assert_eq!(
        dalembert_codegen::equations(DoublePendulum::SOURCE, unicode).unwrap(),
        DoublePendulum::EQUATIONS
    );
    let recording = swing(2, 50);
    let carried = Scene::of(&pendulum).unwrap().poses(&recording).unwrap();
    let pasted = Scene::new(DOUBLE_PENDULUM, &[1.5, 0.7, 9.81])
        .unwrap()
        .poses(&recording)
        .unwrap();
    assert_eq!(carried.len(), 50);
    assert_eq!(carried, pasted);
}

#[test]
fn an_undriven_page_plots_the_energy_error_alone() {
    let bar = RotatingBar {
        m: 1.0,
        l: 1.0,
        d: 0.5,
    };
    let data = embedded_data(&Scene::of(&bar).unwrap().html(&swing(2, 20)).unwrap());
    assert_eq!(data["work"], serde_json::Value::Null);
    assert_eq!(data["error"], serde_json::Value::Null);
    assert_eq!(data["energy"].as_array().unwrap().len(), 20);
}

/// A turntable carrying a mass, driven by a constant torque `u` from rest:
/// its energy grows by the torque's work, `u Δφ`.
#[test]
fn a_driven_page_plots_the_energy_change_beside_the_inputs_work() {
    dalembert::dalembert! {
        pub DrivenTurntable {
            // A mass on an arm of a turntable.
            parameters m, r;
            coordinates phi;
            inputs u;
            frame B = N.rotate_z(phi);
            particle p { mass: m, at: O + r * B.x };
            torque u * N.z on B;
        }
    }
    let table = DrivenTurntable { m: 2.0, r: 0.5 };
    let u = [0.3];
    let dynamics = Unconstrained::new(&table, |_, _: &[f64; 1], _: &[f64; 1]| u);
    let start = State {
        t: 0.0,
        q: [0.0],
        v: [0.0],
    };
    let mut recording = Recording::new();
    let end = integrate::Integration::new(&dynamics, start, 1.0, integrate::Rk4 { steps: 1000 })
        .observe(|s| {
            let power = input_power(&table, s.t, &s.q, &s.v, &u);
            recording.push_driven(s.t, &s.q, energy(&table, &s.q, &s.v), power);
        })
        .run()
        .unwrap()
        .end;
    // The macro's text as written, comments kept.
    assert!(
        DrivenTurntable::SOURCE.starts_with(
            "pub DrivenTurntable {\n    // A mass on an arm of a turntable.\n    parameters m, r;"
        ),
        "{}",
        DrivenTurntable::SOURCE
    );
    assert!(recording.is_driven());
    // Power u φ̇: the work is u Δφ, and the energy grew by as much.
    let work = u[0] * end.q[0];
    assert!(work > 0.05, "the table turned: {work}");
    let gained = energy(&table, &end.q, &end.v) - energy(&table, &start.q, &start.v);
    assert!((gained - work).abs() < 1e-9 * work, "{gained} vs {work}");
    assert_eq!(<DrivenTurntable as MultibodySystem<1, 1, 1>>::INPUTS, ["u"]);
    let html = Scene::of(&table).unwrap().html(&recording).unwrap();
    let data = embedded_data(&html);
    let (energy_change, work_drawn) = (
        data["energy"].as_array().unwrap(),
        data["work"].as_array().unwrap(),
    );
    assert_eq!(energy_change.len(), work_drawn.len());
    assert!(!energy_change.is_empty());
    let last = |list: &[serde_json::Value]| list.last().unwrap().as_f64().unwrap();
    assert!(
        (last(work_drawn) - work).abs() < 1e-4 * work,
        "trapezoidal work"
    );
    assert!((last(energy_change) - gained).abs() < 1e-4 * gained);
    // RK4 is exact for this motion (φ quadratic in t): no energy error.
    let error = data["error"].as_f64().unwrap();
    assert!(error < 1e-9 * work, "energy error {error}");
    assert!(html.contains("energy change E(t) − E(0)"));
    assert!(html.contains("work of the inputs W(t)"));
}
