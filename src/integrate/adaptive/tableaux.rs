//! The coefficients of the embedded explicit Runge–Kutta pairs: Dormand and
//! Prince's 5(4) pair (`DOPRI5`) and their 8(5,3) pair (`DOP853`), as
//! published by Hairer, Nørsett and Wanner, *Solving Ordinary Differential
//! Equations I* (2nd ed., 1993), §II.5 and the codes `dopri5.f`/`dop853.f`.

/// An explicit Runge–Kutta method of `S` stages with an embedded error
/// estimate and the constants of its step-size controller.
pub(crate) struct EmbeddedPair<const S: usize> {
    /// Stage times `cᵢ` as fractions of the step.
    pub(crate) c: [f64; S],
    /// Stage coefficients `aᵢⱼ` (strictly lower triangular).
    pub(crate) a: [[f64; S]; S],
    /// Weights `bᵢ` of the propagated solution.
    pub(crate) b: [f64; S],
    /// How the local error is estimated from the stage slopes.
    pub(crate) estimate: ErrorEstimate<S>,
    /// Order of the propagated solution (Hairer's initial-step heuristic).
    pub(crate) order: i32,
    /// The controller's exponent `1 / (q̂ + 1)`, `q̂` the order of the error
    /// estimate.
    pub(crate) exponent: f64,
    /// Smallest factor by which one step may shrink the next.
    pub(crate) min_factor: f64,
    /// Largest factor by which one step may grow the next.
    pub(crate) max_factor: f64,
}

/// An embedded local-error estimate.
pub(crate) enum ErrorEstimate<const S: usize> {
    /// `h (Σ eᵢ kᵢ + e_new f(y₁))`: the difference of two embedded solutions,
    /// the last slope being that at the new point (first same as last).
    Embedded {
        /// Coefficients of the stage slopes.
        e: [f64; S],
        /// Coefficient of the slope at the new point.
        e_new: f64,
    },
    /// DOP853's blend of a fifth- and a third-order difference,
    /// `h ‖err₅‖² / √(‖err₅‖² + 0.01 ‖err₃‖²)`, which is robust when the
    /// fifth-order one happens to vanish.
    FifthAndThird {
        /// Coefficients of the fifth-order difference.
        e5: [f64; S],
        /// Coefficients of the third-order difference.
        e3: [f64; S],
    },
}

/// Dormand–Prince 5(4), FSAL: six new slopes per step.
pub(crate) const DOPRI5: EmbeddedPair<6> = EmbeddedPair {
    c: [0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0],
    a: [
        [0.0; 6],
        [1.0 / 5.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0],
        [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0],
        [
            19372.0 / 6561.0,
            -25360.0 / 2187.0,
            64448.0 / 6561.0,
            -212.0 / 729.0,
            0.0,
            0.0,
        ],
        [
            9017.0 / 3168.0,
            -355.0 / 33.0,
            46732.0 / 5247.0,
            49.0 / 176.0,
            -5103.0 / 18656.0,
            0.0,
        ],
    ],
    b: [
        35.0 / 384.0,
        0.0,
        500.0 / 1113.0,
        125.0 / 192.0,
        -2187.0 / 6784.0,
        11.0 / 84.0,
    ],
    estimate: ErrorEstimate::Embedded {
        e: [
            71.0 / 57600.0,
            0.0,
            -71.0 / 16695.0,
            71.0 / 1920.0,
            -17253.0 / 339200.0,
            22.0 / 525.0,
        ],
        e_new: -1.0 / 40.0,
    },
    order: 5,
    exponent: 1.0 / 5.0,
    min_factor: 0.2,
    max_factor: 10.0,
};

/// Dormand–Prince 8(5,3): twelve slopes per step, the first being the last
/// step's slope at its new point.
pub(crate) const DOP853: EmbeddedPair<12> = EmbeddedPair {
    c: [
        0.0,
        0.05260015195876773,
        0.0789002279381516,
        0.1183503419072274,
        0.2816496580927726,
        0.3333333333333333,
        0.25,
        0.3076923076923077,
        0.6512820512820513,
        0.6,
        0.8571428571428571,
        1.0,
    ],
    a: [
        [0.0; 12],
        [
            0.05260015195876773,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
        ],
        [
            0.0197250569845379,
            0.0591751709536137,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
        ],
        [
            0.02958758547680685,
            0.0,
            0.08876275643042054,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
        ],
        [
            0.2413651341592667,
            0.0,
            -0.8845494793282861,
            0.924834003261792,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
        ],
        [
            0.037037037037037035,
            0.0,
            0.0,
            0.17082860872947386,
            0.12546768756682242,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
        ],
        [
            0.037109375,
            0.0,
            0.0,
            0.17025221101954405,
            0.06021653898045596,
            -0.017578125,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
        ],
        [
            0.03709200011850479,
            0.0,
            0.0,
            0.17038392571223998,
            0.10726203044637328,
            -0.015319437748624402,
            0.008273789163814023,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
        ],
        [
            0.6241109587160757,
            0.0,
            0.0,
            -3.3608926294469414,
            -0.868219346841726,
            27.59209969944671,
            20.154067550477894,
            -43.48988418106996,
            0.0,
            0.0,
            0.0,
            0.0,
        ],
        [
            0.47766253643826434,
            0.0,
            0.0,
            -2.4881146199716677,
            -0.590290826836843,
            21.230051448181193,
            15.279233632882423,
            -33.28821096898486,
            -0.020331201708508627,
            0.0,
            0.0,
            0.0,
        ],
        [
            -0.9371424300859873,
            0.0,
            0.0,
            5.186372428844064,
            1.0914373489967295,
            -8.149787010746927,
            -18.52006565999696,
            22.739487099350505,
            2.4936055526796523,
            -3.0467644718982196,
            0.0,
            0.0,
        ],
        [
            2.273310147516538,
            0.0,
            0.0,
            -10.53449546673725,
            -2.0008720582248625,
            -17.9589318631188,
            27.94888452941996,
            -2.8589982771350235,
            -8.87285693353063,
            12.360567175794303,
            0.6433927460157636,
            0.0,
        ],
    ],
    b: [
        0.054293734116568765,
        0.0,
        0.0,
        0.0,
        0.0,
        4.450312892752409,
        1.8915178993145003,
        -5.801203960010585,
        0.3111643669578199,
        -0.1521609496625161,
        0.20136540080403034,
        0.04471061572777259,
    ],
    estimate: ErrorEstimate::FifthAndThird {
        e5: [
            0.01312004499419488,
            0.0,
            0.0,
            0.0,
            0.0,
            -1.2251564463762044,
            -0.4957589496572502,
            1.6643771824549864,
            -0.35032884874997366,
            0.3341791187130175,
            0.08192320648511571,
            -0.022355307863886294,
        ],
        e3: [
            -0.18980075407240762,
            0.0,
            0.0,
            0.0,
            0.0,
            4.450312892752409,
            1.8915178993145003,
            -5.801203960010585,
            -0.4226823213237919,
            -0.1521609496625161,
            0.20136540080403034,
            0.02265179219836082,
        ],
    },
    order: 8,
    exponent: 1.0 / 8.0,
    min_factor: 1.0 / 3.0,
    max_factor: 6.0,
};

#[cfg(test)]
mod tests {
    use super::*;

    /// `Σ bᵢ = 1` and `Σⱼ aᵢⱼ = cᵢ`: the conditions every consistent
    /// explicit method meets, which catch a mistyped coefficient.
    fn assert_consistent<const S: usize>(pair: &EmbeddedPair<S>) {
        assert!((pair.b.iter().sum::<f64>() - 1.0).abs() < 1e-14);
        for (row, c) in pair.a.iter().zip(pair.c) {
            assert!((row.iter().sum::<f64>() - c).abs() < 1e-13, "{row:?}");
        }
        let order_two: f64 = pair.b.iter().zip(pair.c).map(|(b, c)| b * c).sum();
        assert!((order_two - 0.5).abs() < 1e-14);
    }

    #[test]
    fn both_pairs_are_consistent() {
        assert_consistent(&DOPRI5);
        assert_consistent(&DOP853);
    }
}
