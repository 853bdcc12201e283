//! The kinematic equation `q̇ = N(q) v` and the configuration update
//! `q ⊕ h v` as inherent `coordinate_rates` and `integrate_configuration`.
//! When every speed is its coordinate's rate, `N` is the identity and the
//! update is `q + h v`. A quaternion joint's update is exact for constant
//! speeds: the quaternion is multiplied by `exp(h ω / 2)` (the rotation by
//! `h |ω|` about `ω`, in the child's axes) and comes out unit, and a free
//! joint's origin follows the screw motion of constant `(v, ω)` (the SE(3)
//! exponential, as Pinocchio's free flyer); other coordinates move by
//! `h` times their speed. Where the rates of a `speeds` statement divide by
//! an expression of the coordinates, `check_coordinate_rates` tests each
//! divisor against zero.

use super::body::{Names, straight_line};
use crate::expr::{Node, Pool, Sym};
use crate::model::{Ball, Model};
use crate::render::text::{SymbolNames, unicode};
use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::{format_ident, quote};

/// `pub fn coordinate_rates(..)` and `pub fn integrate_configuration(..)`.
pub fn emit_configuration(model: &Model, pool: &Pool, names: &Names) -> TokenStream {
    if pool.rates_are_speeds() {
        return emit_identity(model.nq());
    }
    let (nq, nv) = (
        Literal::usize_unsuffixed(model.nq()),
        Literal::usize_unsuffixed(model.nv()),
    );
    let rates = straight_line(pool, names, pool.rates());
    let (statements, outputs) = (&rates.statements, &rates.outputs);
    let argument = |name: &str, sym: fn(&Sym) -> bool| {
        let used = rates.used.iter().any(sym);
        super::argument_name(name, used)
    };
    let (q, qd) = (
        argument("q", |s| matches!(s, Sym::Coord(_))),
        argument("qd", |s| matches!(s, Sym::Speed(_))),
    );
    let (update, doc_own) = emit_update(model, pool, names.libm);
    let mut update_doc = vec![
        " `q ⊕ h v`: the configuration reached from `q` moving at the",
        " constant speeds `v` for the time `h`. Each quaternion is",
        " normalised, then turned exactly (it comes out unit); a free",
        " joint's origin follows the screw motion of its constant speeds;",
    ];
    if doc_own {
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
            #update
        }
    }
}

/// `pub fn check_coordinate_rates(..)` when the rates of `speeds`
/// statements divide by expressions of the coordinates (nothing otherwise:
/// the runtime's provided check accepts every configuration): the first
/// divisor whose magnitude, relative to that of its terms, is not above the
/// runtime's tolerance is an error naming its coordinate and the divisor.
/// NaN fails too.
pub fn emit_rate_check(model: &Model, pool: &Pool, names: &Names) -> TokenStream {
    if model.rate_divisors.is_empty() {
        return TokenStream::new();
    }
    let nq = Literal::usize_unsuffixed(model.nq());
    let roots: Vec<_> = model
        .rate_divisors
        .iter()
        .flat_map(|d| [d.divisor, d.relative])
        .collect();
    let body = straight_line(pool, names, &roots);
    let symbols = SymbolNames::new(&model.parameters, &model.coordinates, &model.inputs);
    let mut outputs = body.outputs.iter();
    let mut listed = Vec::new();
    let checks: Vec<TokenStream> = model
        .rate_divisors
        .iter()
        .map(|d| {
            let (value, relative) = (outputs.next(), outputs.next());
            let coordinate = model.coordinates[d.coordinate].to_string();
            let divisor = unicode(pool, d.divisor, &symbols);
            listed.push(format!(" * `{divisor}`, in the rate of `{coordinate}`"));
            quote! {
                if !(#relative > ::dalembert::dynamics::SINGULAR_RATES_TOLERANCE) {
                    return ::core::result::Result::Err(
                        ::dalembert::DynamicsError::SingularCoordinateRates {
                            coordinate: #coordinate,
                            divisor: #divisor,
                            value: #value,
                        },
                    );
                }
            }
        })
        .collect();
    let statements = &body.statements;
    quote! {
        /// Whether the coordinate rates `q̇ = N(q) v` are defined at `q`:
        /// `DynamicsError::SingularCoordinateRates` naming the first
        /// coordinate whose rate divides by a quantity within
        /// `dalembert::dynamics::SINGULAR_RATES_TOLERANCE` of zero (relative
        /// to its terms, for a sum). The divisors:
        ///
        #(#[doc = #listed])*
        #[inline]
        pub fn check_coordinate_rates(&self, q: &[f64; #nq]) -> ::core::result::Result<(), ::dalembert::DynamicsError> {
            #statements
            #(#checks)*
            ::core::result::Result::Ok(())
        }
    }
}

/// The body of `integrate_configuration`, on destructured arrays (no
/// indexing): every coordinate `qᵢ` and speed `vₖ` by name, the new
/// configuration as an array of names; and whether some coordinates come
/// from `speeds` statements.
fn emit_update(model: &Model, pool: &Pool, libm: bool) -> (TokenStream, bool) {
    let (nq, nv) = (model.nq(), model.nv());
    let q: Vec<Ident> = (0..nq).map(|i| format_ident!("q{}", i)).collect();
    let v: Vec<Ident> = (0..nv).map(|k| format_ident!("v{}", k)).collect();
    let mut next: Vec<TokenStream> = q.iter().map(|name| quote!(#name)).collect();
    let mut steps = Vec::new();
    let in_ball = |i: usize| {
        model.balls.iter().any(|b| {
            b.quaternion.contains(&i) || b.translation.is_some_and(|(p, _)| p.contains(&i))
        })
    };
    let mut own = Vec::new();
    // The speeds read by name (the others are left out of the pattern).
    let mut read = vec![false; nv];
    for i in (0..nq).filter(|&i| !in_ball(i)) {
        let k = match pool.rates().get(i).map(|&r| pool.node(r)) {
            Some(Node::Sym(Sym::Speed(k))) => *k as usize,
            None => i,
            Some(_) => {
                own.push(i);
                continue;
            }
        };
        let (qi, vk) = (&q[i], &v[k]);
        next[i] = quote!(#qi + h * #vk);
        read[k] = true;
    }
    for ball in &model.balls {
        let mut speeds = ball.angular.to_vec();
        speeds.extend(ball.translation.iter().flat_map(|(_, v)| *v));
        speeds.into_iter().for_each(|k| read[k] = true);
    }
    for ball in &model.balls {
        let (step, outputs) = emit_ball(ball, &q, &v, libm);
        steps.push(step);
        let mut indices: Vec<usize> = ball.quaternion.to_vec();
        indices.extend(ball.translation.iter().flat_map(|(p, _)| *p));
        for (i, name) in indices.into_iter().zip(outputs) {
            next[i] = quote!(#name);
        }
    }
    if !own.is_empty() {
        steps.push(emit_own_rates(&own, &q, &mut next));
    }
    let pattern = v.iter().zip(&read).map(|(name, &read)| match read {
        true => quote!(#name),
        false => quote!(_),
    });
    let destructure_v = read
        .contains(&true)
        .then(|| quote!(let [#(#pattern),*] = *v;));
    let body = quote! {
        let [#(#q),*] = *q;
        #destructure_v
        #(#steps)*
        [#(#next),*]
    };
    (body, !own.is_empty())
}

/// The coordinates `own` whose rates a `speeds` statement gives: one
/// classical Runge–Kutta step of `q̇ = N(q) v` at constant `v`, the other
/// coordinates held; their new values go into `next`.
fn emit_own_rates(own: &[usize], q: &[Ident], next: &mut [TokenStream]) -> TokenStream {
    let stage_names = |stage: &str| -> Vec<TokenStream> {
        (0..q.len())
            .map(|i| match own.contains(&i) {
                true => {
                    let name = format_ident!("{}_{}", stage, i);
                    quote!(#name)
                }
                false => quote!(_),
            })
            .collect()
    };
    let state = |stage: &str, c: TokenStream| -> Vec<TokenStream> {
        (0..q.len())
            .map(|i| {
                let qi = &q[i];
                match own.contains(&i) {
                    true => {
                        let k = format_ident!("{}_{}", stage, i);
                        quote!(#qi + #c * h * #k)
                    }
                    false => quote!(#qi),
                }
            })
            .collect()
    };
    let [k1, k2, k3, k4] = ["k1", "k2", "k3", "k4"].map(stage_names);
    let (s2, s3, s4) = (
        state("k1", quote!(0.5)),
        state("k2", quote!(0.5)),
        state("k3", quote!(1.0)),
    );
    for &i in own {
        let name = format_ident!("n{}", i);
        next[i] = quote!(#name);
    }
    let finals = own.iter().map(|&i| {
        let (qi, name) = (&q[i], format_ident!("n{}", i));
        let [a, b, c, d] = ["k1", "k2", "k3", "k4"].map(|s| format_ident!("{}_{}", s, i));
        quote!(let #name = #qi + h / 6.0 * (#a + 2.0 * #b + 2.0 * #c + #d);)
    });
    quote! {
        let [#(#k1),*] = self.coordinate_rates(q, v);
        let [#(#k2),*] = self.coordinate_rates(&[#(#s2),*], v);
        let [#(#k3),*] = self.coordinate_rates(&[#(#s3),*], v);
        let [#(#k4),*] = self.coordinate_rates(&[#(#s4),*], v);
        #(#finals)*
    }
}

/// The update of one quaternion joint: its statements and the names of the
/// new quaternion `(x, y, z, w)` and, for a free joint, position.
fn emit_ball(ball: &Ball, q: &[Ident], v: &[Ident], libm: bool) -> (TokenStream, Vec<Ident>) {
    let call = |function: &str, x: TokenStream| {
        let function = Ident::new(function, Span::call_site());
        if libm {
            quote!(::libm::#function(#x))
        } else {
            quote!(#x.#function())
        }
    };
    let [qx, qy, qz, qw] = ball.quaternion.map(|i| &q[i]);
    let [wx, wy, wz] = ball.angular.map(|k| &v[k]);
    let first = ball.quaternion[0];
    let out = |what: &str| format_ident!("n{}_{}", first, what);
    let quaternion_out = ["x", "y", "z", "w"].map(out);
    let [nx, ny, nz, nw] = &quaternion_out;
    let norm = call(
        "sqrt",
        quote!((#qx * #qx + #qy * #qy + #qz * #qz + #qw * #qw)),
    );
    let speed = call("sqrt", quote!(oo));
    let (sin_half, cos_half) = (call("sin", quote!(half)), call("cos", quote!(half)));
    let (sin, cos) = (call("sin", quote!(theta)), call("cos", quote!(theta)));
    let norm_turned = call("sqrt", quote!((t0 * t0 + t1 * t1 + t2 * t2 + t3 * t3)));
    let mut outputs = quaternion_out.to_vec();
    let translation = ball.translation.map(|(position, velocity)| {
        let [x, y, z] = position.map(|i| &q[i]);
        let [vx, vy, vz] = velocity.map(|k| &v[k]);
        let position_out = ["px", "py", "pz"].map(out);
        let [px, py, pz] = &position_out;
        outputs.extend(position_out.clone());
        quote! {
            // The screw motion: r + R(q) (h v + c1 ω × v + c2 ω × (ω × v)).
            let (c1, c2) = if theta < 1e-4 {
                (h * h * (0.5 - theta * theta / 24.0), h * h * h * (1.0 / 6.0 - theta * theta / 120.0))
            } else {
                ((1.0 - #cos) / oo, (h - #sin / w) / oo)
            };
            let (u0, u1, u2) = (#vx, #vy, #vz);
            let (wu0, wu1, wu2) = (o1 * u2 - o2 * u1, o2 * u0 - o0 * u2, o0 * u1 - o1 * u0);
            let (wwu0, wwu1, wwu2) = (o1 * wu2 - o2 * wu1, o2 * wu0 - o0 * wu2, o0 * wu1 - o1 * wu0);
            let d0 = h * u0 + c1 * wu0 + c2 * wwu0;
            let d1 = h * u1 + c1 * wu1 + c2 * wwu1;
            let d2 = h * u2 + c1 * wu2 + c2 * wwu2;
            let #px = #x
                + (a3 * a3 + a0 * a0 - a1 * a1 - a2 * a2) * d0
                + 2.0 * (a0 * a1 - a3 * a2) * d1
                + 2.0 * (a0 * a2 + a3 * a1) * d2;
            let #py = #y
                + 2.0 * (a0 * a1 + a3 * a2) * d0
                + (a3 * a3 - a0 * a0 + a1 * a1 - a2 * a2) * d1
                + 2.0 * (a1 * a2 - a3 * a0) * d2;
            let #pz = #z
                + 2.0 * (a0 * a2 - a3 * a1) * d0
                + 2.0 * (a1 * a2 + a3 * a0) * d1
                + (a3 * a3 - a0 * a0 - a1 * a1 + a2 * a2) * d2;
        }
    });
    let step = quote! {
        let (#(#outputs),*) = {
            let norm = #norm;
            let (a0, a1, a2, a3) = (#qx / norm, #qy / norm, #qz / norm, #qw / norm);
            let (o0, o1, o2) = (#wx, #wy, #wz);
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
            let (e0, e1, e2) = (s * o0, s * o1, s * o2);
            #translation
            let t0 = a3 * e0 + a0 * c + a1 * e2 - a2 * e1;
            let t1 = a3 * e1 + a1 * c + a2 * e0 - a0 * e2;
            let t2 = a3 * e2 + a2 * c + a0 * e1 - a1 * e0;
            let t3 = a3 * c - a0 * e0 - a1 * e1 - a2 * e2;
            let unit = #norm_turned;
            let (#nx, #ny, #nz, #nw) = (t0 / unit, t1 / unit, t2 / unit, t3 / unit);
            (#(#outputs),*)
        };
    };
    (step, outputs)
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

    fn model(source: &str) -> (Model, Pool) {
        let system = crate::language::parse_system(source.parse().unwrap()).unwrap();
        crate::model::resolve(&system).unwrap()
    }

    #[test]
    fn azimuth_and_elevation_rates_check_the_cosine_they_divide_by() {
        // Azimuth and elevation with the body's rates about its y and z
        // axes: ψ̇ = ω_z / cos θ.
        let (model, pool) = model(
            "pub Pointer {
                parameters I;
                coordinates psi, theta;
                speeds wy, wz { psi: wz / cos(theta), theta: wy };
                frame A = N.rotate_z(psi);
                frame B = A.rotate_y(theta);
                body b { mass: 1, center: O, frame: B, inertia: [I, I, I] };
            }",
        );
        let names = super::super::names(&model, super::super::Target::Std);
        let expected = quote! {
            /// Whether the coordinate rates `q̇ = N(q) v` are defined at `q`:
            /// `DynamicsError::SingularCoordinateRates` naming the first
            /// coordinate whose rate divides by a quantity within
            /// `dalembert::dynamics::SINGULAR_RATES_TOLERANCE` of zero (relative
            /// to its terms, for a sum). The divisors:
            ///
            #[doc = " * `cos θ`, in the rate of `psi`"]
            #[inline]
            pub fn check_coordinate_rates(&self, q: &[f64; 2]) -> ::core::result::Result<(), ::dalembert::DynamicsError> {
                let [_, theta] = *q;
                let cos_theta = theta.cos();
                let x0 = cos_theta.abs();
                if !(x0 > ::dalembert::dynamics::SINGULAR_RATES_TOLERANCE) {
                    return ::core::result::Result::Err(
                        ::dalembert::DynamicsError::SingularCoordinateRates {
                            coordinate: "psi",
                            divisor: "cos θ",
                            value: cos_theta,
                        },
                    );
                }
                ::core::result::Result::Ok(())
            }
        };
        let emitted = emit_rate_check(&model, &pool, &names);
        assert_eq!(emitted.to_string(), expected.to_string());
    }

    #[test]
    fn a_sum_is_checked_relative_to_its_terms_and_regular_rates_need_no_check() {
        let (rolling, pool) = model(
            "S {
                parameters m, a;
                coordinates x;
                speeds w { x: w / (a + cos(x)) };
                particle p { mass: m, at: O + x * N.x };
            }",
        );
        let names = super::super::names(&rolling, super::super::Target::Std);
        let emitted = emit_rate_check(&rolling, &pool, &names).to_string();
        assert!(
            emitted.contains("let xx0 = a + cos_x ; let xx1 = xx0 . abs () ; let abs_a = a . abs () ; let xx2 = cos_x . abs () ; if ! (xx1 / (abs_a + xx2) >"),
            "{emitted}"
        );
        assert!(emitted.contains(r#"divisor : "a + cos x""#), "{emitted}");
        let (pendulum, pool) = model(
            "S {
                parameters m, l;
                coordinates x;
                speeds w { x: l * cos(x) * w };
                particle p { mass: m, at: O + x * N.x };
            }",
        );
        let names = super::super::names(&pendulum, super::super::Target::Std);
        assert!(emit_rate_check(&pendulum, &pool, &names).is_empty());
    }
}
