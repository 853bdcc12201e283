//! Test-only: renders an expression fully parenthesised, so that tests can
//! state the tree a parse should give as a string (`-x^2` → `(-(x^2))`).

use super::ast::{BinOp, Expr};

/// `expr` with every operation in parentheses; `^` is written without
/// spaces, the other operators with one on each side.
pub fn render(expr: &Expr) -> String {
    match expr {
        Expr::Number { text, .. } => text.clone(),
        Expr::Name(name) => name.to_string(),
        Expr::Member { base, member } => format!("{base}.{member}"),
        Expr::Call { func, args, .. } => format!("{func}({})", list(args)),
        Expr::MethodCall {
            receiver,
            method,
            args,
            ..
        } => format!("{receiver}.{method}({})", list(args)),
        Expr::Array { items, .. } => format!("[{}]", list(items)),
        Expr::Neg { operand, .. } => format!("(-{})", render(operand)),
        Expr::Binary { op, lhs, rhs, .. } => {
            let (lhs, rhs) = (render(lhs), render(rhs));
            match op {
                BinOp::Add => format!("({lhs} + {rhs})"),
                BinOp::Sub => format!("({lhs} - {rhs})"),
                BinOp::Mul => format!("({lhs} * {rhs})"),
                BinOp::Div => format!("({lhs} / {rhs})"),
                BinOp::Pow => format!("({lhs}^{rhs})"),
            }
        }
        Expr::Paren { inner, .. } => format!("({})", render(inner)),
    }
}

/// The items rendered and separated by `, `.
fn list(items: &[Expr]) -> String {
    items.iter().map(render).collect::<Vec<_>>().join(", ")
}
