//! Acceptance models written from the language of `docs/language.md` against
//! dal_sympy's values: a bead on a hoop spun at a set rate (time in the
//! geometry) and a spherical pendulum (`rotate_x` then `rotate_y`) whose bob
//! has products of inertia. The numbers are dal_sympy's, and the
//! accelerations solve its `M`, `f` at 30 digits; none comes from this project.

use crate::dal_sympy::{Expected, check_unconstrained};

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
