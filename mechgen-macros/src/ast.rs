//! The declaration as written: `syn` parsing, no meaning attached yet.
//!
//! ```text
//! mechanism! {
//!     /// docs
//!     pub struct FourBar {
//!         params: pub l1, pub l2, pub l3, pub l4, pub gamma: angle;
//!         input: theta2: angle;
//!         unknowns: theta3: angle, theta4: angle;
//!         loop: l2 @ theta2 + l3 @ theta3 - l4 @ theta4 - l1 @ 0;
//!         point coupler = l2 @ theta2 + a @ (theta3 + gamma);
//!         generate: position, velocity, acceleration;
//!         scene trace: coupler, coupler_dot;
//!     }
//! }
//! ```

use std::cell::Cell;

use proc_macro2::Span;
use syn::parse::{Parse, ParseStream};
use syn::punctuated::Punctuated;
use syn::{Attribute, Ident, Token, Visibility, braced};

/// The whole macro input.
pub struct Declaration {
    pub attrs: Vec<Attribute>,
    pub vis: Visibility,
    pub name: Ident,
    pub sections: Vec<Section>,
}

/// One `keyword: ...;` statement inside the braces.
pub enum Section {
    Params(Ident, Vec<SymbolDecl>),
    Input(Ident, Vec<SymbolDecl>),
    Unknowns(Ident, Vec<SymbolDecl>),
    Loop(VectorSum),
    Point(Vec<Attribute>, Ident, VectorSum),
    Generate(Ident, Vec<Ident>),
    /// `scene name: output, output_dot, ...;`, with doc attributes.
    Scene(Vec<Attribute>, Ident, Vec<Ident>),
}

/// `name` or `name: kind`, with doc attributes and, for a parameter, a visibility.
pub struct SymbolDecl {
    pub attrs: Vec<Attribute>,
    pub vis: Visibility,
    pub name: Ident,
    pub kind: Option<Ident>,
}

/// `± magnitude @ angle ± ...`
pub struct VectorSum {
    pub terms: Vec<VectorTerm>,
}

/// `± magnitude @ angle`: the polar vector `magnitude·e^{i·angle}`, possibly negated.
pub struct VectorTerm {
    pub negated: bool,
    pub magnitude: Scalar,
    pub angle: Scalar,
}

/// A scalar expression over declared names and numbers.
pub enum Scalar {
    Name(Ident),
    Number(f64, Span),
    /// `90 deg`: an angle written in degrees (the number as written).
    Degrees(f64, Span),
    Neg(Span, Box<Scalar>),
    Binary(BinaryOp, Span, Box<Scalar>, Box<Scalar>),
    /// `sqrt(21.25)`, `atan2(1, 4.5)`: one of [`FUNCTIONS`] of numbers, evaluated at compile
    /// time; the span is the closing parenthesis's.
    Call(Ident, Vec<Scalar>, Span),
    /// `(inner)`: kept so that messages and docs show the expression as it was written.
    Paren(Box<Scalar>),
}

/// The functions a declaration may apply to numbers, with how many arguments each takes.
pub const FUNCTIONS: [(&str, usize); 6] = [
    ("sqrt", 1),
    ("sin", 1),
    ("cos", 1),
    ("tan", 1),
    ("atan2", 2),
    ("hypot", 2),
];

#[derive(Clone, Copy, PartialEq, Eq)]
pub enum BinaryOp {
    Add,
    Sub,
    Mul,
    Div,
}

impl Scalar {
    /// The span of the expression's first token.
    pub fn span(&self) -> Span {
        match self {
            Scalar::Name(name) => name.span(),
            Scalar::Number(_, span) | Scalar::Degrees(_, span) | Scalar::Neg(span, _) => *span,
            Scalar::Binary(_, _, left, _) => left.span(),
            Scalar::Call(function, ..) => function.span(),
            Scalar::Paren(inner) => inner.span(),
        }
    }

    /// The numbers written without a unit, each with its span, left to right.
    pub fn numbers(&self) -> Box<dyn Iterator<Item = (f64, Span)> + '_> {
        match self {
            Scalar::Number(value, span) => Box::new(std::iter::once((*value, *span))),
            // A function's value is computed, in radians where it is an angle.
            Scalar::Name(_) | Scalar::Degrees(..) | Scalar::Call(..) => {
                Box::new(std::iter::empty())
            }
            Scalar::Neg(_, inner) | Scalar::Paren(inner) => inner.numbers(),
            Scalar::Binary(_, _, left, right) => Box::new(left.numbers().chain(right.numbers())),
        }
    }

    /// The names it mentions, left to right (`pi` among them).
    pub fn names(&self) -> Box<dyn Iterator<Item = &Ident> + '_> {
        match self {
            Scalar::Name(name) => Box::new(std::iter::once(name)),
            Scalar::Number(..) | Scalar::Degrees(..) => Box::new(std::iter::empty()),
            Scalar::Neg(_, inner) | Scalar::Paren(inner) => inner.names(),
            Scalar::Binary(_, _, left, right) => Box::new(left.names().chain(right.names())),
            Scalar::Call(_, arguments, _) => Box::new(arguments.iter().flat_map(Scalar::names)),
        }
    }

    /// The span of the expression's last token.
    pub fn last_span(&self) -> Span {
        match self {
            Scalar::Name(name) => name.span(),
            Scalar::Number(_, span) | Scalar::Degrees(_, span) => *span,
            Scalar::Neg(_, inner) | Scalar::Binary(_, _, _, inner) | Scalar::Paren(inner) => {
                inner.last_span()
            }
            Scalar::Call(_, _, close) => *close,
        }
    }

    /// An error underlining the whole expression. (`Span::join` is unavailable on stable, but
    /// `syn::Error::new_spanned` spans from a stream's first token to its last.)
    pub fn error(&self, message: impl std::fmt::Display) -> syn::Error {
        let first = proc_macro2::Ident::new("first", self.span());
        let last = proc_macro2::Ident::new("last", self.last_span());
        syn::Error::new_spanned(quote::quote!(#first #last), message)
    }
}

const SECTIONS: &str = "`params`, `input`, `unknowns`, `loop`, `point`, `generate` or `scene`";

impl Parse for Declaration {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        let attrs = input.call(Attribute::parse_outer)?;
        let vis = input.parse()?;
        input.parse::<Token![struct]>()?;
        let name = input.parse()?;
        let body;
        braced!(body in input);
        let mut sections = Vec::new();
        while !body.is_empty() {
            sections.push(body.parse()?);
        }
        Ok(Declaration {
            attrs,
            vis,
            name,
            sections,
        })
    }
}

impl Parse for Section {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        let attrs = input.call(Attribute::parse_outer)?;
        let documented = input
            .fork()
            .parse::<Ident>()
            .is_ok_and(|i| i == "point" || i == "scene");
        if let (Some(attr), false) = (attrs.first(), documented) {
            return Err(syn::Error::new_spanned(
                attr,
                "doc comments and attributes go on points, scenes and declared names, not on \
                 other sections",
            ));
        }
        if input.peek(Token![loop]) {
            input.parse::<Token![loop]>()?;
            input.parse::<Token![:]>()?;
            let sum = input.parse()?;
            input.parse::<Token![;]>()?;
            return Ok(Section::Loop(sum));
        }
        let keyword: Ident = input
            .parse()
            .map_err(|e| syn::Error::new(e.span(), format!("expected {SECTIONS}")))?;
        let section = match keyword.to_string().as_str() {
            "params" => Section::Params(keyword, parse_symbol_list(input)?),
            "input" => Section::Input(keyword, parse_symbol_list(input)?),
            "unknowns" => Section::Unknowns(keyword, parse_symbol_list(input)?),
            "point" => {
                let name = input.parse()?;
                input.parse::<Token![=]>()?;
                Section::Point(attrs, name, input.parse()?)
            }
            "generate" => {
                input.parse::<Token![:]>()?;
                let outputs = Punctuated::<Ident, Token![,]>::parse_separated_nonempty(input)?;
                Section::Generate(keyword, outputs.into_iter().collect())
            }
            "scene" => {
                let name = input.parse()?;
                input.parse::<Token![:]>()?;
                let outputs = Punctuated::<Ident, Token![,]>::parse_separated_nonempty(input)?;
                Section::Scene(attrs, name, outputs.into_iter().collect())
            }
            _ => {
                return Err(syn::Error::new(
                    keyword.span(),
                    format!("unknown section `{keyword}`: expected {SECTIONS}"),
                ));
            }
        };
        input.parse::<Token![;]>()?;
        Ok(section)
    }
}

fn parse_symbol_list(input: ParseStream) -> syn::Result<Vec<SymbolDecl>> {
    input.parse::<Token![:]>()?;
    let list = Punctuated::<SymbolDecl, Token![,]>::parse_separated_nonempty(input)?;
    Ok(list.into_iter().collect())
}

impl Parse for SymbolDecl {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        let attrs = input.call(Attribute::parse_outer)?;
        let vis = input.parse()?;
        let name = input.parse()?;
        let kind = if input.peek(Token![:]) {
            input.parse::<Token![:]>()?;
            Some(input.parse()?)
        } else {
            None
        };
        Ok(SymbolDecl {
            attrs,
            vis,
            name,
            kind,
        })
    }
}

/// The most vectors a loop or a point may sum, the deepest an expression may nest
/// (parentheses, calls and unary minus) and the most names, numbers and operators it may
/// hold. The passes after parsing recurse through a loop's sum and an expression's tree:
/// beyond these, a compile error on the token past the limit, where a declaration with
/// thousands would run the compiler out of stack. Real mechanisms are far inside them.
const MAX_TERMS: usize = 256;
const MAX_NESTING: usize = 32;
const MAX_NODES: usize = 256;

thread_local! {
    /// The nesting depth and node count of the magnitude or angle being parsed.
    static EXPRESSION: Cell<(usize, usize)> = const { Cell::new((0, 0)) };
}

/// A whole magnitude or angle (`unary (('*' | '/') unary)*`), its size checked against the
/// limits above.
fn parse_expression(input: ParseStream) -> syn::Result<Scalar> {
    EXPRESSION.with(|e| e.set((0, 0)));
    parse_product(input)
}

/// One more name, number or operator of the expression, at `span`.
fn count_node(span: Span) -> syn::Result<()> {
    let (depth, nodes) = EXPRESSION.with(Cell::get);
    if nodes >= MAX_NODES {
        return Err(syn::Error::new(
            span,
            format!(
                "this expression is too long: a magnitude or an angle holds at most \
                 {MAX_NODES} names, numbers and operators"
            ),
        ));
    }
    EXPRESSION.with(|e| e.set((depth, nodes + 1)));
    Ok(())
}

/// `parse` one level deeper, in parentheses, a call's arguments or after a unary minus, at
/// `span`.
fn nested<R>(span: Span, parse: impl FnOnce() -> syn::Result<R>) -> syn::Result<R> {
    let (depth, nodes) = EXPRESSION.with(Cell::get);
    if depth >= MAX_NESTING {
        return Err(syn::Error::new(
            span,
            format!(
                "this expression is nested too deeply: at most {MAX_NESTING} levels of \
                 parentheses, calls and signs"
            ),
        ));
    }
    EXPRESSION.with(|e| e.set((depth + 1, nodes)));
    let parsed = parse();
    EXPRESSION.with(|e| e.set((depth, e.get().1)));
    parsed
}

impl Parse for VectorSum {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        let mut terms = Vec::new();
        let mut negated = parse_sign(input)?.unwrap_or(false);
        loop {
            if terms.len() == MAX_TERMS {
                return Err(input.error(format!(
                    "too many vectors: a loop or a point sums at most {MAX_TERMS}"
                )));
            }
            let magnitude = parse_expression(input)?;
            if !input.peek(Token![@]) {
                return Err(syn::Error::new(
                    magnitude.span(),
                    "expected `@` after this magnitude: each term is `length @ angle`; \
                     write a sum of angles in parentheses, as in `r @ (theta4 + gamma)`",
                ));
            }
            input.parse::<Token![@]>()?;
            let angle = parse_expression(input)?;
            terms.push(VectorTerm {
                negated,
                magnitude,
                angle,
            });
            match parse_sign(input)? {
                Some(sign) => negated = sign,
                None => break,
            }
        }
        Ok(VectorSum { terms })
    }
}

/// `+` gives `Some(false)`, `-` gives `Some(true)`, anything else `None` (nothing consumed).
fn parse_sign(input: ParseStream) -> syn::Result<Option<bool>> {
    if input.peek(Token![+]) {
        input.parse::<Token![+]>()?;
        Ok(Some(false))
    } else if input.peek(Token![-]) {
        input.parse::<Token![-]>()?;
        Ok(Some(true))
    } else {
        Ok(None)
    }
}

/// `product (('+' | '-') product)*`, used inside parentheses.
fn parse_sum(input: ParseStream) -> syn::Result<Scalar> {
    let mut left = parse_product(input)?;
    loop {
        let op = if input.peek(Token![+]) {
            BinaryOp::Add
        } else if input.peek(Token![-]) {
            BinaryOp::Sub
        } else {
            return Ok(left);
        };
        let span = input.span();
        count_node(span)?;
        input.parse::<proc_macro2::Punct>()?;
        let right = parse_product(input)?;
        left = Scalar::Binary(op, span, Box::new(left), Box::new(right));
    }
}

/// `unary (('*' | '/') unary)*`: a vector's magnitude or angle outside parentheses, so
/// `c @ pi / 2` needs none.
fn parse_product(input: ParseStream) -> syn::Result<Scalar> {
    let mut left = parse_unary(input)?;
    loop {
        let op = if input.peek(Token![*]) {
            BinaryOp::Mul
        } else if input.peek(Token![/]) {
            BinaryOp::Div
        } else {
            return Ok(left);
        };
        let span = input.span();
        count_node(span)?;
        input.parse::<proc_macro2::Punct>()?;
        let right = parse_unary(input)?;
        left = Scalar::Binary(op, span, Box::new(left), Box::new(right));
    }
}

fn parse_unary(input: ParseStream) -> syn::Result<Scalar> {
    if input.peek(Token![-]) {
        let minus: Token![-] = input.parse()?;
        count_node(minus.span)?;
        let operand = nested(minus.span, || parse_unary(input))?;
        return Ok(Scalar::Neg(minus.span, Box::new(operand)));
    }
    parse_atom(input)
}

fn parse_atom(input: ParseStream) -> syn::Result<Scalar> {
    let lookahead = input.lookahead1();
    if lookahead.peek(syn::token::Paren) {
        let inner;
        let parens = syn::parenthesized!(inner in input);
        let scalar = nested(parens.span.open(), || parse_sum(&inner))?;
        if !inner.is_empty() {
            return Err(inner.error("expected `+`, `-`, `*`, `/` or `)`"));
        }
        Ok(Scalar::Paren(Box::new(scalar)))
    } else if lookahead.peek(Ident) {
        let name: Ident = input.parse()?;
        count_node(name.span())?;
        if input.peek(syn::token::Paren) {
            return nested(name.span(), || parse_call(input, name));
        }
        Ok(Scalar::Name(name))
    } else if lookahead.peek(syn::LitInt) {
        let literal: syn::LitInt = input.parse()?;
        count_node(literal.span())?;
        reject_suffix(literal.suffix(), literal.span())?;
        in_degrees(input, finite(literal.base10_parse()?, literal.span())?)
    } else if lookahead.peek(syn::LitFloat) {
        let literal: syn::LitFloat = input.parse()?;
        count_node(literal.span())?;
        reject_suffix(literal.suffix(), literal.span())?;
        in_degrees(input, finite(literal.base10_parse()?, literal.span())?)
    } else {
        Err(lookahead.error())
    }
}

/// `function(argument, …)`, after the function's name: one of [`FUNCTIONS`], with as many
/// arguments as it takes.
fn parse_call(input: ParseStream, function: Ident) -> syn::Result<Scalar> {
    let inner;
    let parens = syn::parenthesized!(inner in input);
    let Some(&(_, arity)) = FUNCTIONS.iter().find(|(name, _)| function == name) else {
        let known: Vec<String> = FUNCTIONS
            .iter()
            .map(|(name, _)| format!("`{name}`"))
            .collect();
        return Err(syn::Error::new(
            function.span(),
            format!(
                "`{function}` is not a function a declaration knows: it knows {}",
                known.join(", ")
            ),
        ));
    };
    let arguments =
        syn::punctuated::Punctuated::<Scalar, Token![,]>::parse_terminated_with(&inner, parse_sum)?;
    let arguments: Vec<Scalar> = arguments.into_iter().collect();
    if arguments.len() != arity {
        let plural = if arity == 1 { "" } else { "s" };
        return Err(syn::Error::new(
            parens.span.join(),
            format!(
                "`{function}` takes {arity} argument{plural}, not {}",
                arguments.len()
            ),
        ));
    }
    Ok(Scalar::Call(function, arguments, parens.span.close()))
}

/// `number deg` (an angle in degrees) where `deg` follows the number, else the number.
fn in_degrees(input: ParseStream, number: Scalar) -> syn::Result<Scalar> {
    let follows = input
        .fork()
        .parse::<Ident>()
        .is_ok_and(|unit| unit == "deg");
    match number {
        Scalar::Number(value, span) if follows => {
            input.parse::<Ident>()?;
            Ok(Scalar::Degrees(value, span))
        }
        other => Ok(other),
    }
}

fn finite(value: f64, span: Span) -> syn::Result<Scalar> {
    if value.is_finite() {
        Ok(Scalar::Number(value, span))
    } else {
        Err(syn::Error::new(span, "this number is too large for f64"))
    }
}

fn reject_suffix(suffix: &str, span: Span) -> syn::Result<()> {
    if suffix.is_empty() {
        Ok(())
    } else {
        Err(syn::Error::new(
            span,
            "write numbers without a type suffix: the generated code picks the float type",
        ))
    }
}
