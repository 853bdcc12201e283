//! Acceptance models written from the language of `docs/language.md` against the independent
//! SymPy reading of the language (`dal_sympy.py --values`, 30
//! digits): a bead on a hoop spun at a set rate (time in the geometry), a
//! spherical pendulum (`rotate_x` then `rotate_y`) whose bob has products of
//! inertia, two bodies on a massless tilted frame with every kind of load
//! (`force` at a point built through several frames, `torque .. reacting`,
//! `potential`, `dissipation`, `t` and speeds in loads, `^` with negative
//! exponents, two `gravity` statements, a particle), a sled with a
//! nonholonomic knife edge, a rheonomic slider and a nonholonomic row with a
//! time term, and a torque on a massless frame that carries only a particle.
//! The numbers below are dal_sympy's, and the accelerations solve its `M`,
//! `f` (and `A`, `b`) at 30 digits; none comes from this project.

use dalembert::constrained::constrained_accelerations;
use dalembert::{ConstrainedSystem, MultibodySystem};
use dalembert_fixtures::reference::{assert_near, assert_near_all};

/// dal_sympy's values at one state.
struct Expected<const N: usize, const NU: usize> {
    t: f64,
    q: [f64; N],
    v: [f64; N],
    u: [f64; NU],
    mass: [[f64; N]; N],
    forcing: [f64; N],
    kinetic: f64,
    potential: f64,
    accelerations: [f64; N],
}

/// dal_sympy's `A`, `b` and residual at the same state.
struct Constraints<const N: usize, const NC: usize> {
    jacobian: [[f64; N]; NC],
    bias: [f64; NC],
    residual: [f64; NC],
}

/// dal_sympy's values are good to 30 digits: every comparison at 1e-11.
const TOLERANCE: f64 = 1e-11;

fn close(what: &str, actual: f64, expected: f64) {
    assert_near(what, actual, expected, TOLERANCE);
}

fn close_all(what: &str, actual: &[f64], expected: &[f64]) {
    assert_near_all(what, actual, expected, TOLERANCE);
}

fn close_rows<const C: usize>(what: &str, actual: &[[f64; C]], expected: &[[f64; C]]) {
    for (k, (a, e)) in actual.iter().zip(expected).enumerate() {
        close_all(&format!("{what}[{k}]"), a, e);
    }
}

/// `M`, `f`, `T` and `V` at the expected state.
fn check_equations<S, const N: usize, const NU: usize>(system: &S, e: &Expected<N, NU>)
where
    S: MultibodySystem<N, N, NU>,
{
    close_rows("M", &system.mass_matrix(&e.q), &e.mass);
    close_all("f", &system.forcing(e.t, &e.q, &e.v, &e.u), &e.forcing);
    close("T", system.kinetic_energy(&e.q, &e.v), e.kinetic);
    close("V", system.potential_energy(&e.q), e.potential);
}

fn check_unconstrained<S, const N: usize, const NU: usize>(system: &S, e: &Expected<N, NU>)
where
    S: MultibodySystem<N, N, NU>,
{
    check_equations(system, e);
    let vdot = dalembert::accelerations(system, e.t, &e.q, &e.v, &e.u).expect("regular");
    close_all("accelerations", &vdot, &e.accelerations);
}

fn check_constrained<S, const N: usize, const NU: usize, const NC: usize>(
    system: &S,
    e: &Expected<N, NU>,
    c: &Constraints<N, NC>,
) where
    S: ConstrainedSystem<N, N, NU, NC>,
{
    check_equations(system, e);
    close_rows("A", &system.constraint_jacobian(&e.q), &c.jacobian);
    close_all("b", &system.constraint_bias(e.t, &e.q, &e.v), &c.bias);
    close_all(
        "residual",
        &system.constraint_residual(e.t, &e.q),
        &c.residual,
    );
    let (vdot, _) = constrained_accelerations(system, e.t, &e.q, &e.v, &e.u).expect("regular");
    close_all("accelerations", &vdot, &e.accelerations);
}

dalembert::dalembert! {
    /// A bead on a hoop spun about the vertical at the set rate `W`.
    pub Hoop {
        parameters m, R, W, g;
        coordinates th;
        frame H = N.rotate_z(W * t);
        point P = O + R * sin(th) * H.x - R * cos(th) * H.z;
        particle bead { mass: m, at: P };
        gravity -g * N.z;
    }
}

#[test]
fn bead_on_a_spun_hoop() {
    let system = Hoop {
        m: 0.7,
        R: 1.3,
        W: 2.1,
        g: 9.81,
    };
    let states: [Expected<1, 0>; 3] = [
        Expected {
            t: 0.789646992846347,
            q: [-0.8238327648331624],
            v: [-1.8068543054927506],
            u: [],
            mass: [[1.183]],
            forcing: [3.9494943605131194],
            kinetic: 3.335499376639482,
            potential: -6.065195765865094,
            accelerations: [3.338541302208892],
        },
        Expected {
            t: 0.7313778338251711,
            q: [-1.3212742919913083],
            v: [-1.7680043009011728],
            u: [],
            mass: [[1.183]],
            forcing: [7.4022328916121225],
            kinetic: 4.298382244570067,
            potential: -2.2044654352545243,
            accelerations: [6.2571706607034],
        },
        Expected {
            t: 0.17189446737834335,
            q: [-1.0074357331894204],
            v: [-0.3273113945169621],
            u: [],
            mass: [[1.183]],
            forcing: [5.192041709608429],
            kinetic: 1.9279654202286143,
            potential: -4.767343437064925,
            accelerations: [4.388877184791571],
        },
    ];
    for expected in &states {
        check_unconstrained(&system, expected);
    }
}

dalembert::dalembert! {
    /// A spherical pendulum (`rotate_x` then `rotate_y`) whose bob has products of inertia.
    pub Spherical {
        parameters m, l, g, Ixx, Iyy, Izz, Ixy, Iyz, Izx;
        coordinates a, b;
        frame A = N.rotate_x(a);
        frame B = A.rotate_y(b);
        point G = O - l * B.z;
        body bob { mass: m, center: G, frame: B, inertia: [Ixx, Iyy, Izz, Ixy, Iyz, Izx] };
        gravity -g * N.z;
    }
}

#[test]
fn spherical_pendulum_with_products_of_inertia() {
    let system = Spherical {
        m: 1.2,
        l: 0.8,
        g: 9.81,
        Ixx: 0.31,
        Iyy: 0.27,
        Izz: 0.12,
        Ixy: 0.03,
        Iyz: -0.05,
        Izx: 0.02,
    };
    let states: [Expected<2, 0>; 3] = [
        Expected {
            t: 0.14487257333508552,
            q: [-0.8238327648331624, -0.8948234964231735],
            v: [0.1435280172267568, -0.5372443323496578],
            u: [],
            mass: [
                [0.4754823887601711, 0.05777462862567636],
                [0.05777462862567636, 1.038],
            ],
            forcing: [4.397133792912927, 5.000963672776621],
            kinetic: 0.1502422929612532,
            potential: -4.0032308611445275,
            accelerations: [8.721306246982264, 4.332459964572668],
        },
        Expected {
            t: 0.8363443027415189,
            q: [-0.5579989247747068, 0.5374956584419849],
            v: [-1.0373479994919, 0.204189015165543],
            u: [],
            mass: [
                [0.8444711232978911, 0.00017048756759460772],
                [0.00017048756759460772, 1.038],
            ],
            forcing: [4.111367866999479, -4.53345420361036],
            kinetic: 0.47596646879132865,
            potential: -6.862589016472899,
            accelerations: [4.869453190978133, -4.368289388092876],
        },
        Expected {
            t: 1.1542058972349973,
            q: [-0.5591105060789892, -1.4474497007074874],
            v: [-0.41327810139687937, 1.9050204223716802],
            u: [],
            mass: [
                [0.12961764376353113, 0.05331114494601987],
                [0.05331114494601987, 1.038],
            ],
            forcing: [0.6825285507314667, 7.9395667350828045],
            kinetic: 1.8526015902572743,
            potential: -0.9822495803945445,
            accelerations: [2.165489742434759, 7.537689785688579],
        },
    ];
    for expected in &states {
        check_unconstrained(&system, expected);
    }
}

dalembert::dalembert! {
    /// Two bodies on a massless tilted frame, with every kind of load.
    pub Mixed {
        parameters m1, m2, l1, l2, k, c, g, h, F0, w;
        coordinates q1, q2, q3;
        inputs u1, u2;
        frame A = N.rotate_z(q1);
        frame T = A.rotate_x(0.3);
        frame B = T.rotate_y(q2);
        point P1 = O + l1 * A.x;
        point P2 = P1 + l2 * T.z + q3 * B.x;
        point Tip = P2 + l2 / 2 * B.y - l1 / 3 * T.x + 0.2 * N.z;
        body b1 { mass: m1, center: P1, frame: A, inertia: [m1*l1^2/12, m1*l1^2/12, m1*l1^2/6] };
        body b2 { inertia: [1.5*m2, 2*m2, 2.5*m2, 0.1*m2, -0.2*m2, 0.05*m2], frame: B, center: P2, mass: m2 };
        particle tip { mass: m1 / 4, at: Tip };
        gravity -g * N.z;
        gravity h * N.x;
        force (F0 * sin(w * t) + u1) * B.z + q3^-2 * A.y - t^2 * dt(q3) * N.x at Tip;
        torque (u2 - c * dt(q2)) * T.y on B reacting A;
        torque 0.5 * u1 * T.x on T;
        potential k / 2 * q3^2 + k * (1 + q2^2)^-1 + exp(-q1^2);
        dissipation c / 2 * dt(q1)^2 + c * dt(q3)^2 * (2 + cos(q2));
    }
}

#[test]
fn massless_frame_reacting_torques_potential_dissipation_and_time_in_loads() {
    let system = Mixed {
        m1: 1.1,
        m2: 0.9,
        l1: 0.6,
        l2: 0.45,
        k: 3.2,
        c: 0.4,
        g: 9.81,
        h: 1.7,
        F0: 2.3,
        w: 1.9,
    };
    let states: [Expected<3, 2>; 3] = [
        Expected {
            t: 0.7313778338251711,
            q: [
                -0.8238327648331624,
                -0.8948234964231735,
                -0.5724362866675428,
            ],
            v: [
                -1.7680043009011728,
                0.02974293275768103,
                -1.8500173662320605,
            ],
            u: [-0.39812589802568477, -2.5808674585522864],
            mass: [
                [2.254689619797616, 0.49302797169707346, -0.08906837951775264],
                [
                    0.49302797169707346,
                    2.1850278801951273,
                    5.793197272716806e-32,
                ],
                [-0.08906837951775264, 5.793197272716806e-32, 1.175],
            ],
            forcing: [0.3997132100229272, -6.702291913045639, -2.3848704287687466],
            kinetic: 5.218367104389127,
            potential: 2.4662479633679117,
            accelerations: [0.8102400445791713, -3.250193273587911, -1.9682584348746281],
        },
        Expected {
            t: 1.1542058972349973,
            q: [0.5907130133438651, -0.5591105060789892, -1.4474497007074874],
            v: [
                -0.41327810139687937,
                1.9050204223716802,
                -1.8136692775289749,
            ],
            u: [2.1508107542920776, -1.2623442820099424],
            mass: [
                [2.995458083719379, 0.8489801459699922, -0.019537412698454628],
                [0.8489801459699922, 4.261754997391879, 2.896598636358403e-32],
                [-0.019537412698454628, 2.896598636358403e-32, 1.175],
            ],
            forcing: [3.5638782733770094, -24.744967775220147, 0.8407013572007352],
            kinetic: 9.238455051016146,
            potential: 4.061634994030237,
            accelerations: [3.0103511449770948, -6.405975037610395, 0.7655453871382282],
        },
        Expected {
            t: 0.7447950854514624,
            q: [
                -0.6442550833574375,
                -1.0709136896467344,
                -0.6030557124435914,
            ],
            v: [
                0.19097786283823126,
                -1.7488441001067074,
                -1.7615953201350694,
            ],
            u: [-1.7642477230840408, 1.0823998390907157],
            mass: [
                [2.1769750656983735, 0.5443129494338961, -0.12202028111177605],
                [
                    0.5443129494338961,
                    2.227319525965246,
                    -1.4482993181792014e-32,
                ],
                [-0.12202028111177605, -1.4482993181792014e-32, 1.175],
            ],
            forcing: [
                1.4163367819035588,
                0.0019640249598812678,
                -6.299886093593196,
            ],
            kinetic: 5.128174962465061,
            potential: 1.171403681507295,
            accelerations: [0.3749510843109654, -0.09074885901126502, -5.322667622878644],
        },
    ];
    for expected in &states {
        check_unconstrained(&system, expected);
    }
}

dalembert::dalembert! {
    /// A torque on a massless frame that carries only a particle, and a motor reacting on the ground.
    pub Massless {
        parameters m, l, c, g;
        coordinates a, b;
        inputs u;
        frame A = N.rotate_z(a);
        frame B = A.rotate_x(b);
        point P = O + l * B.y + 0.3 * l * A.x;
        particle bob { mass: m, at: P };
        gravity -g * N.z;
        torque u * A.x - c * dt(b) * B.x on B;
        torque u * N.z on A reacting N;
    }
}

#[test]
fn torque_on_a_massless_frame_carrying_a_particle() {
    let system = Massless {
        m: 0.8,
        l: 0.9,
        c: 0.3,
        g: 9.81,
    };
    let states: [Expected<2, 1>; 3] = [
        Expected {
            t: 0.14487257333508552,
            q: [-0.8238327648331624, -0.8948234964231735],
            v: [0.1435280172267568, -0.5372443323496578],
            u: [-2.652006451351759],
            mass: [
                [0.31197705753254495, 0.15165118003069408],
                [0.15165118003069408, 0.648],
            ],
            forcing: [-2.5681256929959635, -6.903454965898386],
            kinetic: 0.08503624241219152,
            potential: -5.509992874448551,
            accelerations: [-3.445064968947551, -9.847232713078832],
        },
        Expected {
            t: 0.13971084714923787,
            q: [-1.0074357331894204, 0.5859472336891717],
            v: [-1.6371479466245398, -0.30192324342994414],
            u: [1.9611127480322281],
            mass: [
                [0.5081637556537605, -0.10750103334513902],
                [-0.10750103334513902, 0.648],
            ],
            forcing: [2.2710320812930713, -4.63351053256264],
            kinetic: 0.6574018834473402,
            potential: 3.905870878206718,
            accelerations: [3.0639551223982466, -6.642179306761877],
        },
        Expected {
            t: 1.1542058972349973,
            q: [-0.6238019611496456, -1.130625915731737],
            v: [-0.41327810139687937, 1.9050204223716802],
            u: [-2.7205039162934623],
            mass: [
                [0.1759681511636307, 0.17586961029165063],
                [0.17586961029165063, 0.648],
            ],
            forcing: [-2.0265753470385808, -6.2589308457636355],
            kinetic: 1.0523941728369537,
            potential: -6.389929173929973,
            accelerations: [-2.5568248806866314, -8.964912114835311],
        },
    ];
    for expected in &states {
        check_unconstrained(&system, expected);
    }
}

dalembert::dalembert! {
    /// A knife-edge sled with a slider driven along its axis (rheonomic) and a nonholonomic row with a time term.
    pub Sled {
        parameters m, I, a, w, c, g;
        coordinates x, y, psi, s;
        inputs u;
        frame B = N.rotate_z(psi);
        point G = O + x * N.x + y * N.y;
        point S = G + s * B.y;
        body sled { mass: m, center: G, frame: B, inertia: [I/2, I/2, I] };
        particle slider { mass: m / 3, at: S };
        gravity -g * N.x;
        force u * B.x at G;
        constraint dt(x) * sin(psi) - dt(y) * cos(psi) == 0;
        constraint s == a * sin(w * t) + c;
        constraint dt(psi) + x * dt(s) == t^2 + 1;
    }
}

#[test]
fn rheonomic_and_nonholonomic_constraints() {
    let system = Sled {
        m: 2.0,
        I: 0.35,
        a: 0.2,
        w: 3.0,
        c: 0.1,
        g: 1.3,
    };
    let states: [(Expected<4, 1>, Constraints<4, 3>); 3] = [
        (
            Expected {
                t: 1.8194081262862045,
                q: [
                    -0.8238327648331624,
                    -0.8948234964231735,
                    -0.5724362866675428,
                    -0.8656889169125855,
                ],
                v: [
                    -1.141207276657353,
                    -1.6562110652433133,
                    -0.3273113945169621,
                    -1.0373479994919,
                ],
                u: [0.3062835227483145],
                mass: [
                    [
                        2.6666666666666665,
                        0.0,
                        0.4851227077951701,
                        0.3611210382238872,
                    ],
                    [
                        0.0,
                        2.6666666666666665,
                        -0.3126184804543853,
                        0.5603891863665342,
                    ],
                    [
                        0.4851227077951701,
                        -0.3126184804543853,
                        0.8496115339101903,
                        0.0,
                    ],
                    [
                        0.3611210382238872,
                        0.5603891863665342,
                        0.0,
                        0.6666666666666666,
                    ],
                ],
                forcing: [
                    -2.862156978519214,
                    -0.46310772075895235,
                    -0.2387496580805853,
                    -0.5312864386449979,
                ],
                kinetic: 7.200090135523735,
                potential: -3.262357609345664,
                accelerations: [
                    -1.3130532562039148,
                    0.8703431092505703,
                    3.5442080057739056,
                    1.3221382847866991,
                ],
            },
            Constraints {
                jacobian: [
                    [-0.5416815573358308, -0.8405837795498013, 0.0, 0.0],
                    [0.0, 0.0, 0.0, 1.0],
                    [0.0, 0.0, 1.0, -0.8238327648331624],
                ],
                bias: [
                    -0.020339567593549924,
                    1.3221382847866991,
                    2.4549871671263044,
                ],
                residual: [0.0, -0.8187846630473967, 0.0],
            },
        ),
        (
            Expected {
                t: 0.09316536123551256,
                q: [
                    -0.5591105060789892,
                    -1.4474497007074874,
                    1.0771029486174988,
                    -0.5495893133897715,
                ],
                v: [
                    1.433873836194718,
                    -0.841562854673295,
                    -1.4229796665702499,
                    -1.5288310476865266,
                ],
                u: [-1.1491090553883938],
                mass: [
                    [
                        2.6666666666666665,
                        0.0,
                        0.173626790738094,
                        -0.587059096809152,
                    ],
                    [
                        0.0,
                        2.6666666666666665,
                        0.3226414059345612,
                        0.31592097318485707,
                    ],
                    [
                        0.173626790738094,
                        0.3226414059345612,
                        0.5513656089281602,
                        0.0,
                    ],
                    [
                        -0.587059096809152,
                        0.31592097318485707,
                        0.0,
                        0.6666666666666666,
                    ],
                ],
                forcing: [
                    -1.9833315670325686,
                    1.1908245776996451,
                    1.3684572721649786,
                    0.02127846928611445,
                ],
                kinetic: 6.748456528437203,
                potential: -1.518815926692233,
                accelerations: [
                    -0.19462742256726437,
                    -0.17673882720539077,
                    2.100844963687294,
                    -0.496568379604689,
                ],
            },
            Constraints {
                jacobian: [
                    [0.8805886452137279, -0.4738814597772856, 0.0, 0.0],
                    [0.0, 0.0, 0.0, 1.0],
                    [0.0, 0.0, 1.0, -0.5591105060789892],
                ],
                bias: [-0.08763344492453105, -0.496568379604689, 2.378481561710895],
                residual: [0.0, -0.7047635777902924, 0.0],
            },
        ),
        (
            Expected {
                t: 0.9928289902269836,
                q: [
                    -1.3161263591200314,
                    -0.6030557124435914,
                    -0.8723975427257312,
                    -1.0643682931333867,
                ],
                v: [
                    0.12688098632074274,
                    1.108915099923228,
                    -0.137592536641304,
                    1.693765534555446,
                ],
                u: [-0.830505864332602],
                mass: [
                    [
                        2.6666666666666665,
                        0.0,
                        0.45625366254848854,
                        0.510581825320721,
                    ],
                    [
                        0.0,
                        2.6666666666666665,
                        -0.5434471059215449,
                        0.42866145627593477,
                    ],
                    [
                        0.45625366254848854,
                        -0.5434471059215449,
                        1.1052532422851193,
                        0.0,
                    ],
                    [
                        0.510581825320721,
                        0.42866145627593477,
                        0.0,
                        0.6666666666666666,
                    ],
                ],
                forcing: [
                    -4.210762500455096,
                    0.8654058144599115,
                    -0.9238637542095132,
                    -0.6771899114167267,
                ],
                kinetic: 3.6176085826225237,
                potential: -5.269052615980784,
                accelerations: [
                    -0.9688971836435487,
                    1.3183400200760504,
                    1.3860604930761637,
                    -0.29229020685713986,
                ],
            },
            Constraints {
                jacobian: [
                    [-0.7658727379810816, -0.6429921844139022, 0.0, 0.0],
                    [0.0, 0.0, 0.0, 1.0],
                    [0.0, 0.0, 1.0, -1.3161263591200314],
                ],
                bias: [
                    -0.10563039044972382,
                    -0.29229020685713986,
                    1.7707513388334921,
                ],
                residual: [0.0, -1.19684498278418, 0.0],
            },
        ),
    ];
    for (expected, constraints) in &states {
        check_constrained(&system, expected, constraints);
    }
}
