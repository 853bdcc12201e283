//! Straight-line function bodies from expression DAGs: every symbol is
//! loaded once, every shared subexpression (and every `sin`/`cos`) is bound
//! to a `let` once, in dependency order, and the rest is written inline.

use crate::expr::{ExprId, Func, Node, Number, Pool, Sym, SymKinds};
use crate::plan::{DECLARED_AHEAD_ABOVE, DECLARED_TOGETHER};
use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::{format_ident, quote};
use std::collections::{BTreeSet, HashMap};

/// Rust names for the symbols of one model.
#[derive(Clone)]
pub struct Names {
    /// Parameter field names, by index.
    pub parameters: Vec<Ident>,
    /// Coordinate names, by index.
    pub coordinates: Vec<Ident>,
    /// Speed names, by index.
    pub speeds: Vec<Ident>,
    /// Names of the speeds' rates, by index.
    pub accelerations: Vec<Ident>,
    /// Input names, by index.
    pub inputs: Vec<Ident>,
    /// Prefix of temporaries, chosen to collide with no other name.
    pub temporary: String,
    /// Prefix of the multipliers or weights (`Sym::Multiplier`): `lambda`,
    /// lengthened until no user name is the prefix and a number.
    pub multiplier: String,
    /// Whether elementary functions are called through `libm` (for
    /// `#![no_std]` crates) instead of as `f64`'s methods.
    pub libm: bool,
    /// Whether the body computes four states at once, one in each lane of
    /// a `dalembert::__private::lanes::Lanes` (`super::lanes`): the
    /// parameters are loaded into every lane, the temporaries are lanes,
    /// and the functions are the runtime's `lanes` module's.
    pub lanes: bool,
    /// Whether the weights (`Sym::Multiplier`) are lanes in an otherwise
    /// scalar body (the adjoint rows of `accelerations_jacobian`, a few rows
    /// a pass): a temporary that reads them is then a
    /// `dalembert::__private::WeightLanes` where it is declared ahead.
    pub weights_in_lanes: bool,
}

impl Names {
    /// Whether a user's parameter, coordinate, speed or input has this name.
    fn is_taken(&self, name: &str) -> bool {
        self.parameters
            .iter()
            .chain(&self.coordinates)
            .chain(&self.speeds)
            .chain(&self.accelerations)
            .chain(&self.inputs)
            .any(|ident| ident == name)
    }
}

impl Names {
    /// The type of the body's numbers: `f64`, or the lanes.
    fn number_type(&self) -> TokenStream {
        match self.lanes {
            true => quote!(::dalembert::__private::lanes::Lanes),
            false => quote!(::core::primitive::f64),
        }
    }

    /// The runtime's module of elementary functions for the body.
    fn functions(&self) -> TokenStream {
        match self.lanes {
            true => quote!(::dalembert::__private::lanes),
            false => quote!(::dalembert::__private::math),
        }
    }

    fn symbol(&self, sym: Sym) -> Ident {
        match sym {
            Sym::Time => Ident::new("t", Span::call_site()),
            Sym::Param(i) => self.parameters[i as usize].clone(),
            Sym::Coord(i) => self.coordinates[i as usize].clone(),
            Sym::Speed(i) => self.speeds[i as usize].clone(),
            Sym::Input(i) => self.inputs[i as usize].clone(),
            Sym::Accel(i) => self.accelerations[i as usize].clone(),
            Sym::Multiplier(i) => self.multiplier(i as usize),
        }
    }

    /// The name of multiplier (or weight) `i`, which no user name shadows.
    pub fn multiplier(&self, i: usize) -> Ident {
        format_ident!("{}{}", self.multiplier, i)
    }

    /// `base`, or `base` with its last character repeated until it is no
    /// user's name: a generated name that a user's `let` cannot shadow or
    /// clash with (the const generic `K` of `taylor_coefficients`).
    pub fn unused(&self, base: &str) -> Ident {
        let mut name = base.to_string();
        while self.is_taken(&name) {
            name.extend(base.chars().last());
        }
        Ident::new(&name, Span::call_site())
    }

    /// One statement binding every used symbol from the arguments and
    /// `self`, all read before any is bound, so that no user name (a
    /// parameter called `q`, a coordinate called `u`) can shadow an argument
    /// another load still needs.
    fn load(&self, used: &BTreeSet<Sym>, taken: Option<(TokenStream, TokenStream)>) -> TokenStream {
        let mut patterns = Vec::new();
        let mut values = Vec::new();
        for (i, name) in self.parameters.iter().enumerate() {
            if used.contains(&Sym::Param(i as u32)) {
                patterns.push(quote!(#name));
                values.push(match self.lanes {
                    true => quote!(::dalembert::__private::lanes::splat(self.#name)),
                    false => quote!(self.#name),
                });
            }
        }
        let arrays: [ArrayArgument<'_>; 4] = [
            ("q", &self.coordinates, Sym::Coord),
            ("qd", &self.speeds, Sym::Speed),
            ("qdd", &self.accelerations, Sym::Accel),
            ("u", &self.inputs, Sym::Input),
        ];
        for (array, names, sym) in arrays {
            let elements: Vec<TokenStream> = names
                .iter()
                .enumerate()
                .map(|(i, name)| {
                    if used.contains(&sym(i as u32)) {
                        quote!(#name)
                    } else {
                        quote!(_)
                    }
                })
                .collect();
            if (0..names.len() as u32).any(|i| used.contains(&sym(i))) {
                let array = Ident::new(array, Span::call_site());
                patterns.push(quote!([#(#elements),*]));
                values.push(quote!(*#array));
            }
        }
        if let Some((pattern, value)) = taken {
            patterns.push(pattern);
            values.push(value);
        }
        match (patterns.as_slice(), values.as_slice()) {
            ([], _) => TokenStream::new(),
            ([pattern], [value]) => quote!(let #pattern = #value;),
            _ => quote!(let (#(#patterns),*) = (#(#values),*);),
        }
    }
}

/// An array argument: its name, the names of its elements, their symbols.
type ArrayArgument<'a> = (&'static str, &'a [Ident], fn(u32) -> Sym);

/// A function body: `let` statements, then the output expressions.
pub struct Straight {
    /// Symbol loads and shared temporaries, in order.
    pub statements: TokenStream,
    /// One expression per root, referring to the statements' names.
    pub outputs: Vec<TokenStream>,
    /// The symbols the body reads.
    pub used: BTreeSet<Sym>,
}

/// Where a function body takes the sines and cosines of its coordinates'
/// angles.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Angles {
    /// All with one call at the top, right after loading the coordinates
    /// ([`Writer::bind_angles`]).
    AtTop,
    /// Each where it is first needed: a long recursion then keeps fewer
    /// values live (the articulated-body `accelerations`).
    WhereNeeded,
}

/// Writes the straight-line code computing `roots`, with the angles' sines
/// and cosines taken at the top.
pub fn straight_line(pool: &Pool, names: &Names, roots: &[ExprId]) -> Straight {
    straight_line_taking(pool, names, roots, Angles::AtTop)
}

/// Writes the straight-line code computing `roots`, taking the angles'
/// sines and cosines as `angles` says.
pub fn straight_line_taking(
    pool: &Pool,
    names: &Names,
    roots: &[ExprId],
    angles: Angles,
) -> Straight {
    write(pool, names, roots, angles, None)
}

/// Values an earlier body computed, that a body takes instead of computing
/// them again: the array named `array` holds the values of `expressions`,
/// in order.
pub struct Given<'a> {
    /// The array's name, at the scope of the body (like `q` or `qdd`).
    pub array: Ident,
    /// The expressions whose values it holds.
    pub expressions: &'a [ExprId],
}

/// Writes the straight-line code computing `roots`, taking the values of
/// `given` from its array (loaded with the symbols) wherever they occur.
pub fn straight_line_given(
    pool: &Pool,
    names: &Names,
    roots: &[ExprId],
    given: &Given<'_>,
) -> Straight {
    write(pool, names, roots, Angles::AtTop, Some(given))
}

/// The straight-line code computing `roots` ([`straight_line_taking`]),
/// with the values of `given`, if any, taken from its array.
fn write(
    pool: &Pool,
    names: &Names,
    roots: &[ExprId],
    angles: Angles,
    given: Option<&Given<'_>>,
) -> Straight {
    let is_given = |e: ExprId| given.is_some_and(|g| g.expressions.contains(&e));
    let order = pool.post_order(roots, |e| !is_given(e));
    let nested = nested_sums(pool, &order);
    let uses = count_uses(pool, &order, roots, &nested);
    let mut writer = Writer {
        pool,
        names,
        nested,
        bound: HashMap::new(),
        statements: TokenStream::new(),
        temporaries: 0,
        declared: None,
    };
    let mut used = BTreeSet::new();
    for &e in &order {
        if let Node::Sym(sym) = pool.node(e) {
            used.insert(*sym);
        }
    }
    let taken = given.map(|given| writer.take(given, &uses));
    let loads = names.load(&used, taken);
    let pairs = sin_cos_pairs(pool, &order);
    if angles == Angles::AtTop {
        writer.bind_angles(&angle_pairs(pool, &order, &pairs));
    }
    let bindings = order
        .iter()
        .filter(|&&e| writer.needs_binding(e, &uses))
        .count();
    if bindings > DECLARED_AHEAD_ABOVE {
        writer.declared = Some(Vec::new());
    }
    for &e in &order {
        if !writer.needs_binding(e, &uses) {
            continue;
        }
        if writer.alias_group(e) {
            continue;
        }
        match pairs.get(&e) {
            Some(&(sine, cosine, arg)) => writer.bind_sin_cos(sine, cosine, arg),
            None => writer.bind(e),
        }
    }
    let outputs = roots.iter().map(|&r| writer.output(r)).collect();
    let declarations = declarations(writer.declared.as_deref().unwrap_or_default(), names);
    let statements = writer.statements;
    Straight {
        statements: quote!(#loads #declarations #statements),
        outputs,
        used,
    }
}

/// `let (x1, x2, …): (f64, f64, …);` declaring `declared` ahead of their
/// assignments, [`DECLARED_TOGETHER`] to a statement, each of the body's
/// number type or (one that reads lanes of weights) a lane.
fn declarations(declared: &[(Ident, bool)], names: &Names) -> TokenStream {
    let (number, lane) = (
        names.number_type(),
        quote!(::dalembert::__private::WeightLanes),
    );
    declared
        .chunks(DECLARED_TOGETHER)
        .map(|chunk| {
            let names = chunk.iter().map(|(name, _)| name);
            let types = chunk.iter().map(|(_, weighted)| match weighted {
                true => &lane,
                false => &number,
            });
            match chunk {
                [(name, weighted)] => {
                    let ty = if *weighted { &lane } else { &number };
                    quote!(let #name: #ty;)
                }
                _ => quote!(let (#(#names),*): (#(#types),*);),
            }
        })
        .collect()
}

fn count_uses(
    pool: &Pool,
    order: &[ExprId],
    roots: &[ExprId],
    nested: &HashMap<ExprId, NestedSum>,
) -> HashMap<ExprId, usize> {
    let mut uses: HashMap<ExprId, usize> = HashMap::new();
    for &e in order {
        let written = match nested.get(&e) {
            Some(sum) => std::iter::once(sum.inner)
                .chain(sum.rest.iter().copied())
                .collect(),
            None => pool.children(e).to_vec(),
        };
        for child in written {
            *uses.entry(child).or_default() += 1;
        }
    }
    for &r in roots {
        *uses.entry(r).or_default() += 1;
    }
    uses
}

/// A sum written as an earlier sum plus a constant and other terms, or as
/// the other terms and a constant minus an earlier sum.
struct NestedSum {
    /// The earlier sum, all of whose non-constant terms this sum holds
    /// (negated if `negated`).
    inner: ExprId,
    /// Whether this sum holds the earlier sum's terms negated: it is
    /// written `rest − inner`, not `inner + rest`.
    negated: bool,
    /// This sum's constant less the earlier one's (plus it, if `negated`).
    constant: Number,
    /// The terms not in the earlier sum.
    rest: Vec<ExprId>,
}

/// Sums as they are written: a sum that holds every non-constant term of
/// an earlier sum (the largest such, one holding them with their signs
/// before one holding them negated, ties to the lower id) is written as
/// that sum plus the difference, or as the difference minus that sum, so
/// that the running totals of a recursion — which canonical sums flatten —
/// cost one addition per step again. The negated case is the pool's one
/// form per sum at work: a sum whose first term would be negative is
/// stored as `−1` times the sum with every sign turned, so a later sum may
/// hold an earlier one's terms with every sign turned.
fn nested_sums(pool: &Pool, order: &[ExprId]) -> HashMap<ExprId, NestedSum> {
    // The earlier sums holding each term, the term as its coefficient-free
    // part and coefficient (so that its negation is found without building it).
    let mut containing: HashMap<(ExprId, Number), Vec<ExprId>> = HashMap::new();
    let mut nested = HashMap::new();
    for &e in order {
        let Node::Add(terms) = pool.node(e) else {
            continue;
        };
        let (constant, variable) = split_constant(pool, terms);
        let mut counts: HashMap<(ExprId, bool), usize> = HashMap::new();
        for &term in variable {
            let (c, rest) = pool.split_coefficient(term);
            for (negated, key) in [(false, (rest, c)), (true, (rest, -c))] {
                for &sum in containing.get(&key).into_iter().flatten() {
                    *counts.entry((sum, negated)).or_default() += 1;
                }
            }
        }
        let best = counts
            .into_iter()
            .filter(|&((sum, _), count)| {
                count >= 2 && count == split_constant(pool, pool.children(sum)).1.len()
            })
            .max_by_key(|&((sum, negated), count)| (count, !negated, std::cmp::Reverse(sum)));
        if let Some(((inner, negated), _)) = best {
            let (inner_constant, inner_terms) = split_constant(pool, pool.children(inner));
            let held = |t: ExprId| {
                let (c, rest) = pool.split_coefficient(t);
                let c = if negated { -c } else { c };
                inner_terms
                    .iter()
                    .any(|&i| pool.split_coefficient(i) == (c, rest))
            };
            nested.insert(
                e,
                NestedSum {
                    inner,
                    negated,
                    constant: match negated {
                        true => constant + inner_constant,
                        false => constant + -inner_constant,
                    },
                    rest: variable.iter().copied().filter(|&t| !held(t)).collect(),
                },
            );
        }
        for &term in variable {
            let (c, rest) = pool.split_coefficient(term);
            containing.entry((rest, c)).or_default().push(e);
        }
    }
    nested
}

/// A canonical sum's constant (its first term, if a number) and the rest.
fn split_constant<'a>(pool: &Pool, terms: &'a [ExprId]) -> (Number, &'a [ExprId]) {
    match terms.split_first() {
        Some((&first, rest)) => match pool.as_number(first) {
            Some(n) => (n, rest),
            None => (Number::ZERO, terms),
        },
        None => (Number::ZERO, terms),
    }
}

/// For each sine whose cosine also occurs (and the reverse): the pair and
/// their argument.
fn sin_cos_pairs(pool: &Pool, order: &[ExprId]) -> HashMap<ExprId, (ExprId, ExprId, ExprId)> {
    let mut by_argument: HashMap<ExprId, [Option<ExprId>; 2]> = HashMap::new();
    for &e in order {
        match pool.node(e) {
            Node::Func(Func::Sin, arg) => by_argument.entry(*arg).or_default()[0] = Some(e),
            Node::Func(Func::Cos, arg) => by_argument.entry(*arg).or_default()[1] = Some(e),
            _ => {}
        }
    }
    let mut pairs = HashMap::new();
    for (arg, found) in by_argument {
        if let [Some(sine), Some(cosine)] = found {
            pairs.insert(sine, (sine, cosine, arg));
            pairs.insert(cosine, (sine, cosine, arg));
        }
    }
    pairs
}

/// The sine–cosine pairs of the symbols (the coordinates' angles), in
/// the order of `order`: the ones a function can take all at once at its
/// top, right after loading the symbols.
fn angle_pairs(
    pool: &Pool,
    order: &[ExprId],
    pairs: &HashMap<ExprId, (ExprId, ExprId, ExprId)>,
) -> Vec<(ExprId, ExprId, ExprId)> {
    order
        .iter()
        .filter_map(|e| pairs.get(e).filter(|&&(sine, ..)| sine == *e))
        .filter(|&&(.., arg)| matches!(pool.node(arg), Node::Sym(_)))
        .copied()
        .collect()
}

struct Writer<'a> {
    pool: &'a Pool,
    names: &'a Names,
    /// Sums written as an earlier sum plus other terms ([`nested_sums`]).
    nested: HashMap<ExprId, NestedSum>,
    bound: HashMap<ExprId, TokenStream>,
    statements: TokenStream,
    temporaries: usize,
    /// The temporaries declared ahead of their assignments, in a long body
    /// ([`DECLARED_AHEAD_ABOVE`]); `None` in a short one, whose every
    /// temporary has its own `let`.
    declared: Option<Vec<(Ident, bool)>>,
}

impl Writer<'_> {
    /// Elementary functions are always bound (they are the expensive calls,
    /// and groups the steps of a recursion), other compound expressions when
    /// they are used more than once.
    fn needs_binding(&self, e: ExprId, uses: &HashMap<ExprId, usize>) -> bool {
        if self.bound.contains_key(&e) {
            return false;
        }
        match self.pool.node(e) {
            Node::Number(_) | Node::Sym(_) => false,
            Node::Func(..) | Node::Group(_) => true,
            _ => uses.get(&e).copied().unwrap_or(0) > 1,
        }
    }

    /// A group (a step of a recursion) whose content already has a name (a
    /// symbol or a bound temporary) takes that name: no `let x2 = x1;`.
    /// Returns whether it did. (A literal keeps its typed `let`.)
    fn alias_group(&mut self, e: ExprId) -> bool {
        let Node::Group(arg) = self.pool.node(e) else {
            return false;
        };
        let named = self
            .bound
            .get(arg)
            .cloned()
            .or_else(|| match self.pool.node(*arg) {
                Node::Sym(_) => Some(self.compound(*arg)),
                _ => None,
            });
        match named {
            Some(name) => {
                self.bound.insert(e, name);
                true
            }
            None => false,
        }
    }

    /// `let (s, c) = ::dalembert::__private::math::sin_cos(x);` binding a sine and the
    /// cosine of the same argument with one call (the runtime's, cheaper
    /// than `f64::sin_cos`: see its `math` module); `::libm::sincos(x)`
    /// without the runtime.
    fn bind_sin_cos(&mut self, sine: ExprId, cosine: ExprId, arg: ExprId) {
        let call = match self.names.libm {
            true => self.method_call(arg, "sin_cos"),
            false => {
                let (argument, functions) = (self.expr(arg), self.names.functions());
                quote!(#functions::sin_cos(#argument))
            }
        };
        let (s, c) = (self.temporary_name(sine), self.temporary_name(cosine));
        self.statements.extend(quote!(let (#s, #c) = #call;));
        self.bound.insert(sine, quote!(#s));
        self.bound.insert(cosine, quote!(#c));
    }

    /// `let ([s1, s2, …], [c1, c2, …]) = ::dalembert::__private::math::sin_cos_all([x1,
    /// x2, …]);` binding the sines and cosines of several angles with one
    /// call of the runtime (which computes them side by side, see its `math`
    /// module). Without the runtime, or for a single angle, one
    /// [`Writer::bind_sin_cos`] per angle.
    fn bind_angles(&mut self, angles: &[(ExprId, ExprId, ExprId)]) {
        if self.names.libm || angles.len() < 2 {
            for &(sine, cosine, arg) in angles {
                self.bind_sin_cos(sine, cosine, arg);
            }
            return;
        }
        let arguments: Vec<TokenStream> = angles.iter().map(|&(.., arg)| self.expr(arg)).collect();
        let mut sines = Vec::new();
        let mut cosines = Vec::new();
        for &(sine, cosine, _) in angles {
            let (s, c) = (self.temporary_name(sine), self.temporary_name(cosine));
            self.bound.insert(sine, quote!(#s));
            self.bound.insert(cosine, quote!(#c));
            sines.push(s);
            cosines.push(c);
        }
        let functions = self.names.functions();
        self.statements.extend(quote!(
            let ([#(#sines),*], [#(#cosines),*]) = #functions::sin_cos_all([#(#arguments),*]);
        ));
    }

    /// The pattern and value that load the array of `given`: each of its
    /// values that the body uses (per `uses`) bound to the name the body
    /// would have given it, the others to `_`.
    fn take(
        &mut self,
        given: &Given<'_>,
        uses: &HashMap<ExprId, usize>,
    ) -> (TokenStream, TokenStream) {
        let elements: Vec<TokenStream> = given
            .expressions
            .iter()
            .map(|&e| match uses.contains_key(&e) {
                true => {
                    let name = self.temporary_name(e);
                    self.bound.insert(e, quote!(#name));
                    quote!(#name)
                }
                false => quote!(_),
            })
            .collect();
        let array = &given.array;
        (quote!([#(#elements),*]), quote!(#array))
    }

    /// `let x = value;`, typed `f64` where the value holds no symbol, so
    /// that no literal's type is left for Rust to guess; in a long body
    /// ([`DECLARED_AHEAD_ABOVE`]) `x = value;`, `x` declared ahead.
    fn bind(&mut self, e: ExprId) {
        let value = match self.names.lanes && self.pool.kinds(e).is_empty() {
            true => {
                let value = self.compound(e);
                quote!(::dalembert::__private::lanes::splat(#value))
            }
            false => self.compound(e),
        };
        let name = self.temporary_name(e);
        self.statements.extend(match &mut self.declared {
            Some(declared) => {
                let weighted = self.names.weights_in_lanes
                    && self.pool.kinds(e).intersects(SymKinds::MULTIPLIER);
                declared.push((name.clone(), weighted));
                quote!(#name = #value;)
            }
            None if self.pool.kinds(e).is_empty() && !self.names.lanes => {
                quote!(let #name: ::core::primitive::f64 = #value;)
            }
            None => quote!(let #name = #value;),
        });
        self.bound.insert(e, quote!(#name));
    }

    /// `sin_theta1` for functions of a symbol (unless a user name is
    /// spelled so), else `x12`.
    fn temporary_name(&mut self, e: ExprId) -> Ident {
        if let Node::Func(f, arg) = self.pool.node(e) {
            if let Node::Sym(sym) = self.pool.node(*arg) {
                let name = format_ident!("{}_{}", f.name(), self.names.symbol(*sym));
                if !self.names.is_taken(&name.to_string()) {
                    return name;
                }
            }
        }
        self.temporaries += 1;
        format_ident!("{}{}", self.names.temporary, self.temporaries - 1)
    }

    /// The expression of the root `e`: [`Writer::expr`], a constant put
    /// into every lane in a body over lanes, so that a function's results
    /// have one type.
    fn output(&self, e: ExprId) -> TokenStream {
        let value = self.expr(e);
        match self.names.lanes && self.pool.kinds(e).is_empty() && !self.bound.contains_key(&e) {
            true => quote!(::dalembert::__private::lanes::splat(#value)),
            false => value,
        }
    }

    /// The expression of `e`, by name if bound.
    fn expr(&self, e: ExprId) -> TokenStream {
        match self.bound.get(&e) {
            Some(name) => name.clone(),
            None => self.compound(e),
        }
    }

    /// `e` written out (its children by name where bound).
    fn compound(&self, e: ExprId) -> TokenStream {
        match self.pool.node(e) {
            Node::Number(n) => number(*n),
            Node::Sym(sym) => {
                let name = self.names.symbol(*sym);
                quote!(#name)
            }
            Node::Add(terms) => match self.nested.get(&e) {
                Some(nested) => self.nested_sum(nested),
                None => self.sum(terms),
            },
            Node::Mul(_) | Node::Pow(..) => self.product(e),
            Node::Func(f, arg) => self.method_call(*arg, f.name()),
            Node::Group(sum) => self.expr(*sum),
        }
    }

    /// `x.method()`, or `f64::method(2.0)` on a literal, whose type a
    /// method call could not infer.
    fn method_call(&self, arg: ExprId, method: &str) -> TokenStream {
        if self.names.libm {
            let function = Ident::new(libm_name(method), Span::call_site());
            let argument = self.expr(arg);
            return quote!(::libm::#function(#argument));
        }
        let method = Ident::new(method, Span::call_site());
        if self.names.lanes {
            let argument = self.expr(arg);
            return quote!(::dalembert::__private::lanes::#method(#argument));
        }
        let receiver = self.operand(arg);
        if !self.bound.contains_key(&arg) && matches!(self.pool.node(arg), Node::Number(_)) {
            quote!(::core::primitive::f64::#method(#receiver))
        } else {
            quote!(#receiver.#method())
        }
    }

    /// A child in a position that binds tighter than `*`: parenthesised
    /// unless it is a name, a literal or a method call.
    fn operand(&self, e: ExprId) -> TokenStream {
        let tokens = self.expr(e);
        let simple = self.bound.contains_key(&e)
            || match self.pool.node(e) {
                Node::Sym(_) | Node::Func(..) => true,
                Node::Number(n) => !n.is_negative(),
                _ => false,
            };
        if simple { tokens } else { quote!((#tokens)) }
    }

    /// `a + b - c`: terms with a negative coefficient are subtracted.
    /// `inner ± constant ± rest…`, or `rest… − inner ± constant` for an
    /// earlier sum held negated.
    fn nested_sum(&self, sum: &NestedSum) -> TokenStream {
        let mut out = match sum.negated {
            false => {
                let inner = self.expr(sum.inner);
                quote!(#inner)
            }
            true => {
                let (rest, inner) = (self.terms(&sum.rest, true, false), self.operand(sum.inner));
                match sum.rest.is_empty() {
                    true => quote!(-#inner),
                    false => quote!(#rest - #inner),
                }
            }
        };
        if !sum.constant.is_zero() {
            let magnitude = number(sum.constant.abs());
            out.extend(if sum.constant.is_negative() {
                quote!(- #magnitude)
            } else {
                quote!(+ #magnitude)
            });
        }
        if !sum.negated {
            out.extend(self.terms(&sum.rest, false, false));
        }
        out
    }

    fn sum(&self, terms: &[ExprId]) -> TokenStream {
        self.terms(terms, true, false)
    }

    /// Terms joined by their signs (every sign turned if `turned`); `first`
    /// if they start the sum.
    fn terms(&self, terms: &[ExprId], first: bool, turned: bool) -> TokenStream {
        let mut out = TokenStream::new();
        for (i, &term) in terms.iter().enumerate() {
            let i = if first { i } else { i + 1 };
            let (negative, magnitude) = self.sign(term);
            let negative = negative != turned;
            let written = magnitude.unwrap_or_else(|| self.expr(term));
            out.extend(match (i, negative) {
                (0, false) => quote!(#written),
                (0, true) => quote!(-#written),
                (_, false) => quote!(+ #written),
                (_, true) => quote!(- #written),
            });
        }
        out
    }

    /// Whether an unbound term has a negative coefficient, and the term
    /// with that coefficient made positive.
    fn sign(&self, term: ExprId) -> (bool, Option<TokenStream>) {
        if self.bound.contains_key(&term) {
            return (false, None);
        }
        match self.pool.node(term) {
            Node::Number(n) if n.is_negative() => (true, Some(number(-*n))),
            Node::Mul(factors) => match self.pool.as_number(factors[0]) {
                Some(c) if c.is_negative() => (true, Some(self.product_of(-c, &factors[1..]))),
                _ => (false, None),
            },
            _ => (false, None),
        }
    }

    fn product(&self, e: ExprId) -> TokenStream {
        match self.pool.node(e) {
            Node::Mul(factors) => match self.pool.as_number(factors[0]) {
                Some(c) => self.product_of(c, &factors[1..]),
                None => self.product_of(
                    Number::Rational(crate::expr::Rational { num: 1, den: 1 }),
                    factors,
                ),
            },
            _ => self.product_of(
                Number::Rational(crate::expr::Rational { num: 1, den: 1 }),
                &[e],
            ),
        }
    }

    /// `c * a * b^2 / (d * e)`; `−1` times a sum written out is the sum
    /// with its signs turned (`-a + b`, not `-((a - b))`).
    fn product_of(&self, coefficient: Number, factors: &[ExprId]) -> TokenStream {
        if let [f] = factors
            && coefficient == Number::from(-1i64)
            && !self.bound.contains_key(f)
            && !self.nested.contains_key(f)
            && let Node::Add(terms) = self.pool.node(*f)
        {
            return self.terms(terms, true, true);
        }
        let mut numerator = Vec::new();
        let mut denominator = Vec::new();
        // Whether the denominator is a product (`x * x` from `x⁻²` is one
        // even alone), which needs parentheses below the `/`.
        let mut product_below = false;
        for &f in factors {
            match self.pool.node(f) {
                // `i32::MIN` has no positive counterpart: it stays a `powi`.
                Node::Pow(base, n) if *n < 0 && *n != i32::MIN && !self.bound.contains_key(&f) => {
                    product_below |= matches!(n, -3 | -2);
                    denominator.push(self.power(*base, -n))
                }
                _ => numerator.push(self.factor(f)),
            }
        }
        let negative = coefficient.is_negative();
        let magnitude = if negative { -coefficient } else { coefficient };
        if !magnitude.is_one() || numerator.is_empty() {
            numerator.insert(0, number(magnitude));
        }
        let mut out = join(&numerator, quote!(*));
        if !denominator.is_empty() {
            let below = join(&denominator, quote!(*));
            out = if denominator.len() == 1 && !product_below {
                quote!(#out / #below)
            } else {
                quote!(#out / (#below))
            };
        }
        if negative { quote!(-(#out)) } else { out }
    }

    fn factor(&self, f: ExprId) -> TokenStream {
        match (self.bound.contains_key(&f), self.pool.node(f)) {
            (false, Node::Pow(base, n)) => self.power(*base, *n),
            _ => self.operand(f),
        }
    }

    /// `x^n` for `n ≥ 1`: repeated products up to the cube, `powi` above.
    fn power(&self, base: ExprId, n: i32) -> TokenStream {
        let x = self.operand(base);
        match n {
            1 => x,
            2 => quote!(#x * #x),
            3 => quote!(#x * #x * #x),
            _ if self.names.libm => {
                let n = Literal::f64_unsuffixed(f64::from(n));
                quote!(::libm::pow(#x, #n))
            }
            _ if self.names.lanes => {
                let n = Literal::i32_unsuffixed(n);
                quote!(::dalembert::__private::lanes::powi(#x, #n))
            }
            _ => {
                let n = Literal::i32_unsuffixed(n);
                quote!(#x.powi(#n))
            }
        }
    }
}

/// The `libm` function for an `f64` method of the same meaning.
fn libm_name(method: &str) -> &str {
    match method {
        "sin_cos" => "sincos",
        "ln" => "log",
        "abs" => "fabs",
        same => same,
    }
}

fn join(items: &[TokenStream], separator: TokenStream) -> TokenStream {
    let mut out = TokenStream::new();
    for (i, item) in items.iter().enumerate() {
        if i > 0 {
            out.extend(separator.clone());
        }
        out.extend(item.clone());
    }
    out
}

/// A float literal for `n`, the nearest double to its exact value
/// (suffixed, so that a method call on it has a type).
pub fn number(n: Number) -> TokenStream {
    let value = n.to_f64();
    let magnitude = if value.is_nan() {
        quote!(::core::primitive::f64::NAN)
    } else if value.is_infinite() {
        quote!(::core::primitive::f64::INFINITY)
    } else {
        let literal = Literal::f64_unsuffixed(value.abs());
        quote!(#literal)
    };
    if value < 0.0 {
        quote!((-#magnitude))
    } else {
        magnitude
    }
}
