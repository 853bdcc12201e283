//! The kinematic equation `q̇ = N(q) v` and the configuration update
//! `q ⊕ h v` as inherent `coordinate_rates` and `integrate_configuration`.
//! Every coordinate's speed is its rate today, so `N` is the identity and
//! the update is `q + h v`.

use proc_macro2::{Literal, TokenStream};
use quote::{format_ident, quote};

/// `pub fn coordinate_rates(..)` and `pub fn integrate_configuration(..)`
/// for a system of `nq` coordinates whose speeds are their rates.
pub fn emit_configuration(nq: usize) -> TokenStream {
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
        assert_eq!(emit_configuration(2).to_string(), expected.to_string());
    }

    #[test]
    fn no_coordinates_read_nothing() {
        let emitted = emit_configuration(0).to_string();
        assert!(
            emitted.contains("_v : & [f64 ; 0]") && emitted.contains("[]"),
            "{emitted}"
        );
    }
}
