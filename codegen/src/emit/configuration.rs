//! The kinematic equation `q̇ = N(q) v` and the configuration update
//! `q ⊕ h v` as inherent `coordinate_rates` and `integrate_configuration`.
//! When every speed is its coordinate's rate, `N` is the identity and the
//! update is `q + h v`. A quaternion joint's update is exact for constant
//! speeds: the quaternion is multiplied by `exp(h ω / 2)` (the rotation by
//! `h |ω|` about `ω`, in the child's axes) and comes out unit, and a free
//! joint's origin follows the screw motion of constant `(v, ω)` (the SE(3)
//! exponential, as Pinocchio's free flyer); other coordinates move by
//! `h` times their speed.

use super::body::{Names, straight_line};
use crate::expr::{Node, Sym};
use crate::model::{Ball, Model};
use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::{format_ident, quote};

/// `pub fn coordinate_rates(..)` and `pub fn integrate_configuration(..)`.
pub fn emit_configuration(model: &Model, names: &Names) -> TokenStream {
    if model.pool.rates_are_speeds() {
        return emit_identity(model.nq());
    }
    let (nq, nv) = (
        Literal::usize_unsuffixed(model.nq()),
        Literal::usize_unsuffixed(model.nv()),
    );
    let rates = straight_line(&model.pool, names, model.pool.rates());
    let (statements, outputs) = (&rates.statements, &rates.outputs);
    let argument = |name: &str, sym: fn(&Sym) -> bool| {
        let used = rates.used.iter().any(sym);
        super::argument_name(name, used)
    };
    let (q, qd) = (
        argument("q", |s| matches!(s, Sym::Coord(_))),
        argument("qd", |s| matches!(s, Sym::Speed(_))),
    );
    let slides = model
        .pool
        .rates()
        .iter()
        .enumerate()
        .filter_map(|(i, &rate)| match model.pool.node(rate) {
            Node::Sym(Sym::Speed(k)) => {
                let (i, k) = (index(i), index(*k as usize));
                Some(quote!(next[#i] = q[#i] + h * v[#k];))
            }
            _ => None,
        });
    let balls = model.balls.iter().map(|ball| emit_ball(ball, names.libm));
    let own = emit_own_rates(model, &nq);
    let mut update_doc = vec![
        " `q ⊕ h v`: the configuration reached from `q` moving at the",
        " constant speeds `v` for the time `h`. Each quaternion is",
        " normalised, then turned exactly (it comes out unit); a free",
        " joint's origin follows the screw motion of its constant speeds;",
    ];
    if !own.is_empty() {
        update_doc.extend([
            " the coordinates of `speeds` statements take one classical RK4",
            " step of `q̇ = N(q) v`;",
        ]);
    }
    update_doc.push(" other coordinates move by `h v`.");
    quote! {
        /// The coordinate rates `q̇ = N(q) v` (a quaternion's from its
        /// joint's angular velocity, a free joint's position's from the
        /// velocity in the child's axes).
        #[inline]
        #[must_use]
        pub fn coordinate_rates(&self, #q: &[f64; #nq], #qd: &[f64; #nv]) -> [f64; #nq] {
            #statements
            [#(#outputs),*]
        }
        #(#[doc = #update_doc])*
        #[inline]
        #[must_use]
        pub fn integrate_configuration(&self, q: &[f64; #nq], v: &[f64; #nv], h: f64) -> [f64; #nq] {
            let mut next = *q;
            #(#slides)*
            #(#balls)*
            #own
            next
        }
    }
}

/// The coordinates whose rates a `speeds` statement gives (neither a
/// speed nor a quaternion joint's): one classical Runge–Kutta step of
/// `q̇ = N(q) v` at constant `v`, the other coordinates held.
fn emit_own_rates(model: &Model, nq: &Literal) -> TokenStream {
    let in_ball = |i: usize| {
        model.balls.iter().any(|b| {
            b.quaternion.contains(&i) || b.translation.is_some_and(|(p, _)| p.contains(&i))
        })
    };
    let own: Vec<Literal> = (0..model.nq())
        .filter(|&i| {
            let plain = matches!(
                model.pool.rates().get(i).map(|&r| model.pool.node(r)),
                None | Some(Node::Sym(Sym::Speed(_)))
            );
            !plain && !in_ball(i)
        })
        .map(index)
        .collect();
    if own.is_empty() {
        return TokenStream::new();
    }
    quote! {
        {
            let stage = |rates: &[f64; #nq], c: f64| {
                let mut stage = *q;
                #(stage[#own] = q[#own] + c * h * rates[#own];)*
                stage
            };
            let k1 = self.coordinate_rates(q, v);
            let k2 = self.coordinate_rates(&stage(&k1, 0.5), v);
            let k3 = self.coordinate_rates(&stage(&k2, 0.5), v);
            let k4 = self.coordinate_rates(&stage(&k3, 1.0), v);
            #(next[#own] = q[#own] + h / 6.0 * (k1[#own] + 2.0 * k2[#own] + 2.0 * k3[#own] + k4[#own]);)*
        }
    }
}

fn index(i: usize) -> Literal {
    Literal::usize_unsuffixed(i)
}

/// The update of one quaternion joint, in a block of its own.
fn emit_ball(ball: &Ball, libm: bool) -> TokenStream {
    let call = |function: &str, x: TokenStream| {
        let function = Ident::new(function, Span::call_site());
        if libm {
            quote!(::libm::#function(#x))
        } else {
            quote!(#x.#function())
        }
    };
    let [qx, qy, qz, qw] = ball.quaternion.map(index);
    let [wx, wy, wz] = ball.angular.map(index);
    let norm = call(
        "sqrt",
        quote!((q[#qx] * q[#qx] + q[#qy] * q[#qy] + q[#qz] * q[#qz] + q[#qw] * q[#qw])),
    );
    let speed = call("sqrt", quote!(oo));
    let (sin_half, cos_half) = (call("sin", quote!(half)), call("cos", quote!(half)));
    let (sin, cos) = (call("sin", quote!(theta)), call("cos", quote!(theta)));
    let norm_turned = call(
        "sqrt",
        quote!(
            (turned[0] * turned[0]
                + turned[1] * turned[1]
                + turned[2] * turned[2]
                + turned[3] * turned[3])
        ),
    );
    let translation = ball.translation.map(|(position, velocity)| {
        let [x, y, z] = position.map(index);
        let [vx, vy, vz] = velocity.map(index);
        quote! {
            // The screw motion: r + R(q) (h v + c1 ω × v + c2 ω × (ω × v)).
            let (c1, c2) = if theta < 1e-4 {
                (h * h * (0.5 - theta * theta / 24.0), h * h * h * (1.0 / 6.0 - theta * theta / 120.0))
            } else {
                ((1.0 - #cos) / oo, (h - #sin / w) / oo)
            };
            let u = [v[#vx], v[#vy], v[#vz]];
            let wu = [o1 * u[2] - o2 * u[1], o2 * u[0] - o0 * u[2], o0 * u[1] - o1 * u[0]];
            let wwu = [o1 * wu[2] - o2 * wu[1], o2 * wu[0] - o0 * wu[2], o0 * wu[1] - o1 * wu[0]];
            let d = [0, 1, 2].map(|i| h * u[i] + c1 * wu[i] + c2 * wwu[i]);
            let r = [
                [a3 * a3 + a0 * a0 - a1 * a1 - a2 * a2, 2.0 * (a0 * a1 - a3 * a2), 2.0 * (a0 * a2 + a3 * a1)],
                [2.0 * (a0 * a1 + a3 * a2), a3 * a3 - a0 * a0 + a1 * a1 - a2 * a2, 2.0 * (a1 * a2 - a3 * a0)],
                [2.0 * (a0 * a2 - a3 * a1), 2.0 * (a1 * a2 + a3 * a0), a3 * a3 - a0 * a0 - a1 * a1 + a2 * a2],
            ];
            next[#x] = q[#x] + r[0][0] * d[0] + r[0][1] * d[1] + r[0][2] * d[2];
            next[#y] = q[#y] + r[1][0] * d[0] + r[1][1] * d[1] + r[1][2] * d[2];
            next[#z] = q[#z] + r[2][0] * d[0] + r[2][1] * d[1] + r[2][2] * d[2];
        }
    });
    quote! {
        {
            let norm = #norm;
            let [a0, a1, a2, a3] = [q[#qx] / norm, q[#qy] / norm, q[#qz] / norm, q[#qw] / norm];
            let [o0, o1, o2] = [v[#wx], v[#wy], v[#wz]];
            let oo = o0 * o0 + o1 * o1 + o2 * o2;
            let w = #speed;
            let theta = h * w;
            // exp(h ω / 2) = (s ω, c) with s = sin(θ/2) / |ω|, c = cos(θ/2).
            let half = 0.5 * theta;
            let (s, c) = if theta < 1e-4 {
                (0.5 * h * (1.0 - half * half / 6.0), 1.0 - half * half / 2.0)
            } else {
                (#sin_half / w, #cos_half)
            };
            let [e0, e1, e2] = [s * o0, s * o1, s * o2];
            #translation
            let turned = [
                a3 * e0 + a0 * c + a1 * e2 - a2 * e1,
                a3 * e1 + a1 * c + a2 * e0 - a0 * e2,
                a3 * e2 + a2 * c + a0 * e1 - a1 * e0,
                a3 * c - a0 * e0 - a1 * e1 - a2 * e2,
            ];
            let unit = #norm_turned;
            next[#qx] = turned[0] / unit;
            next[#qy] = turned[1] / unit;
            next[#qz] = turned[2] / unit;
            next[#qw] = turned[3] / unit;
        }
    }
}

/// `pub fn coordinate_rates(..)` and `pub fn integrate_configuration(..)`
/// for a system of `nq` coordinates whose speeds are their rates.
fn emit_identity(nq: usize) -> TokenStream {
    let n = Literal::usize_unsuffixed(nq);
    let (v, h, q) = if nq == 0 {
        (quote!(_v), quote!(_h), quote!(_q))
    } else {
        (quote!(v), quote!(h), quote!(q))
    };
    let coordinates: Vec<_> = (0..nq).map(|i| format_ident!("q{}", i)).collect();
    let speeds: Vec<_> = (0..nq).map(|i| format_ident!("v{}", i)).collect();
    let destructure =
        (nq > 0).then(|| quote!(let [#(#coordinates),*] = *q; let [#(#speeds),*] = *v;));
    quote! {
        /// The coordinate rates `q̇ = N(q) v`: the speeds themselves, since
        /// every speed is its coordinate's rate.
        #[inline]
        pub fn coordinate_rates(&self, _q: &[f64; #n], #v: &[f64; #n]) -> [f64; #n] {
            *#v
        }
        /// `q ⊕ h v`: the configuration reached from `q` moving at the
        /// constant speeds `v` for the time `h`, here `q + h v`.
        #[inline]
        pub fn integrate_configuration(&self, #q: &[f64; #n], #v: &[f64; #n], #h: f64) -> [f64; #n] {
            #destructure
            [#(#coordinates + h * #speeds),*]
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_coordinates_move_by_h_times_their_speeds() {
        let expected = quote! {
            /// The coordinate rates `q̇ = N(q) v`: the speeds themselves, since
            /// every speed is its coordinate's rate.
            #[inline]
            pub fn coordinate_rates(&self, _q: &[f64; 2], v: &[f64; 2]) -> [f64; 2] {
                *v
            }
            /// `q ⊕ h v`: the configuration reached from `q` moving at the
            /// constant speeds `v` for the time `h`, here `q + h v`.
            #[inline]
            pub fn integrate_configuration(&self, q: &[f64; 2], v: &[f64; 2], h: f64) -> [f64; 2] {
                let [q0, q1] = *q;
                let [v0, v1] = *v;
                [q0 + h * v0, q1 + h * v1]
            }
        };
        assert_eq!(emit_identity(2).to_string(), expected.to_string());
    }

    #[test]
    fn no_coordinates_read_nothing() {
        let emitted = emit_identity(0).to_string();
        assert!(
            emitted.contains("_v : & [f64 ; 0]") && emitted.contains("[]"),
            "{emitted}"
        );
    }
}
