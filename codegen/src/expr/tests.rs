//! Tests of the engine as a whole: the canonical forms working together on
//! the kind of expressions kinematics builds, and size guards against
//! expression swell.

use super::test_util::{Point, Rng, Scratch, assert_close, random_expression};
use super::{ExprId, Node, Pool, Sym};

/// A 2×2 matrix of expressions.
type Mat2 = [[ExprId; 2]; 2];

/// `a · b`.
fn matmul(p: &mut Pool, a: &Mat2, b: &Mat2) -> Mat2 {
    let entry = |p: &mut Pool, r: usize, k: usize| {
        let terms = [p.mul(a[r][0], b[0][k]), p.mul(a[r][1], b[1][k])];
        p.sum(terms)
    };
    [
        [entry(p, 0, 0), entry(p, 0, 1)],
        [entry(p, 1, 0), entry(p, 1, 1)],
    ]
}

/// The rotation by `q` about z, in the plane.
fn rz(p: &mut Pool, q: Sym) -> Mat2 {
    let q = p.sym(q);
    let (c, s) = (p.cos(q), p.sin(q));
    let minus_s = p.neg(s);
    [[c, minus_s], [s, c]]
}

/// `R_n = R_{n-1} · Rz(q_n)` for a planar chain of `links` links.
fn chain_rotation(p: &mut Pool, links: u32) -> Mat2 {
    let (zero, one) = (p.zero(), p.one());
    let mut r = [[one, zero], [zero, one]];
    for i in 0..links {
        let step = rz(p, Sym::Coord(i));
        r = matmul(p, &r, &step);
    }
    r
}

#[test]
fn thirty_link_rotation_stays_linear_in_size() {
    let mut p = Pool::new();
    let r = chain_rotation(&mut p, 30);
    assert!(p.len() < 40 * 30, "{} nodes for 30 links", p.len());
    // R = Rz(Σq): check numerically.
    let coords: Vec<Sym> = (0..30).map(Sym::Coord).collect();
    let env = Point::random(&mut Rng::new(3), &coords);
    let angle: f64 = env.0.values().sum();
    let values = p.eval_many(&[r[0][0], r[0][1], r[1][0], r[1][1]], &env);
    let expected = [angle.cos(), -angle.sin(), angle.sin(), angle.cos()];
    for (v, e) in values.iter().zip(expected) {
        assert_close(*v, e, 1e-12, "rotation entry");
    }
}

#[test]
fn derivatives_of_a_long_chain_stay_linear() {
    let mut p = Pool::new();
    let r = chain_rotation(&mut p, 30);
    let before = p.len();
    let rates: Vec<ExprId> = r.iter().flatten().map(|&e| p.time_derivative(e)).collect();
    let second: Vec<ExprId> = rates.iter().map(|&e| p.time_derivative(e)).collect();
    let grown = p.len() - before;
    assert!(grown < 400 * 30, "time derivatives built {grown} nodes");
    // d/dt R00 = -sin(Σq) Σq̇, checked at a random point.
    let syms: Vec<Sym> = (0..30)
        .flat_map(|i| [Sym::Coord(i), Sym::Speed(i), Sym::Accel(i)])
        .collect();
    let env = Point::random(&mut Rng::new(5), &syms);
    let sum_of = |kind: fn(u32) -> Sym| (0..30).map(|i| env.0[&kind(i)]).sum::<f64>();
    let (angle, rate, accel) = (sum_of(Sym::Coord), sum_of(Sym::Speed), sum_of(Sym::Accel));
    let values = p.eval_many(&[rates[0], second[0]], &env);
    assert_close(values[0], -angle.sin() * rate, 1e-11, "dR00/dt");
    let expected = -angle.cos() * rate * rate - angle.sin() * accel;
    assert_close(values[1], expected, 1e-11, "d²R00/dt²");
}

#[test]
fn association_does_not_matter_after_expansion() {
    let mut p = Pool::new();
    let [a, b, c] = [0, 1, 2].map(|i| rz(&mut p, Sym::Coord(i)));
    let ab = matmul(&mut p, &a, &b);
    let left = matmul(&mut p, &ab, &c);
    let bc = matmul(&mut p, &b, &c);
    let right = matmul(&mut p, &a, &bc);
    for (l, r) in left.iter().flatten().zip(right.iter().flatten()) {
        assert_eq!(p.expand(*l), p.expand(*r));
    }
    // det R = 1 needs sin² + cos² = 1, which canonical forms do not know;
    // numerically it holds.
    let det = {
        let (x, y) = (p.mul(left[0][0], left[1][1]), p.mul(left[0][1], left[1][0]));
        p.sub(x, y)
    };
    let env = Point::random(
        &mut Rng::new(11),
        &[Sym::Coord(0), Sym::Coord(1), Sym::Coord(2)],
    );
    assert_close(p.eval(det, &env), 1.0, 1e-14, "det R");
}

/// One form per sum: in a pool with positive sums, `b − a` and `−(a − b)`
/// are one node, for named differences and for random expressions, and
/// every sum the pool holds has a positive first non-constant term, so no
/// sum of the pool is another with every sign turned.
#[test]
fn a_pool_holds_one_form_per_sum() {
    let mut s = Scratch {
        pool: Pool::with_positive_sums(),
    };
    assert_eq!(s.e("q1 - q0"), s.e("-(q0 - q1)"));
    assert_eq!(s.e("2*p0 - q0*u0 + 1"), s.e("-(q0*u0 - 2*p0 - 1)"));
    // A multiple of a sum stays whole inside another sum, so the random
    // operands are kept to those that are not sums or multiples of one.
    let is_sum =
        |pool: &Pool, e: ExprId| matches!(pool.node(pool.split_coefficient(e).1), Node::Add(_));
    let mut rng = Rng::new(36);
    let mut differences = 0;
    while differences < 200 {
        let a = random_expression(&mut s.pool, &mut rng, 3);
        let b = random_expression(&mut s.pool, &mut rng, 3);
        if is_sum(&s.pool, a) || is_sum(&s.pool, b) {
            continue;
        }
        let (a_minus_b, b_minus_a) = (s.pool.sub(a, b), s.pool.sub(b, a));
        assert_eq!(
            s.pool.neg(a_minus_b),
            b_minus_a,
            "{} and {}",
            s.show(a_minus_b),
            s.show(b_minus_a)
        );
        differences += 1;
    }
    let sums: Vec<ExprId> = (0..s.pool.len() as u32)
        .map(ExprId)
        .filter(|&e| matches!(s.pool.node(e), Node::Add(_)))
        .collect();
    assert!(sums.len() > 200, "only {} sums", sums.len());
    for &sum in &sums {
        let first = s
            .pool
            .children(sum)
            .iter()
            .find(|&&t| s.pool.as_number(t).is_none())
            .expect("a sum has a term besides its constant");
        let (c, _) = s.pool.split_coefficient(*first);
        assert!(
            !c.is_negative(),
            "{} leads with a negative term",
            s.show(sum)
        );
    }
}
