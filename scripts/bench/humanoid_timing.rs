//! The timing side of scripts/bench/humanoid.sh: per-call thread CPU time of
//! the generated `mass_matrix` + `forcing`, `dalembert::accelerations` and
//! `accelerations_jacobian` of the floating humanoids and Solo-12, and of the
//! first two of dm_control's humanoid and cheetah, by the peers' harness's
//! method (1000 random states, the median of 9 repeats of passes over them,
//! each repeat about 20 ms). humanoid.sh generates the models with
//! `dalembert urdf`/`dalembert mjcf` and `dalembert generate` into the folder
//! `$HUMANOID_MODELS` at compile time, and builds this file in a temporary
//! crate that depends on the repository's `dalembert`. Prints `robot function
//! nanoseconds` lines.
#![allow(missing_docs)]
use std::hint::black_box;

mod g1 {
    include!(concat!(env!("HUMANOID_MODELS"), "/g1.rs"));
}
mod talos {
    include!(concat!(env!("HUMANOID_MODELS"), "/talos_reduced.rs"));
}
mod solo {
    include!(concat!(env!("HUMANOID_MODELS"), "/solo12.rs"));
}
mod humanoid {
    include!(concat!(env!("HUMANOID_MODELS"), "/humanoid.rs"));
}
mod cheetah {
    include!(concat!(env!("HUMANOID_MODELS"), "/cheetah.rs"));
}

#[repr(C)]
struct Timespec {
    sec: i64,
    nsec: i64,
}
unsafe extern "C" {
    fn clock_gettime(clk: i32, tp: *mut Timespec) -> i32;
}
/// The thread's CPU time in seconds (`CLOCK_THREAD_CPUTIME_ID`, Linux).
fn cpu() -> f64 {
    let mut t = Timespec { sec: 0, nsec: 0 };
    unsafe { clock_gettime(3, &mut t) };
    t.sec as f64 + 1e-9 * t.nsec as f64
}

/// A deterministic uniform draw in [-1, 1) (xorshift64*).
struct Rng(u64);
impl Rng {
    fn uniform(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        ((self.0.wrapping_mul(2685821657736338717) >> 11) as f64) / 4503599627370496.0 - 1.0
    }
}

/// One call's arguments.
struct State<const NQ: usize, const NV: usize, const NU: usize> {
    q: [f64; NQ],
    v: [f64; NV],
    u: [f64; NU],
}

/// 1000 states: coordinates U(-π, π) (a free joint's quaternion, after its
/// position, a normalised draw), speeds U(-2, 2), inputs U(-10, 10).
fn states<const NQ: usize, const NV: usize, const NU: usize>(free: bool) -> Vec<State<NQ, NV, NU>> {
    let mut r = Rng(20261128);
    (0..1000)
        .map(|_| {
            let mut q = [0.0; NQ];
            for x in q.iter_mut() {
                *x = std::f64::consts::PI * r.uniform();
            }
            if free {
                let mut p = [r.uniform(), r.uniform(), r.uniform(), r.uniform()];
                let n = p.iter().map(|x| x * x).sum::<f64>().sqrt();
                for x in p.iter_mut() {
                    *x /= n;
                }
                q[3..7].copy_from_slice(&p);
            }
            let mut v = [0.0; NV];
            for x in v.iter_mut() {
                *x = 2.0 * r.uniform();
            }
            let mut u = [0.0; NU];
            for x in u.iter_mut() {
                *x = 10.0 * r.uniform();
            }
            State { q, v, u }
        })
        .collect()
}

/// The median over 9 repeats of the time per call of `f` over the states.
fn time<T>(states: usize, mut f: impl FnMut(usize) -> T) -> f64 {
    let pass = |f: &mut dyn FnMut(usize) -> T| {
        let t = cpu();
        for k in 0..states {
            black_box(f(k));
        }
        cpu() - t
    };
    pass(&mut f);
    let once = pass(&mut f);
    let passes = ((0.02 / once.max(1e-9)).ceil() as usize).max(1);
    let mut v: Vec<f64> = (0..9)
        .map(|_| {
            let t = cpu();
            for _ in 0..passes {
                for k in 0..states {
                    black_box(f(k));
                }
            }
            (cpu() - t) * 1e9 / (passes * states) as f64
        })
        .collect();
    v.sort_by(|a, b| a.partial_cmp(b).unwrap());
    v[4]
}

macro_rules! bench {
    ($name:expr, $sys:expr, $nq:expr, $nv:expr, $nu:expr, $free:expr $(, $jac:path)?) => {{
        let s = $sys;
        let st = states::<$nq, $nv, $nu>($free);
        for x in &st { dalembert::accelerations(&s, 0.0, &x.q, &x.v, &x.u).expect("solvable"); }
        let mf = time(st.len(), |k| { let x = &st[k]; (black_box(&s).mass_matrix(&x.q), black_box(&s).forcing(0.0, &x.q, &x.v, &x.u)) });
        let acc = time(st.len(), |k| { let x = &st[k]; dalembert::accelerations(black_box(&s), 0.0, &x.q, &x.v, &x.u) });
        println!("{} mass_matrix+forcing {:.1}", $name, mf);
        println!("{} accelerations {:.1}", $name, acc);
        $( let j = time(st.len(), |k| { let x = &st[k]; $jac(black_box(&s), 0.0, &x.q, &x.v, &x.u) });
           println!("{} accelerations_jacobian {:.1}", $name, j); )?
    }};
}

fn main() {
    bench!(
        "g1",
        g1::G1 {},
        36,
        35,
        29,
        true,
        g1::G1::accelerations_jacobian
    );
    bench!(
        "talos_reduced",
        talos::Talos {},
        39,
        38,
        32,
        true,
        talos::Talos::accelerations_jacobian
    );
    bench!(
        "floating_solo12",
        solo::FloatingSolo12 {},
        19,
        18,
        12,
        true,
        solo::FloatingSolo12::accelerations_jacobian
    );
    bench!("humanoid", humanoid::Humanoid {}, 28, 27, 21, true);
    bench!("cheetah", cheetah::Cheetah {}, 9, 9, 9, false);
}
