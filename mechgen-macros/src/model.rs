//! The declaration with its names resolved and its rules checked: what the mechanism is,
//! independent of how it was written.
//!
//! Every rule below reports on the tokens that break it, and all broken rules are reported
//! together.

use std::collections::btree_map::Entry;
use std::collections::{BTreeMap, BTreeSet};
use std::fmt;

use proc_macro2::Span;
use syn::{Attribute, Ident, Visibility};

use crate::ast::{self, BinaryOp, Declaration, Scalar, Section, SymbolDecl};
use crate::errors::Errors;
use crate::formula::{Formula, Function};
use crate::scene::{self, Declared, Scene};

/// Whether a symbol is a length or an angle. Magnitudes must be lengths, angles angles.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    Length,
    Angle,
}

impl fmt::Display for Kind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Kind::Length => "length",
            Kind::Angle => "angle",
        })
    }
}

/// A declared name: which list it is in and its index there.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum SymbolRef {
    Param(usize),
    /// One of the driven inputs, in declaration order.
    Input(usize),
    Unknown(usize),
}

pub struct Symbol {
    pub name: Ident,
    pub kind: Kind,
    pub docs: Vec<Attribute>,
    /// The field's visibility, for a parameter (private unless declared `pub`, as in Rust).
    pub vis: Visibility,
}

/// `Σ coefficient·symbol + Σ coefficient·formula + constant`: every scalar in a loop is
/// linear in the declared names; formulas of the parameters (see [`Formula`]) are terms of
/// their own.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Linear {
    pub coefficients: BTreeMap<SymbolRef, f64>,
    pub formulas: Vec<(f64, Formula)>,
    pub constant: f64,
}

impl Linear {
    fn constant(value: f64) -> Self {
        Linear {
            constant: value,
            ..Linear::default()
        }
    }

    fn symbol(symbol: SymbolRef) -> Self {
        Linear {
            coefficients: BTreeMap::from([(symbol, 1.0)]),
            ..Linear::default()
        }
    }

    fn formula(formula: Formula) -> Self {
        Linear {
            formulas: vec![(1.0, formula)],
            ..Linear::default()
        }
    }

    fn scaled(mut self, factor: f64) -> Self {
        self.coefficients.values_mut().for_each(|c| *c *= factor);
        self.formulas.iter_mut().for_each(|(c, _)| *c *= factor);
        self.constant *= factor;
        self
    }

    fn divided(mut self, divisor: f64) -> Self {
        self.coefficients.values_mut().for_each(|c| *c /= divisor);
        self.formulas.iter_mut().for_each(|(c, _)| *c /= divisor);
        self.constant /= divisor;
        self
    }

    fn is_finite(&self) -> bool {
        self.constant.is_finite()
            && self.coefficients.values().all(|c| c.is_finite())
            && self.formulas.iter().all(|(c, _)| c.is_finite())
    }

    fn plus(mut self, other: Linear) -> Self {
        for (symbol, coefficient) in other.coefficients {
            *self.coefficients.entry(symbol).or_insert(0.0) += coefficient;
        }
        self.coefficients.retain(|_, c| *c != 0.0);
        self.formulas.extend(other.formulas);
        self.constant += other.constant;
        self
    }

    /// Without the names and formulas whose factor is zero (`0 * theta2`, or a product of
    /// numbers that underflows), as a cancellation leaves it: the loops do not depend on them.
    fn without_zeros(mut self) -> Self {
        self.coefficients.retain(|_, c| *c != 0.0);
        self.formulas.retain(|(c, _)| *c != 0.0);
        self
    }

    /// Its value with each symbol's from `value_of`.
    fn value(&self, value_of: &mut dyn FnMut(SymbolRef) -> f64) -> f64 {
        let symbols: f64 = self
            .coefficients
            .iter()
            .map(|(&symbol, factor)| factor * value_of(symbol))
            .sum();
        let formulas: f64 = self
            .formulas
            .iter()
            .map(|(factor, formula)| factor * formula.value(&mut |i| value_of(SymbolRef::Param(i))))
            .sum();
        symbols + formulas + self.constant
    }

    fn as_constant(&self) -> Option<f64> {
        (self.coefficients.is_empty() && self.formulas.is_empty()).then_some(self.constant)
    }
}

/// `± magnitude·e^{i·angle}`.
pub struct Term {
    pub negated: bool,
    pub magnitude: Linear,
    pub angle: Linear,
    /// The spans of the term's first and last tokens as written, for diagnostics.
    pub span: [Span; 2],
}

/// A vector sum: a loop that must close, or a point's position from the origin.
pub struct VectorSum {
    pub terms: Vec<Term>,
    /// The sum as the user wrote it, for generated docs.
    pub source: String,
}

impl VectorSum {
    /// An error underlining term `term`, or the whole sum. (`Span::join` is unavailable on
    /// stable, but `syn::Error::new_spanned` spans from a stream's first token to its last.)
    pub fn error(&self, term: Option<usize>, message: impl std::fmt::Display) -> syn::Error {
        let [first, last] = match term {
            Some(t) => self.terms[t].span,
            None => [
                self.terms.first().map_or(Span::call_site(), |t| t.span[0]),
                self.terms.last().map_or(Span::call_site(), |t| t.span[1]),
            ],
        };
        let first = Ident::new("first", first);
        let last = Ident::new("last", last);
        syn::Error::new_spanned(quote::quote!(#first #last), message)
    }
}

pub struct Point {
    pub name: Ident,
    pub docs: Vec<Attribute>,
    pub position: VectorSum,
}

/// Which functions to generate. Position is always generated.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Outputs {
    pub velocity: bool,
    pub acceleration: bool,
    /// `generate: assemble`: the closed forms are required, so a declaration without one is
    /// an error at the loop that has none, rather than a type without `assemble`.
    pub assemble: bool,
    /// `generate: sensitivities`: the unknowns' and the points' derivatives with respect to
    /// the parameters, at a solved position.
    pub sensitivities: bool,
}

pub struct Model {
    pub attrs: Vec<Attribute>,
    pub vis: Visibility,
    pub name: Ident,
    pub params: Vec<Symbol>,
    /// The driven inputs, in declaration order: at least one.
    pub inputs: Vec<Symbol>,
    pub unknowns: Vec<Symbol>,
    pub loops: Vec<VectorSum>,
    pub points: Vec<Point>,
    pub outputs: Outputs,
    pub scenes: Vec<Scene>,
}

impl Model {
    pub fn symbol(&self, symbol: SymbolRef) -> &Symbol {
        match symbol {
            SymbolRef::Param(i) => &self.params[i],
            SymbolRef::Input(i) => &self.inputs[i],
            SymbolRef::Unknown(i) => &self.unknowns[i],
        }
    }
}

/// The sizes a name's factor in a magnitude or an angle may have (see [`Scope::resolve`]):
/// `2 * l3`, `l3 / 1000`, `-3 * theta2` are far inside.
const FACTORS: std::ops::RangeInclusive<f64> = 1e-6..=1e6;

/// Names a declaration cannot give its values: the generated code binds each with `let`,
/// where these are patterns.
const PRELUDE_VARIANTS: [&str; 4] = ["Ok", "Err", "Some", "None"];

/// Resolves and checks a parsed declaration.
pub fn build(declaration: Declaration) -> syn::Result<Model> {
    let mut errors = Errors::default();
    let Declaration {
        attrs,
        vis,
        name,
        sections,
    } = declaration;

    let mut params = None;
    let mut input = None;
    let mut unknowns = None;
    let mut loops = Vec::new();
    let mut points = Vec::new();
    let mut generate = None;
    let mut scenes = Vec::new();
    // Every declared name with what it names, in the order written.
    let mut declared = Vec::new();
    for section in sections {
        let names = |what, decls: &[SymbolDecl]| -> Vec<(Declared, Ident)> {
            decls.iter().map(|d| (what, d.name.clone())).collect()
        };
        match &section {
            Section::Params(_, decls) => declared.extend(names(Declared::Param, decls)),
            Section::Input(_, decls) => declared.extend(names(Declared::Input, decls)),
            Section::Unknowns(_, decls) => declared.extend(names(Declared::Unknown, decls)),
            Section::Point(_, name, _) => declared.push((Declared::Point, name.clone())),
            _ => {}
        }
        match section {
            Section::Params(keyword, decls) => set_once(&mut params, keyword, decls, &mut errors),
            Section::Input(keyword, decls) => set_once(&mut input, keyword, decls, &mut errors),
            Section::Unknowns(keyword, decls) => {
                set_once(&mut unknowns, keyword, decls, &mut errors)
            }
            Section::Loop(sum) => loops.push(sum),
            Section::Point(attrs, name, sum) => {
                let docs = docs_only(
                    attrs,
                    &format!("point `{name}`"),
                    "a point is a field of several generated structs and a part of every \
                     generated function, which an attribute cannot all follow",
                    &mut errors,
                );
                points.push((docs, name, sum))
            }
            Section::Generate(keyword, outputs) => {
                set_once(&mut generate, keyword, outputs, &mut errors)
            }
            Section::Scene(attrs, name, outputs) => {
                let docs = docs_only(
                    attrs,
                    &format!("scene `{name}`"),
                    "a scene is several generated items (its output struct, its method, its \
                     batch kernel), which an attribute cannot all follow",
                    &mut errors,
                );
                scenes.push((docs, name, outputs))
            }
        }
    }

    if name == "T" {
        errors.error_at(
            &name,
            "a mechanism cannot be named `T`: the generated code's float type parameter is `T`; \
             pick another name",
        );
    }

    let required = |what: &str, example: &str, errors: &mut Errors| {
        errors.error_at(
            &name,
            format!("`{name}` has no {what}: add `{example};` to its declaration"),
        );
    };
    if input.is_none() {
        required("driven input", "input: theta2: angle", &mut errors);
    }
    if unknowns.is_none() {
        required(
            "unknowns",
            "unknowns: theta3: angle, theta4: angle",
            &mut errors,
        );
    }
    if loops.is_empty() {
        let example = example_loop(&params, &input, &unknowns);
        required("loop", &example, &mut errors);
    }

    let mut undetermined = BTreeSet::new();
    let params = params
        .map(|(_, decls)| symbols(decls, Some(Kind::Length), &mut undetermined, &mut errors))
        .unwrap_or_default();
    let input = input
        .map(|(_, decls)| symbols(decls, None, &mut undetermined, &mut errors))
        .unwrap_or_default();
    let (unknowns_span, unknowns) = match unknowns {
        Some((keyword, decls)) => (
            keyword.span(),
            symbols(decls, None, &mut undetermined, &mut errors),
        ),
        None => (name.span(), Vec::new()),
    };

    let mut scope = Scope::new(&params, &input, &unknowns, &undetermined, &mut errors);
    // The names refused above need no second error where they are used.
    scope.poisoned.extend(
        params
            .iter()
            .chain(&input)
            .chain(&unknowns)
            .map(|symbol| symbol.name.to_string())
            .filter(|name| PRELUDE_VARIANTS.contains(&name.as_str())),
    );
    // Each loop, and whether every magnitude and angle in it resolved.
    let (loops, resolved): (Vec<VectorSum>, Vec<bool>) = loops
        .iter()
        .map(|sum| {
            let failures = scope.failures;
            let sum = scope.vector_sum(sum, &mut errors);
            (sum, scope.failures == failures)
        })
        .unzip();
    let in_loops = std::mem::take(&mut scope.appearing);
    let written_in_loops = std::mem::take(&mut scope.written);
    let mut point_names: Vec<&Ident> = Vec::new();
    let points: Vec<Point> = points
        .iter()
        .map(|(docs, point_name, sum)| {
            if point_names.contains(&point_name) {
                errors.error_at(
                    point_name,
                    format!("point `{point_name}` is declared twice"),
                );
            }
            point_names.push(point_name);
            Point {
                name: point_name.clone(),
                docs: docs.clone(),
                position: scope.vector_sum(sum, &mut errors),
            }
        })
        .collect();

    if !check_no_loop_is_identically_zero(&loops, &resolved, &params, &mut errors) {
        check_counts(&loops, &unknowns, unknowns_span, &mut errors);
    }
    check_every_symbol_in_a_loop(
        &scope,
        &in_loops,
        &written_in_loops,
        &input,
        &unknowns,
        &mut errors,
    );
    scene::check_unambiguous(&declared, &mut errors);
    let outputs = outputs(generate, input.len(), &mut errors);
    let scenes = scene::resolve(
        scenes,
        &scene::Names {
            params: &params.iter().map(|p| p.name.clone()).collect::<Vec<_>>(),
            inputs: &input.iter().map(|i| i.name.clone()).collect::<Vec<_>>(),
            unknowns: &unknowns.iter().map(|u| u.name.clone()).collect::<Vec<_>>(),
            points: &points.iter().map(|p| p.name.clone()).collect::<Vec<_>>(),
        },
        &mut errors,
    );

    let inputs = if input.is_empty() {
        // Reported above as a missing input; a placeholder keeps the other checks going.
        vec![Symbol {
            name: Ident::new("input", name.span()),
            kind: Kind::Angle,
            docs: Vec::new(),
            vis: Visibility::Inherited,
        }]
    } else {
        input
    };
    errors.finish(Model {
        attrs,
        vis,
        name,
        params,
        inputs,
        unknowns,
        loops,
        points,
        outputs,
        scenes,
    })
}

/// Records a section that may appear once. A repeat is an error, but its entries are kept,
/// so the names it declares do not also show up as undeclared.
fn set_once<T>(
    slot: &mut Option<(Ident, Vec<T>)>,
    keyword: Ident,
    value: Vec<T>,
    errors: &mut Errors,
) {
    match slot {
        Some((_, existing)) => {
            errors.error_at(
                &keyword,
                format!("`{keyword}` is given twice: list everything in one `{keyword}:` section"),
            );
            existing.extend(value);
        }
        None => *slot = Some((keyword, value)),
    }
}

/// Rule: a declared name, a point or a scene takes doc comments (which document what is
/// generated for it) and no other attribute: `#[cfg]` or `#[allow]` would reach only one of
/// the items generated for it, and the others would no longer compile or mean the same.
/// Returns the doc comments.
fn docs_only(attrs: Vec<Attribute>, what: &str, why: &str, errors: &mut Errors) -> Vec<Attribute> {
    let (docs, others): (Vec<_>, Vec<_>) = attrs
        .into_iter()
        .partition(|attr| attr.path().is_ident("doc"));
    for attr in others {
        errors.error_at(
            attr,
            format!("only doc comments are allowed on {what}: {why}"),
        );
    }
    docs
}

/// Resolves kinds. `default` is the kind of an undeclared one; `None` makes the kind required.
///
/// A symbol whose kind is missing or misspelled is reported here and recorded in
/// `undetermined`, so that its uses are not reported again as being of the wrong kind.
fn symbols(
    decls: Vec<SymbolDecl>,
    default: Option<Kind>,
    undetermined: &mut BTreeSet<String>,
    errors: &mut Errors,
) -> Vec<Symbol> {
    decls
        .into_iter()
        .map(
            |SymbolDecl {
                 attrs,
                 vis,
                 name,
                 kind,
             }| {
                // `#[cfg]` would remove a value the loops read.
                let docs = docs_only(
                    attrs,
                    &format!("`{name}`"),
                    "the loops need every declared name, whatever an attribute would do to its \
                     field",
                    errors,
                );
                if !matches!(vis, Visibility::Inherited) && default.is_none() {
                    errors.error_at(
                        &vis,
                        "only parameters have a visibility: the input and unknowns are arguments \
                     and fields of the public unknowns struct",
                    );
                }
                let kind = match (kind, default) {
                    (Some(kind), _) => match kind.to_string().as_str() {
                        "angle" => Kind::Angle,
                        "length" => Kind::Length,
                        _ => {
                            errors.error_at(&kind, "expected `angle` or `length`");
                            undetermined.insert(name.to_string());
                            Kind::Length
                        }
                    },
                    (None, Some(default)) => default,
                    (None, None) => {
                        errors.error_at(
                            &name,
                            format!(
                                "say whether `{name}` is an angle or a length: \
                             `{name}: angle` or `{name}: length`"
                            ),
                        );
                        undetermined.insert(name.to_string());
                        Kind::Length
                    }
                };
                Symbol {
                    name,
                    kind,
                    docs,
                    vis,
                }
            },
        )
        .collect()
}

/// Declared names, for resolving the loops.
struct Scope {
    /// Each name's symbol, and its kind unless the declaration left it undetermined.
    names: BTreeMap<String, (SymbolRef, Option<Kind>)>,
    /// Names declared in error (a prelude variant): using one reports nothing more.
    poisoned: BTreeSet<String>,
    /// Symbols the resolved sums depend on so far (see [`Scope::resolve`]).
    appearing: BTreeSet<SymbolRef>,
    /// Symbols mentioned by the expression being resolved.
    seen: BTreeSet<SymbolRef>,
    /// Symbols the resolved sums mention so far, whether they depend on them or not.
    written: BTreeSet<SymbolRef>,
    /// How many magnitudes and angles failed to resolve so far.
    failures: usize,
}

impl Scope {
    fn new(
        params: &[Symbol],
        inputs: &[Symbol],
        unknowns: &[Symbol],
        undetermined: &BTreeSet<String>,
        errors: &mut Errors,
    ) -> Self {
        let declared = params
            .iter()
            .enumerate()
            .map(|(i, s)| (SymbolRef::Param(i), s))
            .chain(
                inputs
                    .iter()
                    .enumerate()
                    .map(|(i, s)| (SymbolRef::Input(i), s)),
            )
            .chain(
                unknowns
                    .iter()
                    .enumerate()
                    .map(|(i, s)| (SymbolRef::Unknown(i), s)),
            );
        let mut names = BTreeMap::new();
        for (symbol, Symbol { name, kind, .. }) in declared {
            let text = name.to_string();
            if text == "pi" {
                errors.error_at(
                    name,
                    "`pi` is reserved for the constant π; pick another name",
                );
            } else if PRELUDE_VARIANTS.contains(&text.as_str()) {
                // The generated code binds each name with `let`, where these are patterns.
                errors.error_at(
                    name,
                    format!(
                        "`{text}` is a variant of Rust's prelude, which the generated code \
                         cannot bind as a value; pick another name"
                    ),
                );
            } else {
                let kind = (!undetermined.contains(&text)).then_some(*kind);
                match names.entry(text) {
                    Entry::Occupied(_) => {
                        errors.error_at(name, format!("`{name}` is declared twice"))
                    }
                    Entry::Vacant(slot) => {
                        slot.insert((symbol, kind));
                    }
                }
            }
        }
        Scope {
            names,
            poisoned: BTreeSet::new(),
            appearing: BTreeSet::new(),
            seen: BTreeSet::new(),
            written: BTreeSet::new(),
            failures: 0,
        }
    }

    /// The declared name most like `name`, if one is close: the same but for case (`PI` for
    /// `pi`, `Theta2`), or a misspelling within a third of its letters (`theta` for `theta2`;
    /// never `l4` for `l5`, which is more likely a name left undeclared).
    fn closest(&self, name: &str) -> Option<String> {
        let folded = name.to_lowercase();
        let names = self.names.keys().map(String::as_str);
        if let Some(same) = names
            .clone()
            .chain(["pi"])
            .find(|c| c.to_lowercase() == folded)
        {
            return Some(same.to_string());
        }
        names
            .map(|candidate| (strsim::levenshtein(name, candidate), candidate))
            .filter(|(distance, _)| *distance <= name.chars().count() / 3)
            .min()
            .map(|(_, candidate)| candidate.to_string())
    }

    /// The name of a symbol or formula term of `linear` whose factor is out of [`FACTORS`],
    /// with the factor.
    fn factor_out_of_range(&self, linear: &Linear) -> Option<(String, f64)> {
        let name_of = |symbol: SymbolRef| {
            self.names
                .iter()
                .find(|(_, (s, _))| *s == symbol)
                .map_or_else(String::new, |(name, _)| name.clone())
        };
        let symbols = linear
            .coefficients
            .iter()
            .map(|(&symbol, &factor)| (name_of(symbol), factor));
        let formulas = linear.formulas.iter().map(|(factor, formula)| {
            let param = |i| name_of(SymbolRef::Param(i));
            (formula.display(&param).to_string(), *factor)
        });
        symbols
            .chain(formulas)
            .find(|(_, factor)| !FACTORS.contains(&factor.abs()))
    }

    /// Whether `symbol` is the one its name resolves to (a duplicate declaration is not).
    fn resolves_to(&self, symbol: SymbolRef) -> bool {
        self.names.values().any(|(s, _)| *s == symbol)
    }

    fn vector_sum(&mut self, sum: &ast::VectorSum, errors: &mut Errors) -> VectorSum {
        let terms = sum
            .terms
            .iter()
            .map(|term| Term {
                negated: term.negated,
                magnitude: self.resolve(&term.magnitude, Kind::Length, errors),
                angle: self.resolve(&term.angle, Kind::Angle, errors),
                span: [term.magnitude.span(), term.angle.last_span()],
            })
            .collect();
        VectorSum {
            terms,
            source: sum.to_string(),
        }
    }

    /// Resolves one magnitude or angle and records which symbols it really depends on (a
    /// name whose coefficient cancels, as in `theta2 - theta2`, or is zero, as in
    /// `0 * theta2`, does not count). After an error, every name it mentions counts, so no
    /// "appears in no loop" follows from it.
    fn resolve(&mut self, scalar: &Scalar, expected: Kind, errors: &mut Errors) -> Linear {
        self.seen.clear();
        let resolved = self.linear(scalar, expected, errors).and_then(|linear| {
            if linear.is_finite() {
                Some(linear.without_zeros())
            } else {
                errors.push(scalar.error("this expression overflows f64"));
                None
            }
        });
        // Rule: a name's factor is within [`FACTORS`]. A factor far from 1 scales that name's
        // column of the Jacobian away from the others' (`1e300 * theta3` makes the system
        // singular in any precision), and one beyond f32's range (`1e-320 * l3`) is zero or
        // infinite in the generated f32 code.
        let resolved = resolved.and_then(|linear| match self.factor_out_of_range(&linear) {
            Some((name, factor)) => {
                errors.push(scalar.error(format!(
                    "`{scalar}` multiplies `{name}` by {}: a name's factor must be between {:e} \
                     and {:e} in size, so that its derivatives stay in proportion to the others'",
                    number(factor),
                    FACTORS.start(),
                    FACTORS.end(),
                )));
                None
            }
            None => Some(linear),
        });
        // A bare number in an angle is radians: beyond a turn, it is degrees written without
        // their unit far more often than an angle of several turns.
        let resolved = resolved.and_then(|linear| {
            let turn = std::f64::consts::TAU;
            let literal = (expected == Kind::Angle && linear.constant.abs() > turn)
                .then(|| scalar.numbers().find(|(value, _)| value.abs() > turn))
                .flatten();
            match literal {
                Some((value, span)) => {
                    errors.error_at_span(
                        span,
                        format!(
                            "`{value}` in an angle is {value} radians, more than a turn: \
                             write `{value} deg` for degrees",
                            value = number(value),
                        ),
                    );
                    None
                }
                None => Some(linear),
            }
        });
        // A bare number in a length is a length in no unit the mechanism knows: it would not
        // scale with the declared lengths, which every solver scales to keep the digits of a
        // mechanism of any size.
        let resolved = resolved.and_then(|linear| {
            if expected == Kind::Length && linear.constant != 0.0 {
                errors.push(scalar.error(
                    "a vector's magnitude cannot hold a length as a bare number: declare it \
                     in `params` (a number may multiply or divide a declared length)",
                ));
                None
            } else {
                Some(linear)
            }
        });
        match resolved {
            Some(linear) => {
                self.appearing.extend(linear.coefficients.keys().copied());
                self.written.append(&mut self.seen);
                linear
            }
            None => {
                self.appearing.append(&mut self.seen);
                self.failures += 1;
                Linear::default()
            }
        }
    }

    /// Resolves `scalar`, which must be of kind `expected` and linear in the declared names.
    /// `None` means an error was recorded; enclosing expressions then record nothing more.
    fn linear(&mut self, scalar: &Scalar, expected: Kind, errors: &mut Errors) -> Option<Linear> {
        match scalar {
            Scalar::Number(value, _) => Some(Linear::constant(*value)),
            Scalar::Degrees(value, _) if expected == Kind::Length => {
                errors.push(scalar.error(format!(
                    "`{value} deg` is an angle: degrees are for a vector's angle, not its magnitude"
                )));
                None
            }
            Scalar::Degrees(value, _) => Some(Linear::constant(radians(*value))),
            Scalar::Paren(inner) => self.linear(inner, expected, errors),
            Scalar::Name(name) => match self.names.get(&name.to_string()).copied() {
                Some((symbol, kind)) => {
                    self.seen.insert(symbol);
                    match kind {
                        Some(kind) if kind != expected => {
                            let place = match expected {
                                Kind::Length => "a vector's magnitude must be a length",
                                Kind::Angle => "a vector's angle must be an angle",
                            };
                            let article = article(kind);
                            // A parameter is a length unless declared otherwise.
                            let hint = match symbol {
                                SymbolRef::Param(_) if expected == Kind::Angle => {
                                    format!(" (declare it `{name}: angle` in `params`)")
                                }
                                _ => String::new(),
                            };
                            errors.error_at(
                                name,
                                format!("`{name}` is {article} {kind}: {place}{hint}"),
                            );
                            None
                        }
                        _ => Some(Linear::symbol(symbol)),
                    }
                }
                None if name == "pi" => Some(Linear::constant(std::f64::consts::PI)),
                None if self.poisoned.contains(&name.to_string()) => None,
                None => {
                    let hint = match self.closest(&name.to_string()) {
                        Some(close) => {
                            // Meant, so it counts as appearing (no "appears in no loop").
                            if let Some(&(symbol, _)) = self.names.get(&close) {
                                self.seen.insert(symbol);
                            }
                            format!("; did you mean `{close}`?")
                        }
                        None => String::new(),
                    };
                    errors.error_at(
                        name,
                        format!(
                            "cannot find `{name}` in this mechanism: \
                             declare it in `params`, `input` or `unknowns`{hint}"
                        ),
                    );
                    None
                }
            },
            Scalar::Neg(_, inner) => Some(self.linear(inner, expected, errors)?.scaled(-1.0)),
            // A function of parameters: a formula, a term of its own.
            Scalar::Call(..) if scalar.names().any(|name| name != "pi") => {
                self.formula_term(scalar, expected, errors)
            }
            // A product or quotient of parameters (not of a number): a formula too.
            Scalar::Binary(BinaryOp::Mul | BinaryOp::Div, _, left, right)
                if self.of_parameters(left) && self.of_parameters(right) =>
            {
                self.formula_term(scalar, expected, errors)
            }
            Scalar::Call(..) => {
                let value = constant_value(scalar);
                if value.is_finite() {
                    Some(Linear::constant(value))
                } else {
                    errors.push(scalar.error(format!("`{scalar}` is not a finite number")));
                    None
                }
            }
            Scalar::Binary(op, op_span, left, right) => {
                let l = self.linear(left, expected, errors);
                let r = self.linear(right, expected, errors);
                let (l, r) = (l?, r?);
                match op {
                    BinaryOp::Add => Some(l.plus(r)),
                    BinaryOp::Sub => Some(l.plus(r.scaled(-1.0))),
                    BinaryOp::Mul => match (l.as_constant(), r.as_constant()) {
                        (Some(c), _) => Some(r.scaled(c)),
                        (_, Some(c)) => Some(l.scaled(c)),
                        (None, None) => {
                            errors.error_at_span(
                                *op_span,
                                "loop terms are linear in the declared names: \
                                 multiply by numbers only",
                            );
                            None
                        }
                    },
                    BinaryOp::Div => match r.as_constant() {
                        Some(c) if c != 0.0 => Some(l.divided(c)),
                        Some(_) => {
                            errors.push(right.error("division by zero"));
                            None
                        }
                        None => {
                            errors.push(right.error(
                                "loop terms are linear in the declared names: \
                                 divide by numbers only",
                            ));
                            None
                        }
                    },
                }
            }
        }
    }
}

impl Scope {
    /// Whether `scalar` mentions a name and every name it mentions is a parameter (or `pi`):
    /// a factor that makes a product of parameters a formula rather than an error.
    fn of_parameters(&self, scalar: &Scalar) -> bool {
        let mut names = scalar.names().filter(|name| *name != "pi").peekable();
        names.peek().is_some()
            && names.all(|name| {
                matches!(
                    self.names.get(&name.to_string()),
                    Some((SymbolRef::Param(_), _))
                )
            })
    }

    /// `scalar` as a formula term of kind `expected`: a magnitude's formula must be a length
    /// (of degree 1 in length), an angle's an angle or a number (of degree 0).
    fn formula_term(
        &mut self,
        scalar: &Scalar,
        expected: Kind,
        errors: &mut Errors,
    ) -> Option<Linear> {
        let (formula, degree) = self.formula(scalar, errors)?;
        let wanted = match expected {
            Kind::Length => 1.0,
            Kind::Angle => 0.0,
        };
        if degree != wanted {
            let place = match expected {
                Kind::Length => "a vector's magnitude must be a length",
                Kind::Angle => "a vector's angle must be an angle or a number",
            };
            errors.push(scalar.error(format!("`{scalar}` is {}: {place}", dimension(degree))));
            return None;
        }
        Some(Linear::formula(formula))
    }

    /// Resolves `scalar` as a formula of numbers and parameters, with its degree in length
    /// (see [`crate::formula`]). `None` means an error was recorded.
    fn formula(&mut self, scalar: &Scalar, errors: &mut Errors) -> Option<(Formula, f64)> {
        match scalar {
            Scalar::Number(value, _) => Some((Formula::Number(*value), 0.0)),
            Scalar::Degrees(value, _) => Some((Formula::Number(radians(*value)), 0.0)),
            Scalar::Paren(inner) => self.formula(inner, errors),
            Scalar::Name(name) => match self.names.get(&name.to_string()).copied() {
                Some((symbol @ SymbolRef::Param(i), kind)) => {
                    self.seen.insert(symbol);
                    let degree = if kind == Some(Kind::Angle) { 0.0 } else { 1.0 };
                    Some((Formula::Param(i), degree))
                }
                Some((symbol, _)) => {
                    self.seen.insert(symbol);
                    let what = match symbol {
                        SymbolRef::Input(_) => "an input",
                        _ => "an unknown",
                    };
                    errors.error_at(
                        name,
                        format!(
                            "`{name}` is {what}: products and functions take numbers and \
                             parameters only, so that the loops stay linear in the inputs and \
                             unknowns"
                        ),
                    );
                    None
                }
                None if name == "pi" => Some((Formula::Number(std::f64::consts::PI), 0.0)),
                // Not declared: the linear resolution says so, with its hints.
                None => self.linear(scalar, Kind::Length, errors).and(None),
            },
            Scalar::Neg(_, inner) => {
                let (inner, degree) = self.formula(inner, errors)?;
                Some((Formula::Neg(Box::new(inner)), degree))
            }
            Scalar::Binary(op, op_span, left, right) => {
                let l = self.formula(left, errors);
                let r = self.formula(right, errors);
                let ((a, da), (b, db)) = (l?, r?);
                let (a, b) = (Box::new(a), Box::new(b));
                match op {
                    BinaryOp::Add | BinaryOp::Sub if da != db => {
                        errors.error_at_span(
                            *op_span,
                            format!(
                                "`{scalar}` adds {} and {}: the terms of a sum are of one kind",
                                dimension(da),
                                dimension(db)
                            ),
                        );
                        None
                    }
                    BinaryOp::Add => Some((Formula::Add(a, b), da)),
                    BinaryOp::Sub => Some((Formula::Sub(a, b), da)),
                    BinaryOp::Mul => Some((Formula::Mul(a, b), da + db)),
                    BinaryOp::Div if *b == Formula::Number(0.0) => {
                        errors.push(right.error("division by zero"));
                        None
                    }
                    BinaryOp::Div => Some((Formula::Div(a, b), da - db)),
                }
            }
            Scalar::Call(name, arguments, _) => {
                let resolved: Vec<Option<(Formula, f64)>> = arguments
                    .iter()
                    .map(|argument| self.formula(argument, errors))
                    .collect();
                let resolved: Vec<(Formula, f64)> = resolved.into_iter().collect::<Option<_>>()?;
                let Some((function, _)) = Function::named(&name.to_string()) else {
                    unreachable!("the parser takes only the known functions");
                };
                let degrees: Vec<f64> = resolved.iter().map(|(_, degree)| *degree).collect();
                match function.degree(&degrees) {
                    Ok(degree) => {
                        let arguments = resolved.into_iter().map(|(f, _)| f).collect();
                        Some((Formula::Call(function, arguments), degree))
                    }
                    Err(why) => {
                        errors.push(scalar.error(format!("`{name}` {why}")));
                        None
                    }
                }
            }
        }
    }
}

/// `degrees` in radians, reduced to within a turn first: `%` is exact in floating point, so
/// `1e308 deg` is exactly the angle of `296 deg` (1e308 mod 360), where converting first
/// would scale the number's rounding error by π/180 into an unrelated angle.
fn radians(degrees: f64) -> f64 {
    (degrees % 360.0).to_radians()
}

/// A number as a message or a doc shows it: as Rust prints it where that is short, else in
/// scientific notation (`1e300`, not its 301 digits).
fn number(value: f64) -> String {
    let plain = value.to_string();
    if plain.len() <= 24 {
        plain
    } else {
        format!("{value:e}")
    }
}

/// A degree in length in words: "a number", "a length", "a length squared", ...
fn dimension(degree: f64) -> String {
    match degree {
        0.0 => "a number".to_string(),
        1.0 => "a length".to_string(),
        2.0 => "a length squared (an area)".to_string(),
        _ => format!("a length to the power {degree}"),
    }
}

fn article(kind: Kind) -> &'static str {
    match kind {
        Kind::Length => "a",
        Kind::Angle => "an",
    }
}

/// Rule: each loop closes in x and in y, so there must be exactly two unknowns per loop.
fn check_counts(loops: &[VectorSum], unknowns: &[Symbol], span: Span, errors: &mut Errors) {
    let equations = 2 * loops.len();
    if !loops.is_empty() && unknowns.len() != equations {
        let loop_count = match loops.len() {
            1 => "1 loop".to_string(),
            n => format!("{n} loops"),
        };
        errors.error_at_span(
            span,
            format!(
                "{} unknowns but {loop_count}: each loop closes in x and y, giving 2 \
                 equations, so {loop_count} must have exactly {equations} unknowns",
                unknowns.len()
            ),
        );
    }
}

/// Rule: the input drives the loops and the loops determine the unknowns, so each of them
/// must appear in at least one loop, with a factor that is not zero: where every loop that
/// writes it cancels it (`theta2 - theta2`) or multiplies it by zero (`0 * theta2`), the
/// velocities would all come out zero, or nothing would determine the unknown.
fn check_every_symbol_in_a_loop(
    scope: &Scope,
    in_loops: &BTreeSet<SymbolRef>,
    written: &BTreeSet<SymbolRef>,
    inputs: &[Symbol],
    unknowns: &[Symbol],
    errors: &mut Errors,
) {
    // A duplicate declaration was reported already and stands for no symbol of its own.
    let missing = |symbol: SymbolRef| scope.resolves_to(symbol) && !in_loops.contains(&symbol);
    let cancelled = "the loops that write it cancel it or multiply it by zero";
    for (i, input) in inputs.iter().enumerate() {
        let symbol = SymbolRef::Input(i);
        if missing(symbol) {
            let name = &input.name;
            let message = if written.contains(&symbol) {
                format!("input `{name}` drives nothing: {cancelled}")
            } else {
                format!("input `{name}` appears in no loop, so it drives nothing")
            };
            errors.error_at(name, message);
        }
    }
    for (i, unknown) in unknowns.iter().enumerate() {
        let symbol = SymbolRef::Unknown(i);
        if missing(symbol) {
            let name = &unknown.name;
            let message = if written.contains(&symbol) {
                format!("no equation determines unknown `{name}`: {cancelled}")
            } else {
                format!("unknown `{name}` appears in no loop, so no equation determines it")
            };
            errors.error_at(name, message);
        }
    }
}

/// Rule: a loop is an equation. One whose vectors cancel for every value of the names
/// (`l1 @ 0 - l1 @ 0`) closes whatever the unknowns are and determines none of them; it is
/// reported at the loop, and the count of unknowns is not judged while one is there.
/// Returns whether one was found.
///
/// The loop is evaluated at a few points drawn at random (by a fixed sequence, so that the
/// verdict is the same on every build): a sum that is not identically zero is almost surely
/// not zero at any of them.
fn check_no_loop_is_identically_zero(
    loops: &[VectorSum],
    resolved: &[bool],
    params: &[Symbol],
    errors: &mut Errors,
) -> bool {
    let mut random = crate::sample::fixed_sequence();
    let mut found = false;
    // A loop with an expression in error (resolved as zero) was reported already.
    let clean = loops
        .iter()
        .enumerate()
        .filter(|(index, _)| resolved[*index]);
    for (index, sum) in clean {
        let mut zero_at = 0;
        for _ in 0..12 {
            if zero_at == 3 {
                break;
            }
            // Lengths near 1, angles anywhere; the values of other symbols are drawn as
            // they are needed, each once.
            let params: Vec<f64> = params
                .iter()
                .map(|p| match p.kind {
                    Kind::Length => 1.0 + random(),
                    Kind::Angle => std::f64::consts::TAU * random(),
                })
                .collect();
            let mut others = BTreeMap::new();
            let mut value_of = |symbol: SymbolRef| match symbol {
                SymbolRef::Param(i) => params[i],
                other => *others
                    .entry(other)
                    .or_insert_with(|| 1.0 + std::f64::consts::TAU * random()),
            };
            let (mut x, mut y, mut size) = (0.0, 0.0, 0.0);
            for term in &sum.terms {
                let magnitude = term.magnitude.value(&mut value_of);
                let angle = term.angle.value(&mut value_of);
                let sign = if term.negated { -1.0 } else { 1.0 };
                x += sign * magnitude * angle.cos();
                y += sign * magnitude * angle.sin();
                size += magnitude.abs();
            }
            if !(x.is_finite() && y.is_finite() && size.is_finite()) {
                // A formula undefined at these dimensions tells nothing.
                continue;
            }
            // The rounding of a sum that cancels exactly, with room to spare.
            let rounding = 64.0 * f64::EPSILON * size * sum.terms.len() as f64;
            if x.abs() > rounding || y.abs() > rounding {
                break;
            }
            zero_at += 1;
        }
        if zero_at == 3 {
            found = true;
            errors.push(sum.error(
                None,
                format!(
                    "loop {} is identically zero: its vectors cancel whatever the dimensions, \
                     input and unknowns, so it closes everywhere and determines nothing; \
                     remove it",
                    index + 1
                ),
            ));
        }
    }
    found
}

const OUTPUTS: [&str; 5] = [
    "position",
    "velocity",
    "acceleration",
    "assemble",
    "sensitivities",
];

/// Rule: outputs are `position`, `velocity`, `acceleration`, each needing the one before;
/// `assemble`, which asks for the closed forms (checked once the loops are planned); and
/// `sensitivities`, the derivatives with respect to the parameters. Without a `generate`
/// section, the first three are generated, and the closed forms where the loops have them.
fn outputs(generate: Option<(Ident, Vec<Ident>)>, inputs: usize, errors: &mut Errors) -> Outputs {
    let Some((_, names)) = generate else {
        return Outputs {
            velocity: true,
            acceleration: true,
            assemble: false,
            sensitivities: false,
        };
    };
    let mut seen = [None::<&Ident>; 5];
    for name in &names {
        match OUTPUTS.iter().position(|o| name == o) {
            Some(i) if seen[i].is_some() => {
                errors.error_at(name, format!("`{name}` is listed twice"))
            }
            Some(i) => seen[i] = Some(name),
            None => errors.error_at(
                name,
                format!(
                    "unknown output `{name}`: expected `position`, `velocity`, `acceleration`, \
                     `assemble` or `sensitivities`"
                ),
            ),
        }
    }
    for i in 1..3 {
        if let (Some(name), None) = (seen[i], seen[i - 1]) {
            errors.error_at(
                name,
                format!(
                    "`{}` needs `{}`: add it to `generate`",
                    OUTPUTS[i],
                    OUTPUTS[i - 1]
                ),
            );
        }
    }
    if let (Some(name), true) = (seen[4], inputs > 1) {
        errors.error_at(
            name,
            "`sensitivities` (and the `mechgen::Design` they implement) are for a mechanism \
             of one input, and this one has several",
        );
    }
    Outputs {
        velocity: seen[1].is_some(),
        acceleration: seen[2].is_some(),
        assemble: seen[3].is_some(),
        sensitivities: seen[4].is_some(),
    }
}

impl fmt::Display for ast::VectorSum {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, term) in self.terms.iter().enumerate() {
            match (i, term.negated) {
                (0, true) => f.write_str("-")?,
                (0, false) => {}
                (_, true) => f.write_str(" - ")?,
                (_, false) => f.write_str(" + ")?,
            }
            write!(f, "{} @ {}", term.magnitude, term.angle)?;
        }
        Ok(())
    }
}

/// The value of a function's argument: numbers (`30 deg` in radians, `pi`) and what
/// arithmetic and the functions make of them, evaluated at compile time. A function that
/// mentions a declared name is a formula instead (see [`Scope::formula`]).
fn constant_value(scalar: &Scalar) -> f64 {
    match scalar {
        Scalar::Number(value, _) => *value,
        Scalar::Degrees(value, _) => radians(*value),
        Scalar::Name(name) if name == "pi" => std::f64::consts::PI,
        Scalar::Name(_) => unreachable!("a function of a declared name is a formula"),
        Scalar::Neg(_, inner) => -constant_value(inner),
        Scalar::Paren(inner) => constant_value(inner),
        Scalar::Binary(op, _, left, right) => {
            let (l, r) = (constant_value(left), constant_value(right));
            match op {
                BinaryOp::Add => l + r,
                BinaryOp::Sub => l - r,
                BinaryOp::Mul => l * r,
                BinaryOp::Div => l / r,
            }
        }
        Scalar::Call(function, arguments, _) => {
            let values: Vec<f64> = arguments.iter().map(constant_value).collect();
            match (function.to_string().as_str(), values.as_slice()) {
                ("sqrt", [x]) => x.sqrt(),
                ("sin", [x]) => x.sin(),
                ("cos", [x]) => x.cos(),
                ("tan", [x]) => x.tan(),
                ("atan2", [y, x]) => y.atan2(*x),
                ("hypot", [x, y]) => x.hypot(*y),
                _ => unreachable!("the parser takes only the known functions, with their arity"),
            }
        }
    }
}

impl fmt::Display for Scalar {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Scalar::Name(name) => write!(f, "{name}"),
            Scalar::Number(value, _) => f.write_str(&number(*value)),
            Scalar::Degrees(value, _) => write!(f, "{} deg", number(*value)),
            Scalar::Neg(_, inner) => write!(f, "-{inner}"),
            // A sum shows its own parentheses (below), as it always has: the generated docs
            // quote loops so (`((theta4 + gamma) + delta)`), and the expansion snapshots of
            // the shipped mechanisms pin those docs.
            Scalar::Paren(inner)
                if matches!(**inner, Scalar::Binary(BinaryOp::Add | BinaryOp::Sub, ..)) =>
            {
                write!(f, "{inner}")
            }
            Scalar::Paren(inner) => write!(f, "({inner})"),
            Scalar::Call(function, arguments, _) => {
                let arguments: Vec<String> = arguments.iter().map(|a| a.to_string()).collect();
                write!(f, "{function}({})", arguments.join(", "))
            }
            Scalar::Binary(op, _, left, right) => {
                let op = match op {
                    BinaryOp::Add => "+",
                    BinaryOp::Sub => "-",
                    BinaryOp::Mul => "*",
                    BinaryOp::Div => "/",
                };
                // A product's operands are atoms or products to its left, as the parser reads
                // them; one in parentheses shows them (`Scalar::Paren`).
                match op {
                    "+" | "-" => write!(f, "({left} {op} {right})"),
                    _ => write!(f, "{left} {op} {right}"),
                }
            }
        }
    }
}

/// A loop to suggest for a declaration that has none, from its own names: the input's vector,
/// one for each unknown angle, and the ground's, with the declared lengths (placeholders
/// where there are too few).
fn example_loop(
    params: &Option<(Ident, Vec<SymbolDecl>)>,
    input: &Option<(Ident, Vec<SymbolDecl>)>,
    unknowns: &Option<(Ident, Vec<SymbolDecl>)>,
) -> String {
    let names = |section: &Option<(Ident, Vec<SymbolDecl>)>| -> Vec<String> {
        section
            .as_ref()
            .map(|(_, decls)| decls.iter().map(|d| d.name.to_string()).collect())
            .unwrap_or_default()
    };
    let lengths = names(params);
    let mut length = lengths
        .iter()
        .cloned()
        .chain((1..).map(|k| format!("r{k}")));
    let input = names(input)
        .into_iter()
        .next()
        .unwrap_or_else(|| "theta2".into());
    let mut terms = vec![format!("{} @ {input}", length.next().unwrap_or_default())];
    let angles = names(unknowns);
    let angles = if angles.is_empty() {
        vec!["theta3".to_string(), "theta4".to_string()]
    } else {
        angles
    };
    for (k, angle) in angles.iter().enumerate() {
        let sign = if k == 0 { "+" } else { "-" };
        terms.push(format!(
            "{sign} {} @ {angle}",
            length.next().unwrap_or_default()
        ));
    }
    terms.push(format!("- {} @ 0", length.next().unwrap_or_default()));
    format!("loop: {}", terms.join(" "))
}

#[cfg(test)]
mod tests {
    use super::{number, radians};

    #[test]
    fn degrees_are_reduced_to_a_turn_exactly_before_radians() {
        assert_eq!(radians(1e308), radians(296.0));
        assert_eq!(radians(-1e308), radians(-296.0));
        assert_eq!(radians(720.5), radians(0.5));
        // Within a turn, the same bits as converting directly.
        for degrees in [0.0, 30.0, -90.0, 180.0, 359.999] {
            assert_eq!(radians(degrees), f64::to_radians(degrees));
        }
    }

    #[test]
    fn numbers_too_long_to_read_show_in_scientific_notation() {
        assert_eq!(number(0.5), "0.5");
        assert_eq!(number(180.0), "180");
        assert_eq!(number(1e300), "1e300");
        assert_eq!(number(1e-320), "1e-320");
    }
}
