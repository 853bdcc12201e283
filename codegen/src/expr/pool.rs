//! The arena: interning (hash-consing), per-node summaries, leaf
//! constructors, queries, and the iterative traversal every pass uses.

use std::collections::{BTreeSet, HashMap, HashSet};

use super::decimal::parse_literal;
use super::kinds::{Signature, SymKinds};
use super::{ExprId, Node, Number, Pool, Rational, Sym};

/// What the pool remembers about each node besides the node itself.
#[derive(Clone, Copy, Debug)]
pub(super) struct Meta {
    /// Kinds of the symbols in the node.
    kinds: SymKinds,
    /// Signature of the symbols in the node.
    signature: Signature,
    /// The node without its numeric coefficient (see
    /// [`Pool::split_coefficient`]).
    rest: ExprId,
}

impl Default for Pool {
    fn default() -> Pool {
        Pool::new()
    }
}

impl Pool {
    const ZERO: ExprId = ExprId(0);
    const ONE: ExprId = ExprId(1);

    /// An empty pool holding only `0` and `1`.
    pub fn new() -> Pool {
        let mut pool = Pool {
            nodes: Vec::new(),
            meta: Vec::new(),
            index: HashMap::default(),
            derivatives: HashMap::default(),
            rates: Vec::new(),
            positive_sums: false,
        };
        let zero = pool.number(Number::ZERO);
        let one = pool.number(Number::ONE);
        debug_assert_eq!((zero, one), (Pool::ZERO, Pool::ONE));
        pool
    }

    /// An empty pool that builds every sum whose first term (after its
    /// constant) has a negative coefficient as `−1` times the sum with every
    /// sign turned: `b − a` and `a − b` then share one sum, which a
    /// derivation full of cross products (`a × b = −b × a`) needs to compute
    /// each value once. The setting is the pool's from its first node to its
    /// last, so that it holds one form per sum; the readable forms read `−1`
    /// times a sum as its terms negated (`crate::readable`), and the
    /// printers decide how to show it.
    pub fn with_positive_sums() -> Pool {
        Pool {
            positive_sums: true,
            ..Pool::new()
        }
    }

    /// The node named by `e`.
    pub fn node(&self, e: ExprId) -> &Node {
        &self.nodes[e.0 as usize]
    }

    /// The number of distinct nodes interned so far.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// The id of `node`, interning it if it is new. `node` must already be
    /// canonical: this is the only place nodes are created, and only the
    /// canonicalising constructors call it. Panics only beyond 2³² nodes
    /// (some 200 GB of expressions).
    pub(super) fn intern(&mut self, node: Node) -> ExprId {
        if let Some(&id) = self.index.get(&node) {
            return id;
        }
        let (kinds, signature) = self.summarise(&node);
        let rest = self.coefficient_rest(&node);
        let id = ExprId(u32::try_from(self.nodes.len()).expect("more than 2^32 expression nodes"));
        self.meta.push(Meta {
            kinds,
            signature,
            rest: rest.unwrap_or(id),
        });
        self.nodes.push(node.clone());
        self.index.insert(node, id);
        id
    }

    /// The symbol summaries of a node from those of its children.
    fn summarise(&self, node: &Node) -> (SymKinds, Signature) {
        match node {
            Node::Sym(s) => (s.kind(), Signature::of(*s)),
            _ => node_children(node).iter().fold(
                (SymKinds::EMPTY, Signature::default()),
                |(k, s), &c| {
                    let m = self.meta[c.0 as usize];
                    (k | m.kinds, s.union(m.signature))
                },
            ),
        }
    }

    /// For a number, `1`; for a product with a coefficient, the product of
    /// its other factors (interned here, so that
    /// [`split_coefficient`](Pool::split_coefficient) needs no `&mut`);
    /// otherwise `None`: the node is its own rest.
    fn coefficient_rest(&mut self, node: &Node) -> Option<ExprId> {
        match node {
            Node::Number(_) => Some(Pool::ONE),
            Node::Mul(factors) if self.as_number(factors[0]).is_some() => {
                Some(match &factors[1..] {
                    [single] => *single,
                    rest => self.intern(Node::Mul(rest.into())),
                })
            }
            _ => None,
        }
    }

    /// `0`.
    pub fn zero(&self) -> ExprId {
        Pool::ZERO
    }

    /// `1`.
    pub fn one(&self) -> ExprId {
        Pool::ONE
    }

    /// The integer `i`.
    pub fn int(&mut self, i: i64) -> ExprId {
        self.number(Number::from(i))
    }

    /// The exact fraction `num/den`; a float (`±inf`, `NaN`) if `den == 0`.
    pub fn rational(&mut self, num: i128, den: i128) -> ExprId {
        self.number(Number::ratio(num, den))
    }

    /// The number `n`.
    pub fn number(&mut self, n: Number) -> ExprId {
        self.intern(Node::Number(n))
    }

    /// The exact value of a Rust numeric literal's text (`"1.3"` is
    /// `13/10`; suffixes, `_` and exponents allowed), `None` if it is not
    /// one.
    pub fn decimal(&mut self, text: &str) -> Option<ExprId> {
        parse_literal(text).map(|n| self.number(n))
    }

    /// The symbol `s`.
    pub fn sym(&mut self, s: Sym) -> ExprId {
        self.intern(Node::Sym(s))
    }

    /// The value of `e` if it is a number.
    pub fn as_number(&self, e: ExprId) -> Option<Number> {
        match self.node(e) {
            Node::Number(n) => Some(*n),
            _ => None,
        }
    }

    /// The exact value of `e` if it is a rational number.
    pub fn as_rational(&self, e: ExprId) -> Option<Rational> {
        self.as_number(e).and_then(Number::as_rational)
    }

    /// Whether `e` is the number zero.
    pub fn is_zero(&self, e: ExprId) -> bool {
        self.as_number(e).is_some_and(Number::is_zero)
    }

    /// The kinds of the symbols occurring in `e` (O(1)).
    pub fn kinds(&self, e: ExprId) -> SymKinds {
        self.meta[e.0 as usize].kinds
    }

    /// Whether `e` may contain `s`: `false` proves it does not (O(1)).
    pub(super) fn may_contain(&self, e: ExprId, s: Sym) -> bool {
        self.meta[e.0 as usize].signature.may_contain(s)
    }

    /// The symbols occurring in `e`.
    pub fn free_symbols(&self, e: ExprId) -> BTreeSet<Sym> {
        let nodes = self.post_order(&[e], |n| !self.kinds(n).is_empty());
        nodes
            .into_iter()
            .filter_map(|n| match self.node(n) {
                Node::Sym(s) => Some(*s),
                _ => None,
            })
            .collect()
    }

    /// `(c, rest)` with `e == c * rest` and `rest` free of a numeric
    /// coefficient: `(n, 1)` for a number `n`, the leading factor and the
    /// others for a product with a coefficient, `(1, e)` otherwise (sums
    /// included). O(1).
    pub fn split_coefficient(&self, e: ExprId) -> (Number, ExprId) {
        let coefficient = match self.node(e) {
            Node::Number(n) => *n,
            Node::Mul(factors) => self.as_number(factors[0]).unwrap_or(Number::ONE),
            _ => Number::ONE,
        };
        (coefficient, self.meta[e.0 as usize].rest)
    }

    /// The sum `s` if `e` is `−s`: how a pool
    /// [with positive sums](Pool::with_positive_sums) holds a sum whose
    /// first term is negative. The printers write it, and the emitter an
    /// unshared one, as the terms of `s` negated.
    pub fn negated_sum(&self, e: ExprId) -> Option<ExprId> {
        let (c, sum) = self.split_coefficient(e);
        (c == -Number::ONE && matches!(self.node(sum), Node::Add(_))).then_some(sum)
    }

    /// The children of `e` (terms, factors, base or argument).
    pub fn children(&self, e: ExprId) -> &[ExprId] {
        node_children(self.node(e))
    }

    /// Every node reachable from `roots` whose ancestors were all
    /// `enter`ed, children before parents, each once; `enter` is asked once
    /// per distinct node and a node it refuses is neither listed nor
    /// descended into. Iterative (an explicit stack), so deep expressions
    /// cannot overflow the call stack; the order depends only on the DAG and
    /// the order of `roots`.
    pub(crate) fn post_order(
        &self,
        roots: &[ExprId],
        mut enter: impl FnMut(ExprId) -> bool,
    ) -> Vec<ExprId> {
        let mut seen = HashSet::new();
        let mut order = Vec::new();
        let mut stack: Vec<(ExprId, usize)> = Vec::new();
        for &root in roots {
            if seen.insert(root) && enter(root) {
                stack.push((root, 0));
            }
            while let Some((node, next)) = stack.last_mut() {
                let node = *node;
                match self.children(node).get(*next) {
                    Some(&child) => {
                        *next += 1;
                        if seen.insert(child) && enter(child) {
                            stack.push((child, 0));
                        }
                    }
                    None => {
                        stack.pop();
                        order.push(node);
                    }
                }
            }
        }
        order
    }

    /// Every node reachable from `roots`, children before parents, each
    /// once, in an order that depends only on the DAG and on `roots`.
    pub fn topo_order(&self, roots: &[ExprId]) -> Vec<ExprId> {
        self.post_order(roots, |_| true)
    }
}

/// The children of a node.
fn node_children(node: &Node) -> &[ExprId] {
    match node {
        Node::Add(terms) => terms,
        Node::Mul(factors) => factors,
        Node::Pow(base, _) | Node::Group(base) => std::slice::from_ref(base),
        Node::Func(_, arg) => std::slice::from_ref(arg),
        Node::Number(_) | Node::Sym(_) => &[],
    }
}

#[cfg(test)]
mod tests {
    use super::super::test_util::Scratch;
    use super::*;

    #[test]
    fn interning_shares_equal_nodes() {
        let mut p = Pool::new();
        assert_eq!(p.len(), 2);
        assert_eq!(p.node(p.zero()), &Node::Number(Number::ZERO));
        assert_eq!(p.node(p.one()), &Node::Number(Number::ONE));
        let x = p.sym(Sym::Coord(0));
        assert_eq!(p.sym(Sym::Coord(0)), x);
        assert_eq!(p.int(1), p.one());
        assert_eq!(p.rational(4, 2), p.int(2));
        assert_eq!(p.len(), 4);
    }

    #[test]
    fn division_by_exact_zero_is_a_float() {
        let mut p = Pool::new();
        let inf = p.rational(-3, 0);
        assert_eq!(
            p.as_number(inf).map(Number::to_f64),
            Some(f64::NEG_INFINITY)
        );
        assert_eq!(p.as_rational(inf), None);
        let nan = p.rational(0, 0);
        assert!(p.as_number(nan).unwrap().to_f64().is_nan());
    }

    #[test]
    fn decimal_constructor_is_exact() {
        let mut p = Pool::new();
        let exact = p.rational(13, 10);
        assert_eq!(p.decimal("1.3"), Some(exact));
        assert_eq!(p.as_rational(exact), Rational::new(13, 10));
        let e = p.decimal("2.5E+2");
        assert_eq!(e, Some(p.int(250)));
        assert_eq!(p.decimal("theta"), None);
    }

    #[test]
    fn summaries_and_free_symbols() {
        let mut s = Scratch::default();
        let e = s.e("p0*sin(q1)*u1");
        let p = &s.pool;
        assert_eq!(
            p.kinds(e),
            SymKinds::PARAM | SymKinds::COORD | SymKinds::SPEED
        );
        assert_eq!(p.kinds(p.one()), SymKinds::EMPTY);
        assert!(p.may_contain(e, Sym::Coord(1)) && !p.may_contain(e, Sym::Coord(0)));
        let expected: BTreeSet<Sym> = [Sym::Param(0), Sym::Coord(1), Sym::Speed(1)].into();
        assert_eq!(p.free_symbols(e), expected);
        let constant = s.e("sqrt(2) + 5");
        assert!(s.pool.free_symbols(constant).is_empty());
        assert!(s.pool.is_zero(s.pool.zero()) && !s.pool.is_zero(constant));
    }

    #[test]
    fn split_coefficient_cases() {
        let mut s = Scratch::default();
        for (text, coefficient, rest) in [
            ("3", Number::from(3), "1"),
            ("q0", Number::ONE, "q0"),
            ("3*q0*q1", Number::from(3), "q0*q1"),
            ("q0/2", Number::ratio(1, 2), "q0"),
            ("-(q0 + q1)", Number::from(-1), "q0 + q1"),
            ("q0 + q1", Number::ONE, "q0 + q1"),
        ] {
            let (e, rest) = (s.e(text), s.e(rest));
            assert_eq!(s.pool.split_coefficient(e), (coefficient, rest), "{text}");
        }
    }

    #[test]
    fn topo_order_puts_children_first() {
        let mut s = Scratch::default();
        let (c, a) = (s.e("(2*sin(q0)*q1 + sin(q0))^3"), s.e("2*sin(q0)*q1"));
        let order = s.pool.topo_order(&[c, a]);
        let position: HashMap<ExprId, usize> =
            order.iter().enumerate().map(|(i, &e)| (e, i)).collect();
        assert_eq!(position.len(), order.len(), "a node is listed twice");
        for &e in &order {
            for child in s.pool.children(e) {
                assert!(position[child] < position[&e], "child after parent");
            }
        }
        for text in [
            "q0",
            "q1",
            "2",
            "sin(q0)",
            "2*sin(q0)*q1",
            "2*sin(q0)*q1 + sin(q0)",
        ] {
            assert!(position.contains_key(&s.e(text)), "{text} missing");
        }
        assert_eq!(order.len(), 7);
        assert_eq!(order, s.pool.topo_order(&[c, a]), "not deterministic");
    }

    #[test]
    fn post_order_survives_very_deep_expressions() {
        let mut p = Pool::new();
        let mut e = p.sym(Sym::Coord(0));
        for _ in 0..200_000 {
            e = p.sin(e);
        }
        assert_eq!(p.topo_order(&[e]).len(), 200_001);
        assert_eq!(p.free_symbols(e).len(), 1);
    }
}
