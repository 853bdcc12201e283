//! Expressions: a Pratt parser over token trees.
//!
//! Precedence, loosest first: `+ -` (left-associative) < `* /`
//! (left-associative) < unary `-` < `^` (right-associative). So `-x^2` is
//! `-(x^2)`, `2^3^2` is `2^(3^2)`, and the exponent of `^` may start with a
//! unary minus: `x^-2` is `x^(-2)`.
//!
//! Unary `+` is rejected (with a message saying so) rather than read as a
//! no-op: the language has one spelling for each expression, and the syntax
//! tree has no node that would keep its span.
//!
//! An expression ends at the first token that cannot continue it, so the
//! contextual words `at`, `on`, `reacting` and the `==` of a constraint end
//! the expression before them without being reserved.

use proc_macro2::{Delimiter, Group, Ident, Literal, Span, TokenTree};
use syn::Lit;

use super::ast::{BinOp, Expr};
use super::cursor::Cursor;

/// How deeply parentheses, brackets, calls and unary minus may nest before
/// the parser reports an error instead of risking the stack.
const MAX_DEPTH: usize = 256;

/// How many binary operators one expression may have. A chain `a + b + ...`
/// parses in a loop, but its syntax tree is as deep as it is long, and the
/// later layers walk it recursively: with nesting, this bounds the tree's
/// depth (a sum of 12 000 terms overflowed the compiler's stack).
const MAX_OPERATORS: usize = 2048;

/// Binding power of `+` and `-`.
const ADDITIVE: u8 = 1;
/// Binding power of `*` and `/`.
const MULTIPLICATIVE: u8 = 2;
/// Binding power of the operand of unary `-`: it takes `^` but not `*`.
const UNARY: u8 = 3;
/// Binding power of `^`.
const POWER: u8 = 4;

/// Parses one expression, stopping at the first token that cannot continue
/// it.
pub fn expression(cursor: &mut Cursor) -> syn::Result<Expr> {
    binary(cursor, 0, 0, &mut 0)
}

/// Parses comma-separated expressions up to the end of `cursor`'s group
/// (call arguments, array items); a trailing comma is allowed.
fn expression_list(
    cursor: &mut Cursor,
    depth: usize,
    operators: &mut usize,
) -> syn::Result<Vec<Expr>> {
    let mut items = Vec::new();
    while !cursor.is_end() {
        items.push(binary(cursor, 0, depth, operators)?);
        if cursor.eat_punct(',').is_none() && !cursor.is_end() {
            return Err(cursor.expected(format!("`,` or {}", cursor.end_name())));
        }
    }
    Ok(items)
}

/// Parses an expression whose operators all bind at least as tightly as
/// `min_power`; `operators` counts those of the whole expression so far.
fn binary(
    cursor: &mut Cursor,
    min_power: u8,
    depth: usize,
    operators: &mut usize,
) -> syn::Result<Expr> {
    let mut lhs = prefix(cursor, depth, operators)?;
    while let Some((op, op_span)) = peek_operator(cursor) {
        let power = binding_power(op);
        if power < min_power {
            break;
        }
        *operators += 1;
        if *operators > MAX_OPERATORS {
            return Err(syn::Error::new(
                op_span,
                format!(
                    "expression too long (more than {MAX_OPERATORS} operators); split it into \
                     several statements (loads and potentials add up, points can be built from \
                     points)"
                ),
            ));
        }
        cursor.next_token();
        // Left-associative operators parse their right operand one level
        // tighter; `^` parses it at its own level, so it groups to the right.
        let rhs_power = if op == BinOp::Pow { power } else { power + 1 };
        let rhs = binary(cursor, rhs_power, depth + 1, operators)?;
        lhs = Expr::Binary {
            op,
            op_span,
            lhs: Box::new(lhs),
            rhs: Box::new(rhs),
        };
    }
    Ok(lhs)
}

/// Parses an operand: a unary minus and its operand, or a primary.
fn prefix(cursor: &mut Cursor, depth: usize, operators: &mut usize) -> syn::Result<Expr> {
    if depth > MAX_DEPTH {
        return Err(cursor.error(format!(
            "expression nested too deeply (more than {MAX_DEPTH} levels)"
        )));
    }
    if let Some(op) = cursor.eat_punct('-') {
        let operand = binary(cursor, UNARY, depth + 1, operators)?;
        return Ok(Expr::Neg {
            op,
            operand: Box::new(operand),
        });
    }
    if cursor.peek_punct('+').is_some() {
        return Err(cursor.error(format!(
            "expected an expression, found {}; unary `+` is not supported: write the operand alone",
            cursor.found()
        )));
    }
    primary(cursor, depth, operators)
}

/// Parses a number, a name, a member, a call, a method call, an array or a
/// parenthesised expression.
fn primary(cursor: &mut Cursor, depth: usize, operators: &mut usize) -> syn::Result<Expr> {
    match cursor.peek() {
        Some(TokenTree::Literal(literal)) => {
            let number = number(literal.clone())?;
            cursor.next_token();
            Ok(number)
        }
        Some(TokenTree::Ident(first)) => {
            let first = first.clone();
            cursor.next_token();
            let path = path(cursor, first, depth, operators)?;
            no_chained_dot(cursor).map(|()| path)
        }
        Some(TokenTree::Group(group)) if group.delimiter() != Delimiter::Brace => {
            let group = group.clone();
            cursor.next_token();
            let grouped = grouped(&group, depth + 1, operators)?;
            no_chained_dot(cursor).map(|()| grouped)
        }
        _ => Err(cursor.expected("an expression")),
    }
}

/// A `.` follows only a frame's name: `N.x.y`, `(N).x` or
/// `N.rotate_z(a).rotate_x(b)` are reported at the second `.`, which would
/// otherwise read as a missing `;`.
fn no_chained_dot(cursor: &Cursor) -> syn::Result<()> {
    match cursor.peek_punct('.') {
        Some(_) => Err(cursor.error(
            "expected an operator, found `.`: a `.` follows only a frame's name (`F.x`, \
             `F.rotate_z(angle)`), so chained rotations take one `frame` statement each",
        )),
        None => Ok(()),
    }
}

/// Parses `( inner )`, `[a, b, ...]`, or an invisible group (a macro
/// fragment such as `$e:expr`), which reads as its contents.
fn grouped(group: &Group, depth: usize, operators: &mut usize) -> syn::Result<Expr> {
    let mut cursor = Cursor::group(group);
    if group.delimiter() == Delimiter::Bracket {
        return Ok(Expr::Array {
            items: expression_list(&mut cursor, depth, operators)?,
            span: group.span(),
        });
    }
    let inner = binary(&mut cursor, 0, depth, operators)?;
    if !cursor.is_end() {
        return Err(cursor.expected(format!("an operator or {}", cursor.end_name())));
    }
    Ok(match group.delimiter() {
        Delimiter::Parenthesis => Expr::Paren {
            inner: Box::new(inner),
            span: group.span(),
        },
        _ => inner,
    })
}

/// Parses what follows the name `first`: nothing, `(args)`, `.member` or
/// `.method(args)`.
fn path(
    cursor: &mut Cursor,
    first: Ident,
    depth: usize,
    operators: &mut usize,
) -> syn::Result<Expr> {
    if let Some(args) = cursor.eat_group(Delimiter::Parenthesis) {
        return Ok(Expr::Call {
            parens: args.span(),
            args: expression_list(&mut Cursor::group(&args), depth + 1, operators)?,
            func: first,
        });
    }
    if cursor.eat_punct('.').is_none() {
        return Ok(Expr::Name(first));
    }
    let member = cursor.expect_ident(format!("a member name after `{first}.`"))?;
    match cursor.eat_group(Delimiter::Parenthesis) {
        Some(args) => Ok(Expr::MethodCall {
            parens: args.span(),
            args: expression_list(&mut Cursor::group(&args), depth + 1, operators)?,
            receiver: first,
            method: member,
        }),
        None => Ok(Expr::Member {
            base: first,
            member,
        }),
    }
}

/// Reads a numeric literal, keeping its text as written. Suffixes (`2f64`),
/// non-decimal integers (`0x10`) and non-numeric literals are rejected.
fn number(literal: Literal) -> syn::Result<Expr> {
    let span = literal.span();
    let text = literal.to_string();
    let suffix_free = match Lit::new(literal) {
        Lit::Int(int) => int.suffix().is_empty(),
        Lit::Float(float) => float.suffix().is_empty(),
        _ => {
            return Err(syn::Error::new(
                span,
                format!(
                    "expected an expression, found `{text}`; only numeric literals are allowed"
                ),
            ));
        }
    };
    let decimal = !["0x", "0o", "0b"]
        .iter()
        .any(|prefix| text.starts_with(prefix));
    if suffix_free && decimal {
        Ok(Expr::Number { text, span })
    } else {
        Err(syn::Error::new(
            span,
            format!(
                "expected a plain decimal number, found `{text}`; write it without a type suffix or base prefix"
            ),
        ))
    }
}

/// The binary operator at the cursor, if any, with its span.
fn peek_operator(cursor: &Cursor) -> Option<(BinOp, Span)> {
    let Some(TokenTree::Punct(punct)) = cursor.peek() else {
        return None;
    };
    let op = match punct.as_char() {
        '+' => BinOp::Add,
        '-' => BinOp::Sub,
        '*' => BinOp::Mul,
        '/' => BinOp::Div,
        '^' => BinOp::Pow,
        _ => return None,
    };
    Some((op, punct.span()))
}

/// How tightly `op` binds its operands.
fn binding_power(op: BinOp) -> u8 {
    match op {
        BinOp::Add | BinOp::Sub => ADDITIVE,
        BinOp::Mul | BinOp::Div => MULTIPLICATIVE,
        BinOp::Pow => POWER,
    }
}

#[cfg(test)]
mod tests {
    use proc_macro2::{LineColumn, Span, TokenStream};

    use super::super::render::render;
    use super::*;

    /// A cursor over `source`, which must lex.
    fn cursor(source: &str) -> Cursor {
        let tokens: TokenStream = source.parse().expect("test source lexes");
        Cursor::new(tokens, Span::call_site())
    }

    /// `source` parsed as one whole expression, rendered.
    fn parsed(source: &str) -> String {
        let mut cursor = cursor(source);
        let expr = expression(&mut cursor).expect("test expression parses");
        assert!(cursor.is_end(), "`{source}` left {}", cursor.found());
        render(&expr)
    }

    /// The message and start of the first error parsing `source` gives.
    fn error(source: &str) -> (String, LineColumn) {
        let error = expression(&mut cursor(source)).expect_err("test expression fails");
        (error.to_string(), error.span().start())
    }

    /// Line 1, column `column` (0-based, as proc_macro2 counts).
    fn at(column: usize) -> LineColumn {
        LineColumn { line: 1, column }
    }

    #[test]
    fn a_dot_after_a_member_a_call_or_parentheses_is_reported_there() {
        for (source, column) in [
            ("N.x.y", 3),
            ("N.rotate_z(a).rotate_x(b)", 13),
            ("(N).x", 3),
        ] {
            let (message, start) = error(source);
            assert!(
                message.contains("a `.` follows only a frame's name"),
                "{message}"
            );
            assert_eq!(start, at(column), "{source}");
        }
    }

    #[test]
    fn unary_minus_binds_looser_than_power() {
        assert_eq!(parsed("-x^2"), "(-(x^2))");
        assert_eq!(parsed("-a*b"), "((-a) * b)");
        assert_eq!(parsed("- -a"), "(-(-a))");
    }

    #[test]
    fn additive_and_multiplicative_operators_group_to_the_left() {
        assert_eq!(parsed("a - b + c"), "((a - b) + c)");
        assert_eq!(parsed("a*b/c"), "((a * b) / c)");
        assert_eq!(parsed("a - b * c + d"), "((a - (b * c)) + d)");
    }

    #[test]
    fn power_groups_to_the_right_and_takes_a_negative_exponent() {
        assert_eq!(parsed("2^3^2"), "(2^(3^2))");
        assert_eq!(parsed("x^-2"), "(x^(-2))");
        assert_eq!(parsed("x^-2*y"), "((x^(-2)) * y)");
        assert_eq!(parsed("m*L^2/12"), "((m * (L^2)) / 12)");
    }

    #[test]
    fn members_scale_and_subtract() {
        assert_eq!(parsed("-L/2 * B1.y"), "(((-L) / 2) * B1.y)");
        assert_eq!(parsed("P1 - L/2 * B2.y"), "(P1 - ((L / 2) * B2.y))");
        assert_eq!(
            parsed("O + x * N.x + y * N.y"),
            "((O + (x * N.x)) + (y * N.y))"
        );
    }

    #[test]
    fn calls_arrays_and_parentheses() {
        assert_eq!(parsed("N.rotate_z(theta1)"), "N.rotate_z(theta1)");
        assert_eq!(parsed("l/2 * sin(theta)"), "((l / 2) * sin(theta))");
        assert_eq!(parsed("f()"), "f()");
        assert_eq!(parsed("atan2(y, x,)"), "atan2(y, x)");
        assert_eq!(parsed("[0, 0, m*L^2/12,]"), "[0, 0, ((m * (L^2)) / 12)]");
        assert_eq!(parsed("(a + b) * c"), "(((a + b)) * c)");
        assert_eq!(parsed("dt(q1)^2"), "(dt(q1)^2)");
    }

    #[test]
    fn an_invisible_group_reads_as_its_contents() {
        let fragment = Group::new(Delimiter::None, "a + b".parse().expect("lexes"));
        let mut tokens = TokenStream::from(TokenTree::Group(fragment));
        tokens.extend("* c".parse::<TokenStream>());
        let expr = expression(&mut Cursor::new(tokens, Span::call_site()));
        assert_eq!(
            expr.map(|expr| render(&expr)).ok(),
            Some("((a + b) * c)".into())
        );
    }

    #[test]
    fn numbers_keep_their_text() {
        assert_eq!(parsed("1e-3 * x"), "(1e-3 * x)");
        assert_eq!(parsed("2.50"), "2.50");
    }

    #[test]
    fn an_expression_stops_at_a_token_that_cannot_continue_it() {
        for (source, rest) in [
            ("F * N.x at P", "`at`"),
            ("x == 0", "`=`"),
            ("M * N.z on B", "`on`"),
            ("a, b", "`,`"),
        ] {
            let mut cursor = cursor(source);
            expression(&mut cursor).expect("test expression parses");
            assert_eq!(cursor.found(), rest, "{source}");
        }
    }

    #[test]
    fn spans_cover_the_whole_construct() {
        let mut cursor = cursor("2 * N.rotate_z(q)");
        let Ok(Expr::Binary { rhs, .. }) = expression(&mut cursor) else {
            panic!("expected a product");
        };
        let range = rhs.range();
        assert_eq!((range.start.start(), range.end.end()), (at(4), at(17)));
        let array = expression(&mut self::cursor(" [a, (b)]")).expect("array parses");
        let range = array.range();
        assert_eq!((range.start.start(), range.end.end()), (at(1), at(9)));
    }

    #[test]
    fn errors_say_what_was_found_and_what_is_expected() {
        let cases = [
            ("", "expected an expression, found end of input", 0),
            ("a + ;", "expected an expression, found `;`", 4),
            ("()", "expected an expression, found `)`", 1),
            ("(a b)", "expected an operator or `)`, found `b`", 3),
            ("f(a b)", "expected `,` or `)`, found `b`", 4),
            ("{a}", "expected an expression, found `{`", 0),
            (
                "x.",
                "expected a member name after `x.`, found end of input",
                0,
            ),
            ("x.1", "expected a member name after `x.`, found `1`", 2),
            (
                "+x",
                "expected an expression, found `+`; unary `+` is not supported: write the operand alone",
                0,
            ),
            (
                "2 * 2f64",
                "expected a plain decimal number, found `2f64`; write it without a type suffix or base prefix",
                4,
            ),
            (
                "0x10",
                "expected a plain decimal number, found `0x10`; write it without a type suffix or base prefix",
                0,
            ),
            (
                "\"s\"",
                "expected an expression, found `\"s\"`; only numeric literals are allowed",
                0,
            ),
        ];
        for (source, message, column) in cases {
            let (found, start) = error(source);
            assert_eq!(found, message, "{source}");
            if !source.is_empty() {
                assert_eq!(start, at(column), "{source}");
            }
        }
    }

    #[test]
    fn deep_nesting_is_an_error_not_a_stack_overflow() {
        let ok = format!("{}x{}", "(".repeat(100), ")".repeat(100));
        assert!(expression(&mut cursor(&ok)).is_ok());
        for deep in [
            format!("{}x{}", "(".repeat(1000), ")".repeat(1000)),
            format!("{}x", "-".repeat(1000)),
            format!("x{}", "^x".repeat(1000)),
            format!("{}x{}", "f(".repeat(1000), ")".repeat(1000)),
            format!("{}x{}", "[".repeat(1000), "]".repeat(1000)),
        ] {
            let (message, _) = error(&deep);
            assert_eq!(
                message,
                "expression nested too deeply (more than 256 levels)"
            );
        }
    }

    #[test]
    fn long_chains_are_an_error_not_a_stack_overflow() {
        let longest = format!("x{}", " + x".repeat(MAX_OPERATORS));
        assert!(expression(&mut cursor(&longest)).is_ok());
        let message = "expression too long (more than 2048 operators); split it into several \
                       statements (loads and potentials add up, points can be built from points)";
        let (found, start) = error(&format!("{longest} - x + x"));
        assert_eq!((found.as_str(), start), (message, at(longest.len() + 1)));
        let groups = format!("(x{})", " * x".repeat(100)).repeat(30);
        let (found, _) = error(&groups.replace(")(", ") + ("));
        assert_eq!(found, message);
    }
}
