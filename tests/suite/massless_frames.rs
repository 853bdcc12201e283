//! Acceptance models written from the language of `docs/language.md` against
//! dal_sympy's values: two bodies on a massless tilted frame with every kind
//! of load (`force` at a point built through several frames, `torque ..
//! reacting`, `potential`, `dissipation`, `t` and speeds in loads, `^` with
//! negative exponents, two `gravity` statements, a particle), and a torque on
//! a massless frame that carries only a particle. The numbers are dal_sympy's,
//! and the accelerations solve its `M`, `f` at 30 digits; none comes from
//! this project.

use crate::dal_sympy::{Expected, check_unconstrained};

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
