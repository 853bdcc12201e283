//! The system and its statements: `/// docs`, `pub Name { statement; ... }`.
//!
//! A statement is recognised by its first identifier (see
//! [`keyword`](super::keyword)). After an error the parser skips to the
//! next `;` and goes on, so one run reports every error it can; a missing
//! `;` before a statement keyword resumes at that keyword.

use std::fmt::Display;

use proc_macro2::{Delimiter, Group, Ident, Literal, Span, TokenStream, TokenTree};
use syn::Lit;

use super::ast::{Expr, Field, OutputRequest, SpeedName, Statement, System};
use super::cursor::Cursor;
use super::expression::expression;
use super::keyword::{self, STATEMENTS};

/// Parses a whole system from the macro's tokens (or a `.dal` file
/// tokenised by proc_macro2): doc comments, optional `pub`, the name, and
/// the statements in braces. Every syntax error found is reported, combined
/// into one [`syn::Error`].
pub fn parse_system(input: TokenStream) -> syn::Result<System> {
    let mut cursor = Cursor::new(input, Span::call_site());
    let docs = doc_comments(&mut cursor)?;
    let public = cursor.eat_keyword(keyword::PUB).is_some();
    let name = cursor.expect_ident("the system's name")?;
    let Some(body) = cursor.eat_group(Delimiter::Brace) else {
        return Err(cursor.expected(format!("`{{` after the system's name `{name}`")));
    };
    let mut errors = Errors::default();
    let statements = statements(&mut Cursor::group(&body), &mut errors);
    if !cursor.is_end() {
        errors.push(trailing_tokens(&cursor));
    }
    errors.finish(System {
        docs,
        public,
        name,
        statements,
    })
}

/// The error at tokens after the system's closing brace: a second system
/// (doc comments, `pub`, a name and braces), which needs its own macro or
/// file, or anything else.
fn trailing_tokens(cursor: &Cursor) -> syn::Error {
    let mut ahead = cursor.clone();
    let second = match doc_comments(&mut ahead) {
        Ok(_) => {
            ahead.eat_keyword(keyword::PUB);
            ahead
                .eat_ident()
                .filter(|_| ahead.eat_group(Delimiter::Brace).is_some())
        }
        Err(_) => None,
    };
    match second {
        Some(name) => cursor.error(format!(
            "a second system `{name}`: a `dalembert!` or a `.dal` file holds one system; \
             give `{name}` its own"
        )),
        None => cursor.error(format!(
            "unexpected tokens after the system's closing brace, starting with {}",
            cursor.found()
        )),
    }
}

/// Spanned errors collected while parsing goes on.
#[derive(Default)]
struct Errors(Option<syn::Error>);

impl Errors {
    /// Adds `error` to those already found.
    fn push(&mut self, error: syn::Error) {
        match &mut self.0 {
            Some(errors) => errors.combine(error),
            None => self.0 = Some(error),
        }
    }

    /// `value` if no error was found, else every error found.
    fn finish<T>(self, value: T) -> syn::Result<T> {
        match self.0 {
            Some(errors) => Err(errors),
            None => Ok(value),
        }
    }
}

/// Parses `#[doc = "text"]` attributes, the form `///` comments take in a
/// token stream, and returns their texts.
fn doc_comments(cursor: &mut Cursor) -> syn::Result<Vec<String>> {
    let mut docs = Vec::new();
    while cursor.eat_punct('#').is_some() {
        let Some(attribute) = cursor.eat_group(Delimiter::Bracket) else {
            return Err(cursor.expected("`[` after `#` (only `///` doc comments are allowed)"));
        };
        docs.push(doc_text(&attribute)?);
    }
    Ok(docs)
}

/// The text of one `[doc = "text"]` attribute.
fn doc_text(attribute: &Group) -> syn::Result<String> {
    let mut cursor = Cursor::group(&meta_of(attribute));
    cursor.expect_keyword(
        keyword::DOC,
        "`doc` (the only attribute allowed is a `///` doc comment)",
    )?;
    cursor.expect_punct('=', "`=` after `doc`")?;
    let text = match cursor.peek() {
        Some(TokenTree::Literal(literal)) => string_value(literal.clone()),
        _ => None,
    }
    .ok_or_else(|| cursor.expected("a string after `doc =`"))?;
    cursor.next_token();
    if !cursor.is_end() {
        return Err(cursor.expected("`]` after the doc comment's text"));
    }
    Ok(text)
}

/// The attribute `[..]` itself, or the invisible group that is all its
/// contents: a doc comment that a `macro_rules!` passes on as a
/// `#[$doc:meta]` fragment arrives as `[⟦doc = "text"⟧]`.
fn meta_of(attribute: &Group) -> Group {
    let mut tokens = attribute.stream().into_iter();
    match (tokens.next(), tokens.next()) {
        (Some(TokenTree::Group(inner)), None) if inner.delimiter() == Delimiter::None => inner,
        _ => attribute.clone(),
    }
}

/// The value of `literal` if it is a string literal.
fn string_value(literal: Literal) -> Option<String> {
    match Lit::new(literal) {
        Lit::Str(string) => Some(string.value()),
        _ => None,
    }
}

/// Parses the statements inside the system's braces, adding each error to
/// `errors` and resuming after it.
fn statements(cursor: &mut Cursor, errors: &mut Errors) -> Vec<Statement> {
    let mut statements = Vec::new();
    loop {
        if let Err(error) = doc_comments(cursor) {
            errors.push(error);
            cursor.skip_past(';');
            continue;
        }
        if cursor.is_end() {
            return statements;
        }
        match statement(cursor) {
            Ok(statement) => {
                statements.push(statement);
                terminator(cursor, errors);
            }
            Err(error) => {
                errors.push(error);
                cursor.skip_past(';');
            }
        }
    }
}

/// Consumes the `;` that ends a statement. When it is missing, the parser
/// resumes at a following statement keyword, or else after the next `;`.
fn terminator(cursor: &mut Cursor, errors: &mut Errors) {
    if cursor.eat_punct(';').is_some() {
        return;
    }
    errors.push(cursor.expected("`;` after the statement"));
    let at_statement = cursor
        .peek_ident()
        .is_some_and(|ident| STATEMENTS.iter().any(|keyword| ident == keyword));
    if !at_statement {
        cursor.skip_past(';');
    }
}

/// Parses one statement, without its `;`.
fn statement(cursor: &mut Cursor) -> syn::Result<Statement> {
    let Some(keyword) = cursor.eat_ident() else {
        return Err(cursor.expected(format!(
            "a statement (one of {})",
            keyword::statement_list()
        )));
    };
    Ok(match keyword.to_string().as_str() {
        keyword::PARAMETERS => Statement::Parameters(names(cursor, &keyword)?),
        keyword::COORDINATES => Statement::Coordinates(names(cursor, &keyword)?),
        keyword::INPUTS => Statement::Inputs(names(cursor, &keyword)?),
        keyword::FRAME => {
            let (name, value) = definition(cursor, &keyword)?;
            Statement::Frame { name, value }
        }
        keyword::POINT => {
            let (name, value) = definition(cursor, &keyword)?;
            Statement::Point { name, value }
        }
        keyword::BODY => {
            let (name, fields) = named_fields(cursor, &keyword)?;
            Statement::Body { name, fields }
        }
        keyword::PARTICLE => {
            let (name, fields) = named_fields(cursor, &keyword)?;
            Statement::Particle { name, fields }
        }
        keyword::JOINT => {
            let kind = cursor.expect_ident(
                "the joint's kind (`revolute`, `prismatic`, `spherical` or `free`)",
            )?;
            let (name, fields) = named_fields(cursor, &keyword)?;
            Statement::Joint { kind, name, fields }
        }
        keyword::GRAVITY => Statement::Gravity {
            value: expression(cursor)?,
        },
        keyword::FORCE => {
            let value = expression(cursor)?;
            cursor.expect_keyword(keyword::AT, "`at` and a point after the force")?;
            let at = expression(cursor)?;
            Statement::Force { value, at }
        }
        keyword::TORQUE => torque(cursor)?,
        keyword::POTENTIAL => Statement::Potential {
            value: expression(cursor)?,
        },
        keyword::DISSIPATION => Statement::Dissipation {
            value: expression(cursor)?,
        },
        keyword::ARMATURE => {
            let value = expression(cursor)?;
            cursor.expect_keyword(keyword::ON, "`on` and a speed after the armature")?;
            let speed = expression(cursor)?;
            Statement::Armature { value, speed }
        }
        keyword::CONSTRAINT => constraint(cursor, keyword)?,
        keyword::CLOSURE => {
            let (name, fields) = named_fields(cursor, &keyword)?;
            Statement::Closure { name, fields }
        }
        keyword::ROLLING => {
            let (name, fields) = named_fields(cursor, &keyword)?;
            Statement::Rolling { name, fields }
        }
        keyword::OUTPUTS => Statement::Outputs(outputs(cursor)?),
        keyword::SPEEDS => {
            let names = names(cursor, &keyword)?;
            let Some(block) = cursor.eat_group(Delimiter::Brace) else {
                return Err(
                    cursor.expected("`{` with each coordinate's rate in the new speeds, `q: rate`")
                );
            };
            Statement::Speeds {
                keyword,
                names,
                rates: fields(&block)?,
            }
        }
        _ => {
            return Err(syn::Error::new(
                keyword.span(),
                format!(
                    "unknown statement `{keyword}`; expected one of {}",
                    keyword::statement_list()
                ),
            ));
        }
    })
}

/// Parses `a, b, ...` after `parameters`, `coordinates` or `inputs`; a
/// trailing comma is allowed.
fn names(cursor: &mut Cursor, keyword: &Ident) -> syn::Result<Vec<Ident>> {
    let mut names = vec![cursor.expect_ident(format!("a name after `{keyword}`"))?];
    while cursor.eat_punct(',').is_some() {
        match cursor.eat_ident() {
            Some(name) => names.push(name),
            None => break,
        }
    }
    Ok(names)
}

/// Parses `NAME = <expr>` after `frame` or `point`.
fn definition(cursor: &mut Cursor, keyword: &Ident) -> syn::Result<(Ident, Expr)> {
    let name = cursor.expect_ident(format!("the {keyword}'s name after `{keyword}`"))?;
    cursor.expect_punct('=', format!("`=` after `{keyword} {name}`"))?;
    Ok((name, expression(cursor)?))
}

/// Parses `NAME { field: value, ... }` after `body`, `particle`,
/// `joint KIND` or `closure`.
fn named_fields(cursor: &mut Cursor, keyword: &Ident) -> syn::Result<(Ident, Vec<Field>)> {
    let name = cursor.expect_ident(format!("the {keyword}'s name"))?;
    let Some(block) = cursor.eat_group(Delimiter::Brace) else {
        return Err(cursor.expected(format!("`{{` with the fields of `{name}`")));
    };
    Ok((name, fields(&block)?))
}

/// Parses `field: value, ...` inside braces; a trailing comma is allowed.
/// After an error it resumes at the next field.
fn fields(block: &Group) -> syn::Result<Vec<Field>> {
    let mut cursor = Cursor::group(block);
    let mut errors = Errors::default();
    let mut fields = Vec::new();
    while !cursor.is_end() {
        match field(&mut cursor) {
            Ok(field) => fields.push(field),
            Err(error) => {
                errors.push(error);
                cursor.skip_past(',');
            }
        }
    }
    errors.finish(fields)
}

/// Parses one `name: value` and the `,` after it (unless it is the last).
fn field(cursor: &mut Cursor) -> syn::Result<Field> {
    let name = cursor.expect_ident("a field name")?;
    cursor.expect_punct(':', format!("`:` after the field name `{name}`"))?;
    let value = expression(cursor)?;
    if cursor.eat_punct(',').is_none() && !cursor.is_end() {
        return Err(cursor.expected("`,` or `}` after the field's value"));
    }
    Ok(Field { name, value })
}

/// Parses `<vec> on F` or `<vec> on F reacting G` after `torque`.
fn torque(cursor: &mut Cursor) -> syn::Result<Statement> {
    let value = expression(cursor)?;
    cursor.expect_keyword(keyword::ON, "`on` and a frame after the torque")?;
    let on = expression(cursor)?;
    let reacting = match cursor.eat_keyword(keyword::REACTING) {
        Some(_) => Some(expression(cursor)?),
        None => None,
    };
    Ok(Statement::Torque {
        value,
        on,
        reacting,
    })
}

/// Parses `lhs == rhs` after `constraint`.
fn constraint(cursor: &mut Cursor, keyword: Ident) -> syn::Result<Statement> {
    let lhs = expression(cursor)?;
    cursor
        .eat_double_equals()
        .ok_or_else(|| cursor.expected("`==` in a constraint"))?;
    let rhs = expression(cursor)?;
    Ok(Statement::Constraint { keyword, lhs, rhs })
}

/// Parses `name, name(P), name(P in F), ...` after `outputs`; a trailing
/// comma is allowed.
fn outputs(cursor: &mut Cursor) -> syn::Result<Vec<OutputRequest>> {
    let mut requests = vec![output(cursor)?];
    while cursor.eat_punct(',').is_some() {
        if cursor.peek_ident().is_none() {
            break;
        }
        requests.push(output(cursor)?);
    }
    Ok(requests)
}

/// Parses one `name`, `name(P)`, `name(P in F)` or `name(a, b, ..)`.
fn output(cursor: &mut Cursor) -> syn::Result<OutputRequest> {
    let name =
        cursor.expect_ident("the name of an output (`inverse_dynamics`, `position(P)`, ...)")?;
    let Some(group) = cursor.eat_group(Delimiter::Parenthesis) else {
        return Ok(OutputRequest {
            name,
            of: None,
            more: Vec::new(),
            speeds: Vec::new(),
            axes: None,
        });
    };
    let mut inside = Cursor::group(&group);
    let of = argument(
        &mut inside,
        format!("a point, frame or coordinate in `{name}(..)`"),
    )?;
    let mut more = Vec::new();
    while inside.eat_punct(',').is_some() {
        more.push(argument(&mut inside, "a coordinate after `,`")?);
    }
    let mut speeds = Vec::new();
    if inside.eat_punct(';').is_some() {
        speeds.push(speed_name(&mut inside)?);
        while inside.eat_punct(',').is_some() {
            speeds.push(speed_name(&mut inside)?);
        }
    }
    let axes = match inside.eat_keyword(keyword::IN) {
        Some(_) => Some(inside.expect_ident("a frame after `in`")?),
        None => None,
    };
    if !inside.is_end() {
        return Err(inside.expected(format!("`)` after `{name}({of}`, or `in` and a frame")));
    }
    Ok(OutputRequest {
        name,
        of: Some(of),
        more,
        speeds,
        axes,
    })
}

/// Parses one point, frame or coordinate of an output's parentheses; a
/// speed `dt(q)` there is an error at `dt` saying where speeds go.
fn argument(cursor: &mut Cursor, expected: impl Display) -> syn::Result<Ident> {
    let name = cursor.expect_ident(expected)?;
    let is_group = |token: Option<&TokenTree>| matches!(token, Some(TokenTree::Group(group)) if group.delimiter() == Delimiter::Parenthesis);
    if name == keyword::DT && is_group(cursor.peek()) {
        return Err(syn::Error::new(
            name.span(),
            "`dt(..)` is a speed, where a point, frame or coordinate is expected: \
             `linearize(..)` names its independent coordinates, then its independent \
             speeds after `;`, as `linearize(x, theta; dt(theta))`",
        ));
    }
    Ok(name)
}

/// Parses one speed of `linearize(..; ..)`: `dt(q)` or a speed's name.
fn speed_name(cursor: &mut Cursor) -> syn::Result<SpeedName> {
    let name = cursor.expect_ident("a speed, `dt(q)` or its name, after `;` or `,`")?;
    if name != keyword::DT {
        return Ok(SpeedName { name, rate: false });
    }
    let group = cursor
        .eat_group(Delimiter::Parenthesis)
        .ok_or_else(|| cursor.expected("`(` and a coordinate after `dt`"))?;
    let mut inside = Cursor::group(&group);
    let name = inside.expect_ident("a coordinate in `dt(..)`")?;
    if !inside.is_end() {
        return Err(inside.expected("`)` after the coordinate in `dt(..)`"));
    }
    Ok(SpeedName { name, rate: true })
}

#[cfg(test)]
mod tests {
    use proc_macro2::{LineColumn, TokenStream};

    use super::super::render::render;
    use super::*;
    use crate::seeds::{CONSTRAINED_PENDULUM, DOUBLE_PENDULUM, ROTATING_BAR};

    /// `source` lexed and parsed.
    fn parse(source: &str) -> syn::Result<System> {
        parse_system(source.parse().expect("test source lexes"))
    }

    /// `source` parsed successfully.
    fn system(source: &str) -> System {
        parse(source).expect("test system parses")
    }

    /// Every error parsing `source` gives: message, line and column
    /// (1-based line, 0-based column, as proc_macro2 counts).
    fn errors(source: &str) -> Vec<(String, usize, usize)> {
        let error = parse(source).expect_err("test system fails");
        error
            .into_iter()
            .map(|error| {
                let LineColumn { line, column } = error.span().start();
                (error.to_string(), line, column)
            })
            .collect()
    }

    /// The names of `fields`, in order.
    fn field_names(fields: &[Field]) -> Vec<String> {
        fields.iter().map(|field| field.name.to_string()).collect()
    }

    /// A doc comment passed on by a `macro_rules!` as `#[$doc:meta]` is an
    /// invisible group inside the brackets; it reads as the comment.
    #[test]
    fn a_doc_comment_from_a_meta_fragment_is_read() {
        let meta = Group::new(
            Delimiter::None,
            r#"doc = " Forwarded.""#.parse().expect("lexes"),
        );
        let attribute = Group::new(Delimiter::Bracket, TokenTree::Group(meta).into());
        let mut tokens: TokenStream = "#".parse().expect("lexes");
        tokens.extend([TokenTree::Group(attribute)]);
        tokens.extend("pub S { }".parse::<TokenStream>());
        let system = parse_system(tokens).expect("parses");
        assert_eq!(system.docs, [" Forwarded."]);
    }

    #[test]
    fn parses_seed_example_1() {
        let system = system(DOUBLE_PENDULUM);
        assert_eq!(
            system.docs,
            [" Seed example 1: double pendulum, absolute angles from the downward vertical."]
        );
        assert!(system.public);
        assert_eq!(system.name, "DoublePendulum");
        assert_eq!(system.statements.len(), 10);
        let Statement::Parameters(parameters) = &system.statements[0] else {
            panic!("expected parameters first");
        };
        assert_eq!(parameters.len(), 3);
        let Statement::Frame { name, value } = &system.statements[2] else {
            panic!("expected a frame third");
        };
        assert_eq!(name, "B1");
        let Expr::MethodCall {
            receiver,
            method,
            args,
            ..
        } = value
        else {
            panic!("expected a method call, found {}", render(value));
        };
        assert_eq!([receiver, method].map(Ident::to_string), ["N", "rotate_z"]);
        assert_eq!(args.iter().map(render).collect::<Vec<_>>(), ["theta1"]);
        let Statement::Point { value, .. } = &system.statements[6] else {
            panic!("expected a point seventh");
        };
        assert_eq!(render(value), "(P1 - ((L / 2) * B2.y))");
        let Statement::Body { name, fields } = &system.statements[7] else {
            panic!("expected a body eighth");
        };
        assert_eq!(name, "link1");
        assert_eq!(field_names(fields), ["mass", "center", "frame", "inertia"]);
        assert_eq!(render(&fields[3].value), "[0, 0, ((m * (L^2)) / 12)]");
        let Statement::Gravity { value, .. } = &system.statements[9] else {
            panic!("expected gravity last");
        };
        assert_eq!(render(value), "((-g) * N.y)");
    }

    #[test]
    fn parses_seed_example_2() {
        let system = system(ROTATING_BAR);
        assert_eq!(system.docs.len(), 1);
        assert_eq!(system.statements.len(), 9);
        let Statement::Inputs(inputs) = &system.statements[2] else {
            panic!("expected inputs third");
        };
        assert_eq!(inputs, &["M_phi", "M_theta"]);
        let Statement::Torque {
            value,
            on,
            reacting: Some(reacting),
            ..
        } = &system.statements[8]
        else {
            panic!("expected a reacting torque last");
        };
        assert_eq!(
            [value, on, reacting].map(render),
            ["(M_theta * F.y)", "B", "F"]
        );
        assert!(matches!(
            &system.statements[7],
            Statement::Torque { reacting: None, .. }
        ));
    }

    #[test]
    fn parses_seed_example_3() {
        let system = system(CONSTRAINED_PENDULUM);
        assert_eq!(system.statements.len(), 10);
        let Statement::Constraint { lhs, rhs, .. } = &system.statements[8] else {
            panic!("expected a constraint");
        };
        assert_eq!(render(lhs), "(x - ((l / 2) * sin(theta)))");
        assert_eq!(render(rhs), "0");
    }

    #[test]
    fn parses_the_other_statements() {
        let system = system(
            "S {
                /// Ignored.
                parameters k, c, m,;
                particle p { mass: m, at: P, };
                joint revolute J1 { parent: N, child: B1, axis: z, coordinate: q1, at: O };
                force F * N.x at P;
                potential k * q1^2 / 2;
                dissipation c * dt(q1)^2 / 2;
            }",
        );
        assert!(!system.public);
        assert_eq!(system.statements.len(), 6);
        assert!(matches!(&system.statements[0], Statement::Parameters(names) if names.len() == 3));
        let Statement::Particle { fields, .. } = &system.statements[1] else {
            panic!("expected a particle");
        };
        assert_eq!(field_names(fields), ["mass", "at"]);
        let Statement::Joint { kind, name, fields } = &system.statements[2] else {
            panic!("expected a joint");
        };
        assert_eq!([kind, name].map(Ident::to_string), ["revolute", "J1"]);
        assert_eq!(
            field_names(fields),
            ["parent", "child", "axis", "coordinate", "at"]
        );
        let Statement::Force { value, at, .. } = &system.statements[3] else {
            panic!("expected a force");
        };
        assert_eq!([value, at].map(render), ["(F * N.x)", "P"]);
        assert!(matches!(&system.statements[4], Statement::Potential { .. }));
        assert!(matches!(
            &system.statements[5],
            Statement::Dissipation { .. }
        ));
    }

    #[test]
    fn every_statement_keyword_is_recognised() {
        for keyword in STATEMENTS {
            for (message, ..) in errors(&format!("S {{ {keyword} }}")) {
                assert!(
                    !message.starts_with("unknown statement"),
                    "{keyword}: {message}"
                );
            }
        }
    }

    #[test]
    fn a_missing_semicolon_points_at_the_next_token_and_parsing_goes_on() {
        let source = "S {
    frame B = N.rotate_z(q)
    frame C = B.rotate_x(q);
    point P = ;
}";
        assert_eq!(
            errors(source),
            [
                (
                    "expected `;` after the statement, found `frame`".to_owned(),
                    3,
                    4
                ),
                ("expected an expression, found `;`".to_owned(), 4, 14),
            ]
        );
    }

    #[test]
    fn an_unknown_statement_lists_the_keywords() {
        assert_eq!(
            errors("S {\n  bodyy b { mass: m };\n}"),
            [(
                "unknown statement `bodyy`; expected one of `parameters`, `coordinates`, \
                 `inputs`, `frame`, `point`, `body`, `particle`, `joint`, `gravity`, \
                 `force`, `torque`, `potential`, `dissipation`, `constraint`, `closure`, \
                 `rolling`, `outputs`, `speeds`, `armature`"
                    .to_owned(),
                2,
                2
            )]
        );
        let (message, line, column) = &errors("S { ; }")[0];
        assert!(message.starts_with("expected a statement (one of `parameters`"));
        assert!(message.ends_with("), found `;`"));
        assert_eq!((line, column), (&1, &4));
    }

    #[test]
    fn statement_errors_point_at_the_offending_token() {
        let cases = [
            (
                "S { constraint x = 0; }",
                "expected `==` in a constraint, found `=`",
                17,
            ),
            (
                "S { constraint x 0; }",
                "expected `==` in a constraint, found `0`",
                17,
            ),
            ("S { gravity ; }", "expected an expression, found `;`", 12),
            (
                "S { force F P; }",
                "expected `at` and a point after the force, found `P`",
                12,
            ),
            (
                "S { torque T at B; }",
                "expected `on` and a frame after the torque, found `at`",
                13,
            ),
            (
                "S { frame = x; }",
                "expected the frame's name after `frame`, found `=`",
                10,
            ),
            (
                "S { point P O; }",
                "expected `=` after `point P`, found `O`",
                12,
            ),
            (
                "S { parameters ; }",
                "expected a name after `parameters`, found `;`",
                15,
            ),
            (
                "S { parameters a b; }",
                "expected `;` after the statement, found `b`",
                17,
            ),
            (
                "S { frame B = (a + b c); }",
                "expected an operator or `)`, found `c`",
                21,
            ),
            (
                "S { body { mass: m }; }",
                "expected the body's name, found `{`",
                9,
            ),
            (
                "S { body b [mass: m]; }",
                "expected `{` with the fields of `b`, found `[`",
                11,
            ),
            (
                "S { joint { }; }",
                "expected the joint's kind (`revolute`, `prismatic`, `spherical` or `free`), found `{`",
                10,
            ),
            (
                "S { body b { } }",
                "expected `;` after the statement, found `}`",
                15,
            ),
            (
                "S { body b { mass: m center: G }; }",
                "expected `,` or `}` after the field's value, found `center`",
                21,
            ),
            (
                "S { #[allow(x)] gravity g; }",
                "expected `doc` (the only attribute allowed is a `///` doc comment), found `allow`",
                6,
            ),
            (
                "pub S { } extra",
                "unexpected tokens after the system's closing brace, starting with `extra`",
                10,
            ),
            (
                "pub S { } /// T.\npub T { }",
                "a second system `T`: a `dalembert!` or a `.dal` file holds one system; \
                 give `T` its own",
                10,
            ),
            (
                "pub S { } T { }",
                "a second system `T`: a `dalembert!` or a `.dal` file holds one system; \
                 give `T` its own",
                10,
            ),
            (
                "pub S;",
                "expected `{` after the system's name `S`, found `;`",
                5,
            ),
            ("pub { }", "expected the system's name, found `{`", 4),
            (
                "#[doc = 1] S { }",
                "expected a string after `doc =`, found `1`",
                8,
            ),
            (
                "# S { }",
                "expected `[` after `#` (only `///` doc comments are allowed), found `S`",
                2,
            ),
        ];
        for (source, message, column) in cases {
            assert_eq!(
                errors(source),
                [(message.to_owned(), 1, column)],
                "{source}"
            );
        }
        assert_eq!(
            errors("")[0].0,
            "expected the system's name, found end of input"
        );
    }

    #[test]
    fn every_error_is_reported() {
        let source = "S {
    body b { mass m, center G };
    frame B = ;
    constraint x = 0;
} trailing";
        assert_eq!(
            errors(source),
            [
                (
                    "expected `:` after the field name `mass`, found `m`".to_owned(),
                    2,
                    18
                ),
                (
                    "expected `:` after the field name `center`, found `G`".to_owned(),
                    2,
                    28
                ),
                ("expected an expression, found `;`".to_owned(), 3, 14),
                ("expected `==` in a constraint, found `=`".to_owned(), 4, 17),
                (
                    "unexpected tokens after the system's closing brace, starting with `trailing`"
                        .to_owned(),
                    5,
                    2
                ),
            ]
        );
    }

    #[test]
    fn garbage_never_panics() {
        let mut inputs: Vec<String> = Vec::new();
        for source in [DOUBLE_PENDULUM, ROTATING_BAR, CONSTRAINED_PENDULUM] {
            inputs.extend(
                source
                    .char_indices()
                    .map(|(end, _)| source[..end].to_owned()),
            );
        }
        // Shuffled sequences of the language's tokens, from a fixed-seed
        // linear congruential generator so that every run tries the same.
        let vocabulary = [
            "pub",
            "S",
            "{",
            "}",
            "(",
            ")",
            "[",
            "]",
            ";",
            ",",
            ":",
            "=",
            "==",
            "-",
            "+",
            "*",
            "/",
            "^",
            ".",
            "#",
            "frame",
            "point",
            "body",
            "joint",
            "torque",
            "force",
            "constraint",
            "parameters",
            "at",
            "on",
            "reacting",
            "N",
            "rotate_z",
            "x",
            "1e-3",
            "2",
            "\"doc\"",
            "doc",
            "///x\n",
            "'c'",
        ];
        let mut state: u64 = 0x2545_f491_4f6c_dd1d;
        let mut random = |bound: usize| {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            usize::try_from(state >> 33).unwrap_or(0) % bound
        };
        for _ in 0..3000 {
            let length = random(40);
            let body: Vec<&str> = (0..length)
                .map(|_| vocabulary[random(vocabulary.len())])
                .collect();
            inputs.push(body.join(" "));
            inputs.push(format!("pub S {{ {} }}", body.join(" ")));
        }
        let mut parsed = 0;
        for input in &inputs {
            if let Ok(tokens) = input.parse::<TokenStream>() {
                let _ = parse_system(tokens);
                parsed += 1;
            }
        }
        assert!(parsed > 1000, "only {parsed} inputs lexed");
    }

    #[test]
    fn parses_outputs_with_subjects_and_axes() {
        let system = system(
            "S { coordinates q; outputs inverse_dynamics, position(P), velocity(P in B),; }",
        );
        let Statement::Outputs(requests) = &system.statements[1] else {
            panic!("expected outputs second");
        };
        let written: Vec<(String, Option<String>, Option<String>)> = requests
            .iter()
            .map(|r| {
                (
                    r.name.to_string(),
                    r.of.as_ref().map(Ident::to_string),
                    r.axes.as_ref().map(Ident::to_string),
                )
            })
            .collect();
        let owned = |s: &str| Some(s.to_owned());
        assert_eq!(
            written,
            [
                ("inverse_dynamics".to_owned(), None, None),
                ("position".to_owned(), owned("P"), None),
                ("velocity".to_owned(), owned("P"), owned("B")),
            ]
        );
    }

    #[test]
    fn a_malformed_output_is_reported_at_its_token() {
        assert_eq!(
            errors("S {\n  outputs position(P B);\n  outputs 3;\n}"),
            [
                (
                    "expected `)` after `position(P`, or `in` and a frame, found `B`".to_owned(),
                    2,
                    21
                ),
                (
                    "expected the name of an output (`inverse_dynamics`, `position(P)`, ...), \
                     found `3`"
                        .to_owned(),
                    3,
                    10
                ),
            ]
        );
    }
}
