//! The coefficients of the embedded explicit Runge–Kutta pairs: Dormand and
//! Prince's 5(4) pair (`DOPRI5`) and their 8(5,3) pair (`DOP853`), as
//! published by Hairer, Nørsett and Wanner, *Solving Ordinary Differential
//! Equations I* (2nd ed., 1993), §II.5 and the codes `dopri5.f`/`dop853.f`.

/// An explicit Runge–Kutta method of `S` stages with an embedded error
/// estimate, the constants of its step-size controller and its continuous
/// extension over `T` slopes.
pub(crate) struct EmbeddedPair<const S: usize, const T: usize> {
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
    /// The dense output.
    pub(crate) dense: DenseOutput<T>,
}

/// A continuous extension of a step from `y₀` to `y₁` of length `h`, written
/// in Hairer's nested form
/// `y(θ) = r₁ + θ (r₂ + θ' (r₃ + θ (r₄ + θ' (r₅ + θ (r₆ + θ' (r₇ + θ r₈))))))`,
/// `θ' = 1 − θ`, with `r₁ = y₀`, `r₂ = y₁ − y₀`, `r₃ = h k₁ − r₂`,
/// `r₄ = r₂ − h f(y₁) − r₃` and `r₅…` the rows of `d` applied to the `T`
/// slopes: the step's stages, the slope at `y₁`, then the extra stages.
pub(crate) struct DenseOutput<const T: usize> {
    /// The extra stages: time fraction and coefficients over the slopes
    /// before them.
    pub(crate) extra: &'static [(f64, [f64; T])],
    /// `h` times these rows applied to the slopes are `r₅, r₆, …`.
    pub(crate) d: &'static [[f64; T]],
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
pub(crate) const DOPRI5: EmbeddedPair<6, 7> = EmbeddedPair {
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
    // Shampine's fourth-order extension (`contd5` of `dopri5.f`).
    dense: DenseOutput {
        extra: &[],
        d: &[[
            -12715105075.0 / 11282082432.0,
            0.0,
            87487479700.0 / 32700410799.0,
            -10690763975.0 / 1880347072.0,
            701980252875.0 / 199316789632.0,
            -1453857185.0 / 822651844.0,
            69997945.0 / 29380423.0,
        ]],
    },
};

/// Dormand–Prince 8(5,3): twelve slopes per step, the first being the last
/// step's slope at its new point.
pub(crate) const DOP853: EmbeddedPair<12, 16> = EmbeddedPair {
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
    // The seventh-order extension of `dop853.f` (`contd8`): three more
    // stages at c = 0.1, 0.2 and 7/9.
    dense: DenseOutput {
        extra: &[
            (
                0.1,
                dop853_row(&[
                    (1, 0.056167502283047954),
                    (7, 0.25350021021662483),
                    (8, -0.2462390374708025),
                    (9, -0.12419142326381637),
                    (10, 0.15329179827876568),
                    (11, 0.00820105229563469),
                    (12, 0.007567897660545699),
                    (13, -8.298e-3),
                ]),
            ),
            (
                0.2,
                dop853_row(&[
                    (1, 0.03183464816350214),
                    (6, 0.028300909672366776),
                    (7, 0.053541988307438566),
                    (8, -0.05492374857139099),
                    (11, -0.00010834732869724932),
                    (12, 0.0003825710908356584),
                    (13, -0.00034046500868740456),
                    (14, 0.1413124436746325),
                ]),
            ),
            (
                7.0 / 9.0,
                dop853_row(&[
                    (1, -0.42889630158379194),
                    (6, -4.697621415361164),
                    (7, 7.683421196062599),
                    (8, 4.06898981839711),
                    (9, 0.3567271874552811),
                    (13, -0.0013990241651590145),
                    (14, 2.9475147891527724),
                    (15, -9.15095847217987),
                ]),
            ),
        ],
        d: &[
            dop853_row(&[
                (1, -8.428938276109013),
                (6, 0.5667149535193777),
                (7, -3.0689499459498917),
                (8, 2.38466765651207),
                (9, 2.117034582445028),
                (10, -0.871391583777973),
                (11, 2.2404374302607883),
                (12, 0.6315787787694688),
                (13, -0.08899033645133331),
                (14, 18.148505520854727),
                (15, -9.194632392478356),
                (16, -4.436036387594894),
            ]),
            dop853_row(&[
                (1, 10.427508642579134),
                (6, 242.28349177525817),
                (7, 165.20045171727028),
                (8, -374.5467547226902),
                (9, -22.113666853125306),
                (10, 7.733432668472264),
                (11, -30.674084731089398),
                (12, -9.332130526430229),
                (13, 15.697238121770845),
                (14, -31.139403219565178),
                (15, -9.35292435884448),
                (16, 35.81684148639408),
            ]),
            dop853_row(&[
                (1, 19.985053242002433),
                (6, -387.0373087493518),
                (7, -189.17813819516758),
                (8, 527.8081592054236),
                (9, -11.57390253995963),
                (10, 6.8812326946963),
                (11, -1.0006050966910838),
                (12, 0.7777137798053443),
                (13, -2.778205752353508),
                (14, -60.19669523126412),
                (15, 84.32040550667716),
                (16, 11.99229113618279),
            ]),
            dop853_row(&[
                (1, -25.69393346270375),
                (6, -154.18974869023643),
                (7, -231.5293791760455),
                (8, 357.6391179106141),
                (9, 93.40532418362432),
                (10, -37.45832313645163),
                (11, 104.0996495089623),
                (12, 29.8402934266605),
                (13, -43.53345659001114),
                (14, 96.32455395918828),
                (15, -39.17726167561544),
                (16, -149.72683625798564),
            ]),
        ],
    },
};

/// A row over DOP853's sixteen slopes from its non-zero entries, numbered
/// from 1 as in `dop853.f` (`k₁…k₁₂` the stages, `k₁₃ = f(y₁)`, `k₁₄…k₁₆`
/// the extra stages of the dense output).
const fn dop853_row(entries: &[(usize, f64)]) -> [f64; 16] {
    let mut row = [0.0; 16];
    let mut i = 0;
    while i < entries.len() {
        row[entries[i].0 - 1] = entries[i].1;
        i += 1;
    }
    row
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `Σ bᵢ = 1` and `Σⱼ aᵢⱼ = cᵢ`: the conditions every consistent
    /// explicit method meets, which catch a mistyped coefficient.
    fn assert_consistent<const S: usize, const T: usize>(pair: &EmbeddedPair<S, T>) {
        assert!((pair.b.iter().sum::<f64>() - 1.0).abs() < 1e-14);
        for (row, c) in pair.a.iter().zip(pair.c) {
            assert!((row.iter().sum::<f64>() - c).abs() < 1e-13, "{row:?}");
        }
        let order_two: f64 = pair.b.iter().zip(pair.c).map(|(b, c)| b * c).sum();
        assert!((order_two - 0.5).abs() < 1e-14);
    }

    /// The extra stages of a dense output are consistent too.
    fn assert_extra_stages_consistent<const S: usize, const T: usize>(pair: &EmbeddedPair<S, T>) {
        for (c, row) in pair.dense.extra {
            assert!((row.iter().sum::<f64>() - c).abs() < 1e-13, "{row:?}");
        }
    }

    #[test]
    fn the_dense_outputs_extra_stages_are_consistent() {
        assert_extra_stages_consistent(&DOPRI5);
        assert_extra_stages_consistent(&DOP853);
    }

    #[test]
    fn both_pairs_are_consistent() {
        assert_consistent(&DOPRI5);
        assert_consistent(&DOP853);
    }
}
