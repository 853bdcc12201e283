//! Sums of parameter products collected for the reader: the terms of a
//! readable form that share everything but their parameters and numbers
//! print as one, `2 (I₃ − I_1c − m ℓ²) cos θ sin θ ψ̇ θ̇` for three terms
//! `2 I₃ …`, `−2 I_1c …`, `−2 m ℓ² …`, with the parameters and the number
//! common to all of them outside the parentheses (`(m_B − m_A) g y`).
//!
//! The collected sum is a group ([`Node::Group`](crate::expr::Node::Group))
//! of the parameter parts, which the printers parenthesise; it is for the
//! docs only (the equations and the generated code never see it).

use crate::expr::{ExprId, Node, Number, Pool, Sym};
use crate::readable::{factors, terms};

/// One term split into its number, its parameter factors and the product
/// of everything else.
struct Split {
    number: Number,
    parameters: Vec<(ExprId, i32)>,
}

/// `e` with the terms that differ only in parameters and numbers collected
/// into one per product of the rest, in the order they first appear; `e`
/// itself when no two terms share their rest, or when all of them share a
/// rest of `1` and no parameter (`I_1c + m ℓ²` stays, `m_A g − m_B g` is
/// `(m_A − m_B) g`).
pub fn collect_parameters(pool: &mut Pool, e: ExprId) -> ExprId {
    // `−(a − b)` read as `−a + b`, every sign seen.
    let terms = terms(pool, e);
    if terms.len() < 2 {
        return e;
    }
    let mut groups: Vec<(ExprId, Vec<Split>)> = Vec::new();
    for &term in &terms {
        let (number, rest) = pool.split_coefficient(term);
        let (parameters, varying): (Vec<_>, Vec<_>) = factors(pool, rest)
            .into_iter()
            .partition(|&(base, _)| matches!(pool.node(base), Node::Sym(Sym::Param(_))));
        let varying = power_product(pool, &varying);
        let split = Split { number, parameters };
        match groups.iter_mut().find(|(rest, _)| *rest == varying) {
            Some((_, members)) => members.push(split),
            None => groups.push((varying, vec![split])),
        }
    }
    // A sum of parameters alone is collected only for a common parameter.
    let alone = groups.len() == 1
        && groups[0].0 == pool.one()
        && common_parameters(&groups[0].1).is_empty();
    if groups.len() == terms.len() || alone {
        return e;
    }
    let collected: Vec<ExprId> = groups
        .into_iter()
        .map(|(varying, members)| collected_term(pool, varying, &members))
        .collect();
    pool.sum(collected)
}

/// `Σ members · varying` as `n · common parameters · (Σ the rest) · varying`,
/// with `n` as [`common_number`] finds it; the members as they were where
/// nothing would stand outside the parentheses.
fn collected_term(pool: &mut Pool, varying: ExprId, members: &[Split]) -> ExprId {
    let number = common_number(members);
    let common = common_parameters(members);
    let bare = number == Number::ONE && common.is_empty() && varying == pool.one();
    let inner: Vec<ExprId> = members
        .iter()
        .map(|member| {
            let own: Vec<(ExprId, i32)> = member
                .parameters
                .iter()
                .map(|&(base, exp)| {
                    let shared = common.iter().find(|c| c.0 == base).map_or(0, |c| c.1);
                    (base, exp - shared)
                })
                .filter(|&(_, exp)| exp != 0)
                .collect();
            let product = power_product(pool, &own);
            let scale = member.number * number.powi(-1);
            let scale = pool.number(scale);
            pool.mul(scale, product)
        })
        .collect();
    let inner = pool.sum(inner);
    if bare {
        return inner;
    }
    let group = pool.group(inner);
    let common = power_product(pool, &common);
    let number = pool.number(number);
    pool.product([number, common, group, varying])
}

/// The magnitude that more than half of the members have and none
/// exceeds (`½` of `½ m_A + ½ m_B + ¼ m_p`; none of
/// `⅓ m₁ L₁² + ⅓ m₂ L₂² + m₂ L₁²`, which would leave a `3` inside),
/// negative when all of them are, else `1`.
fn common_number(members: &[Split]) -> Number {
    let magnitudes = || members.iter().map(|m| m.number.abs());
    let majority = magnitudes().find(|&n| {
        let exceeded = magnitudes().any(|other| other.to_f64() > n.to_f64());
        2 * magnitudes().filter(|&other| other == n).count() > members.len() && !exceeded
    });
    let number = majority.unwrap_or(Number::ONE);
    match members.iter().all(|m| m.number.is_negative()) {
        true => -number,
        false => number,
    }
}

/// The parameters with a positive power in every member, at the least
/// such power.
fn common_parameters(members: &[Split]) -> Vec<(ExprId, i32)> {
    members[0]
        .parameters
        .iter()
        .filter_map(|&(base, _)| {
            let powers = members
                .iter()
                .map(|m| m.parameters.iter().find(|p| p.0 == base).map_or(0, |p| p.1));
            let least = powers.min().unwrap_or(0);
            (least > 0).then_some((base, least))
        })
        .collect()
}

/// `Π baseᵉˣᵖ`.
fn power_product(pool: &mut Pool, powers: &[(ExprId, i32)]) -> ExprId {
    let factors: Vec<ExprId> = powers
        .iter()
        .map(|&(base, exp)| pool.powi(base, exp))
        .collect();
    pool.product(factors)
}

#[cfg(test)]
mod tests {
    use super::collect_parameters;
    use crate::expr::{Pool, Sym};
    use crate::render::text::{SymbolNames, unicode};

    #[test]
    fn the_heavy_tops_forcing_collects_its_inertias() {
        let mut p = Pool::new();
        let [m, l, i1, i3] = [0, 1, 2, 3].map(|i| p.sym(Sym::Param(i)));
        let theta = p.sym(Sym::Coord(1));
        let [psi_dot, theta_dot] = [0, 1].map(|i| p.sym(Sym::Speed(i)));
        let (c, s) = (p.cos(theta), p.sin(theta));
        let rest = p.product([s, c, psi_dot, theta_dot]);
        let l2 = p.powi(l, 2);
        let two = p.int(2);
        let minus_two = p.int(-2);
        let terms = [
            p.product([two, i3, rest]),
            p.product([minus_two, i1, rest]),
            p.product([minus_two, m, l2, rest]),
        ];
        let f = p.sum(terms);
        let collected = collect_parameters(&mut p, f);
        let names = SymbolNames::new(&["m", "l", "I1c", "I3"], &["psi", "theta"], &[] as &[&str]);
        assert_eq!(
            unicode(&p, collected, &names),
            "2 (I₃ − I_1c − m ℓ²) cos θ sin θ ψ̇ θ̇"
        );
    }

    #[test]
    fn a_common_parameter_moves_out_and_lone_terms_stay() {
        let mut p = Pool::new();
        let [ma, mb, g] = [0, 1, 2].map(|i| p.sym(Sym::Param(i)));
        let y = p.sym(Sym::Coord(0));
        let minus_two = p.int(-2);
        let minus_one = p.int(-1);
        let terms = [
            p.product([mb, g, y]),
            p.product([minus_one, ma, g, y]),
            p.product([minus_two, ma, g]),
            p.product([minus_two, mb, g]),
        ];
        let v = p.sum(terms);
        let collected = collect_parameters(&mut p, v);
        let names = SymbolNames::new(&["m_A", "m_B", "g"], &["y"], &[] as &[&str]);
        assert_eq!(
            unicode(&p, collected, &names),
            "(m_B − m_A) g y − 2 (m_A + m_B) g"
        );
        // Nothing shared: the sum as it was.
        let alone = p.sum([ma, mb]);
        assert_eq!(collect_parameters(&mut p, alone), alone);
    }
}
