//! The adversary's oracle: the true kinematics of every shipped mechanism in multiple-precision
//! arithmetic (`astro-float`, pure Rust, 256 bits unless told otherwise), written from
//! KINEMATICS.md and each mechanism's declaration, sharing no code with the generator or the
//! runtime.
//!
//! Dimensions and inputs are the exact `f64` (or `f32`) values a mechanism holds, converted
//! exactly; everything after that is rounded at 256 bits, about 77 digits, so the oracle's own
//! error is far below any float's epsilon even where the problem loses half its digits (a
//! toggle an ulp away).
//!
//! - Single loops (four-bar, slider-crank, inverted slider-crank): closed forms written
//!   independently of `mechgen::closed` (the four-bar's chord by its half-angle form, each
//!   discriminant factored so a thin triangle loses nothing), on the branch each mechanism
//!   documents, with the reach (how far the loop is from closing or opening, in length) and the
//!   margin (how far the input is from the nearest limit angle, by half-angle formulas).
//! - Loop by loop (Watt six-bar, Jansen leg): the same circle–circle closed form per loop.
//! - Every mechanism, the coupled Stephenson six-bar included: the loop equations written out
//!   by hand from its declaration ([`Model`]), and a Newton polish ([`polish`]) of a candidate
//!   on them, which reports whether it converged quadratically, Kantorovich's `h` at the
//!   candidate, and the branch signs of the root it found.
//! - Rates from the same model: `J·q̇ = −∂f/∂input·ω`, and `J·q̈` from the loops' second time
//!   derivative, solved by Gaussian elimination at full precision; κ and the Jacobian's column
//!   norms as the accuracy contract defines them.
//!
//! [`judge`] holds the accuracy contract as checks on mechgen's results against this oracle,
//! and [`draw`] the cases `tests/tests/edges.rs` and `src/bin/edges.rs` run.

use std::cell::{Cell, RefCell};
use std::cmp::Ordering;
use std::ops::{Add, Div, Mul, Neg, Sub};

use astro_float::{BigFloat, Consts, RoundingMode, Sign};
use mechgen::Branch;

const ROUNDING: RoundingMode = RoundingMode::ToEven;

/// The oracle's working precision in bits, unless [`with_precision`] says otherwise.
pub const BITS: usize = 256;

thread_local! {
    static PRECISION: Cell<usize> = const { Cell::new(BITS) };
    static CONSTS: RefCell<Consts> =
        RefCell::new(Consts::new().expect("astro-float's constants cache"));
}

fn bits() -> usize {
    PRECISION.with(Cell::get)
}

/// Runs `f` with the oracle working at `precision` bits (to check that the answers do not move
/// when the precision is raised).
pub fn with_precision<R>(precision: usize, f: impl FnOnce() -> R) -> R {
    let old = PRECISION.with(|p| p.replace(precision));
    let result = f();
    PRECISION.with(|p| p.set(old));
    result
}

// ---------------------------------------------------------------------------------------------
// Numbers

/// A multiple-precision real at the oracle's precision.
#[derive(Clone, Debug)]
pub struct Big(BigFloat);

impl Big {
    /// `x` exactly.
    pub fn from_f64(x: f64) -> Big {
        assert!(x.is_finite(), "the oracle takes finite numbers, not {x}");
        Big(BigFloat::from_f64(x, bits()))
    }

    pub fn zero() -> Big {
        Big::from_f64(0.0)
    }

    pub fn one() -> Big {
        Big::from_f64(1.0)
    }

    /// A decimal number, rounded to the working precision.
    pub fn parse(decimal: &str) -> Big {
        CONSTS.with(|c| {
            Big(BigFloat::parse(
                decimal,
                astro_float::Radix::Dec,
                bits(),
                ROUNDING,
                &mut c.borrow_mut(),
            ))
        })
    }

    /// The nearest `f64` (to within an ulp; ±∞ beyond its range).
    pub fn to_f64(&self) -> f64 {
        if self.0.is_nan() {
            return f64::NAN;
        }
        if self.0.is_inf_pos() {
            return f64::INFINITY;
        }
        if self.0.is_inf_neg() {
            return f64::NEG_INFINITY;
        }
        let Some((words, _, sign, exponent, _)) = self.0.as_raw_parts() else {
            return f64::NAN;
        };
        // The value is 0.m × 2^exponent, the most significant word last.
        let top = words.last().copied().unwrap_or(0);
        if top == 0 {
            return 0.0;
        }
        let magnitude = scale2(top as f64, exponent - 64);
        if sign == Sign::Neg {
            -magnitude
        } else {
            magnitude
        }
    }

    pub fn sqrt(&self) -> Big {
        assert!(!self.is_negative() || self.is_zero(), "√ of a negative");
        Big(self.0.sqrt(bits(), ROUNDING))
    }

    pub fn sin(&self) -> Big {
        CONSTS.with(|c| Big(self.0.sin(bits(), ROUNDING, &mut c.borrow_mut())))
    }

    pub fn cos(&self) -> Big {
        CONSTS.with(|c| Big(self.0.cos(bits(), ROUNDING, &mut c.borrow_mut())))
    }

    pub fn atan(&self) -> Big {
        CONSTS.with(|c| Big(self.0.atan(bits(), ROUNDING, &mut c.borrow_mut())))
    }

    pub fn pi() -> Big {
        CONSTS.with(|c| Big(c.borrow_mut().pi(bits(), ROUNDING)))
    }

    /// The angle of `(x, y)` in (−π, π], from one arc tangent of the smaller ratio.
    pub fn atan2(y: &Big, x: &Big) -> Big {
        if x.is_zero() && y.is_zero() {
            return Big::zero();
        }
        if x.abs() >= y.abs() {
            let angle = (y / x).atan();
            if x.is_negative() {
                if y.is_negative() {
                    angle - Big::pi()
                } else {
                    angle + Big::pi()
                }
            } else {
                angle
            }
        } else {
            let half_pi = Big::pi().half();
            let angle = (x / y).atan();
            if y.is_negative() {
                -half_pi - angle
            } else {
                half_pi - angle
            }
        }
    }

    pub fn abs(&self) -> Big {
        Big(self.0.abs())
    }

    /// Strictly negative.
    pub fn is_negative(&self) -> bool {
        self.0.is_negative() && !self.0.is_zero()
    }

    pub fn is_zero(&self) -> bool {
        self.0.is_zero()
    }

    /// `x/2`, exactly.
    pub fn half(&self) -> Big {
        self * &Big::from_f64(0.5)
    }

    pub fn square(&self) -> Big {
        self * self
    }

    pub fn max(self, other: Big) -> Big {
        if other > self { other } else { self }
    }

    pub fn min(self, other: Big) -> Big {
        if other < self { other } else { self }
    }

    /// `x` wrapped into (−π, π].
    pub fn wrapped(&self) -> Big {
        let pi = Big::pi();
        let tau = &pi + &pi;
        let mut x = self.clone();
        while x > pi {
            x = x - &tau;
        }
        while x <= -&pi {
            x = x + &tau;
        }
        x
    }
}

/// `x·2^k`, without overflowing on the way.
fn scale2(mut x: f64, mut k: i32) -> f64 {
    while k > 1000 {
        x *= 2f64.powi(1000);
        k -= 1000;
    }
    while k < -1000 {
        x *= 2f64.powi(-1000);
        k += 1000;
    }
    x * 2f64.powi(k)
}

impl PartialEq for Big {
    fn eq(&self, other: &Big) -> bool {
        self.0.cmp(&other.0) == Some(0)
    }
}

impl PartialOrd for Big {
    fn partial_cmp(&self, other: &Big) -> Option<Ordering> {
        self.0.cmp(&other.0).map(|c| c.cmp(&0))
    }
}

macro_rules! binary {
    ($trait:ident, $method:ident, $op:ident) => {
        impl $trait<&Big> for &Big {
            type Output = Big;
            fn $method(self, other: &Big) -> Big {
                Big(self.0.$op(&other.0, bits(), ROUNDING))
            }
        }
        impl $trait<Big> for Big {
            type Output = Big;
            fn $method(self, other: Big) -> Big {
                (&self).$method(&other)
            }
        }
        impl $trait<&Big> for Big {
            type Output = Big;
            fn $method(self, other: &Big) -> Big {
                (&self).$method(other)
            }
        }
        impl $trait<Big> for &Big {
            type Output = Big;
            fn $method(self, other: Big) -> Big {
                self.$method(&other)
            }
        }
    };
}

binary!(Add, add, add);
binary!(Sub, sub, sub);
binary!(Mul, mul, mul);
binary!(Div, div, div);

impl Neg for Big {
    type Output = Big;
    fn neg(self) -> Big {
        Big(BigFloat::neg(&self.0))
    }
}

impl Neg for &Big {
    type Output = Big;
    fn neg(self) -> Big {
        Big(BigFloat::neg(&self.0))
    }
}

/// A complex number (a planar vector).
#[derive(Clone, Debug)]
pub struct C {
    pub re: Big,
    pub im: Big,
}

impl C {
    pub fn new(re: Big, im: Big) -> C {
        C { re, im }
    }

    pub fn zero() -> C {
        C::new(Big::zero(), Big::zero())
    }

    /// `e^{iθ}` of an exact angle.
    pub fn expi(theta: &Big) -> C {
        C::new(theta.cos(), theta.sin())
    }

    pub fn add(&self, o: &C) -> C {
        C::new(&self.re + &o.re, &self.im + &o.im)
    }

    pub fn sub(&self, o: &C) -> C {
        C::new(&self.re - &o.re, &self.im - &o.im)
    }

    pub fn mul(&self, o: &C) -> C {
        C::new(
            &self.re * &o.re - &self.im * &o.im,
            &self.re * &o.im + &self.im * &o.re,
        )
    }

    pub fn scale(&self, s: &Big) -> C {
        C::new(&self.re * s, &self.im * s)
    }

    /// `i·z`.
    pub fn turn(&self) -> C {
        C::new(-&self.im, self.re.clone())
    }

    pub fn norm2(&self) -> Big {
        self.re.square() + self.im.square()
    }

    pub fn norm(&self) -> Big {
        self.norm2().sqrt()
    }

    /// `x1·y2 − y1·x2`.
    pub fn cross(&self, o: &C) -> Big {
        &self.re * &o.im - &self.im * &o.re
    }

    pub fn dot(&self, o: &C) -> Big {
        &self.re * &o.re + &self.im * &o.im
    }

    pub fn angle(&self) -> Big {
        Big::atan2(&self.im, &self.re)
    }
}

// ---------------------------------------------------------------------------------------------
// The loop model

/// A variable of a mechanism: its input, or one of its unknowns (by index).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Var {
    Input,
    Unknown(usize),
}

/// The magnitude of a loop vector: a fixed length, or an unknown length.
#[derive(Clone, Debug)]
pub enum Magnitude {
    Fixed(Big),
    Unknown(usize),
}

/// One vector `±r @ (var + offset)` of a loop or a point, as the declaration writes it.
#[derive(Clone, Debug)]
pub struct Term {
    pub negative: bool,
    pub magnitude: Magnitude,
    /// The variable angle the vector turns with, if any.
    pub angle: Option<Var>,
    /// `e^{i·offset}` of the constant part of the angle.
    pub offset: C,
}

/// `±r @ (var + offset)`.
fn term(negative: bool, magnitude: Magnitude, angle: Option<Var>, offset: C) -> Term {
    Term {
        negative,
        magnitude,
        angle,
        offset,
    }
}

fn fixed(x: f64) -> Magnitude {
    Magnitude::Fixed(Big::from_f64(x))
}

/// `e^{i·0}`.
fn along_x() -> C {
    C::new(Big::one(), Big::zero())
}

/// `e^{i·π/2}`, exactly.
fn along_y() -> C {
    C::new(Big::zero(), Big::one())
}

fn direction(angle: f64) -> C {
    C::expi(&Big::from_f64(angle))
}

/// Which mechanism a model or case is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Kind {
    FourBar,
    SliderCrank,
    InvertedSliderCrank,
    WattSixBar,
    StephensonSixBar,
    JansenLeg,
}

impl Kind {
    pub const ALL: [Kind; 6] = [
        Kind::FourBar,
        Kind::SliderCrank,
        Kind::InvertedSliderCrank,
        Kind::WattSixBar,
        Kind::StephensonSixBar,
        Kind::JansenLeg,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Kind::FourBar => "four-bar",
            Kind::SliderCrank => "slider-crank",
            Kind::InvertedSliderCrank => "inverted slider-crank",
            Kind::WattSixBar => "Watt six-bar",
            Kind::StephensonSixBar => "Stephenson six-bar",
            Kind::JansenLeg => "Jansen leg",
        }
    }

    /// How many loops, so how many branches.
    pub fn loops(self) -> usize {
        match self {
            Kind::FourBar | Kind::SliderCrank | Kind::InvertedSliderCrank => 1,
            Kind::WattSixBar | Kind::StephensonSixBar => 2,
            Kind::JansenLeg => 3,
        }
    }

    pub fn unknowns(self) -> usize {
        2 * self.loops()
    }
}

/// A mechanism's parameters by name, as it holds them (read from its `Debug` output, so the
/// derived ones, such as a six-bar's pivot distance and direction or the Jansen leg's triangle
/// angles, are the values it computed).
#[derive(Clone, Debug, Default)]
pub struct Params(pub Vec<(String, f64)>);

impl Params {
    /// The parameters in a mechanism's `Debug` output (`Name { l1: 1.0, l2: … }`), each parsed
    /// as the float type `T` it was printed from, which round-trips it exactly.
    pub fn from_debug<T: std::str::FromStr + Into<f64>>(debug: &str) -> Params {
        let inner = debug
            .split_once('{')
            .and_then(|(_, rest)| rest.rsplit_once('}'))
            .map_or("", |(inner, _)| inner);
        Params(
            inner
                .split(',')
                .filter_map(|field| {
                    let (name, value) = field.split_once(':')?;
                    let value: T = value.trim().parse().ok()?;
                    Some((name.trim().to_string(), value.into()))
                })
                .collect(),
        )
    }

    /// The parameter `name`, or `default` where it is not given (a coupler point's).
    pub fn get_or(&self, name: &str, default: f64) -> f64 {
        self.0
            .iter()
            .find(|(n, _)| n == name)
            .map_or(default, |(_, v)| *v)
    }

    pub fn get(&self, name: &str) -> f64 {
        self.0
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, v)| *v)
            .unwrap_or_else(|| panic!("no parameter {name} in {:?}", self.0))
    }
}

/// A mechanism's loops and tracked points, written out by hand from its `mechanism!`
/// declaration, with the loops' length parameters (whose sum is its size).
#[derive(Clone, Debug)]
pub struct Model {
    pub kind: Kind,
    pub loops: Vec<Vec<Term>>,
    /// Which unknowns are angles (the others are lengths).
    pub angles: Vec<bool>,
    /// The tracked points the scenes return, by name.
    pub points: Vec<(&'static str, Vec<Term>)>,
    /// The mechanism's size: the sum of the loops' length parameters, each counted once.
    pub size: f64,
}

impl Model {
    /// The model of a `kind` holding `p`.
    pub fn new(kind: Kind, p: &Params) -> Model {
        use Var::{Input, Unknown as U};
        let x = along_x;
        let m = |name: &str| fixed(p.get(name));
        let lengths = |names: &[&str]| names.iter().map(|n| p.get(n).abs()).sum::<f64>();
        match kind {
            Kind::FourBar => Model {
                kind,
                // l2 @ theta2 + l3 @ theta3 - l4 @ theta4 - l1 @ 0
                loops: vec![vec![
                    term(false, m("l2"), Some(Input), x()),
                    term(false, m("l3"), Some(U(0)), x()),
                    term(true, m("l4"), Some(U(1)), x()),
                    term(true, m("l1"), None, x()),
                ]],
                angles: vec![true, true],
                points: vec![
                    ("crank_pin", vec![term(false, m("l2"), Some(Input), x())]),
                    (
                        "rocker_pin",
                        vec![
                            term(false, m("l1"), None, x()),
                            term(false, m("l4"), Some(U(1)), x()),
                        ],
                    ),
                    (
                        "coupler_point",
                        vec![
                            term(false, m("l2"), Some(Input), x()),
                            term(
                                false,
                                fixed(p.get_or("a", 0.0)),
                                Some(U(0)),
                                direction(p.get_or("delta", 0.0)),
                            ),
                        ],
                    ),
                ],
                size: lengths(&["l1", "l2", "l3", "l4"]),
            },
            Kind::SliderCrank => Model {
                kind,
                // l2 @ theta2 + l3 @ theta3 - c @ pi / 2 - d @ 0
                loops: vec![vec![
                    term(false, m("l2"), Some(Input), x()),
                    term(false, m("l3"), Some(U(0)), x()),
                    term(true, m("c"), None, along_y()),
                    term(true, Magnitude::Unknown(1), None, x()),
                ]],
                angles: vec![true, false],
                points: vec![],
                size: lengths(&["l2", "l3", "c"]),
            },
            Kind::InvertedSliderCrank => Model {
                kind,
                // l2 @ theta2 - b @ (theta4 + gamma) - c @ theta4 - l1 @ 0
                loops: vec![vec![
                    term(false, m("l2"), Some(Input), x()),
                    term(
                        true,
                        Magnitude::Unknown(1),
                        Some(U(0)),
                        direction(p.get("gamma")),
                    ),
                    term(true, m("c"), Some(U(0)), x()),
                    term(true, m("l1"), None, x()),
                ]],
                angles: vec![true, false],
                points: vec![],
                size: lengths(&["l1", "l2", "c"]),
            },
            Kind::WattSixBar => Model {
                kind,
                loops: vec![
                    // l2 @ theta2 + l3 @ theta3 - l4 @ theta4 - l1 @ 0
                    vec![
                        term(false, m("l2"), Some(Input), x()),
                        term(false, m("l3"), Some(U(0)), x()),
                        term(true, m("l4"), Some(U(1)), x()),
                        term(true, m("l1"), None, x()),
                    ],
                    // l1 @ 0 + l5 @ (theta4 + beta) + l6 @ theta5 - l7 @ theta6 - g @ phi
                    vec![
                        term(false, m("l1"), None, x()),
                        term(false, m("l5"), Some(U(1)), direction(p.get("beta"))),
                        term(false, m("l6"), Some(U(2)), x()),
                        term(true, m("l7"), Some(U(3)), x()),
                        term(true, m("g"), None, direction(p.get("phi"))),
                    ],
                ],
                angles: vec![true; 4],
                points: vec![],
                size: lengths(&["l1", "l2", "l3", "l4", "l5", "l6", "l7", "g"]),
            },
            Kind::StephensonSixBar => Model {
                kind,
                loops: vec![
                    // l2 @ theta2 + l3 @ theta3 + bc @ theta5 - l4 @ theta4 - l1 @ 0
                    vec![
                        term(false, m("l2"), Some(Input), x()),
                        term(false, m("l3"), Some(U(0)), x()),
                        term(false, m("bc"), Some(U(2)), x()),
                        term(true, m("l4"), Some(U(1)), x()),
                        term(true, m("l1"), None, x()),
                    ],
                    // l1 @ 0 + l4 @ theta4 + cd @ (theta5 + beta) - l6 @ theta6 - g @ phi
                    vec![
                        term(false, m("l1"), None, x()),
                        term(false, m("l4"), Some(U(1)), x()),
                        term(false, m("cd"), Some(U(2)), direction(p.get("beta"))),
                        term(true, m("l6"), Some(U(3)), x()),
                        term(true, m("g"), None, direction(p.get("phi"))),
                    ],
                ],
                angles: vec![true; 4],
                points: vec![],
                size: lengths(&["l1", "l2", "l3", "bc", "cd", "l4", "l6", "g"]),
            },
            Kind::JansenLeg => {
                // Unknowns phi_j, phi_b, phi_k, phi_c, phi_f, phi_g.
                let base = || {
                    vec![
                        term(true, m("a"), None, x()),
                        term(true, m("l"), None, along_y()),
                    ]
                };
                let mut foot = base();
                foot.push(term(false, m("c"), Some(U(3)), x()));
                foot.push(term(false, m("i"), Some(U(5)), direction(p.get("delta2"))));
                Model {
                    kind,
                    loops: vec![
                        // m @ theta + j @ phi_j - b @ phi_b + a @ 0 + l @ pi / 2
                        vec![
                            term(false, m("m"), Some(Input), x()),
                            term(false, m("j"), Some(U(0)), x()),
                            term(true, m("b"), Some(U(1)), x()),
                            term(false, m("a"), None, x()),
                            term(false, m("l"), None, along_y()),
                        ],
                        // m @ theta + k @ phi_k - c @ phi_c + a @ 0 + l @ pi / 2
                        vec![
                            term(false, m("m"), Some(Input), x()),
                            term(false, m("k"), Some(U(2)), x()),
                            term(true, m("c"), Some(U(3)), x()),
                            term(false, m("a"), None, x()),
                            term(false, m("l"), None, along_y()),
                        ],
                        // d @ (phi_b + delta1) + f @ phi_f - c @ phi_c - g @ phi_g
                        vec![
                            term(false, m("d"), Some(U(1)), direction(p.get("delta1"))),
                            term(false, m("f"), Some(U(4)), x()),
                            term(true, m("c"), Some(U(3)), x()),
                            term(true, m("g"), Some(U(5)), x()),
                        ],
                    ],
                    angles: vec![true; 6],
                    points: vec![("foot", foot)],
                    size: lengths(&["m", "j", "b", "k", "c", "a", "l", "d", "f", "g"]),
                }
            }
        }
    }

    pub fn unknowns(&self) -> usize {
        self.angles.len()
    }

    /// The sum of each loop's vector magnitudes at a state: the size of the numbers whose
    /// rounding bounds how small that loop's residual can get.
    pub fn loop_magnitudes(&self, state: &State) -> Vec<Big> {
        self.loops
            .iter()
            .map(|terms| {
                terms
                    .iter()
                    .map(|t| state.magnitude(t).abs())
                    .fold(Big::zero(), |a, b| a + b)
            })
            .collect()
    }
}

/// Values of a mechanism's variables: the input and the unknowns, with `e^{iθ}` of each angle.
#[derive(Clone, Debug)]
pub struct State {
    pub input: Big,
    pub input_direction: C,
    pub q: Vec<Big>,
    /// `e^{iq}` for angle unknowns, `None` for lengths.
    pub directions: Vec<Option<C>>,
}

impl State {
    /// A state from values, computing each angle's direction.
    pub fn new(model: &Model, input: Big, q: Vec<Big>) -> State {
        let directions = q
            .iter()
            .zip(&model.angles)
            .map(|(v, &angle)| angle.then(|| C::expi(v)))
            .collect();
        State {
            input_direction: C::expi(&input),
            input,
            q,
            directions,
        }
    }

    /// A state from `f64` values.
    pub fn from_f64(model: &Model, input: f64, q: &[f64]) -> State {
        State::new(
            model,
            Big::from_f64(input),
            q.iter().map(|v| Big::from_f64(*v)).collect(),
        )
    }

    fn variable_direction(&self, var: Var) -> &C {
        match var {
            Var::Input => &self.input_direction,
            Var::Unknown(j) => self.directions[j]
                .as_ref()
                .expect("an angle unknown has a direction"),
        }
    }

    fn magnitude(&self, t: &Term) -> Big {
        match &t.magnitude {
            Magnitude::Fixed(r) => r.clone(),
            Magnitude::Unknown(j) => self.q[*j].clone(),
        }
    }

    /// `e^{iφ}` of a term's whole angle.
    fn direction(&self, t: &Term) -> C {
        match t.angle {
            Some(var) => self.variable_direction(var).mul(&t.offset),
            None => t.offset.clone(),
        }
    }

    /// The signed vector `±r·e^{iφ}` of a term.
    fn vector(&self, t: &Term) -> C {
        let v = self.direction(t).scale(&self.magnitude(t));
        if t.negative { C::new(-v.re, -v.im) } else { v }
    }

    fn sum(&self, terms: &[Term]) -> C {
        terms
            .iter()
            .fold(C::zero(), |acc, t| acc.add(&self.vector(t)))
    }
}

/// A dense real matrix, row-major.
type Matrix = Vec<Vec<Big>>;

/// The loop residual, one complex number per loop.
pub fn residual(model: &Model, state: &State) -> Vec<C> {
    model.loops.iter().map(|terms| state.sum(terms)).collect()
}

/// `∂(Σ terms)/∂var` as a complex number, for the terms of one loop or point.
fn partial(state: &State, terms: &[Term], var: Var) -> C {
    terms.iter().fold(C::zero(), |acc, t| {
        let sign = |v: C| {
            if t.negative { C::new(-v.re, -v.im) } else { v }
        };
        let mut d = C::zero();
        if t.angle == Some(var) {
            d = d.add(&sign(state.direction(t).scale(&state.magnitude(t)).turn()));
        }
        if let (Magnitude::Unknown(j), Var::Unknown(k)) = (&t.magnitude, var) {
            if *j == k {
                d = d.add(&sign(state.direction(t)));
            }
        }
        acc.add(&d)
    })
}

/// The Jacobian of the residual (x and y rows of each loop) with respect to the unknowns.
pub fn jacobian(model: &Model, state: &State) -> Matrix {
    let n = model.unknowns();
    let mut rows = Vec::with_capacity(2 * model.loops.len());
    for terms in &model.loops {
        let columns: Vec<C> = (0..n)
            .map(|j| partial(state, terms, Var::Unknown(j)))
            .collect();
        rows.push(columns.iter().map(|c| c.re.clone()).collect());
        rows.push(columns.iter().map(|c| c.im.clone()).collect());
    }
    rows
}

/// The residual's derivative with respect to the input.
fn input_column(model: &Model, state: &State) -> Vec<Big> {
    model
        .loops
        .iter()
        .flat_map(|terms| {
            let d = partial(state, terms, Var::Input);
            [d.re, d.im]
        })
        .collect()
}

/// A variable's rate and acceleration.
fn rates_of(var: Var, input: (&Big, &Big), q_dot: &[Big], q_ddot: &[Big]) -> (Big, Big) {
    match var {
        Var::Input => (input.0.clone(), input.1.clone()),
        Var::Unknown(j) => (q_dot[j].clone(), q_ddot[j].clone()),
    }
}

/// The first and second time derivatives of `Σ terms`, given the variables' rates and
/// accelerations: `d/dt(r e^{iφ}) = (ṙ + i r φ̇) e^{iφ}` and
/// `d²/dt²(r e^{iφ}) = (r̈ − r φ̇²) e^{iφ} + i (r φ̈ + 2 ṙ φ̇) e^{iφ}`.
fn derivatives(
    state: &State,
    terms: &[Term],
    input: (&Big, &Big),
    q_dot: &[Big],
    q_ddot: &[Big],
) -> (C, C) {
    let mut first = C::zero();
    let mut second = C::zero();
    for t in terms {
        let r = state.magnitude(t);
        let (r_dot, r_ddot) = match t.magnitude {
            Magnitude::Fixed(_) => (Big::zero(), Big::zero()),
            Magnitude::Unknown(j) => (q_dot[j].clone(), q_ddot[j].clone()),
        };
        let (w, a) = match t.angle {
            Some(var) => rates_of(var, input, q_dot, q_ddot),
            None => (Big::zero(), Big::zero()),
        };
        let e = state.direction(t);
        let d1 = e.mul(&C::new(r_dot.clone(), &r * &w));
        let d2 = e.mul(&C::new(
            r_ddot - &r * &w.square(),
            &r * &a + (&r_dot + &r_dot) * &w,
        ));
        if t.negative {
            first = first.sub(&d1);
            second = second.sub(&d2);
        } else {
            first = first.add(&d1);
            second = second.add(&d2);
        }
    }
    (first, second)
}

/// Solves `a·x = b` by Gaussian elimination with partial pivoting; returns `x` and `det a`, or
/// `None` where `a` is exactly singular.
pub fn solve(mut a: Matrix, mut b: Vec<Big>) -> Option<(Vec<Big>, Big)> {
    let n = b.len();
    let mut det = Big::one();
    for k in 0..n {
        let pivot = (k..n)
            .max_by(|&i, &j| a[i][k].abs().partial_cmp(&a[j][k].abs()).unwrap())
            .unwrap();
        if a[pivot][k].is_zero() {
            return None;
        }
        if pivot != k {
            a.swap(pivot, k);
            b.swap(pivot, k);
            det = -det;
        }
        det = det * &a[k][k];
        for i in k + 1..n {
            let factor = &a[i][k] / &a[k][k];
            for j in k..n {
                let v = &a[i][j] - &factor * &a[k][j];
                a[i][j] = v;
            }
            let v = &b[i] - &factor * &b[k];
            b[i] = v;
        }
    }
    let mut x = vec![Big::zero(); n];
    for k in (0..n).rev() {
        let mut sum = b[k].clone();
        for j in k + 1..n {
            sum = sum - &a[k][j] * &x[j];
        }
        x[k] = sum / &a[k][k];
    }
    Some((x, det))
}

fn column_norms(j: &Matrix) -> Vec<Big> {
    let n = j.first().map_or(0, Vec::len);
    (0..n)
        .map(|c| {
            j.iter()
                .fold(Big::zero(), |acc, row| acc + row[c].square())
                .sqrt()
        })
        .collect()
}

/// A solved position with everything the contract measures it by.
#[derive(Clone, Debug)]
pub struct Truth {
    pub state: State,
    /// Rates and accelerations for the input's rate and acceleration; `None` where the
    /// Jacobian is exactly singular.
    pub velocity: Option<Vec<Big>>,
    pub acceleration: Option<Vec<Big>>,
    pub omega: f64,
    pub alpha: f64,
    /// The norms of the Jacobian's columns: how far the loops move per unit of each unknown.
    pub columns: Vec<f64>,
    /// `κ = Π‖column‖ / |det J|` (infinite where singular).
    pub condition: f64,
    /// The branch of each loop, by the signs each mechanism documents (where it has them).
    pub branches: Vec<Branch>,
    /// Those signs' values, each relative to its own scale (a sine): how far from the other
    /// branch.
    pub branch_signs: Vec<f64>,
}

impl Truth {
    /// `ρ = size / min‖column‖`, at least 1: the contract's aspect.
    pub fn aspect(&self, size: f64) -> f64 {
        (size / self.columns.iter().fold(f64::INFINITY, |m, c| m.min(*c))).max(1.0)
    }

    pub fn q(&self) -> &[Big] {
        &self.state.q
    }
}

/// Completes a solved state: columns, κ, rates and accelerations, branch signs.
pub fn complete(model: &Model, state: State, omega: f64, alpha: f64) -> Truth {
    let j = jacobian(model, &state);
    let columns = column_norms(&j);
    let n = model.unknowns();
    let (w, a) = (Big::from_f64(omega), Big::from_f64(alpha));
    let rhs: Vec<Big> = input_column(model, &state)
        .iter()
        .map(|v| -(v * &w))
        .collect();
    let mut velocity = None;
    let mut acceleration = None;
    let mut condition = f64::INFINITY;
    if let Some((v, det)) = solve(j.clone(), rhs) {
        let product = columns.iter().fold(Big::one(), |acc, c| acc * c);
        condition = (product / det.abs()).to_f64();
        // J·q̈ = −(the second derivative with q̈ = 0).
        let zero = vec![Big::zero(); n];
        let rhs: Vec<Big> = model
            .loops
            .iter()
            .flat_map(|terms| {
                let (_, second) = derivatives(&state, terms, (&w, &a), &v, &zero);
                [-second.re, -second.im]
            })
            .collect();
        acceleration = solve(j, rhs).map(|(x, _)| x);
        velocity = Some(v);
    }
    let (branches, branch_signs) = branch_signs(model, &state);
    Truth {
        state,
        velocity,
        acceleration,
        omega,
        alpha,
        columns: columns.iter().map(Big::to_f64).collect(),
        condition,
        branches,
        branch_signs,
    }
}

/// `sin(b − a)` from `e^{ia}` and `e^{ib}`.
fn sine_between(a: &C, b: &C) -> Big {
    a.cross(b)
}

/// The branch of each loop at a state by the sign each mechanism documents, and that sign's
/// value as a sine (or cosine): `≥ 0` is open.
///
/// - four-bar (and the Watt six-bar's first loop): `sin(θ4 − θ3)`;
/// - slider-crank: `cos θ3`;
/// - inverted slider-crank: `b + c·cos γ`, relative to `|b·e^{iγ} + c|`;
/// - Watt six-bar, second loop: `sin(θ6 − θ5)` (`cross(−K, l6·e^{iθ5})` of the generated
///   docs, with `−K = l6·e^{iθ5} − l7·e^{iθ6}`);
/// - Jansen leg: `sin(φb − φj)`, `sin(φc − φk)`, `sin(φg − φf)` (the same for its loops);
/// - Stephenson six-bar (no closed form, so no documented branches): the sides B takes of
///   A → C and D of C → O6, `cross(C − A, B − A)` and `cross(O6 − C, D − C)`, each over the
///   product of the two lengths.
pub fn branch_signs(model: &Model, state: &State) -> (Vec<Branch>, Vec<f64>) {
    let d = |j: usize| state.directions[j].clone().expect("an angle");
    let signs: Vec<Big> = match model.kind {
        Kind::FourBar => vec![sine_between(&d(0), &d(1))],
        Kind::SliderCrank => vec![d(0).re],
        Kind::InvertedSliderCrank => {
            let t = &model.loops[0][1];
            let c = match &model.loops[0][2].magnitude {
                Magnitude::Fixed(c) => c.clone(),
                Magnitude::Unknown(_) => unreachable!(),
            };
            let b = &state.q[1];
            let w = t.offset.scale(b).add(&C::new(c.clone(), Big::zero()));
            let norm = w.norm();
            let sign = b + &c * &t.offset.re;
            vec![if norm.is_zero() { sign } else { sign / norm }]
        }
        Kind::WattSixBar => vec![sine_between(&d(0), &d(1)), sine_between(&d(2), &d(3))],
        Kind::JansenLeg => vec![
            sine_between(&d(0), &d(1)),
            sine_between(&d(2), &d(3)),
            sine_between(&d(4), &d(5)),
        ],
        Kind::StephensonSixBar => {
            // Points from the loops' vectors: A = l2 @ θ2, B = A + l3 @ θ3, C = O4 + l4 @ θ4,
            // D = C + cd @ (θ5 + β), O6 = g @ φ.
            let first = &model.loops[0];
            let second = &model.loops[1];
            let a = state.vector(&first[0]);
            let b = a.add(&state.vector(&first[1]));
            let o4 = C::new(state.magnitude(&first[4]), Big::zero());
            let c = o4.add(&state.vector(&second[1]));
            let dd = c.add(&state.vector(&second[2]));
            let o6 = state.vector(&second[4]);
            let o6 = C::new(-o6.re, -o6.im);
            let side = |p: &C, q: &C, r: &C| {
                let (u, v) = (q.sub(p), r.sub(p));
                let norms = u.norm() * v.norm();
                let cross = u.cross(&v);
                if norms.is_zero() {
                    cross
                } else {
                    cross / norms
                }
            };
            vec![side(&a, &c, &b), side(&c, &o6, &dd)]
        }
    };
    let branches = signs
        .iter()
        .map(|s| {
            if s.is_negative() {
                Branch::Crossed
            } else {
                Branch::Open
            }
        })
        .collect();
    (branches, signs.iter().map(Big::to_f64).collect())
}

/// A tracked point's position, velocity and acceleration at a truth.
pub fn point(model: &Model, truth: &Truth, name: &str) -> Option<[C; 3]> {
    let terms = &model.points.iter().find(|(n, _)| *n == name)?.1;
    let (w, a) = (Big::from_f64(truth.omega), Big::from_f64(truth.alpha));
    let position = truth.state.sum(terms);
    let (v, acc) = (truth.velocity.as_ref()?, truth.acceleration.as_ref()?);
    let (first, second) = derivatives(&truth.state, terms, (&w, &a), v, acc);
    Some([position, first, second])
}

// ---------------------------------------------------------------------------------------------
// Reach: whether a loop closes, and how far from a limit

/// Whether the loops close at an input, and by how much.
#[derive(Clone, Copy, Debug)]
pub struct Reach {
    /// The smallest of the loops' gaps (how much longer the shortest way round could be, or
    /// the longest shorter, before the loop stops closing), over the mechanism's size: `≥ 0`
    /// where the loops close.
    pub gap: f64,
    /// How much that gap can move, over the size, per unit relative perturbation of every
    /// length and of the input: a gap within `η·slack` of zero is within rounding `η` of a
    /// limit, where either answer is right.
    pub slack: f64,
    /// The input's signed distance to the nearest limit angle, radians (positive inside the
    /// range of motion); infinite where the crank turns fully.
    pub margin: f64,
}

impl Reach {
    pub fn reachable(&self) -> bool {
        self.gap >= 0.0
    }

    /// Within relative rounding `eta` of a limit.
    pub fn near_limit(&self, eta: f64) -> bool {
        self.gap.abs() <= eta * self.slack
    }
}

/// Two circles meeting: `P1 = r1·e^{iq1}` and `P2 = −r2·e^{iq2}` span the chord `v`
/// (`P1 + P2 = v`). Returns `(e^{iq1}, e^{iq2})` on the branch `sign` (`cross(v, P1)`'s sign),
/// and the gap `min(r1 + r2 − |v|, |v| − |r1 − r2|)`: negative where they cannot meet.
fn dyad(v: &C, span2: &Big, r1: &Big, r2: &Big, sign: f64) -> (Option<(C, C)>, Big) {
    let span = span2.sqrt();
    let sum = r1 + r2;
    let difference = (r1 - r2).abs();
    let gap = (&sum - &span).min(&span - &difference);
    if gap.is_negative() || span.is_zero() {
        return (None, gap);
    }
    // 4·|v|²·h² = ((r1 + r2)² − |v|²)(|v|² − (r1 − r2)²), each factor a product of exact-ish
    // differences, so a thin triangle loses nothing.
    let h2 = (&sum - &span) * (&sum + &span) * (&span - &difference) * (&span + &difference);
    let two_span = &span + &span;
    let mut h = h2.sqrt() / &two_span;
    if sign < 0.0 {
        h = -h;
    }
    let along = (r1.square() - r2.square() + span2) / &two_span;
    let unit = v.scale(&(Big::one() / &span));
    let p1 = unit.scale(&along).add(&unit.turn().scale(&h));
    let e1 = p1.scale(&(Big::one() / r1));
    let e2 = p1.sub(v).scale(&(Big::one() / r2));
    (Some((e1, e2)), gap)
}

/// `2·atan2(√s, √c)`: an angle from its half-angle's squared sine and cosine (up to a common
/// factor), well conditioned at 0 and π alike.
fn from_half_squares(s: &Big, c: &Big) -> Big {
    let a = Big::atan2(&s.sqrt(), &c.sqrt());
    &a + &a
}

/// The signed distance from `x` to the nearest of `limits` (mod 2π), positive if `inside`.
fn margin(x: &Big, limits: &[Big], inside: bool) -> f64 {
    let distance = limits
        .iter()
        .map(|l| (x - l).wrapped().abs())
        .fold(None::<Big>, |m, d| Some(m.map_or(d.clone(), |m| m.min(d))));
    match distance {
        None => f64::INFINITY,
        Some(d) => {
            let d = d.to_f64();
            if inside { d } else { -d }
        }
    }
}

/// The outcome of a closed-form oracle: the reach, and the truth on the asked branch and on the
/// other (where the loops close).
#[derive(Clone, Debug)]
pub struct Outcome {
    pub model: Model,
    pub reach: Reach,
    pub truth: Option<Truth>,
    /// The same input on the other branch of the last loop whose branch matters most (for one
    /// loop, simply the other branch): near a toggle, where the two meet, either is right.
    pub others: Vec<Truth>,
}

fn branch_sign(b: Branch) -> f64 {
    match b {
        Branch::Open => 1.0,
        Branch::Crossed => -1.0,
    }
}

/// `|A − O4|²` and `A − O4` for a crank `l2` at `θ2` about O2 and a pivot O4 = (l1, 0), by the
/// half-angle form `(l1 − l2)² + 4·l1·l2·sin²(θ2/2)`, exact where the crank folds onto the
/// ground.
fn crank_chord(l1: &Big, l2: &Big, theta2: &Big) -> (C, Big) {
    let half = theta2.half().sin();
    let two_half2 = half.square() + half.square();
    // O4 − A = (l1 − l2·cos θ2, −l2·sin θ2), with 1 − cos θ2 = 2 sin²(θ2/2).
    let v = C::new(l1 - l2 + l2 * &two_half2, -(l2 * theta2.sin()));
    let span2 = (l1 - l2).square() + (l1 * l2) * (&two_half2 + &two_half2);
    (v, span2)
}

/// The four-bar `[l1, l2, l3, l4]` at `θ2` on `branch`.
pub fn four_bar(p: &Params, theta2: f64, branch: Branch, omega: f64, alpha: f64) -> Outcome {
    let model = Model::new(Kind::FourBar, p);
    let [l1, l2, l3, l4] = ["l1", "l2", "l3", "l4"].map(|n| Big::from_f64(p.get(n)));
    let t = Big::from_f64(theta2);
    let (v, span2) = crank_chord(&l1, &l2, &t);
    let solve_on = |b: Branch| {
        let (directions, gap) = dyad(&v, &span2, &l3, &l4, branch_sign(b));
        let truth = directions.map(|(e3, e4)| {
            let state = State {
                input: t.clone(),
                input_direction: C::expi(&t),
                q: vec![e3.angle(), e4.angle()],
                directions: vec![Some(e3), Some(e4)],
            };
            complete(&model, state, omega, alpha)
        });
        (truth, gap)
    };
    let (truth, gap) = solve_on(branch);
    let others = solve_on(branch.other()).0.into_iter().collect();
    // Limits where the chord |O4 − A| equals l3 + l4 or |l3 − l4|:
    // sin²(θ/2) = (r² − (l1 − l2)²)/(4 l1 l2), cos²(θ/2) = ((l1 + l2)² − r²)/(4 l1 l2).
    let mut limits = Vec::new();
    for reach in [&l3 + &l4, (&l3 - &l4).abs()] {
        let s = (&reach - (&l1 - &l2).abs()) * (&reach + (&l1 - &l2).abs());
        let c = (&l1 + &l2 - &reach) * (&l1 + &l2 + &reach);
        if !s.is_negative() && !c.is_negative() && !s.is_zero() && !c.is_zero() {
            let a = from_half_squares(&s, &c);
            limits.push(-&a);
            limits.push(a);
        }
    }
    let size = model.size;
    // The gap moves by at most η(l1 + l2 + l3 + l4) + η·l2·|θ2| when every length moves by η
    // relative and the input by η·|θ2|.
    let slack = (size + p.get("l2") * theta2.abs()) / size;
    let reach = Reach {
        gap: gap.to_f64() / size,
        slack,
        margin: margin(&t, &limits, !gap.is_negative()),
    };
    Outcome {
        model,
        reach,
        truth,
        others,
    }
}

/// The slider-crank `[l2, l3, c]` at `θ2` on `branch`: `sin θ3 = (c − l2·sin θ2)/l3`,
/// `cos θ3 = σ·√(1 − sin² θ3)` (σ = +1 open), `d = l2·cos θ2 + l3·cos θ3`.
pub fn slider_crank(p: &Params, theta2: f64, branch: Branch, omega: f64, alpha: f64) -> Outcome {
    let model = Model::new(Kind::SliderCrank, p);
    let [l2, l3, c] = ["l2", "l3", "c"].map(|n| Big::from_f64(p.get(n)));
    let t = Big::from_f64(theta2);
    let (s2, c2) = (t.sin(), t.cos());
    let rise = &c - &l2 * &s2;
    let gap = &l3 - rise.abs();
    let solve_on = |b: Branch| {
        if gap.is_negative() {
            return None;
        }
        let mut cos3 = ((&l3 - &rise) * (&l3 + &rise)).sqrt() / &l3;
        if b == Branch::Crossed {
            cos3 = -cos3;
        }
        let e3 = C::new(cos3, &rise / &l3);
        let d = &l2 * &c2 + &l3 * &e3.re;
        let state = State {
            input: t.clone(),
            input_direction: C::new(c2.clone(), s2.clone()),
            q: vec![e3.angle(), d],
            directions: vec![Some(e3), None],
        };
        Some(complete(&model, state, omega, alpha))
    };
    // Limits where sin θ2 = (c ∓ l3)/l2, each at asin and π − asin.
    let mut limits = Vec::new();
    for edge in [&c - &l3, &c + &l3] {
        let s = &edge / &l2;
        if s.abs() < Big::one() {
            let a = Big::atan2(&s, &(Big::one() - s.square()).sqrt());
            limits.push(Big::pi() - &a);
            limits.push(a);
        }
    }
    let size = model.size;
    let slack = (size + p.get("l2") * theta2.abs()) / size;
    let reach = Reach {
        gap: gap.to_f64() / size,
        slack,
        margin: margin(&t, &limits, !gap.is_negative()),
    };
    Outcome {
        truth: solve_on(branch),
        others: solve_on(branch.other()).into_iter().collect(),
        model,
        reach,
    }
}

/// The inverted slider-crank `[l1, l2, c, γ]` at `θ2` on `branch`: with `R = A − O4`,
/// `b = −c·cos γ + σ·√(|R|² − c²·sin² γ)` and `θ4 = arg R − arg(b·e^{iγ} + c)`.
pub fn inverted_slider_crank(
    p: &Params,
    theta2: f64,
    branch: Branch,
    omega: f64,
    alpha: f64,
) -> Outcome {
    let model = Model::new(Kind::InvertedSliderCrank, p);
    let [l1, l2, c, gamma] = ["l1", "l2", "c", "gamma"].map(|n| Big::from_f64(p.get(n)));
    let t = Big::from_f64(theta2);
    let (v, span2) = crank_chord(&l1, &l2, &t);
    let r = C::new(-v.re.clone(), -v.im.clone());
    let (sg, cg) = (gamma.sin(), gamma.cos());
    let offset = (&c * &sg).abs();
    let span = span2.sqrt();
    let gap = &span - &offset;
    let solve_on = |b: Branch| {
        if gap.is_negative() {
            return None;
        }
        let mut root = ((&span - &offset) * (&span + &offset)).sqrt();
        if b == Branch::Crossed {
            root = -root;
        }
        let length = &root - &c * &cg;
        let w = C::new(&length * &cg + &c, &length * &sg);
        if w.norm2().is_zero() {
            return None;
        }
        // e^{iθ4} = R·conj(w)/|w|², |R| = |w|.
        let e4 = r
            .mul(&C::new(w.re.clone(), -w.im.clone()))
            .scale(&(Big::one() / w.norm2()));
        let state = State {
            input: t.clone(),
            input_direction: C::expi(&t),
            q: vec![e4.angle(), length],
            directions: vec![Some(e4), None],
        };
        Some(complete(&model, state, omega, alpha))
    };
    // Limits where |R| = |c·sin γ|.
    let mut limits = Vec::new();
    let s = (&offset - (&l1 - &l2).abs()) * (&offset + (&l1 - &l2).abs());
    let k = (&l1 + &l2 - &offset) * (&l1 + &l2 + &offset);
    if !s.is_negative() && !k.is_negative() && !s.is_zero() && !k.is_zero() {
        let a = from_half_squares(&s, &k);
        limits.push(-&a);
        limits.push(a);
    }
    let size = model.size;
    // |R| moves by η(l1 + l2 + l2|θ2|), |c sin γ| by η(|c| + |c|·|γ|).
    let slack =
        (size + p.get("l2") * theta2.abs() + p.get("c").abs() * p.get("gamma").abs()) / size;
    let reach = Reach {
        gap: gap.to_f64() / size,
        slack,
        margin: margin(&t, &limits, !gap.is_negative()),
    };
    Outcome {
        truth: solve_on(branch),
        others: solve_on(branch.other()).into_iter().collect(),
        model,
        reach,
    }
}

/// A loop-by-loop mechanism (Watt six-bar, Jansen leg) solved by the same circle–circle
/// closed form per loop, on `branches`. The reach is the smallest gap of the loops, each
/// loop's slack counting, beyond its own lengths, the vectors that turn with unknowns of the
/// loops before it amplified by those loops' condition.
pub fn chained(
    kind: Kind,
    p: &Params,
    input: f64,
    branches: &[Branch],
    omega: f64,
    alpha: f64,
) -> Outcome {
    let model = Model::new(kind, p);
    let t = Big::from_f64(input);
    let n = model.unknowns();
    let size = model.size;
    let solve_with = |branches: &[Branch]| {
        let mut state = State {
            input: t.clone(),
            input_direction: C::expi(&t),
            q: vec![Big::zero(); n],
            directions: vec![None; n],
        };
        let mut gap = f64::INFINITY;
        let mut slack = 1.0f64;
        let mut upstream_condition = 1.0f64;
        for (k, terms) in model.loops.iter().enumerate() {
            // The two unknowns this loop solves: the first turning with `+r1`, the second
            // with `−r2`.
            let (first, second) = (2 * k, 2 * k + 1);
            let mut known = C::zero();
            let mut loop_slack = 0.0;
            let (mut r1, mut r2) = (Big::zero(), Big::zero());
            for term in terms {
                let r = state.magnitude(term);
                match term.angle {
                    Some(Var::Unknown(j)) if j == first => r1 = r,
                    Some(Var::Unknown(j)) if j == second => r2 = r,
                    Some(Var::Unknown(_)) => {
                        known = known.add(&state.vector(term));
                        loop_slack += r.to_f64() * (1.0 + upstream_condition);
                    }
                    Some(Var::Input) => {
                        known = known.add(&state.vector(term));
                        loop_slack += r.to_f64() * (1.0 + input.abs());
                    }
                    None => {
                        known = known.add(&state.vector(term));
                        loop_slack += r.to_f64();
                    }
                }
            }
            loop_slack += r1.to_f64() + r2.to_f64();
            let chord = C::new(-known.re, -known.im);
            let (solution, loop_gap) =
                dyad(&chord, &chord.norm2(), &r1, &r2, branch_sign(branches[k]));
            let loop_gap = loop_gap.to_f64() / size;
            if loop_gap < gap {
                gap = loop_gap;
                slack = loop_slack / size;
            }
            let Some((e1, e2)) = solution else {
                return (None, gap, slack);
            };
            state.q[first] = e1.angle();
            state.q[second] = e2.angle();
            // This loop's own κ, 1/|sin(q2 − q1)|, amplifies its angles' errors into the
            // chords of the loops after it.
            let condition = (Big::one() / e1.cross(&e2).abs()).to_f64();
            upstream_condition = upstream_condition.max(condition);
            state.directions[first] = Some(e1);
            state.directions[second] = Some(e2);
        }
        (Some(complete(&model, state, omega, alpha)), gap, slack)
    };
    let (truth, gap, slack) = solve_with(branches);
    let mut others = Vec::new();
    for k in 0..branches.len() {
        let mut flipped = branches.to_vec();
        flipped[k] = flipped[k].other();
        if let (Some(other), _, _) = solve_with(&flipped) {
            others.push(other);
        }
    }
    Outcome {
        model,
        reach: Reach {
            gap,
            slack,
            margin: f64::NAN,
        },
        truth,
        others,
    }
}

// ---------------------------------------------------------------------------------------------
// Newton polish

/// What a multiple-precision Newton polish of a candidate found.
#[derive(Clone, Debug)]
pub struct Polish {
    /// The root it converged to, completed (rates, κ, branch signs); `None` if it did not.
    pub truth: Option<Truth>,
    /// Each step's size: the largest over the unknowns of `|Δq|·‖column‖`, over the size.
    pub steps: Vec<f64>,
    /// Whether the steps shrank to the working precision.
    pub converged: bool,
    /// Whether they shrank quadratically: each step, until the last few at the working
    /// precision, at most `K·(previous)²` for the `K = 4·κ·ρ` of the root.
    pub quadratic: bool,
    /// Kantorovich's `h = ‖J⁻¹‖²·L·‖f‖` at the candidate (Frobenius norms, `L` a Lipschitz
    /// constant of the Jacobian there): at most 1/2 certifies a unique root near it, which
    /// Newton reaches quadratically.
    pub kantorovich: f64,
}

/// A Lipschitz constant of the Jacobian near a state: each entry is `±r·(cos|sin)(φ)` or
/// `±(cos|sin)(φ)` (a length unknown's column), so it moves by at most `r` per radian of its
/// angle and by 1 per unit of its length.
fn lipschitz(model: &Model, state: &State) -> Big {
    let mut sum = Big::zero();
    for terms in &model.loops {
        for t in terms {
            let r = state.magnitude(t).abs();
            let angle_unknown = matches!(t.angle, Some(Var::Unknown(_)));
            let length_unknown = matches!(t.magnitude, Magnitude::Unknown(_));
            // Two rows per loop; the angle's column entries move by r per radian, the length's
            // column entries by 1 per radian and the angle's by 1 per unit length.
            let two = Big::from_f64(2.0);
            if angle_unknown {
                sum = sum + &two * &r.square();
            }
            if angle_unknown && length_unknown {
                sum = sum + &two + &two;
            }
        }
    }
    sum.sqrt()
}

/// Polishes `candidate` (the unknowns at `input`) by Newton on the model's loops at the
/// oracle's precision.
pub fn polish(model: &Model, input: f64, candidate: &[f64], omega: f64, alpha: f64) -> Polish {
    let mut state = State::from_f64(model, input, candidate);
    let size = model.size;
    // The working precision's floor, which κ·ρ raises near a singular root.
    let unit = 2f64.powi(-(bits() as i32 - 40)).max(1e-300);
    let mut floor = unit;
    let mut steps = Vec::new();
    let mut kantorovich = f64::INFINITY;
    let n = model.unknowns();
    for iteration in 0..40 {
        let f: Vec<Big> = residual(model, &state)
            .into_iter()
            .flat_map(|c| [c.re, c.im])
            .collect();
        let j = jacobian(model, &state);
        let columns = column_norms(&j);
        if iteration == 0 {
            // ‖J⁻¹‖_F from its columns, J⁻¹·e_k.
            let mut inverse2 = Big::zero();
            let mut singular = false;
            for k in 0..n {
                let mut e = vec![Big::zero(); n];
                e[k] = Big::one();
                match solve(j.clone(), e) {
                    Some((x, _)) => {
                        inverse2 = x.iter().fold(inverse2, |acc, v| acc + v.square());
                    }
                    None => singular = true,
                }
            }
            let f2 = f.iter().fold(Big::zero(), |acc, v| acc + v.square());
            if !singular {
                kantorovich = (inverse2 * lipschitz(model, &state) * f2.sqrt()).to_f64();
            }
        }
        let Some((delta, det)) = solve(j, f) else {
            break;
        };
        let product = columns.iter().fold(Big::one(), |acc, c| acc * c);
        let shortest = columns
            .iter()
            .map(Big::to_f64)
            .fold(f64::INFINITY, f64::min);
        let condition = (product / det.abs()).to_f64();
        floor = unit * (condition * (size / shortest).max(1.0)).max(1.0);
        let step = delta
            .iter()
            .zip(&columns)
            .map(|(d, c)| (d * c).abs().to_f64())
            .fold(0.0, f64::max)
            / size;
        let q: Vec<Big> = state.q.iter().zip(&delta).map(|(x, d)| x - d).collect();
        state = State::new(model, state.input.clone(), q);
        steps.push(step);
        if step <= floor || !step.is_finite() || step > 1e3 {
            break;
        }
    }
    let converged = steps.last().is_some_and(|s| *s <= floor);
    let truth = converged.then(|| complete(model, state, omega, alpha));
    let quadratic = truth.as_ref().is_some_and(|t| {
        let k = 4.0 * t.condition * t.aspect(size);
        // A few steps may come before the quadratic region (k·step < 1); from there on each
        // step is at most k times the square of the one before.
        let before = steps.windows(2).take_while(|w| k * w[0] >= 1.0).count();
        before <= 3
            && steps
                .windows(2)
                .skip(before)
                .all(|w| w[1] <= (k * w[0] * w[0]).max(floor))
    });
    Polish {
        truth,
        steps,
        converged,
        quadratic,
        kantorovich,
    }
}

/// The oracle for a mechanism held as `p` at `input` on `branches` (one per loop): the closed
/// form where the mechanism has one, else `None` (the Stephenson six-bar: use [`polish`]).
pub fn closed_form(
    kind: Kind,
    p: &Params,
    input: f64,
    branches: &[Branch],
    omega: f64,
    alpha: f64,
) -> Option<Outcome> {
    Some(match kind {
        Kind::FourBar => four_bar(p, input, branches[0], omega, alpha),
        Kind::SliderCrank => slider_crank(p, input, branches[0], omega, alpha),
        Kind::InvertedSliderCrank => inverted_slider_crank(p, input, branches[0], omega, alpha),
        Kind::WattSixBar | Kind::JansenLeg => chained(kind, p, input, branches, omega, alpha),
        Kind::StephensonSixBar => return None,
    })
}

/// The weighted error of `got` against a truth: the largest over the unknowns of
/// `|got − true|·‖column‖` (angles compared modulo 2π), over `scale`.
pub fn weighted_error(
    truth: &Truth,
    angles: &[bool],
    got: &[f64],
    want: &[Big],
    scale: f64,
) -> f64 {
    got.iter()
        .zip(want)
        .zip(&truth.columns)
        .zip(angles)
        .map(|(((g, w), c), &angle)| {
            let mut d = Big::from_f64(*g) - w;
            if angle {
                d = d.wrapped();
            }
            (d.abs().to_f64() * c).abs()
        })
        .fold(0.0, f64::max)
        / scale
}

/// The weighted error of a position (angles modulo 2π).
pub fn position_error(model: &Model, truth: &Truth, got: &[f64]) -> f64 {
    weighted_error(truth, &model.angles, got, truth.q(), model.size)
}

/// The size rates are measured against: the larger of `size·scale` (with `scale` the input's
/// rate, or its rate squared plus its acceleration) and the true rates' weighted size.
pub fn rate_size(truth: &Truth, rates: &[Big], size: f64, scale: f64) -> f64 {
    rates
        .iter()
        .zip(&truth.columns)
        .fold(size * scale, |m, (r, c)| m.max((r.to_f64() * c).abs()))
}

/// The largest loop residual of a position (evaluated exactly), each over the sum of its loop's
/// vector magnitudes.
pub fn relative_residual(model: &Model, input: f64, q: &[f64]) -> f64 {
    let state = State::from_f64(model, input, q);
    residual(model, &state)
        .iter()
        .zip(model.loop_magnitudes(&state))
        .map(|(r, m)| (r.norm() / m).to_f64())
        .fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::{self, Status};

    fn params(names: &[&str], values: &[f64]) -> Params {
        Params(
            names
                .iter()
                .zip(values)
                .map(|(n, v)| (n.to_string(), *v))
                .collect(),
        )
    }

    fn reference_params(case: &reference::Case) -> (Kind, Params) {
        match case.mechanism.as_str() {
            "four_bar" => (
                Kind::FourBar,
                params(&["l1", "l2", "l3", "l4"], &case.params),
            ),
            "slider_crank" => (Kind::SliderCrank, params(&["l2", "l3", "c"], &case.params)),
            _ => (
                Kind::InvertedSliderCrank,
                params(&["l1", "l2", "c", "gamma"], &case.params),
            ),
        }
    }

    /// The 25-digit value `text` of the reference CSV, as written there.
    fn field(case: &reference::Case, index: usize) -> String {
        let line = reference::CASES_CSV
            .lines()
            .skip(1)
            .find(|line| {
                let f: Vec<&str> = line.split(',').collect();
                f[0] == case.mechanism
                    && f[1] == case.case
                    && f[2] == case.precision
                    && f[5].parse::<f64>().ok() == Some(case.input)
                    && (f[3] == "open") == (case.branch == Branch::Open)
            })
            .expect("the case's line");
        line.split(',').nth(index).expect("a field").to_string()
    }

    /// `|got − want| ≤ 1e-22·scale`: the references carry 25 significant digits.
    fn agrees(what: &str, got: &Big, want: &str, scale: f64) {
        agrees_as(what, got, want, scale, false);
    }

    fn agrees_as(what: &str, got: &Big, want: &str, scale: f64, angle: bool) {
        let want = Big::parse(want);
        let mut d = got - &want;
        if angle {
            d = d.wrapped();
        }
        let error = d.abs().to_f64();
        assert!(
            error <= 1e-22 * scale,
            "{what}: oracle {} vs reference {} (error {error:e})",
            got.to_f64(),
            want.to_f64()
        );
    }

    #[test]
    fn conversions_and_functions_are_exact_where_they_must_be() {
        for x in [1.0, 0.75, -3.5, 1e-300, 1e300, f64::MIN_POSITIVE, 0.1] {
            assert_eq!(Big::from_f64(x).to_f64(), x);
        }
        let t = Big::from_f64(0.7);
        let one = t.sin().square() + t.cos().square();
        assert!((one - Big::one()).abs().to_f64() < 1e-70);
        for (y, x) in [
            (1.0, 1.0),
            (1.0, -1.0),
            (-1.0, -1.0),
            (-1.0, 1.0),
            (2.0, 0.5),
            (-0.5, 3.0),
        ] {
            let got = Big::atan2(&Big::from_f64(y), &Big::from_f64(x)).to_f64();
            assert!(
                (got - f64::atan2(y, x)).abs() < 1e-15,
                "atan2({y}, {x}) = {got}"
            );
        }
        assert!((Big::pi().to_f64() - std::f64::consts::PI).abs() < 1e-16);
        let w = Big::from_f64(7.0).wrapped().to_f64();
        assert!((w - (7.0 - std::f64::consts::TAU)).abs() < 1e-15);
    }

    /// Every 60-digit reference: the same status, positions, rates, accelerations, condition and
    /// columns to the 25 digits the CSV keeps.
    #[test]
    fn the_oracle_reproduces_every_reference_case() {
        let cases = reference::cases();
        assert!(cases.len() > 150);
        for case in &cases {
            let (kind, p) = reference_params(case);
            let outcome = closed_form(
                kind,
                &p,
                case.input,
                &[case.branch],
                reference::OMEGA2,
                reference::ALPHA2,
            )
            .expect("a closed form");
            let name = format!(
                "{} {} {} δ={} {:?}",
                case.mechanism, case.case, case.precision, case.delta, case.branch
            );
            match case.status {
                Status::Cannot => {
                    assert!(outcome.truth.is_none(), "{name}: the oracle assembles");
                    assert!(
                        !outcome.reach.reachable() && outcome.reach.margin < 0.0,
                        "{name}: {:?}",
                        outcome.reach
                    );
                    continue;
                }
                Status::Singular => {
                    let truth = outcome.truth.as_ref().expect("assembles");
                    assert!(truth.condition > 1e60, "{name}: κ = {}", truth.condition);
                    assert!(outcome.reach.reachable(), "{name}");
                }
                Status::Ok => {
                    let truth = outcome
                        .truth
                        .as_ref()
                        .unwrap_or_else(|| panic!("{name}: no truth"));
                    assert!(outcome.reach.reachable(), "{name}");
                    let size = outcome.model.size;
                    // The references' formulas are not factored: an ulp of input from a toggle
                    // (κ ≥ 1e15) their 60-digit discriminant cancels down to a dozen digits in
                    // the accelerations (the kite's δ = 0, whose trend over δ = 1e-3 … 1e-12 the
                    // oracle continues and the reference leaves; see the next test). There
                    // only positions are compared; the precision-doubling test vouches for the
                    // oracle's rates.
                    let rates_comparable = case.condition < 1e15;
                    for k in 0..2 {
                        let scale = if outcome.model.angles[k] { 1.0 } else { size };
                        let angle = outcome.model.angles[k];
                        agrees_as(
                            &format!("{name} q{k}"),
                            &truth.q()[k],
                            &field(case, 8 + k),
                            scale,
                            angle,
                        );
                        let v = &truth.velocity.as_ref().expect("rates")[k];
                        let a = &truth.acceleration.as_ref().expect("accelerations")[k];
                        if !rates_comparable {
                            continue;
                        }
                        let rate = Big::parse(&field(case, 10 + k)).abs().to_f64().max(1.0);
                        agrees(
                            &format!("{name} q̇{k}"),
                            v,
                            &field(case, 10 + k),
                            rate * scale,
                        );
                        let acc = Big::parse(&field(case, 12 + k)).abs().to_f64().max(1.0);
                        agrees(
                            &format!("{name} q̈{k}"),
                            a,
                            &field(case, 12 + k),
                            acc * scale,
                        );
                        let column = case.columns[k];
                        assert!(
                            (truth.columns[k] - column).abs() <= 1e-15 * column,
                            "{name} column {k}"
                        );
                    }
                    assert!(
                        (truth.condition - case.condition).abs() <= 1e-13 * case.condition,
                        "{name}: κ {} vs {}",
                        truth.condition,
                        case.condition
                    );
                    assert_eq!(
                        truth.branches,
                        vec![case.branch],
                        "{name}: the documented sign"
                    );
                }
            }
        }
    }

    /// The kite folding flat (θ2 → π): α3 tends to −1/6 like −1/6 + 1.48e-4·δ over the
    /// references' δ = 1e-3 … 1e-12; an ulp from π the oracle continues that trend.
    #[test]
    fn the_kite_an_ulp_from_flat_continues_its_trend() {
        let p = params(&["l1", "l2", "l3", "l4"], &[100.0, 50.0, 50.0, 100.0]);
        let outcome = four_bar(&p, std::f64::consts::PI, Branch::Open, 1.0, 0.5);
        let alpha3 = outcome.truth.unwrap().acceleration.unwrap()[0].to_f64();
        assert!((alpha3 + 1.0 / 6.0).abs() < 1e-16, "{alpha3}");
    }

    /// Where a reference case says δ from a limit, the margin says so too.
    #[test]
    fn margins_measure_the_distance_to_the_limit() {
        for case in reference::cases() {
            if case.case != "non-Grashof limit" || case.precision != "f64" {
                continue;
            }
            let (kind, p) = reference_params(&case);
            let outcome = closed_form(kind, &p, case.input, &[case.branch], 1.0, 0.5).unwrap();
            let delta: f64 = case.delta.parse().unwrap();
            // The CSV's inputs are the limit minus δ, rounded to f64.
            let margin = outcome.reach.margin;
            if case.status == Status::Cannot {
                assert!(
                    margin < 0.0 && margin.abs() < 1e-15,
                    "δ={}: {margin:e}",
                    case.delta
                );
            } else {
                assert!(
                    (margin - delta).abs() < 1e-15,
                    "δ={}: {margin:e}",
                    case.delta
                );
            }
        }
    }

    /// The answers do not move when the precision is doubled: the oracle's own error is far
    /// below what it judges.
    #[test]
    fn doubling_the_precision_changes_nothing_that_matters() {
        for case in reference::cases() {
            if case.status != Status::Ok {
                continue;
            }
            let (kind, p) = reference_params(&case);
            let at = |bits| {
                with_precision(bits, || {
                    let o = closed_form(kind, &p, case.input, &[case.branch], 1.0, 0.5).unwrap();
                    let t = o.truth.unwrap();
                    let mut v: Vec<f64> = t.q().iter().map(Big::to_f64).collect();
                    v.extend(t.acceleration.unwrap().iter().map(Big::to_f64));
                    (v, o.reach.gap, t.condition)
                })
            };
            let (low, high) = (at(256), at(512));
            for (k, (a, b)) in low.0.iter().zip(&high.0).enumerate() {
                let mut d = a - b;
                if k < 2 && reference::angle_unknowns(&case)[k] {
                    d = (d + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU)
                        - std::f64::consts::PI;
                }
                assert!(
                    d.abs() <= 1e-15 * b.abs().max(1.0),
                    "{} {}: {a} vs {b}",
                    case.case,
                    case.delta
                );
            }
            assert!((low.1 - high.1).abs() <= 1e-15 * high.1.abs().max(1e-30));
            assert!((low.2 - high.2).abs() <= 1e-12 * high.2);
        }
    }

    /// Polishing each reference position rounded to f64 lands back on it, quadratically, with a
    /// Kantorovich certificate where it is well conditioned.
    #[test]
    fn newton_polish_recovers_the_references() {
        for case in reference::cases() {
            if case.status != Status::Ok || case.precision != "f64" {
                continue;
            }
            let (kind, p) = reference_params(&case);
            let model = Model::new(kind, &p);
            let polished = polish(&model, case.input, &case.q, 1.0, 0.5);
            let name = format!("{} {} δ={}", case.case, case.delta, 0);
            assert!(
                polished.converged && polished.quadratic,
                "{name}: {:?}",
                polished.steps
            );
            let truth = polished.truth.unwrap();
            for k in 0..2 {
                let scale = if model.angles[k] { 1.0 } else { model.size };
                agrees_as(
                    &name,
                    &truth.q()[k],
                    &field(&case, 8 + k),
                    scale,
                    model.angles[k],
                );
            }
            if case.condition < 1e3 {
                assert!(
                    polished.kantorovich < 0.5,
                    "{name}: h = {}",
                    polished.kantorovich
                );
            }
        }
    }

    fn debug_params<T: std::fmt::Debug>(m: &T) -> Params {
        Params::from_debug::<f64>(&format!("{m:?}"))
    }

    /// The loop-by-loop closed forms, the Newton polish and mechgen agree on the shipped
    /// multi-loop examples over a turn: the model's loops, signs and branches are the
    /// declarations'.
    #[test]
    fn multi_loop_models_match_the_shipped_mechanisms() {
        use mechanisms::{JansenLeg, WattSixBar};
        let leg = JansenLeg::<f64>::holy();
        let watt = WattSixBar::new(
            [180.0, 80.0, 200.0, 150.0],
            100.0,
            0.8,
            220.0,
            160.0,
            (300.0, 150.0),
        )
        .unwrap();
        let (stephenson, guess) = crate::examples::stephenson_six_bar();
        let mut previous = guess.to_array().to_vec();
        for degree in (0..360).step_by(15) {
            let t = f64::from(degree).to_radians();
            let drawn = JansenLeg::<f64>::DRAWN;
            let q = leg.assemble(t, drawn).unwrap().to_array();
            let outcome = chained(Kind::JansenLeg, &debug_params(&leg), t, &drawn, 1.0, 0.0);
            let truth = outcome.truth.expect("the leg assembles");
            assert_eq!(truth.branches, drawn.to_vec());
            assert!(
                position_error(&outcome.model, &truth, &q) < 1e-14,
                "Jansen at {degree}°"
            );
            let polished = polish(&outcome.model, t, &q, 1.0, 0.0);
            assert!(
                polished.quadratic && polished.kantorovich < 0.5,
                "{:?}",
                polished.steps
            );
            assert!(relative_residual(&outcome.model, t, &q) < 1e-15);

            for branches in [
                [Branch::Open, Branch::Open],
                [Branch::Crossed, Branch::Open],
                [Branch::Open, Branch::Crossed],
            ] {
                let outcome = chained(
                    Kind::WattSixBar,
                    &debug_params(&watt),
                    t,
                    &branches,
                    1.0,
                    0.0,
                );
                match (watt.assemble(t, branches), outcome.truth) {
                    (Ok(q), Some(truth)) => {
                        assert_eq!(truth.branches, branches.to_vec());
                        assert!(position_error(&outcome.model, &truth, &q.to_array()) < 1e-14);
                    }
                    (Err(_), None) => {}
                    (got, truth) => panic!(
                        "Watt at {degree}° {branches:?}: {got:?} vs {:?}",
                        truth.map(|t| t.condition)
                    ),
                }
            }

            let solved = stephenson
                .position(
                    t,
                    &StephensonSixBarUnknowns::from_array(previous.clone().try_into().unwrap()),
                    &mechgen::NewtonOptions::default(),
                )
                .unwrap();
            let q = solved.value.to_array();
            let model = Model::new(Kind::StephensonSixBar, &debug_params(&stephenson));
            let polished = polish(&model, t, &q, 1.0, 0.0);
            assert!(polished.quadratic, "{:?}", polished.steps);
            let truth = polished.truth.unwrap();
            assert!(position_error(&model, &truth, &q) < 1e-14);
            assert!((truth.condition - solved.condition).abs() < 1e-9 * truth.condition);
            previous = q.to_vec();
        }
    }

    use mechanisms::StephensonSixBarUnknowns;

    #[test]
    fn parameters_round_trip_through_debug_in_either_precision() {
        let m = mechanisms::SliderCrank::<f32>::new(5.0, 1.9e19, 6.0).unwrap();
        let p = Params::from_debug::<f32>(&format!("{m:?}"));
        assert_eq!(p.get("l3"), f64::from(1.9e19f32));
        assert_eq!(p.get("c"), 6.0);
        let leg = mechanisms::JansenLeg::<f64>::holy();
        let p = Params::from_debug::<f64>(&format!("{leg:?}"));
        assert_eq!(p.0.len(), 13);
    }
}
