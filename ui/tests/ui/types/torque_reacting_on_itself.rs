//! A torque cannot react on the frame it acts on.

use dalembert_macros::dalembert;

dalembert! {
    pub Motor {
        coordinates phi;
        inputs tau;
        frame Rotor = N.rotate_x(phi);
        torque tau * Rotor.x on Rotor reacting Rotor;
    }
}

fn main() {}
