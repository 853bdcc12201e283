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
                    (1, 5.61675022830479523392909219681e-2),
                    (7, 2.53500210216624811088794765333e-1),
                    (8, -2.46239037470802489917441475441e-1),
                    (9, -1.24191423263816360469010140626e-1),
                    (10, 1.5329179827876569731206322685e-1),
                    (11, 8.20105229563468988491666602057e-3),
                    (12, 7.56789766054569976138603589584e-3),
                    (13, -8.298e-3),
                ]),
            ),
            (
                0.2,
                dop853_row(&[
                    (1, 3.18346481635021405060768473261e-2),
                    (6, 2.83009096723667755288322961402e-2),
                    (7, 5.35419883074385676223797384372e-2),
                    (8, -5.49237485713909884646569340306e-2),
                    (11, -1.08347328697249322858509316994e-4),
                    (12, 3.82571090835658412954920192323e-4),
                    (13, -3.40465008687404560802977114492e-4),
                    (14, 1.41312443674632500278074618366e-1),
                ]),
            ),
            (
                7.0 / 9.0,
                dop853_row(&[
                    (1, -4.28896301583791923408573538692e-1),
                    (6, -4.69762141536116384314449447206e0),
                    (7, 7.68342119606259904184240953878e0),
                    (8, 4.06898981839711007970213554331e0),
                    (9, 3.56727187455281109270669543021e-1),
                    (13, -1.39902416515901462129418009734e-3),
                    (14, 2.9475147891527723389556272149e0),
                    (15, -9.15095847217987001081870187138e0),
                ]),
            ),
        ],
        d: &[
            dop853_row(&[
                (1, -0.84289382761090128651353491142e+01),
                (6, 0.56671495351937776962531783590e+00),
                (7, -0.30689499459498916912797304727e+01),
                (8, 0.23846676565120698287728149680e+01),
                (9, 0.21170345824450282767155149946e+01),
                (10, -0.87139158377797299206789907490e+00),
                (11, 0.22404374302607882758541771650e+01),
                (12, 0.63157877876946881815570249290e+00),
                (13, -0.88990336451333310820698117400e-01),
                (14, 0.18148505520854727256656404962e+02),
                (15, -0.91946323924783554000451984436e+01),
                (16, -0.44360363875948939664310572000e+01),
            ]),
            dop853_row(&[
                (1, 0.10427508642579134603413151009e+02),
                (6, 0.24228349177525818288430175319e+03),
                (7, 0.16520045171727028198505394887e+03),
                (8, -0.37454675472269020279518312152e+03),
                (9, -0.22113666853125306036270938578e+02),
                (10, 0.77334326684722638389603898808e+01),
                (11, -0.30674084731089398182061213626e+02),
                (12, -0.93321305264302278729567221706e+01),
                (13, 0.15697238121770843886131091075e+02),
                (14, -0.31139403219565177677282850411e+02),
                (15, -0.93529243588444783865713862664e+01),
                (16, 0.35816841486394083752465898540e+02),
            ]),
            dop853_row(&[
                (1, 0.19985053242002433820987653617e+02),
                (6, -0.38703730874935176555105901742e+03),
                (7, -0.18917813819516756882830838328e+03),
                (8, 0.52780815920542364900561016686e+03),
                (9, -0.11573902539959630126141871134e+02),
                (10, 0.68812326946963000169666922661e+01),
                (11, -0.10006050966910838403183860980e+01),
                (12, 0.77771377980534432092869265740e+00),
                (13, -0.27782057523535084065932004339e+01),
                (14, -0.60196695231264120758267380846e+02),
                (15, 0.84320405506677161018159903784e+02),
                (16, 0.11992291136182789328035130030e+02),
            ]),
            dop853_row(&[
                (1, -0.25693933462703749003312586129e+02),
                (6, -0.15418974869023643374053993627e+03),
                (7, -0.23152937917604549567536039109e+03),
                (8, 0.35763911791061412378285349910e+03),
                (9, 0.93405324183624310003907691704e+02),
                (10, -0.37458323136451633156875139351e+02),
                (11, 0.10409964950896230045147246184e+03),
                (12, 0.29840293426660503123344363579e+02),
                (13, -0.43533456590011143754432175058e+02),
                (14, 0.96324553959188282948394950600e+02),
                (15, -0.39177261675615439165231486172e+02),
                (16, -0.14972683625798562581422125276e+03),
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
