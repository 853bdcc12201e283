#!/usr/bin/env python3
"""Arithmetic operations of each function of a generated model, counted in
its straight-line code (the output of `dalembert generate MODEL.dal`).

usage: op_counts.py GENERATED.rs [FUNCTION ...]
Prints CSV: function,add,mul,div,sqrt,sincos,flops,row_solve,runtime_loops,loop_flops
where add counts additions, subtractions and negations of a value (in the
straight-line code), flops = add + mul + div + loop_flops, sincos the angles of `sin_cos_all` and
`sin_cos` calls, row_solve the share of flops in the row operations of the
solve through `L D Lᵀ` (the runtime's `scale_and_subtract`, counted from its
arguments: see add_row_operations), runtime_loops names the runtime's loops
the function calls (`dalembert::dynamics::…`, `TreeRecursion::…`) and
loop_flops the share of flops in the loops of the tree's recursion and
pairs, counted from the function's table of `TreeLink`s (see
add_tree_loops). Every operator in the body counts once: the generated code is
straight-line (no loops of its own), so a static count is the count of one
call. The `finite` checks and index arithmetic are not arithmetic on values
and are left out (`usize` literals and `[i]` indices carry no operators).
"""
import re
import sys

TOKEN = re.compile(
    r"""(?P<num>\d+\.\d*(?:[eE][+-]?\d+)?|\d+(?:[eE][+-]?\d+)?(?:_?f64|usize)?)
      |(?P<ident>[A-Za-z_][A-Za-z0-9_]*)
      |(?P<op>\+=|-=|\*=|/=|->|=>|::|==|!=|<=|>=|&&|\|\||[-+*/(){}\[\];,.=&!<>|:#?'"])
      |(?P<space>\s+)""",
    re.X,
)
OPERAND_END = {")", "]"}


def tokens(text):
    """The tokens of `text`, comments and strings removed."""
    text = re.sub(r"//[^\n]*", "", text)
    text = re.sub(r'r#*"(?:.|\n)*?"#*|"(?:\\.|[^"\\])*"', '""', text)
    out = []
    for m in TOKEN.finditer(text):
        if m.lastgroup != "space":
            out.append((m.lastgroup, m.group()))
    return out


def functions(text):
    """`(name, body)` of every `pub fn` of the generated impl."""
    found = []
    for m in re.finditer(r"\n    pub fn (\w+)", text):
        start = text.index("{", text.index(")", m.end()))
        # The return type may hold braces only in generic bounds, which the
        # generated code has none of; match the body's braces.
        depth, i = 0, start
        while True:
            c = text[i]
            depth += c == "{"
            depth -= c == "}"
            i += 1
            if depth == 0:
                break
        found.append((m.group(1), text[start:i]))
    return found


def count(body):
    counts = dict(add=0, mul=0, div=0, sqrt=0, sincos=0, row_solve=0, loop_flops=0)
    toks = tokens(body)
    for k, (kind, tok) in enumerate(toks):
        prev = toks[k - 1] if k else ("op", "")
        after_operand = prev[0] in ("num", "ident") or prev[1] in OPERAND_END
        if prev[0] == "ident" and prev[1] in ("return", "let", "mut", "in", "if", "else"):
            after_operand = False
        nxt = toks[k + 1] if k + 1 < len(toks) else ("op", "")
        if tok in ("+", "+=", "-=") or (tok == "-" and after_operand):
            counts["add"] += 1
        elif tok == "-" and nxt[0] != "num":
            counts["add"] += 1  # a negated value
        elif tok in ("*=",) or (tok == "*" and after_operand):
            counts["mul"] += 1
        elif tok in ("/", "/="):
            counts["div"] += 1
        elif kind == "ident" and prev[1] == "." and tok in ("sin_cos", "sin", "cos"):
            counts["sincos"] += 1
        elif kind == "ident" and prev[1] == "." and tok == "sqrt":
            counts["sqrt"] += 1
        elif kind == "ident" and prev[1] == "." and tok == "mul_add":
            counts["mul"] += 1
            counts["add"] += 1
    add_row_operations(body, counts)
    add_tree_loops(body, counts)
    for angles in re.findall(r"sin_cos_all\(\[(.*?)\]\)", body, re.S):
        counts["sincos"] += len([a for a in angles.split(",") if a.strip()])
    counts["flops"] = counts["add"] + counts["mul"] + counts["div"] + counts["loop_flops"]
    loops = sorted(set(re.findall(r"dalembert::dynamics::(\w+)", body)))
    calls = sorted(set(re.findall(r"\btree\.(\w+)\(", body)))
    counts["runtime_loops"] = " ".join(loops + [f"TreeRecursion::{c}" for c in calls])
    return counts


def add_row_operations(body, counts):
    """The row operations of the solve through `L D Lᵀ` (the runtime's
    `scale_and_subtract(row, factor, [(l, other), …])`: one product a column
    and a product and a subtraction a column per term, on rows as wide as
    the function's `[[f64; C]; N]` rows; `subtract_on_runs`: a product and a
    subtraction a term and a column of its runs)."""
    # `let [mut b0, …]: [[f64; C]; N] = {`, or the first of a tuple's types
    # where the runtime's loops compute the rest (`: ([[f64; C]; N], …`).
    width = re.search(r"(?:\]|residual,?\s*\))\s*:\s*\(?\s*\[\[f64; (\d+)\]; \d+\]", body)
    calls = re.findall(r"scale_and_subtract\(\s*&mut \w+,\s*[^,]+,\s*\[(.*?)\]\s*,?\s*\)", body, re.S)
    if not calls or not width:
        return
    columns = int(width.group(1))
    for terms in calls:
        k = terms.count("(")
        counts["mul"] += columns * (1 + k)
        counts["add"] += columns * k
        counts["row_solve"] += columns * (1 + 2 * k)
    # `subtract_on_runs(row, [(l, other), …], &[(start, end), …])`: a product
    # and a subtraction a term and a column of the runs.
    partial = re.findall(
        r"subtract_on_runs\(\s*&mut \w+,\s*\[(.*?)\]\s*,\s*&\[(.*?)\]\s*,?\s*\)", body, re.S
    )
    for terms, runs in partial:
        k = terms.count("(")
        width = sum(int(b) - int(a) for a, b in re.findall(r"\((\d+),\s*(\d+)\)", runs))
        counts["mul"] += width * k
        counts["add"] += width * k
        counts["row_solve"] += width * 2 * k


TREE_LINK = re.compile(r"TreeLink \{\s*parent: ([\w:]+),\s*joint: (\d+),")


def add_tree_loops(body, counts):
    """The operations of the runtime's loops over a tree's links
    (`TreeRecursion::sweep`, `mass_and_bias`, `link_vectors`,
    `add_tree_pairs`), from the function's table of `TreeLink`s, as counted
    in their source (src/dynamics/tree_vectors.rs, pairs.rs): per link 995
    (the first pass's 189 outwards, 351 for its own inertia in `N`, 42 for
    `y`, 11 for `f`; the second's 114 and 288), less the 351 of a joint's
    speeds before its last (massless: skipped), plus 27 for `Φ = v × S` of
    a joint of several speeds; 43 a child added into its parent; 3 for
    gravity; per pair of a link and its ancestor-or-self 48 in the pairs
    and 11 in `M`; per strict ancestor 24 more, 48 within one joint (the
    general paths of each step: a turn's or a diagonal inertia's zero
    products are counted)."""
    links = [
        (None if p == "usize::MAX" else int(p), int(j)) for p, j in TREE_LINK.findall(body)
    ]
    if not links:
        return
    several = {j for i, (_, j) in enumerate(links) if j != i}
    flops = 3
    for i, (parent, joint) in enumerate(links):
        flops += 995 + (43 if parent is not None else 0)
        last = i + 1 == len(links) or links[i + 1][1] != joint
        if joint in several:
            flops += 27 - (0 if last else 351)
        ancestor = i
        while ancestor is not None:
            flops += 48 + 11
            if ancestor != i:
                flops += 48 if links[ancestor][1] == joint else 24
            ancestor = links[ancestor][0]
    counts["loop_flops"] = flops


def main():
    path, wanted = sys.argv[1], set(sys.argv[2:])
    text = open(path).read()
    print("function,add,mul,div,sqrt,sincos,flops,row_solve,runtime_loops,loop_flops")
    for name, body in functions(text):
        if wanted and name not in wanted:
            continue
        c = count(body)
        print(f"{name},{c['add']},{c['mul']},{c['div']},{c['sqrt']},{c['sincos']},{c['flops']},{c['row_solve']},{c['runtime_loops']},{c['loop_flops']}")


if __name__ == "__main__":
    main()
