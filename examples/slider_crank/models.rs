//! The constrained models of the slider-crank example, shared with
//! `tests/constraints.rs`: seed example 3 as written in DESIGN §3, and a
//! slider-crank, both in dependent coordinates.

use dalembert::State;

#[path = "../../tests/seeds/mod.rs"]
mod seeds;
pub use seeds::ConstrainedPendulum;

/// Seed example 3 with the parameters of the reference data.
pub const SEED_3: ConstrainedPendulum = ConstrainedPendulum {
    m: 1.7,
    l: 1.1,
    g: 9.81,
};

impl ConstrainedPendulum {
    /// The state at time 0 on the constraint manifold with the bar at angle
    /// `theta` from the downward vertical, turning at `theta_dot`.
    pub fn assembled(&self, theta: f64, theta_dot: f64) -> State<3, 3> {
        let (s, c) = theta.sin_cos();
        let half = self.l / 2.0;
        State {
            t: 0.0,
            q: [half * s, -half * c, theta],
            v: [half * c * theta_dot, half * s * theta_dot, theta_dot],
        }
    }
}

dalembert::dalembert! {
    /// A slider-crank in the vertical plane, in dependent coordinates: the
    /// crank (length `r`) turns by `theta` about `O`, the connecting rod
    /// (length `L`) points along `R.x` at `phi` from the horizontal, and the
    /// slider sits at `s` on the horizontal line through `O`. Two loop-closure
    /// constraints join the rod's far end to the slider. A motor torque
    /// `T_motor` drives the crank.
    pub SliderCrank {
        parameters m_crank, r, m_rod, L, m_slider, g;
        coordinates theta, phi, s;
        inputs T_motor;
        frame C = N.rotate_z(theta);
        frame R = N.rotate_z(phi);
        point A = O + r * C.x;
        point G_crank = O + r/2 * C.x;
        point G_rod = A + L/2 * R.x;
        point P = O + s * N.x;
        body crank { mass: m_crank, center: G_crank, frame: C, inertia: [0, 0, m_crank*r^2/12] };
        body rod { mass: m_rod, center: G_rod, frame: R, inertia: [0, 0, m_rod*L^2/12] };
        particle slider { mass: m_slider, at: P };
        gravity -g * N.y;
        torque T_motor * N.z on C;
        constraint r*cos(theta) + L*cos(phi) - s == 0;
        constraint r*sin(theta) + L*sin(phi) == 0;
    }
}

/// The slider-crank of the examples and tests: a 0.1 m crank and a 0.3 m
/// rod.
pub const SLIDER_CRANK: SliderCrank = SliderCrank {
    m_crank: 0.5,
    r: 0.1,
    m_rod: 0.8,
    L: 0.3,
    m_slider: 1.2,
    g: 9.81,
};

/// The crank speed the examples and tests start [`SLIDER_CRANK`] at: 4
/// revolutions per second, in rad/s.
pub const CRANK_SPEED: f64 = 4.0 * std::f64::consts::TAU;

impl SliderCrank {
    /// The state at time 0 on the constraint manifold with the crank at
    /// `theta`, turning at `theta_dot`, and the rod on the slider's side
    /// (`L ≥ r`, else the mechanism cannot turn fully).
    pub fn assembled(&self, theta: f64, theta_dot: f64) -> State<3, 3> {
        let (sin_theta, cos_theta) = theta.sin_cos();
        let phi = -(self.r * sin_theta / self.L).asin();
        let (sin_phi, cos_phi) = phi.sin_cos();
        let phi_dot = -self.r * cos_theta * theta_dot / (self.L * cos_phi);
        State {
            t: 0.0,
            q: [theta, phi, self.r * cos_theta + self.L * cos_phi],
            v: [
                theta_dot,
                phi_dot,
                -self.r * sin_theta * theta_dot - self.L * sin_phi * phi_dot,
            ],
        }
    }
}
