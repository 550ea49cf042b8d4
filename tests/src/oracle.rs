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
        if x != 0.0 && x.abs() < f64::MIN_POSITIVE {
            // astro-float reads a subnormal double as half its value (edge run case 8366: a
            // slider's rate of 1e-308 judged 2.4e-14 off): take it in scaled into the normal
            // range, which is exact, and scale back by a power of two, exact too.
            let normal = BigFloat::from_f64(x * 2f64.powi(64), bits());
            let back = BigFloat::from_f64(2f64.powi(-64), bits());
            return Big(normal.mul(&back, bits(), ROUNDING));
        }
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
        // Whole turns first (a guess that counts a million of them), exact at 256 bits for
        // any count below 2^53; then at most one more either way.
        let turns = (self / &tau).to_f64().round();
        let mut x = if turns.is_finite() && turns.abs() < 2f64.powi(53) {
            self - &(Big::from_f64(turns) * &tau)
        } else {
            self.clone()
        };
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

    /// How many of the unknowns' columns a position's error moves, as the generated code
    /// counts them (`mechgen::Accuracy::estimate_at`'s `moving`): one per angle, two more per
    /// slide along an unknown angle (the inverted slider-crank's), none for a slide along a
    /// fixed line (the slider-crank's).
    pub fn moving(self) -> f64 {
        match self {
            Kind::FourBar => 2.0,
            Kind::SliderCrank => 1.0,
            Kind::InvertedSliderCrank => 3.0,
            Kind::WattSixBar | Kind::StephensonSixBar => 4.0,
            Kind::JansenLeg => 6.0,
        }
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
        let (upper, lower) = a.split_at_mut(k + 1);
        let pivot_row = &upper[k];
        for (offset, row) in lower.iter_mut().enumerate() {
            let i = k + 1 + offset;
            let factor = &row[k] / &pivot_row[k];
            for (entry, above) in row.iter_mut().zip(pivot_row).skip(k) {
                *entry = &*entry - &factor * above;
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

/// The branches the runtime reads off a position that need not close (Newton's guess): for
/// one loop, the Jacobian's orientation, which [`branch_signs`] follows; for the loop-by-loop
/// mechanisms, the generated `branch_of`, `cross(−K, e^{i·q1}·w1)` per loop with `K` the sum of
/// the loop's other vectors at this position (equal to [`branch_signs`]' sine at a solution,
/// not elsewhere).
pub fn guess_branches(model: &Model, state: &State) -> Vec<Branch> {
    guess_sides(model, state)
        .into_iter()
        .map(|(branch, _)| branch)
        .collect()
}

/// [`guess_branches`], each loop's with how far its moving point lies from its mirror image
/// across the loop's chord (twice its height over the chord, a length) for the loop-by-loop
/// mechanisms, and infinity for the others: where that is within a solution's error, the
/// runtime takes the guess's loop as on neither branch (`mechgen::__private::same_sides`).
pub fn guess_sides(model: &Model, state: &State) -> Vec<(Branch, f64)> {
    if !matches!(model.kind, Kind::WattSixBar | Kind::JansenLeg) {
        return branch_signs(model, state)
            .0
            .into_iter()
            .map(|branch| (branch, f64::INFINITY))
            .collect();
    }
    model
        .loops
        .iter()
        .enumerate()
        .map(|(k, terms)| {
            let (first, second) = (2 * k, 2 * k + 1);
            let mut known = C::zero();
            let mut p1 = C::zero();
            for t in terms {
                match t.angle {
                    Some(Var::Unknown(j)) if j == first => p1 = state.vector(t),
                    Some(Var::Unknown(j)) if j == second => {}
                    _ => known = known.add(&state.vector(t)),
                }
            }
            let chord = C::new(-known.re, -known.im);
            let cross = chord.cross(&p1);
            let norm = chord.norm();
            let mirror = if norm.is_zero() {
                0.0
            } else {
                (cross.abs() * Big::from_f64(2.0) / norm).to_f64()
            };
            let branch = if cross.is_negative() {
                Branch::Crossed
            } else {
                Branch::Open
            };
            (branch, mirror)
        })
        .collect()
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

/// The four-bar's limit angles, where the chord |O4 − A| equals l3 + l4 or |l3 − l4|:
/// `sin²(θ/2) = (r² − (l1 − l2)²)/(4·l1·l2)`, `cos²(θ/2) = ((l1 + l2)² − r²)/(4·l1·l2)`.
fn four_bar_limits(l1: &Big, l2: &Big, l3: &Big, l4: &Big) -> Vec<Big> {
    let mut limits = Vec::new();
    for reach in [l3 + l4, (l3 - l4).abs()] {
        let s = (&reach - (l1 - l2).abs()) * (&reach + (l1 - l2).abs());
        let c = (l1 + l2 - &reach) * (l1 + l2 + &reach);
        if !s.is_negative() && !c.is_negative() && !s.is_zero() && !c.is_zero() {
            let a = from_half_squares(&s, &c);
            limits.push(-&a);
            limits.push(a);
        }
    }
    limits
}

/// The slider-crank's limit angles, where `sin θ2 = (c ∓ l3)/l2`, each at asin and π − asin.
fn slider_crank_limits(l2: &Big, l3: &Big, c: &Big) -> Vec<Big> {
    let mut limits = Vec::new();
    for edge in [c - l3, c + l3] {
        let s = &edge / l2;
        if s.abs() < Big::one() {
            let a = Big::atan2(&s, &(Big::one() - s.square()).sqrt());
            limits.push((Big::pi() - &a).wrapped());
            limits.push(a);
        }
    }
    limits
}

/// The inverted slider-crank's limit angles, where `|A − O4| = |c·sin γ|` (`offset`).
fn inverted_limits(l1: &Big, l2: &Big, offset: &Big) -> Vec<Big> {
    let mut limits = Vec::new();
    let s = (offset - (l1 - l2).abs()) * (offset + (l1 - l2).abs());
    let k = (l1 + l2 - offset) * (l1 + l2 + offset);
    if !s.is_negative() && !k.is_negative() && !s.is_zero() && !k.is_zero() {
        let a = from_half_squares(&s, &k);
        limits.push(-&a);
        limits.push(a);
    }
    limits
}

/// The smallest gap (over the size) of a loop-by-loop mechanism's loops at `input` on
/// `branches`, solving loop by loop as [`chained`] does but keeping only the directions: what
/// the limit search evaluates.
pub fn chain_gap(kind: Kind, p: &Params, input: f64, branches: &[Branch]) -> f64 {
    chain_gap_of(&Model::new(kind, p), input, branches)
}

fn chain_gap_of(model: &Model, input: f64, branches: &[Branch]) -> f64 {
    let t = Big::from_f64(input);
    let n = model.unknowns();
    let mut state = State {
        input: t.clone(),
        input_direction: C::expi(&t),
        q: vec![Big::zero(); n],
        directions: vec![None; n],
    };
    let mut gap = f64::INFINITY;
    for (k, terms) in model.loops.iter().enumerate() {
        let (first, second) = (2 * k, 2 * k + 1);
        let mut known = C::zero();
        let (mut r1, mut r2) = (Big::zero(), Big::zero());
        for term in terms {
            match term.angle {
                Some(Var::Unknown(j)) if j == first => r1 = state.magnitude(term),
                Some(Var::Unknown(j)) if j == second => r2 = state.magnitude(term),
                _ => known = known.add(&state.vector(term)),
            }
        }
        let chord = C::new(-known.re, -known.im);
        let (solution, loop_gap) = dyad(&chord, &chord.norm2(), &r1, &r2, branch_sign(branches[k]));
        gap = gap.min(loop_gap.to_f64() / model.size);
        let Some((e1, e2)) = solution else {
            return gap;
        };
        state.directions[first] = Some(e1);
        state.directions[second] = Some(e2);
    }
    gap
}

/// The input angles in (−π, π] where a mechanism's loops stop closing on `branches`: in closed
/// form for one loop, else by a scan of [`chain_gap`] over 32 inputs and bisection (at 64
/// bits, 48 halvings: to 1e-15 rad) of each sign change.
pub fn limit_angles(kind: Kind, p: &Params, branches: &[Branch]) -> Vec<f64> {
    let b = |n: &str| Big::from_f64(p.get(n));
    let exact = match kind {
        Kind::FourBar => Some(four_bar_limits(&b("l1"), &b("l2"), &b("l3"), &b("l4"))),
        Kind::SliderCrank => Some(slider_crank_limits(&b("l2"), &b("l3"), &b("c"))),
        Kind::InvertedSliderCrank => {
            let offset = (b("c") * b("gamma").sin()).abs();
            Some(inverted_limits(&b("l1"), &b("l2"), &offset))
        }
        _ => None,
    };
    if let Some(limits) = exact {
        return limits.iter().map(Big::to_f64).collect();
    }
    if kind == Kind::StephensonSixBar {
        return Vec::new();
    }
    with_precision(64, || {
        let model = Model::new(kind, p);
        let pi = std::f64::consts::PI;
        let samples = 32;
        let at = |i: usize| -pi + 2.0 * pi * i as f64 / samples as f64;
        let gaps: Vec<f64> = (0..=samples)
            .map(|i| chain_gap_of(&model, at(i), branches))
            .collect();
        let mut limits = Vec::new();
        for i in 0..samples {
            if (gaps[i] >= 0.0) == (gaps[i + 1] >= 0.0) {
                continue;
            }
            let (mut inside, mut outside) = if gaps[i] >= 0.0 {
                (at(i), at(i + 1))
            } else {
                (at(i + 1), at(i))
            };
            for _ in 0..48 {
                let middle = 0.5 * (inside + outside);
                if middle == inside || middle == outside {
                    break;
                }
                if chain_gap_of(&model, middle, branches) >= 0.0 {
                    inside = middle;
                } else {
                    outside = middle;
                }
            }
            limits.push(inside);
        }
        limits
    })
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
    let limits = four_bar_limits(&l1, &l2, &l3, &l4);
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
    let limits = slider_crank_limits(&l2, &l3, &c);
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
    let limits = inverted_limits(&l1, &l2, &offset);
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
        // How far each solved angle can turn, in radians per unit relative perturbation of
        // the data: a loop's chord moves by at most η·(its slack), which turns its angles by at
        // most κ·η·slack/r.
        let mut sensitivity = vec![0.0f64; n];
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
                    Some(Var::Unknown(j)) => {
                        known = known.add(&state.vector(term));
                        loop_slack += r.to_f64() * (1.0 + sensitivity[j]);
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
            let loop_slack = loop_slack / size;
            // The loop nearest its limit, in units of its own rounding.
            if loop_gap < 0.0 || loop_gap / loop_slack < gap / slack {
                gap = loop_gap;
                slack = loop_slack;
            }
            let Some((e1, e2)) = solution else {
                return (None, gap, slack);
            };
            state.q[first] = e1.angle();
            state.q[second] = e2.angle();
            let condition = (Big::one() / e1.cross(&e2).abs()).to_f64();
            sensitivity[first] = condition * loop_slack * size / r1.to_f64();
            sensitivity[second] = condition * loop_slack * size / r2.to_f64();
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

/// The radius (Euclidean, in the unknowns' own units) of a ball about a root from every point
/// of which Kantorovich certifies that Newton converges to it: with `β = ‖J⁻¹‖`, `L` the
/// Jacobian's Lipschitz constant and `‖J‖` (Frobenius norms at the root),
/// `r = 1/(4·β²·L·(‖J‖ + L))` keeps `β·L·r ≤ 1/4`, so `‖J(x)⁻¹‖ ≤ 4β/3`, and
/// `‖f(x)‖ ≤ (‖J‖ + L)·r`, so `h ≤ (16/9)·β²·L·(‖J‖ + L)·r < 1/2`.
pub fn newton_radius(model: &Model, truth: &Truth) -> f64 {
    let j = jacobian(model, &truth.state);
    let n = model.unknowns();
    let mut inverse2 = Big::zero();
    for k in 0..n {
        let mut e = vec![Big::zero(); n];
        e[k] = Big::one();
        match solve(j.clone(), e) {
            Some((x, _)) => inverse2 = x.iter().fold(inverse2, |acc, v| acc + v.square()),
            None => return 0.0,
        }
    }
    let norm = j
        .iter()
        .flatten()
        .fold(Big::zero(), |acc, v| acc + v.square())
        .sqrt();
    let l = lipschitz(model, &truth.state);
    let four = Big::from_f64(4.0);
    (Big::one() / (four * inverse2 * &l * (norm + &l))).to_f64()
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
    scale: &Big,
) -> f64 {
    if got.iter().any(|g| !g.is_finite()) {
        return f64::INFINITY;
    }
    // Weighted and divided at 256 bits, then rounded: a difference below f64's range (an
    // angular acceleration of 1e-400 returned as 0) times a column of 1e300 is not zero, and
    // a scale beyond it (a rod of 1e300 turning at 1e30 rad/s) is not infinite.
    got.iter()
        .zip(want)
        .zip(&truth.columns)
        .zip(angles)
        .map(|(((g, w), c), &angle)| {
            let mut d = Big::from_f64(*g) - w;
            if angle {
                d = d.wrapped();
            }
            if scale.is_zero() {
                // Nothing moves: any difference is infinitely wrong.
                if d.is_zero() { 0.0 } else { f64::INFINITY }
            } else if c.is_finite() {
                (d.abs() * Big::from_f64(*c) / scale).to_f64().abs()
            } else {
                (d.abs() / scale).to_f64().abs() * c
            }
        })
        .fold(0.0, f64::max)
}

/// The weighted error of a position (angles modulo 2π).
pub fn position_error(model: &Model, truth: &Truth, got: &[f64]) -> f64 {
    weighted_error(
        truth,
        &model.angles,
        got,
        truth.q(),
        &Big::from_f64(model.size),
    )
}

/// The size rates at `level` are measured against: the larger of the size times the input's
/// rate (level 1, velocities) or its rate squared plus its acceleration (level 2), and the
/// true rates' weighted size (alone at level 0). At 256 bits, whose exponent range no
/// mechanism leaves: a squared rate that underflows in f64 by itself (1e-200 rad/s on a
/// mechanism of 1e300) still counts, and a size times a squared rate beyond f64's range (1e30
/// rad/s on the same) is a number, not an infinity that would excuse any error.
pub fn rate_size(truth: &Truth, rates: &[Big], size: f64, level: usize) -> Big {
    let (w, a) = (
        Big::from_f64(truth.omega.abs()),
        Big::from_f64(truth.alpha.abs()),
    );
    let size = Big::from_f64(size);
    let floor = match level {
        1 => &size * &w,
        2 => &size * &w * &w + &size * &a,
        _ => Big::zero(),
    };
    rates.iter().zip(&truth.columns).fold(floor, |m, (r, c)| {
        let weighted = if c.is_finite() {
            (r * Big::from_f64(*c)).abs()
        } else {
            Big::from_f64(f64::MAX).square()
        };
        m.max(weighted)
    })
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

/// The largest loop residual component relative to the magnitudes of all the loops together:
/// what Newton, which solves coupled loops at once, documents its floor against
/// (`16·ε·Σ|r|`), component by component as it tests it (the norm of a loop's two components,
/// up to √2 times the larger, read a Watt six-bar Newton left 4 floors up, where it stops if
/// no step lowers the residual, as 5% beyond: edge run seed 34, case 67943). A small loop that
/// shares unknowns with a large one inherits the large one's rounding.
pub fn coupled_relative_residual(model: &Model, input: f64, q: &[f64]) -> f64 {
    let state = State::from_f64(model, input, q);
    let total = model
        .loop_magnitudes(&state)
        .iter()
        .fold(0.0, |sum, m| sum + m.to_f64());
    residual(model, &state)
        .iter()
        .map(|r| r.re.abs().max(r.im.abs()).to_f64() / total)
        .fold(0.0, f64::max)
}

/// The largest component of any loop's residual, in length units: what Newton's
/// `Solved::residual_norm` reports and a stated tolerance bounds, here exact.
pub fn residual_norm(model: &Model, input: f64, q: &[f64]) -> f64 {
    let state = State::from_f64(model, input, q);
    residual(model, &state)
        .iter()
        .map(|r| r.re.abs().to_f64().max(r.im.abs().to_f64()))
        .fold(0.0, f64::max)
}

// ---------------------------------------------------------------------------------------------
// Cases

/// The float type a case runs in.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Float {
    F32,
    F64,
}

impl Float {
    pub fn epsilon(self) -> f64 {
        match self {
            Float::F32 => f64::from(f32::EPSILON),
            Float::F64 => f64::EPSILON,
        }
    }

    /// `x` rounded to this type (exactly representable in it), as an `f64`.
    pub fn round(self, x: f64) -> f64 {
        match self {
            Float::F32 => f64::from(x as f32),
            Float::F64 => x,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Float::F32 => "f32",
            Float::F64 => "f64",
        }
    }
}

/// Which entry point a case calls.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Api {
    /// `assemble(input, branches)`.
    Assemble,
    /// `motion(input, branches, ω, α)`.
    Motion,
    /// Newton: `position(input, &guess, &NewtonOptions::new(tolerance, 50))` (the default
    /// options for a tolerance of 0).
    Position,
    /// Newton and rates: `motion_near(input, &guess, &options, ω, α)`, the options as above.
    MotionNear,
    /// Every scene kernel of `scenes()`.
    Scenes,
}

impl Api {
    pub const ALL: [Api; 5] = [
        Api::Assemble,
        Api::Motion,
        Api::Position,
        Api::MotionNear,
        Api::Scenes,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Api::Assemble => "assemble",
            Api::Motion => "motion",
            Api::Position => "position",
            Api::MotionNear => "motion_near",
            Api::Scenes => "scenes",
        }
    }
}

/// One call of one entry point of one mechanism, with everything needed to repeat it.
#[derive(Clone, Debug)]
pub struct Case {
    pub kind: Kind,
    pub float: Float,
    pub api: Api,
    /// The constructor's arguments, in its order, each exactly representable in `float`:
    /// four-bar `[l1, l2, l3, l4]`, slider-crank `[l2, l3, c]`, inverted slider-crank
    /// `[l1, l2, c, γ]`, Watt `[l1, l2, l3, l4, l5, β, l6, l7, x, y]`, Stephenson
    /// `[l1, l2, l3, bc, cd, β, l4, l6, x, y]`, Jansen `[a, b, …, m]`.
    pub dims: Vec<f64>,
    /// A coupler point `(distance, angle)` for the four-bar's scenes.
    pub coupler: Option<(f64, f64)>,
    pub input: f64,
    /// One per loop.
    pub branches: Vec<Branch>,
    pub omega: f64,
    pub alpha: f64,
    /// A position near the one wanted, where the oracle has no closed form (the Stephenson
    /// six-bar): the oracle polishes it.
    pub near: Option<Vec<f64>>,
    /// Where Newton starts, as multiples of the distance from the true position at which
    /// Kantorovich still certifies convergence: within [−1, 1] inside its ball, beyond for a
    /// guess Newton promises nothing from.
    pub nudge: Vec<f64>,
    /// How the input was placed: `"anywhere"`, or how far from a limit.
    pub placement: String,
    /// Repeat with every length scaled by this factor (a power of two: angles must be
    /// bit-identical; otherwise equal to rounding).
    pub rescale: Option<f64>,
    /// Whole turns added to each angle of Newton's guess (a guess that counts a linkage's
    /// turns), rounded to the float's; 0 for none. Fewer (a quarter at a time) where the
    /// float's rounding at that many would move the guess (the reproducer's guess is the one
    /// used).
    pub turns: f64,
    /// Newton's stated tolerance, in the mechanism's length units (in the float's precision);
    /// 0 for the default options, which go to the rounding floor.
    pub tolerance: f64,
}

impl Case {
    /// The Rust that repeats the call.
    pub fn reproducer(&self) -> String {
        let t = self.float.name();
        let d = |v: f64| match self.float {
            Float::F32 => format!("{:?}", v as f32),
            Float::F64 => format!("{v:?}"),
        };
        let list = |v: &[f64]| v.iter().map(|x| d(*x)).collect::<Vec<_>>().join(", ");
        let dims = &self.dims;
        let build = match self.kind {
            Kind::FourBar => format!("FourBar::<{t}>::new({})?", list(dims)),
            Kind::SliderCrank => format!("SliderCrank::<{t}>::new({})?", list(dims)),
            Kind::InvertedSliderCrank => {
                format!("InvertedSliderCrank::<{t}>::new({})?", list(dims))
            }
            Kind::WattSixBar => format!(
                "WattSixBar::<{t}>::new([{}], {}, {}, {}, {}, ({}, {}))?",
                list(&dims[..4]),
                d(dims[4]),
                d(dims[5]),
                d(dims[6]),
                d(dims[7]),
                d(dims[8]),
                d(dims[9])
            ),
            Kind::StephensonSixBar => format!(
                "StephensonSixBar::<{t}>::new({}, {}, {}, [{}, {}], {}, {}, {}, ({}, {}))?",
                d(dims[0]),
                d(dims[1]),
                d(dims[2]),
                d(dims[3]),
                d(dims[4]),
                d(dims[5]),
                d(dims[6]),
                d(dims[7]),
                d(dims[8]),
                d(dims[9])
            ),
            Kind::JansenLeg => format!("JansenLeg::<{t}>::new([{}])?", list(dims)),
        };
        let build = match self.coupler {
            Some((a, delta)) if self.api == Api::Scenes => {
                format!("{build}.with_coupler_point({}, {})?", d(a), d(delta))
            }
            _ => build,
        };
        let branches = if self.branches.len() == 1 {
            format!("{:?}", self.branches[0])
        } else {
            format!("{:?}", self.branches)
        };
        let options = if self.tolerance == 0.0 {
            "NewtonOptions::default()".to_string()
        } else {
            format!("NewtonOptions::new({}, 50)", d(self.tolerance))
        };
        let call = match self.api {
            Api::Assemble => format!(".assemble({}, {branches})", d(self.input)),
            Api::Motion => format!(
                ".motion({}, {branches}, {}, {})",
                d(self.input),
                d(self.omega),
                d(self.alpha)
            ),
            Api::Position => format!(".position({}, &guess, &{options})", d(self.input)),
            Api::MotionNear => format!(
                ".motion_near({}, &guess, &{options}, {}, {})",
                d(self.input),
                d(self.omega),
                d(self.alpha)
            ),
            Api::Scenes => format!(
                ".scenes()?.<each>({}, {branches}, {}, {})",
                d(self.input),
                d(self.omega),
                d(self.alpha)
            ),
        };
        let rescale = self
            .rescale
            .map_or(String::new(), |f| format!(" [then every length × {f:e}]"));
        let turns = if self.turns == 0.0 {
            String::new()
        } else {
            format!(" [the guess's angles + {} turns]", self.turns)
        };
        format!("{build}{call}{rescale}{turns} [{}]", self.placement)
    }
}

/// Whether a constructor must accept these dimensions: positive, finite lengths that close
/// their loops at some input (and, for the Jansen leg, its two rigid triangles), judged exactly.
/// `None` where that is within rounding `eta` (relative to the lengths involved) of failing,
/// where either answer is right.
pub fn valid_dimensions(kind: Kind, dims: &[f64], eta: f64) -> Option<bool> {
    let b = |i: usize| Big::from_f64(dims[i]);
    if dims.iter().any(|d| !d.is_finite()) {
        return Some(false);
    }
    // Each condition as `slack ≥ 0`, with the size of the numbers it compares.
    let mut conditions: Vec<(Big, Big)> = Vec::new();
    let positive = |slots: &[usize]| slots.iter().all(|&i| dims[i] > 0.0);
    let ok = match kind {
        Kind::FourBar => {
            let size = b(0) + b(1) + b(2) + b(3);
            conditions.push((b(0) + b(1) - (b(2) - b(3)).abs(), size.clone()));
            conditions.push((b(2) + b(3) - (b(0) - b(1)).abs(), size));
            positive(&[0, 1, 2, 3])
        }
        Kind::SliderCrank => {
            conditions.push((b(0) + b(1) - b(2).abs(), b(0) + b(1) + b(2).abs()));
            positive(&[0, 1])
        }
        Kind::InvertedSliderCrank => {
            let offset = (b(2) * b(3).sin()).abs();
            conditions.push((
                b(0) + b(1) - &offset,
                b(0) + b(1) + b(2).abs() * (Big::one() + b(3).abs()),
            ));
            positive(&[0, 1])
        }
        Kind::WattSixBar | Kind::StephensonSixBar => positive(&[0, 1, 2, 3, 4, 6, 7]),
        Kind::JansenLeg => {
            for (p, q, r) in [(1, 3, 4), (6, 8, 7)] {
                let size = b(p) + b(q) + b(r);
                conditions.push((b(r) - (b(p) - b(q)).abs(), size.clone()));
                conditions.push((b(p) + b(q) - b(r), size));
            }
            positive(&(0..13).collect::<Vec<_>>())
        }
    };
    if !ok {
        return Some(false);
    }
    let tolerance = Big::from_f64(eta);
    if conditions
        .iter()
        .any(|(slack, size)| slack.abs() <= &tolerance * size)
    {
        return None;
    }
    Some(conditions.iter().all(|(slack, _)| !slack.is_negative()))
}

// ---------------------------------------------------------------------------------------------
/// The accuracy contract (README, "Accuracy") as checks of mechgen's answers against the
/// oracle. With ε the float's epsilon, κ the condition estimate (the larger of what mechgen
/// reports at its answer and the oracle's at the true position: the contract's κ is an
/// estimate of the latter, and near the singular threshold the answer's own κ moves by more
/// than rounding) and ρ the aspect:
///
/// - every `Ok` is finite; its loops close to the rounding floor, `16·ε·Σ|r|` per loop; it is
///   on the requested branch (or on a branch the oracle cannot tell from it within the bound);
///   its position is within `32·ε·κ` of the truth (each unknown weighted by its Jacobian
///   column, over the size; for Newton, over the larger of the size and each loop's
///   magnitudes at the truth, which its stop is derived from), its rates within `16·ε·κ²·ρ`
///   and its accelerations within `16·ε·κ³·ρ²` (over the rates' size), Newton's with what its
///   position's error carries on top (`32·m·ε·κ²·ρ` and `64·m·ε·κ³·ρ`, m the columns that
///   error moves); a tracked point within the first-order propagation of those bounds through
///   its vectors;
/// - an `Ok` where the oracle finds no assembly only within rounding `16·ε` of a limit (by the
///   reach's slack) or, from Newton, within its own residual of one (its backward error);
/// - every `Err` is the right one: `CannotAssemble` only where the oracle says the loops do not
///   close, or within rounding `16·ε` of a limit (by the reach's slack); `Singular` only where
///   some position within the bound of the truth is at the documented threshold,
///   `1/κ ≤ √ε + N·16·ε·κ·ρ`, or the loops are within rounding of a limit; Newton's
///   `OtherBranch` and `NoConvergence` only where its guess was outside the basin Kantorovich
///   certifies (rounding the guess to the float put it there, or the draw, a tenth of the
///   time, 2 to 10⁴ times as far); from there, an `Ok` on the guess's own branch (a loop
///   whose guess lies within the answer's error of its mirror image on either); nothing else;
/// - scaling every length by a power of two changes no outcome and no angle's bits (lengths
///   scale exactly); by another factor, outcomes change only within rounding of a limit or the
///   threshold, or among Newton's documented outcomes from a guess outside Kantorovich's
///   ball, and results agree to the sum of their bounds and the data's rounding.
pub mod judge {
    use super::*;
    use mechanisms::*;
    use mechgen::{Error, NewtonOptions, Real};
    use std::fmt::Debug;
    use std::str::FromStr;

    /// The contract's factor.
    pub const FACTOR: f64 = 16.0;

    /// The contract's factor for a position (`mechgen::Accuracy::estimate`): twice
    /// [`FACTOR`], since Newton accepts a residual up to `16·ε` of the loops' magnitudes and
    /// the inverse of a column-scaled Jacobian has entries up to κ, so N unknowns' errors can
    /// add.
    pub const POSITION_FACTOR: f64 = 32.0;

    /// A broken promise: its class (what kind of failure) and what happened.
    #[derive(Clone, Debug)]
    pub struct Finding {
        pub class: String,
        pub detail: String,
    }

    /// How a case came out.
    #[derive(Clone, Debug, Default)]
    pub struct Verdict {
        /// `"Ok"`, the error's name, or `"rejected"` (the constructor refused).
        pub outcome: String,
        pub findings: Vec<Finding>,
        /// Whether the outcome's error came from a scene that tracks the coupler point.
        pub point_scene: bool,
    }

    impl Verdict {
        fn fail(&mut self, api: Api, class: &str, detail: String) {
            self.findings.push(Finding {
                class: format!("{}: {class}", api.name()),
                detail,
            });
        }
    }

    /// A scene's output, in terms the oracle knows.
    #[derive(Clone, Debug)]
    pub enum Quantity {
        /// Unknown `index` (0 value, 1 rate, 2 acceleration).
        Unknown {
            index: usize,
            level: usize,
            value: f64,
        },
        /// A tracked point (0 position, 1 velocity, 2 acceleration).
        Point {
            name: &'static str,
            level: usize,
            value: (f64, f64),
        },
    }

    /// What a solver returned, widened to f64.
    type Got<V> = Result<V, Error<f64>>;

    /// Every scene's outputs, by scene name (or why `scenes()` refused).
    pub type Scenes = Got<Vec<(&'static str, Got<Vec<Quantity>>)>>;

    use crate::reference::widen_error as widen;

    fn f<T: Real>(v: &[T]) -> Vec<f64> {
        v.iter().map(|x| x.to_f64().unwrap_or(f64::NAN)).collect()
    }

    pub fn error_name(e: &Error<f64>) -> &'static str {
        match e {
            Error::NonFinite { .. } => "NonFinite",
            Error::CannotAssemble { .. } => "CannotAssemble",
            Error::Singular { .. } => "Singular",
            Error::OtherBranch => "OtherBranch",
            Error::NoConvergence { .. } => "NoConvergence",
            Error::Inaccurate { .. } => "Inaccurate",
            _ => "other",
        }
    }

    /// The entry points of a shipped mechanism in a float type, as the judge calls them.
    pub trait Subject<T: Real>: Sized + Debug {
        const KIND: Kind;
        fn build(dims: &[T], coupler: Option<(T, T)>) -> Option<Self>;
        /// `None` where there is no closed form.
        fn assemble(&self, input: T, b: &[Branch]) -> Option<Got<Vec<f64>>>;
        /// The position, rates and accelerations, and the accuracy the `Motion` states.
        fn motion(
            &self,
            input: T,
            b: &[Branch],
            w: T,
            a: T,
        ) -> Option<Got<([Vec<f64>; 3], Stated)>>;
        /// The position, `Solved::condition` and `Solved::residual_norm`, from Newton with the
        /// stated `tolerance` (0 for the default options).
        fn position(&self, input: T, guess: &[T], tolerance: T) -> Got<(Vec<f64>, f64, f64)>;
        /// The position, rates and accelerations, `Solved::condition`, and the accuracy the
        /// `Motion` states.
        fn motion_near(
            &self,
            input: T,
            guess: &[T],
            tolerance: T,
            w: T,
            a: T,
        ) -> Got<([Vec<f64>; 3], f64, Stated)>;
        fn condition(&self, input: T, q: &[T]) -> f64;
        /// Every scene, by name, with its outputs; `None` where there are no scenes.
        fn scenes(&self, input: T, b: &[Branch], w: T, a: T) -> Option<Scenes>;
    }

    /// What a `Motion` states of its own accuracy (`mechgen::Accuracy`): the estimated
    /// relative errors of its position, velocity and acceleration.
    pub type Stated = [f64; 3];

    fn stated<T: Real>(accuracy: &mechgen::Accuracy<T>) -> Stated {
        [accuracy.position, accuracy.velocity, accuracy.acceleration]
            .map(|a| a.to_f64().unwrap_or(f64::NAN))
    }

    fn point<T: Real>(name: &'static str, level: usize, v: mechgen::Vec2<T>) -> Quantity {
        Quantity::Point {
            name,
            level,
            value: (
                v.x.to_f64().unwrap_or(f64::NAN),
                v.y.to_f64().unwrap_or(f64::NAN),
            ),
        }
    }

    fn unknown<T: Real>(index: usize, level: usize, v: T) -> Quantity {
        Quantity::Unknown {
            index,
            level,
            value: v.to_f64().unwrap_or(f64::NAN),
        }
    }

    fn unknowns<T: Real>(pairs: &[(usize, usize, T)]) -> Vec<Quantity> {
        pairs.iter().map(|&(i, l, v)| unknown(i, l, v)).collect()
    }

    macro_rules! newton_entry_points {
        ($unknowns:ident) => {
            fn position(&self, input: T, guess: &[T], tolerance: T) -> Got<(Vec<f64>, f64, f64)> {
                let guess = $unknowns::from_array(guess.try_into().expect("a guess per unknown"));
                self.position(input, &guess, &NewtonOptions::new(tolerance, 50))
                    .map(|s| {
                        (
                            f(&s.value.to_array()),
                            s.condition.to_f64().unwrap_or(f64::NAN),
                            s.residual_norm.to_f64().unwrap_or(f64::NAN),
                        )
                    })
                    .map_err(widen)
            }

            fn motion_near(
                &self,
                input: T,
                guess: &[T],
                tolerance: T,
                w: T,
                a: T,
            ) -> Got<([Vec<f64>; 3], f64, Stated)> {
                let guess = $unknowns::from_array(guess.try_into().expect("a guess per unknown"));
                let options = NewtonOptions::new(tolerance, 50);
                let general = self.motion_near(input, &guess, &options, w, a);
                // The prepared solver gives the same bits, errors included (compared as
                // printed: a NaN in an error is the same NaN).
                if let Ok(newton) = self.newton() {
                    let prepared = newton.motion_near(input, &guess, &options, w, a);
                    assert_eq!(
                        format!("{prepared:?}"),
                        format!("{general:?}"),
                        "`newton()?.motion_near` against `motion_near`"
                    );
                }
                general
                    .map(|s| {
                        let m = s.value;
                        (
                            [
                                f(&m.position.to_array()),
                                f(&m.velocity.to_array()),
                                f(&m.acceleration.to_array()),
                            ],
                            s.condition.to_f64().unwrap_or(f64::NAN),
                            stated(&m.accuracy),
                        )
                    })
                    .map_err(widen)
            }

            fn condition(&self, input: T, q: &[T]) -> f64 {
                let q = $unknowns::from_array(q.try_into().expect("a value per unknown"));
                self.condition(input, &q).to_f64().unwrap_or(f64::NAN)
            }
        };
    }

    macro_rules! closed_entry_points {
        ($branches:expr) => {
            fn assemble(&self, input: T, b: &[Branch]) -> Option<Got<Vec<f64>>> {
                Some(
                    self.assemble(input, $branches(b))
                        .map(|q| f(&q.to_array()))
                        .map_err(widen),
                )
            }

            fn motion(
                &self,
                input: T,
                b: &[Branch],
                w: T,
                a: T,
            ) -> Option<Got<([Vec<f64>; 3], Stated)>> {
                Some(
                    self.motion(input, $branches(b), w, a)
                        .map(|m| {
                            (
                                [
                                    f(&m.position.to_array()),
                                    f(&m.velocity.to_array()),
                                    f(&m.acceleration.to_array()),
                                ],
                                stated(&m.accuracy),
                            )
                        })
                        .map_err(widen),
                )
            }
        };
    }

    fn one(b: &[Branch]) -> Branch {
        b[0]
    }

    fn two(b: &[Branch]) -> [Branch; 2] {
        [b[0], b[1]]
    }

    fn three(b: &[Branch]) -> [Branch; 3] {
        [b[0], b[1], b[2]]
    }

    impl<T: Real> Subject<T> for FourBar<T> {
        const KIND: Kind = Kind::FourBar;

        fn build(d: &[T], coupler: Option<(T, T)>) -> Option<Self> {
            let m = FourBar::new(d[0], d[1], d[2], d[3]).ok()?;
            match coupler {
                Some((a, delta)) => m.with_coupler_point(a, delta).ok(),
                None => Some(m),
            }
        }

        closed_entry_points!(one);
        newton_entry_points!(FourBarUnknowns);

        fn scenes(&self, input: T, b: &[Branch], w: T, a: T) -> Option<Scenes> {
            let s = match self.scenes() {
                Ok(s) => s,
                Err(e) => return Some(Err(widen(e))),
            };
            let b = b[0];
            Some(Ok(vec![
                (
                    "angles",
                    s.angles(input, b, w, a)
                        .map(|o| {
                            unknowns(&[
                                (0, 0, o.theta3),
                                (1, 0, o.theta4),
                                (0, 1, o.theta3_dot),
                                (1, 1, o.theta4_dot),
                                (0, 2, o.theta3_ddot),
                                (1, 2, o.theta4_ddot),
                            ])
                        })
                        .map_err(widen),
                ),
                (
                    "joints",
                    s.joints(input, b)
                        .map(|o| {
                            vec![
                                point("crank_pin", 0, o.crank_pin),
                                point("rocker_pin", 0, o.rocker_pin),
                            ]
                        })
                        .map_err(widen),
                ),
                (
                    "coupler_path",
                    s.coupler_path(input, b)
                        .map(|o| vec![point("coupler_point", 0, o.coupler_point)])
                        .map_err(widen),
                ),
                (
                    "coupler_motion",
                    s.coupler_motion(input, b, w, a)
                        .map(|o| {
                            vec![
                                point("coupler_point", 0, o.coupler_point),
                                point("coupler_point", 1, o.coupler_point_dot),
                                point("coupler_point", 2, o.coupler_point_ddot),
                            ]
                        })
                        .map_err(widen),
                ),
            ]))
        }
    }

    impl<T: Real> Subject<T> for SliderCrank<T> {
        const KIND: Kind = Kind::SliderCrank;

        fn build(d: &[T], _: Option<(T, T)>) -> Option<Self> {
            SliderCrank::new(d[0], d[1], d[2]).ok()
        }

        closed_entry_points!(one);
        newton_entry_points!(SliderCrankUnknowns);

        fn scenes(&self, input: T, b: &[Branch], w: T, a: T) -> Option<Scenes> {
            let s = match self.scenes() {
                Ok(s) => s,
                Err(e) => return Some(Err(widen(e))),
            };
            let b = b[0];
            Some(Ok(vec![
                (
                    "state",
                    s.state(input, b, w, a)
                        .map(|o| {
                            unknowns(&[
                                (0, 0, o.theta3),
                                (1, 0, o.d),
                                (0, 1, o.theta3_dot),
                                (1, 1, o.d_dot),
                                (0, 2, o.theta3_ddot),
                                (1, 2, o.d_ddot),
                            ])
                        })
                        .map_err(widen),
                ),
                (
                    "slider",
                    s.slider(input, b, w, a)
                        .map(|o| unknowns(&[(1, 0, o.d), (1, 1, o.d_dot), (1, 2, o.d_ddot)]))
                        .map_err(widen),
                ),
            ]))
        }
    }

    impl<T: Real> Subject<T> for InvertedSliderCrank<T> {
        const KIND: Kind = Kind::InvertedSliderCrank;

        fn build(d: &[T], _: Option<(T, T)>) -> Option<Self> {
            InvertedSliderCrank::new(d[0], d[1], d[2], d[3]).ok()
        }

        closed_entry_points!(one);
        newton_entry_points!(InvertedSliderCrankUnknowns);

        fn scenes(&self, input: T, b: &[Branch], w: T, a: T) -> Option<Scenes> {
            let s = match self.scenes() {
                Ok(s) => s,
                Err(e) => return Some(Err(widen(e))),
            };
            Some(Ok(vec![(
                "state",
                s.state(input, b[0], w, a)
                    .map(|o| {
                        unknowns(&[
                            (0, 0, o.theta4),
                            (1, 0, o.b),
                            (0, 1, o.theta4_dot),
                            (1, 1, o.b_dot),
                            (0, 2, o.theta4_ddot),
                            (1, 2, o.b_ddot),
                        ])
                    })
                    .map_err(widen),
            )]))
        }
    }

    impl<T: Real> Subject<T> for WattSixBar<T> {
        const KIND: Kind = Kind::WattSixBar;

        fn build(d: &[T], _: Option<(T, T)>) -> Option<Self> {
            WattSixBar::new(
                [d[0], d[1], d[2], d[3]],
                d[4],
                d[5],
                d[6],
                d[7],
                (d[8], d[9]),
            )
            .ok()
        }

        closed_entry_points!(two);
        newton_entry_points!(WattSixBarUnknowns);

        fn scenes(&self, input: T, b: &[Branch], w: T, a: T) -> Option<Scenes> {
            let s = match self.scenes() {
                Ok(s) => s,
                Err(e) => return Some(Err(widen(e))),
            };
            Some(Ok(vec![(
                "output",
                s.output(input, two(b), w, a)
                    .map(|o| {
                        unknowns(&[
                            (3, 0, o.theta6),
                            (3, 1, o.theta6_dot),
                            (3, 2, o.theta6_ddot),
                        ])
                    })
                    .map_err(widen),
            )]))
        }
    }

    impl<T: Real> Subject<T> for StephensonSixBar<T> {
        const KIND: Kind = Kind::StephensonSixBar;

        fn build(d: &[T], _: Option<(T, T)>) -> Option<Self> {
            StephensonSixBar::new(
                d[0],
                d[1],
                d[2],
                [d[3], d[4]],
                d[5],
                d[6],
                d[7],
                (d[8], d[9]),
            )
            .ok()
        }

        fn assemble(&self, _: T, _: &[Branch]) -> Option<Got<Vec<f64>>> {
            None
        }

        fn motion(&self, _: T, _: &[Branch], _: T, _: T) -> Option<Got<([Vec<f64>; 3], Stated)>> {
            None
        }

        newton_entry_points!(StephensonSixBarUnknowns);

        fn scenes(&self, _: T, _: &[Branch], _: T, _: T) -> Option<Scenes> {
            None
        }
    }

    impl<T: Real> Subject<T> for JansenLeg<T> {
        const KIND: Kind = Kind::JansenLeg;

        fn build(d: &[T], _: Option<(T, T)>) -> Option<Self> {
            JansenLeg::new(d.try_into().ok()?).ok()
        }

        closed_entry_points!(three);
        newton_entry_points!(JansenLegUnknowns);

        fn scenes(&self, input: T, b: &[Branch], w: T, a: T) -> Option<Scenes> {
            let s = match self.scenes() {
                Ok(s) => s,
                Err(e) => return Some(Err(widen(e))),
            };
            let b = three(b);
            Some(Ok(vec![
                (
                    "foot_path",
                    s.foot_path(input, b)
                        .map(|o| vec![point("foot", 0, o.foot)])
                        .map_err(widen),
                ),
                (
                    "foot_motion",
                    s.foot_motion(input, b, w, a)
                        .map(|o| {
                            vec![
                                point("foot", 0, o.foot),
                                point("foot", 1, o.foot_dot),
                                point("foot", 2, o.foot_ddot),
                            ]
                        })
                        .map_err(widen),
                ),
            ]))
        }
    }

    /// Judges one case.
    pub fn judge(case: &Case) -> Verdict {
        match case.float {
            Float::F32 => judge_in::<f32>(case),
            Float::F64 => judge_in::<f64>(case),
        }
    }

    fn judge_in<T: Real + FromStr + Into<f64>>(case: &Case) -> Verdict {
        match case.kind {
            Kind::FourBar => run::<T, FourBar<T>>(case),
            Kind::SliderCrank => run::<T, SliderCrank<T>>(case),
            Kind::InvertedSliderCrank => run::<T, InvertedSliderCrank<T>>(case),
            Kind::WattSixBar => run::<T, WattSixBar<T>>(case),
            Kind::StephensonSixBar => run::<T, StephensonSixBar<T>>(case),
            Kind::JansenLeg => run::<T, JansenLeg<T>>(case),
        }
    }

    /// What the oracle says about a case.
    #[derive(Clone)]
    struct Expect {
        model: Model,
        params: Params,
        reach: Option<Reach>,
        truth: Option<Truth>,
        others: Vec<Truth>,
        eps: f64,
        input: f64,
        /// The input's rate and acceleration.
        omega: f64,
        alpha: f64,
        /// Whether Newton's guess was near no solution at the input (an unreachable input's
        /// guess, from the mirrored one): its branch is then undefined, and any accurate
        /// solution is right.
        guess_near_none: bool,
        /// Newton's stated tolerance (0 for the default options).
        tolerance: f64,
        /// Whether the call judged tracks the coupler point (a scene of it).
        point_scene: bool,
    }

    impl Expect {
        fn size(&self) -> f64 {
            self.model.size
        }

        /// The size, with a four-bar's coupler point's distance where the call judged tracks
        /// the point (`point_scene`): how far what it computes reaches, which a point far off
        /// makes far more than the loops (its rates with it).
        fn reach_size(&self, point_scene: bool) -> f64 {
            let coupler = if point_scene && self.model.kind == Kind::FourBar {
                self.params.get_or("a", 0.0).abs()
            } else {
                0.0
            };
            self.size() + coupler
        }

        fn n(&self) -> usize {
            self.model.unknowns()
        }

        /// Within rounding of a limit (or unreachable, for the error checks).
        fn unreachable_or_near_limit(&self) -> bool {
            match &self.reach {
                Some(r) => !r.reachable() || r.near_limit(FACTOR * self.eps),
                None => self.truth.is_none(),
            }
        }

        fn near_limit(&self) -> bool {
            self.reach.is_some_and(|r| r.near_limit(FACTOR * self.eps))
        }

        /// The contract's κ: the larger of the reported one and the truth's.
        fn kappa(&self, reported: f64) -> f64 {
            let truth = self.truth.as_ref().map_or(1.0, |t| t.condition);
            let reported = if reported.is_nan() { 1.0 } else { reported };
            truth.max(reported).max(1.0)
        }

        fn rho(&self) -> f64 {
            self.truth.as_ref().map_or(1.0, |t| t.aspect(self.size()))
        }

        /// What the float's range costs rates (`level` 1) or accelerations (2) relative to
        /// the sizes the contract measures them by: results below its normal range (a rod
        /// of 1e300 turning at 1e-180 rad/s, whose angular acceleration of 1e-360 no f64
        /// holds) are known only to the spacing of its subnormal numbers, against the size
        /// times the input's rate (or its square plus its acceleration), the size at most 1
        /// for an angle's and 1 where every unknown is an angle
        /// (`mechgen::__private::stated_in_own_units`, 16 times).
        fn range_floor(&self, level: i32) -> f64 {
            self.range_floor_scaled(level, 1.0)
        }

        /// [`Self::range_floor`] with every length times `factor` (the rates as they are).
        fn range_floor_scaled(&self, level: i32, factor: f64) -> f64 {
            let Some(t) = &self.truth else {
                return 0.0;
            };
            // A length's rates are nearer the floor on a tiny mechanism; an angle's are not.
            let lengths = self.model.angles.iter().any(|angle| !angle);
            let spacing = if self.eps > 1e-10 {
                f64::from(f32::MIN_POSITIVE) * f64::from(f32::EPSILON)
            } else {
                f64::MIN_POSITIVE * f64::EPSILON
            } * 16.0
                * if lengths {
                    (1.0 / (self.size() * factor)).max(1.0)
                } else {
                    1.0
                };
            let (w, a) = (t.omega.abs(), t.alpha.abs());
            if level == 1 {
                return if w == 0.0 { 0.0 } else { spacing / w };
            }
            // `spacing/(ω² + |α|)` within a factor of 2, where `ω²` underflows in f64.
            if w == 0.0 && a == 0.0 {
                return 0.0;
            }
            let by_rate = if w > 0.0 {
                spacing / w / w
            } else {
                f64::INFINITY
            };
            let by_acceleration = if a > 0.0 { spacing / a } else { f64::INFINITY };
            by_rate.min(by_acceleration)
        }

        /// Whether mechgen's estimate (`mechgen::Accuracy::estimate`, or `estimate_at` for rates
        /// at a `newton` position) of `order` at the true position, with κ up to eight times
        /// the truth's (as it is at a position within its error of the truth near a toggle)
        /// and the judge's aspect, plus the float's floor (64 times [`Self::range_floor`]: the
        /// runtime's is relative to the longest length and the scaled rates, within a few
        /// times of the judge's), exceeds `mechgen::Accuracy::required`: then `Inaccurate` is
        /// the documented answer.
        fn inaccuracy_allowed(&self, order: mechgen::Order, newton: bool) -> bool {
            self.inaccuracy_allowed_scaled(order, newton, 1.0)
        }

        /// [`Self::inaccuracy_allowed`] with every length times `factor`: the same but for
        /// the float's floor, which a tiny mechanism's rates of lengths meet sooner.
        fn inaccuracy_allowed_scaled(
            &self,
            order: mechgen::Order,
            newton: bool,
            factor: f64,
        ) -> bool {
            let Some(t) = &self.truth else {
                return true;
            };
            // Near a toggle κ at the computed position, within the position's error of the
            // truth, can exceed the true κ by several times.
            let kappa = 8.0 * t.condition.max(1.0);
            let shrunk = (self.rho() / 16.0).max(1.0);
            let e = self.eps;
            // A vector shorter than √ε of the size leaves its angle's rates undetermined.
            if order != mechgen::Order::Position && self.rho() * e.sqrt() >= 1.0 {
                return true;
            }
            // A stated tolerance above the floor leaves the position as far off as 2·κ·r, r up
            // to the tolerance, against the loop it is read in (the smallest, at most), the
            // largest loop's magnitudes over the size where they exceed it (README,
            // "Accuracy"): at most this.
            let stopped_short = if newton && self.tolerance > 0.0 {
                let magnitudes: Vec<f64> = self
                    .model
                    .loop_magnitudes(&t.state)
                    .iter()
                    .map(Big::to_f64)
                    .collect();
                let smallest = magnitudes.iter().copied().fold(f64::INFINITY, f64::min);
                let largest = magnitudes.iter().copied().fold(0.0, f64::max);
                2.0 * kappa * self.tolerance / smallest * (largest / self.size()).max(1.0)
            } else {
                0.0
            };
            // Rates at a Newton position carry its error δ, 32·ε·κ on its floor, through the
            // Jacobian (README, "Accuracy"): m·κ·ρ·δ more for a velocity (32·m·ε·κ²·ρ on the
            // floor), 2·m·κ²·ρ·δ for an acceleration (64·m·ε·κ³·ρ), with m the columns the
            // position's error moves.
            let (newton_velocity, newton_acceleration) = if newton {
                let rho = self.rho().max(1.0);
                let delta = (POSITION_FACTOR * e * kappa).max(stopped_short);
                let carried = self.model.kind.moving() * kappa * rho * delta;
                (carried, 2.0 * kappa * carried)
            } else {
                (0.0, 0.0)
            };
            let (estimate, required) = match order {
                mechgen::Order::Position => {
                    ((POSITION_FACTOR * e * kappa).max(stopped_short), e.sqrt())
                }
                mechgen::Order::Velocity => (
                    e * kappa * (64.0 + 12.0 * kappa) * shrunk
                        + newton_velocity
                        + 64.0 * self.range_floor_scaled(1, factor),
                    e.cbrt(),
                ),
                mechgen::Order::Acceleration => (
                    e * kappa * (256.0 + kappa * kappa) * shrunk * shrunk
                        + newton_acceleration
                        + 64.0 * self.range_floor_scaled(2, factor),
                    e.sqrt().sqrt(),
                ),
            };
            !kappa.is_finite() || estimate > required
        }

        /// Whether some position within the bound of the truth is at the singular threshold.
        fn singular_allowed(&self) -> bool {
            if self.near_limit() {
                return true;
            }
            let Some(t) = &self.truth else {
                return true;
            };
            let kappa = t.condition;
            if !kappa.is_finite() {
                return true;
            }
            let n = self.n() as f64;
            1.0 / kappa <= self.eps.sqrt() + n * FACTOR * self.eps * kappa * t.aspect(self.size())
        }

        /// Judges a position.
        fn position(
            &self,
            v: &mut Verdict,
            api: Api,
            q: &[f64],
            reported_kappa: f64,
            wanted: &[Branch],
        ) {
            if q.iter().any(|x| !x.is_finite()) {
                v.fail(api, "not finite inside Ok", format!("{q:?}"));
                return;
            }
            // The floor, 16·ε·Σ|r|, plus what evaluating a loop of n vectors in the float
            // rounds (each vector to ε, each of the n − 1 sums to ε/2: under n·ε·Σ|r|).
            let terms = self.model.loops.iter().map(Vec::len).max().unwrap_or(0) as f64;
            // Newton stops where no step lowers the residual, up to four times its floor
            // (`mechgen::NewtonOptions`), against all the loops' magnitudes together.
            let newton = matches!(api, Api::Position | Api::MotionNear);
            let floor = (FACTOR + terms) * self.eps * if newton { 4.0 } else { 1.0 };
            let residual = if newton {
                coupled_relative_residual(&self.model, self.input, q)
            } else {
                relative_residual(&self.model, self.input, q)
            };
            // A stated tolerance stops Newton where every component of the residual is within
            // it (as the float evaluates it, to the floor's rounding), wherever that is above
            // the floor.
            let stated = newton && self.tolerance > 0.0;
            let absolute = if stated {
                residual_norm(&self.model, self.input, q)
            } else {
                0.0
            };
            let tolerated = stated && absolute <= self.tolerance + floor * self.size();
            if residual > floor && !tolerated {
                v.fail(
                    api,
                    "residual above the rounding floor",
                    if stated {
                        format!("residual {absolute:.2e}, above the tolerance {:.2e} and the floor (16 + n)·ε of the loop's magnitudes", self.tolerance)
                    } else {
                        format!("residual {residual:.2e} of the loop's magnitudes, floor (16 + n)·ε = {floor:.2e}")
                    },
                );
            }
            let Some(truth) = &self.truth else {
                if self.reach.is_none() {
                    // No closed form and no certified root: nothing to judge by.
                    return;
                }
                let state = State::from_f64(&self.model, self.input, q);
                let (branches, _) = branch_signs(&self.model, &state);
                if !self.unreachable_or_near_limit() {
                    v.fail(api, "Ok where the oracle has no position", format!("{q:?}"));
                } else if self.near_limit() || (newton && self.within_backward_error(q)) {
                    // Within rounding of a limit, where the branches meet: either is right.
                } else if self.accurate_elsewhere(q, &branches, reported_kappa) {
                    if !self.guess_near_none {
                        v.fail(
                            api,
                            "wrong branch",
                            format!(
                                "a solution on {branches:?}, asked {wanted:?}, which does not close"
                            ),
                        );
                    }
                } else if branches != wanted && residual <= floor {
                    v.fail(
                        api,
                        "Ok on another branch than asked, without saying so",
                        format!("signs {branches:?}, asked {wanted:?}"),
                    );
                } else {
                    let r = self.reach.expect("a reach");
                    v.fail(
                        api,
                        "Ok beyond the range of motion",
                        format!(
                            "gap {:.2e} of the size ({:.1} × rounding), margin {:.2e} rad",
                            r.gap,
                            r.gap.abs() / (FACTOR * self.eps * r.slack),
                            r.margin
                        ),
                    );
                }
                return;
            };
            let kappa = self.kappa(reported_kappa);
            let on_floor = POSITION_FACTOR * self.eps * kappa * self.newton_size(truth, newton);
            // Above the floor, as far off as 2·κ·r for the residual r it stopped at (README,
            // "Accuracy"; Kantorovich's certificate doubles the Newton step's length at most).
            let bound = on_floor.max(2.0 * kappa * absolute / self.size());
            let error = position_error(&self.model, truth, q);
            let state = State::from_f64(&self.model, self.input, q);
            let (branches, _) = branch_signs(&self.model, &state);
            // Near a toggle the other branch lies within the bound too: either label is right.
            let other_close = self.others.iter().any(|o| {
                position_error(&self.model, o, q) <= bound
                    || position_error(
                        &self.model,
                        o,
                        &truth.q().iter().map(Big::to_f64).collect::<Vec<_>>(),
                    ) <= bound
            });
            if error > bound {
                let on_other = self
                    .others
                    .iter()
                    .any(|o| position_error(&self.model, o, q) <= bound);
                if on_other {
                    v.fail(
                        api,
                        "wrong branch",
                        format!("on another branch than {wanted:?} (κ {kappa:.2e})"),
                    );
                } else {
                    v.fail(
                        api,
                        if stated {
                            "position error beyond 32·ε·κ and 2·κ·r (a stated tolerance)"
                        } else {
                            "position error beyond 32·ε·κ"
                        },
                        format!(
                            "error {error:.2e} = {:.1} × bound (κ {kappa:.2e}, true κ {:.2e})",
                            error / bound,
                            truth.condition
                        ),
                    );
                }
            } else if self.model.kind != Kind::StephensonSixBar
                && branches != wanted
                && !other_close
            {
                v.fail(
                    api,
                    "wrong branch",
                    format!("signs {branches:?}, asked {wanted:?}"),
                );
            }
        }

        /// A Newton position's size over the mechanism's (at least 1): the contract's 32·ε·κ
        /// is derived from Newton's stop (README, "Accuracy"; `mechgen::Accuracy`), a residual
        /// up to 16·ε of each loop's own magnitudes, through an inverse Jacobian whose
        /// column-scaled entries are at most κ: so it is relative to the larger of the
        /// declared lengths' sum and each loop's magnitudes at the position, where a slide's
        /// extension counts (an inverted slider-crank's slide can be 130 times its crank and
        /// the loop twice the declared lengths). 1 for the closed forms, which are held to the
        /// declared lengths.
        fn newton_size(&self, truth: &Truth, newton: bool) -> f64 {
            if !newton {
                return 1.0;
            }
            self.model
                .loop_magnitudes(&truth.state)
                .iter()
                .fold(self.size(), |m, r| m.max(r.to_f64()))
                / self.size()
        }

        /// Whether a Newton position, where the oracle finds no assembly, is the exact one of
        /// data within its own residual: its loops close to that residual (at most the floor
        /// judged above), so it solves the mechanism with each loop's chord moved by that much,
        /// and the reach's gap moves by at most the largest loop's relative residual times the
        /// slack, and by at most the residual itself (a chord moved by a length changes by at
        /// most that length): for a loop far smaller than the mechanism, the residual it is
        /// held to, of its own magnitudes, is small, but the rounding of where it hangs from is
        /// of the size (edge run seed 26, case 830561: an f32 Watt six-bar whose dyad, 1e-8
        /// of the size, closed to 8.8e-8 where the oracle finds it 3.4e-8 short). Such an
        /// answer is past the limit by no more than its backward error, the rounding the
        /// contract allows Newton's stop (README, "Accuracy": up to four times `16·ε·Σ|r|`
        /// where no step lowers it) or a stated tolerance, not by more than rounding.
        ///
        /// The reach is the asked assembly's, and the position's own (where the first loop's
        /// branch sets the second's chord, Newton from a guess on another branch may stop
        /// at another assembly's limit: seed 25, `ratios/newton`, case 96232, an f32 Watt
        /// six-bar whose dyad, 3e-4 of a mechanism of 17, misses by 4.3e-4 on the asked first
        /// loop's branch, Newton's position on the other).
        fn within_backward_error(&self, q: &[f64]) -> bool {
            let eta = relative_residual(&self.model, self.input, q).max(FACTOR * self.eps);
            // Each loop's residual vector, at most √2 times its largest component.
            let moved =
                std::f64::consts::SQRT_2 * residual_norm(&self.model, self.input, q) / self.size();
            let within = |r: &Reach| r.near_limit(eta) || r.gap.abs() <= moved;
            let state = State::from_f64(&self.model, self.input, q);
            let (branches, _) = branch_signs(&self.model, &state);
            let own = closed_form(
                self.model.kind,
                &self.params,
                self.input,
                &branches,
                0.0,
                0.0,
            )
            .map(|o| o.reach);
            self.reach.as_ref().is_some_and(within) || own.as_ref().is_some_and(within)
        }

        /// Whether `q` is within the bound of the truth on `branches` (another branch than asked).
        fn accurate_elsewhere(&self, q: &[f64], branches: &[Branch], reported_kappa: f64) -> bool {
            let Some(o) = closed_form(
                self.model.kind,
                &self.params,
                self.input,
                branches,
                0.0,
                0.0,
            ) else {
                return false;
            };
            let Some(t) = o.truth else {
                return false;
            };
            let kappa = t.condition.max(reported_kappa).max(1.0);
            // A stated tolerance's position, as `position` judges it.
            let stopped_short = if self.tolerance > 0.0 {
                2.0 * kappa * residual_norm(&self.model, self.input, q) / self.size()
            } else {
                0.0
            };
            position_error(&self.model, &t, q)
                <= (POSITION_FACTOR * self.eps * kappa).max(stopped_short)
        }

        /// Judges rates and accelerations.
        fn rates(&self, v: &mut Verdict, api: Api, rates: &[Vec<f64>], reported_kappa: f64) {
            let Some(truth) = &self.truth else {
                return;
            };
            // These bounds are a default solve's, on the floor. Rates solved at a position a
            // stated tolerance stopped short of it carry its error, and the `Motion` says how
            // much: `within_stated` holds them to that (and fails a value that is not finite).
            if matches!(api, Api::Position | Api::MotionNear) && self.tolerance > 0.0 {
                return;
            }
            let (Some(tv), Some(ta)) = (&truth.velocity, &truth.acceleration) else {
                v.fail(
                    api,
                    "rates where the Jacobian is exactly singular",
                    String::new(),
                );
                return;
            };
            let kappa = self.kappa(reported_kappa);
            let rho = self.rho();
            let size = self.size();
            // Rates at a Newton position carry its error, 32·ε·κ on its floor, through the
            // Jacobian (README, "Accuracy"; `mechgen::Accuracy::estimate_at`): m·κ·ρ times
            // it for a velocity, twice κ times that for an acceleration, with m the columns
            // the position's error moves. A closed form's position carries nothing.
            let newton = api == Api::MotionNear;
            let carried = if newton {
                self.model.kind.moving() * kappa * rho.max(1.0) * POSITION_FACTOR * self.eps * kappa
            } else {
                0.0
            };
            for (level, (got, want)) in [(1, (&rates[0], tv)), (2, (&rates[1], ta))] {
                if got.iter().any(|x| !x.is_finite()) {
                    v.fail(api, "not finite inside Ok", format!("{got:?}"));
                    return;
                }
                let rate_scale = rate_size(truth, want, size, level as usize);
                let carried = if level == 1 {
                    carried
                } else {
                    2.0 * kappa * carried
                };
                let bound = FACTOR * self.eps * kappa.powi(level + 1) * rho.powi(level)
                    + carried
                    + self.range_floor(level);
                let error = weighted_error(truth, &vec![false; self.n()], got, want, &rate_scale);
                if error > bound {
                    let what = match (level, newton) {
                        (1, false) => "velocity error beyond 16·ε·κ²·ρ",
                        (1, true) => "velocity error beyond 16·ε·κ²·ρ + 32·m·ε·κ²·ρ",
                        (_, false) => "acceleration error beyond 16·ε·κ³·ρ²",
                        (_, true) => "acceleration error beyond 16·ε·κ³·ρ² + 64·m·ε·κ³·ρ",
                    };
                    v.fail(
                        api,
                        what,
                        format!(
                            "error {error:.2e} = {:.1} × bound (κ {kappa:.2e}, ρ {rho:.2e})",
                            error / bound
                        ),
                    );
                }
            }
        }

        /// Whether a `Motion`'s errors are within the accuracy it states (`Motion::accuracy`,
        /// which the README calls a bound on the true error): its position's against the size
        /// (Newton's too: its estimate is stretched by the largest loop's magnitudes over the
        /// size where they exceed it), its rates' and accelerations' against their sizes,
        /// each unknown weighted by its column, as the contract measures them.
        fn within_stated(&self, v: &mut Verdict, api: Api, got: &[Vec<f64>], stated: &Stated) {
            let Some(truth) = &self.truth else {
                return;
            };
            let (Some(tv), Some(ta)) = (&truth.velocity, &truth.acceleration) else {
                return;
            };
            let size = self.size();
            let position = position_error(&self.model, truth, &got[0]);
            let no_angles = vec![false; self.n()];
            let velocity = weighted_error(
                truth,
                &no_angles,
                &got[1],
                tv,
                &rate_size(truth, tv, size, 1),
            );
            let acceleration = weighted_error(
                truth,
                &no_angles,
                &got[2],
                ta,
                &rate_size(truth, ta, size, 2),
            );
            for (what, error, bound) in [
                ("position", position, stated[0]),
                ("velocity", velocity, stated[1]),
                ("acceleration", acceleration, stated[2]),
            ] {
                // Not within for a NaN error or bound.
                let within = matches!(
                    error.partial_cmp(&bound),
                    Some(Ordering::Less | Ordering::Equal)
                );
                if !within {
                    v.fail(
                        api,
                        "error beyond the accuracy the result states",
                        format!(
                            "{what} error {error:.2e} = {:.1} × the stated {bound:.2e}",
                            error / bound
                        ),
                    );
                }
            }
        }

        /// Whether a true rate or acceleration, or one times its column (a point's speed), is
        /// beyond a sixteenth of the float's largest number, where computing it may overflow
        /// and `NonFinite` is the honest answer (edge run case 810100: an f32 rod's angular
        /// acceleration of 4e38 rad/s², turning at 3e18 rad/s).
        fn rates_unrepresentable(&self) -> bool {
            let Some(t) = &self.truth else {
                return false;
            };
            let largest = if self.eps > 1e-10 {
                f64::from(f32::MAX)
            } else {
                f64::MAX
            } / 16.0;
            let unknowns = [&t.velocity, &t.acceleration]
                .into_iter()
                .flatten()
                .flat_map(|values| values.iter().zip(&t.columns))
                .any(|(value, column)| {
                    let value = value.to_f64();
                    (value * column).abs() > largest || value.abs() > largest
                });
            // A point's acceleration sums each link's centripetal and tangential terms,
            // `|r|·(ω² + |α|)`, the input's and the unknowns' alike (a crank at ω2 = 43 rad/s
            // with a length of 2e35 is beyond f32 by itself): within the mechanism's size
            // times the largest of those.
            let spin = |w: f64, a: f64| (w * w + a.abs()).max(w.abs());
            let mut fastest = spin(t.omega, t.alpha);
            if let (Some(w), Some(a)) = (&t.velocity, &t.acceleration) {
                for (w, a) in w.iter().zip(a) {
                    fastest = fastest.max(spin(w.to_f64(), a.to_f64()));
                }
            }
            unknowns || self.reach_size(self.point_scene) * fastest > largest
        }

        /// Whether, within rounding of a limit (where the oracle has no truth to size the rates
        /// by, and `Ok` and `CannotAssemble` are both right), rates as large as a toggle's at
        /// the float's resolution may overflow: κ up to 1/ε there, and an acceleration grows
        /// as κ^1.5 of the size times the input's spin (edge run case 376075: an f32 four-bar
        /// of size 1e34, 2e-7 rad inside a limit, whose coupler point's acceleration is 3e41).
        fn rates_unbounded_near_limit(&self, size: f64) -> bool {
            let largest = if self.eps > 1e-10 {
                f64::from(f32::MAX)
            } else {
                f64::MAX
            } / 16.0;
            let spin = 1.0 + self.omega.abs() + self.omega * self.omega + self.alpha.abs();
            self.truth.is_none() && self.near_limit() && size * spin / self.eps.powf(1.5) > largest
        }

        /// Judges an error.
        fn error(&self, v: &mut Verdict, api: Api, e: &Error<f64>, newton_outside_basin: bool) {
            if matches!(e, Error::NonFinite { .. })
                && (self.rates_unrepresentable() || self.rates_unbounded_near_limit(self.size()))
            {
                return;
            }
            let documented_newton = matches!(
                e,
                Error::OtherBranch
                    | Error::NoConvergence { .. }
                    | Error::CannotAssemble { .. }
                    | Error::Singular { .. }
            );
            if newton_outside_basin && documented_newton {
                return;
            }
            // From a guess near no solution (an unreachable input's), finding one on another
            // branch and saying so is right.
            if self.guess_near_none && matches!(e, Error::OtherBranch) {
                return;
            }
            // Within rounding of a limit the branches meet, and which one Newton lands on is
            // rounding (an `Ok` on either is right there): saying it is the other is right too
            // (edge run seed 13, case 51538: an f32 slider-crank 1 ulp from a limit, scaled
            // by a factor whose rounding moves the limit by half a percent of the rod).
            if self.near_limit() && matches!(e, Error::OtherBranch) {
                return;
            }
            match e {
                Error::CannotAssemble { .. } => {
                    if !self.unreachable_or_near_limit() {
                        let r = self.reach.map_or(String::from("no closed form"), |r| {
                            format!(
                                "gap {:.2e} of the size ({:.1} × rounding), margin {:.2e} rad",
                                r.gap,
                                r.gap / (FACTOR * self.eps * r.slack),
                                r.margin
                            )
                        });
                        v.fail(api, "CannotAssemble inside the range of motion", r);
                    }
                }
                Error::Singular {
                    relative_determinant,
                    ..
                } => {
                    if !self.singular_allowed() {
                        let kappa = self.truth.as_ref().map_or(f64::NAN, |t| t.condition);
                        v.fail(
                            api,
                            "Singular away from the threshold",
                            format!("true κ {kappa:.2e} (threshold {:.2e}), reported relative determinant {relative_determinant:.2e}", 1.0 / self.eps.sqrt()),
                        );
                    }
                }
                Error::Inaccurate { order, .. } => {
                    let newton = matches!(api, Api::Position | Api::MotionNear);
                    if !self.singular_allowed() && !self.inaccuracy_allowed(*order, newton) {
                        let kappa = self.truth.as_ref().map_or(f64::NAN, |t| t.condition);
                        v.fail(
                            api,
                            "Inaccurate where the estimate is within what is required",
                            format!("true κ {kappa:.2e}, ρ {:.2e}: {e:?}", self.rho()),
                        );
                    }
                }
                other => {
                    // Where: beyond the range (the contract says CannotAssemble), or inside it
                    // from a guess Kantorovich certifies.
                    let place = if self.truth.is_none() && self.reach.is_some() {
                        " beyond the range of motion (documented: CannotAssemble)"
                    } else if matches!(other, Error::NoConvergence { .. } | Error::OtherBranch) {
                        " from a certified guess"
                    } else {
                        " for finite data"
                    };
                    v.fail(
                        api,
                        &format!("{}{place}", error_name(other)),
                        format!("{other:?}"),
                    )
                }
            }
        }

        /// A tracked point's bound at `level`: each vector's error is its length times its
        /// angle's allowed error, and its rates' errors follow by the chain rule (first order),
        /// plus rounding of the sum. At 256 bits, like the error it bounds: a huge mechanism
        /// turning fast has a point acceleration beyond f64's range, which an f64 bound would
        /// make infinite, passing anything. `None` (anything passes) where the oracle has no
        /// rates, or the allowed errors are beyond f64.
        fn point_bound(&self, terms: &[Term], level: usize, kappa: f64) -> Option<Big> {
            let t = self.truth.as_ref()?;
            let (Some(tv), Some(ta)) = (&t.velocity, &t.acceleration) else {
                return None;
            };
            let size = self.size();
            let rho = t.aspect(size);
            let n = self.n();
            let scales = [
                Big::from_f64(size),
                rate_size(t, tv, size, 1),
                rate_size(t, ta, size, 2),
            ];
            // The allowed error of unknown `j`'s angle at `level`; `None` where κ or ρ is
            // beyond f64 (a singular truth), which allows anything.
            let allowed = |j: usize, level: usize| {
                let coefficient =
                    FACTOR * self.eps * kappa.powi(level as i32 + 1) * rho.powi(level as i32)
                        / t.columns[j];
                coefficient
                    .is_finite()
                    .then(|| Big::from_f64(coefficient) * &scales[level])
            };
            let factor = Big::from_f64(FACTOR * self.eps);
            let two = Big::from_f64(2.0);
            let mut bound = Big::zero();
            for term in terms {
                let r = match &term.magnitude {
                    Magnitude::Fixed(r) => r.abs(),
                    Magnitude::Unknown(_) => panic!("points of fixed lengths only"),
                };
                let (d0, d1, d2, w, a) = match term.angle {
                    Some(Var::Unknown(j)) if j < n => (
                        allowed(j, 0)?,
                        allowed(j, 1)?,
                        allowed(j, 2)?,
                        tv[j].abs(),
                        ta[j].abs(),
                    ),
                    Some(Var::Input) => (
                        Big::zero(),
                        Big::zero(),
                        Big::zero(),
                        Big::from_f64(t.omega.abs()),
                        Big::from_f64(t.alpha.abs()),
                    ),
                    _ => (
                        Big::zero(),
                        Big::zero(),
                        Big::zero(),
                        Big::zero(),
                        Big::zero(),
                    ),
                };
                // Rounding of this vector at this level.
                let spin = &r * &a + &r * &w * &w;
                let rounded = match level {
                    0 => r.clone(),
                    1 => &r * &w,
                    _ => spin.clone(),
                };
                bound = bound
                    + &factor * rounded
                    + match level {
                        0 => &r * d0,
                        1 => &r * d1 + &r * &w * d0,
                        _ => &r * d2 + &two * &r * &w * d1 + spin * d0,
                    };
            }
            Some(bound)
        }

        /// Judges a scene's outputs.
        fn quantities(&self, v: &mut Verdict, api: Api, scene: &str, qs: &[Quantity], kappa: f64) {
            let Some(t) = &self.truth else {
                if !self.unreachable_or_near_limit() {
                    v.fail(
                        api,
                        "Ok where the oracle has no position",
                        scene.to_string(),
                    );
                } else if !self.near_limit() {
                    let r = self.reach.expect("a reach");
                    v.fail(
                        api,
                        "Ok beyond the range of motion",
                        format!(
                            "scene {scene}: gap {:.2e} of the size ({:.1} × rounding)",
                            r.gap,
                            r.gap.abs() / (FACTOR * self.eps * r.slack)
                        ),
                    );
                }
                return;
            };
            let kappa = self.kappa(kappa);
            let rho = t.aspect(self.size());
            for q in qs {
                match q {
                    Quantity::Unknown {
                        index,
                        level,
                        value,
                    } => {
                        if !value.is_finite() {
                            v.fail(api, "not finite inside Ok", format!("scene {scene}: {q:?}"));
                            continue;
                        }
                        let (want, scale) = match level {
                            0 => (t.q()[*index].clone(), Big::from_f64(self.size())),
                            1 => {
                                let w = t.velocity.as_ref().expect("rates");
                                (w[*index].clone(), rate_size(t, w, self.size(), 1))
                            }
                            _ => {
                                let w = t.acceleration.as_ref().expect("rates");
                                (w[*index].clone(), rate_size(t, w, self.size(), 2))
                            }
                        };
                        let mut d = Big::from_f64(*value) - &want;
                        if *level == 0 && self.model.angles[*index] {
                            d = d.wrapped();
                        }
                        let column = t.columns[*index];
                        let error = if column.is_finite() {
                            (d.abs() * Big::from_f64(column) / &scale).to_f64()
                        } else {
                            (d.abs() / &scale).to_f64() * column
                        };
                        let bound = if *level == 0 { POSITION_FACTOR } else { FACTOR }
                            * self.eps
                            * kappa.powi(*level as i32 + 1)
                            * rho.powi(*level as i32);
                        if error > bound {
                            let what = [
                                "position error beyond 32·ε·κ",
                                "velocity error beyond 16·ε·κ²·ρ",
                                "acceleration error beyond 16·ε·κ³·ρ²",
                            ][*level];
                            v.fail(api, what, format!("scene {scene}, unknown {index}: error {error:.2e} = {:.1} × bound (κ {kappa:.2e})", error / bound));
                        }
                    }
                    Quantity::Point { name, level, value } => {
                        if !value.0.is_finite() || !value.1.is_finite() {
                            v.fail(api, "not finite inside Ok", format!("scene {scene}: {q:?}"));
                            continue;
                        }
                        let terms = &self
                            .model
                            .points
                            .iter()
                            .find(|(n, _)| n == name)
                            .expect("a point the model tracks")
                            .1;
                        let Some(want) = super::point(&self.model, t, name) else {
                            continue;
                        };
                        let want = &want[*level];
                        let d = C::new(
                            Big::from_f64(value.0) - &want.re,
                            Big::from_f64(value.1) - &want.im,
                        );
                        let error = d.norm();
                        let Some(bound) = self.point_bound(terms, *level, kappa) else {
                            continue;
                        };
                        if error > bound {
                            let (error, bound) = (error.to_f64(), bound.to_f64());
                            let what = [
                                "point position beyond its bound",
                                "point velocity beyond its bound",
                                "point acceleration beyond its bound",
                            ][*level];
                            v.fail(api, what, format!("scene {scene}, {name}: error {error:.2e} = {:.1} × bound (κ {kappa:.2e})", error / bound));
                        }
                    }
                }
            }
        }
    }

    /// The oracle's view of a case at `dims` (as the mechanism holds them).
    fn expect<T: Real>(case: &Case, p: &Params) -> Expect {
        let eps = T::epsilon().to_f64().unwrap_or(f64::NAN);
        let input = case.float.round(case.input);
        match closed_form(case.kind, p, input, &case.branches, case.omega, case.alpha) {
            Some(o) => Expect {
                model: o.model,
                params: p.clone(),
                guess_near_none: false,
                tolerance: case.tolerance,
                point_scene: false,
                reach: Some(o.reach),
                truth: o.truth,
                others: o.others,
                eps,
                input,
                omega: case.omega,
                alpha: case.alpha,
            },
            None => {
                let model = Model::new(case.kind, p);
                let near = case
                    .near
                    .clone()
                    .unwrap_or_else(|| vec![0.0; model.unknowns()]);
                let polished = polish(&model, input, &near, case.omega, case.alpha);
                // Only a certified root counts as the truth: where the construction's
                // rounding left the candidate outside Kantorovich's ball, the case says
                // nothing.
                let truth = polished.truth.filter(|_| polished.kantorovich <= 0.5);
                Expect {
                    model,
                    params: p.clone(),
                    guess_near_none: false,
                    tolerance: case.tolerance,
                    point_scene: false,
                    reach: None,
                    truth,
                    others: Vec::new(),
                    eps,
                    input,
                    omega: case.omega,
                    alpha: case.alpha,
                }
            }
        }
    }

    /// Newton's guess: the truth moved by `case.nudge` times the radius within which
    /// Kantorovich certifies convergence ([`newton_radius`]), rounded to the float. For an
    /// unreachable input, the truth at the input mirrored into the range across the nearest
    /// limit. Returns the guess and whether rounding left it outside that radius (then
    /// Newton's documented failures are right too).
    fn guess(case: &Case, e: &Expect, p: &Params) -> Option<(Vec<f64>, bool)> {
        let (truth, mirrored) = match &e.truth {
            Some(t) => (t.clone(), false),
            None => {
                let limits = limit_angles(case.kind, p, &case.branches);
                let nearest = limits
                    .iter()
                    .copied()
                    .min_by(|a, b| (a - e.input).abs().total_cmp(&(b - e.input).abs()))?;
                let mirrored = case.float.round(2.0 * nearest - e.input);
                let o = closed_form(case.kind, p, mirrored, &case.branches, 0.0, 0.0)?;
                (o.truth?, true)
            }
        };
        let n = e.n();
        let radius = newton_radius(&e.model, &truth);
        let step = radius / (n as f64).sqrt();
        let at = |turns: f64| -> Vec<f64> {
            truth
                .q()
                .iter()
                .enumerate()
                .map(|(j, q)| {
                    let nudge = case.nudge.get(j).copied().unwrap_or(0.0);
                    let turned = if e.model.angles[j] {
                        turns * std::f64::consts::TAU
                    } else {
                        0.0
                    };
                    case.float.round(q.to_f64() + nudge * step + turned)
                })
                .collect()
        };
        // Whole turns the float can carry without moving the guess by more than a
        // sixteenth of Kantorovich's step (a million of them hold an angle to 1e-9 rad in
        // f64, to 0.25 rad in f32): the case is about turns, not about a guess rounding has
        // thrown far from every root, whose branch the oracle and mechgen may read apart.
        let plain = at(0.0);
        let mut turns = case.turns;
        let guess = loop {
            let turned = at(turns);
            let moved = turned
                .iter()
                .zip(&plain)
                .map(|(t, p)| Big::from_f64(t - p).wrapped().abs().to_f64())
                .fold(0.0, f64::max);
            if turns == 0.0 || moved <= step / 16.0 {
                break turned;
            }
            turns = (turns / 4.0).trunc();
        };
        // Angles a turn apart are one angle: the distance of the guess as rounded, turns and
        // all (a float of a million turns holds an angle to 1e-9 in f64, 0.5 in f32).
        let distance = guess
            .iter()
            .zip(truth.q())
            .zip(&e.model.angles)
            .fold(Big::zero(), |acc, ((g, q), &angle)| {
                let d = Big::from_f64(*g) - q;
                acc + if angle { d.wrapped() } else { d }.square()
            })
            .sqrt()
            .to_f64();
        Some((guess, !mirrored && distance > radius))
    }

    fn run<T: Real + FromStr + Into<f64>, S: Subject<T>>(case: &Case) -> Verdict {
        run_from::<T, S>(case, None)
    }

    /// [`run`], Newton starting from `given` (the guess and whether it lies outside
    /// Kantorovich's ball) instead of the case's own guess where it is given.
    fn run_from<T: Real + FromStr + Into<f64>, S: Subject<T>>(
        case: &Case,
        given: Option<(Vec<f64>, bool)>,
    ) -> Verdict {
        let mut verdict = Verdict::default();
        let dims: Vec<T> = case.dims.iter().map(|d| T::constant(*d)).collect();
        let coupler = case
            .coupler
            .filter(|_| case.api == Api::Scenes)
            .map(|(a, d)| (T::constant(a), T::constant(d)));
        let Some(m) = S::build(&dims, coupler) else {
            verdict.outcome = "rejected".into();
            let eta = FACTOR * T::epsilon().to_f64().unwrap_or(f64::NAN);
            // A coupler point scaled beyond the float (a far one, rescaled) is not valid.
            let coupler_valid = coupler.is_none_or(|(a, _)| a.is_finite());
            if coupler_valid && valid_dimensions(case.kind, &case.dims, eta) == Some(true) {
                verdict.fail(
                    case.api,
                    "constructor refuses valid dimensions",
                    format!("{:?}", case.dims),
                );
            }
            return verdict;
        };
        let p = Params::from_debug::<T>(&format!("{m:?}"));
        let mut e = expect::<T>(case, &p);
        let input = T::constant(e.input);
        let (w, a) = (T::constant(case.omega), T::constant(case.alpha));
        let outcome = |r: &Result<(), Error<f64>>| match r {
            Ok(()) => "Ok".to_string(),
            Err(e) => error_name(e).to_string(),
        };
        let api = case.api;
        let result: Result<(), Error<f64>> = match api {
            Api::Assemble | Api::Motion => {
                let r = if api == Api::Assemble {
                    S::assemble(&m, input, &case.branches)
                        .map(|r| r.map(|q| ([q, Vec::new(), Vec::new()], None)))
                } else {
                    S::motion(&m, input, &case.branches, w, a)
                        .map(|r| r.map(|(rates, stated)| (rates, Some(stated))))
                };
                let Some(r) = r else {
                    verdict.outcome = "no closed form".into();
                    return verdict;
                };
                match r {
                    Ok((rates, stated)) => {
                        let q: Vec<T> = rates[0].iter().map(|x| T::constant(*x)).collect();
                        let kappa = S::condition(&m, input, &q);
                        e.position(&mut verdict, api, &rates[0], kappa, &case.branches);
                        if let Some(stated) = stated {
                            e.rates(&mut verdict, api, &rates[1..], kappa);
                            e.within_stated(&mut verdict, api, &rates, &stated);
                        }
                        Ok(())
                    }
                    Err(err) => {
                        e.error(&mut verdict, api, &err, false);
                        Err(err)
                    }
                }
            }
            Api::Position | Api::MotionNear => {
                let Some((guess, outside)) = given.or_else(|| guess(case, &e, &p)) else {
                    verdict.outcome = "no guess".into();
                    return verdict;
                };
                let guess_t: Vec<T> = guess.iter().map(|x| T::constant(*x)).collect();
                // Newton keeps to its guess's branch, which near a toggle a certified guess may
                // be on the other side of: then `OtherBranch` is the answer.
                let guess_state = State::from_f64(&e.model, e.input, &guess);
                let mut wanted = guess_branches(&e.model, &guess_state);
                e.guess_near_none = e.truth.is_none();
                let switched = e.truth.as_ref().is_some_and(|t| t.branches != wanted);
                let tolerance = T::constant(case.tolerance);
                let r = if api == Api::Position {
                    S::position(&m, input, &guess_t, tolerance)
                        .map(|(q, k, _)| ([q, Vec::new(), Vec::new()], k, None))
                } else {
                    S::motion_near(&m, input, &guess_t, tolerance, w, a)
                        .map(|(rates, k, stated)| (rates, k, Some(stated)))
                };
                let before = verdict.findings.len();
                let result = match r {
                    Ok((rates, kappa, stated)) => {
                        // A loop whose guess lies within the answer's error of its mirror image
                        // is on neither branch at the guess (the runtime's `same_sides`): from
                        // a guess outside the ball (a far one, a loop's point almost on its
                        // chord: edge run seed 33, case 1111, an f32 Jansen leg with a stated
                        // tolerance of 1% of its links), its answer may be on either.
                        if outside {
                            let error = 4.0
                                * kappa.max(1.0)
                                * (64.0 * e.eps * e.size()
                                    + residual_norm(&e.model, e.input, &rates[0]));
                            let found = branch_signs(
                                &e.model,
                                &State::from_f64(&e.model, e.input, &rates[0]),
                            )
                            .0;
                            for ((want, (_, mirror)), got) in wanted
                                .iter_mut()
                                .zip(guess_sides(&e.model, &guess_state))
                                .zip(found)
                            {
                                if mirror <= error {
                                    *want = got;
                                }
                            }
                        }
                        // From a guess outside the truth's basin (rounding of a guess that
                        // counts turns, in f32: edge run seed 14, case 2723) the Stephenson
                        // six-bar's Newton may find another root: its contract keeps the
                        // guess's assembly by its own signs (the dyad's closed form, the
                        // reduced Jacobian's orientation), which at a guess this far from every
                        // root need not be the oracle's geometric sides, and promises no
                        // particular root from an uncertified guess. So the root it found is
                        // judged, once certified.
                        // (Judged by a copy: the case's own expectation makes the rescaled
                        // call's guess.)
                        let mut judged = None;
                        if outside && e.reach.is_none() {
                            let found = polish(&e.model, e.input, &rates[0], e.omega, e.alpha);
                            if let Some(t) = found.truth.filter(|_| found.kantorovich <= 0.5) {
                                judged = Some(Expect {
                                    truth: Some(t),
                                    ..e.clone()
                                });
                            }
                        }
                        // From a guess outside the ball on another branch than the case's
                        // (a far one), the root to be is the guess's branch's: judged
                        // against it, so that an `Ok` on the case's is a silent switch.
                        let switched = e.truth.as_ref().is_some_and(|t| t.branches != wanted);
                        if outside && switched && e.reach.is_some() {
                            let theirs = Case {
                                branches: wanted.clone(),
                                ..case.clone()
                            };
                            judged = Some(Expect {
                                guess_near_none: e.guess_near_none,
                                ..expect::<T>(&theirs, &p)
                            });
                        }
                        let judged = judged.as_mut().unwrap_or(&mut e);
                        judged.position(&mut verdict, api, &rates[0], kappa, &wanted);
                        if let Some(stated) = stated {
                            judged.rates(&mut verdict, api, &rates[1..], kappa);
                            judged.within_stated(&mut verdict, api, &rates, &stated);
                        }
                        Ok(())
                    }
                    Err(Error::OtherBranch) if switched => Err(Error::OtherBranch),
                    Err(err) => {
                        e.error(&mut verdict, api, &err, outside);
                        Err(err)
                    }
                };
                for finding in &mut verdict.findings[before..] {
                    finding.detail = format!("{} (guess {guess:?})", finding.detail);
                }
                result
            }
            Api::Scenes => {
                let Some(r) = S::scenes(&m, input, &case.branches, w, a) else {
                    verdict.outcome = "no scenes".into();
                    return verdict;
                };
                match r {
                    Err(err) => {
                        verdict.fail(
                            api,
                            &format!("scenes() refuses valid dimensions ({})", error_name(&err)),
                            format!("{err:?}"),
                        );
                        Err(err)
                    }
                    Ok(scenes) => {
                        let mut first = Ok(());
                        for (scene, r) in scenes {
                            match r {
                                Ok(qs) => {
                                    let values: Vec<T> = qs
                                        .iter()
                                        .filter_map(|q| match q {
                                            Quantity::Unknown {
                                                level: 0, value, ..
                                            } => Some(T::constant(*value)),
                                            _ => None,
                                        })
                                        .collect();
                                    let kappa = if values.len() == e.n() {
                                        S::condition(&m, input, &values)
                                    } else {
                                        f64::NAN
                                    };
                                    e.quantities(&mut verdict, api, scene, &qs, kappa);
                                }
                                Err(err) => {
                                    e.point_scene = scene.starts_with("coupler");
                                    e.error(&mut verdict, api, &err, false);
                                    if first.is_ok() {
                                        verdict.point_scene = e.point_scene;
                                        first = Err(err);
                                    }
                                    e.point_scene = false;
                                }
                            }
                        }
                        first
                    }
                }
            }
        };
        verdict.outcome = outcome(&result);
        if let Some(factor) = case.rescale {
            rescaled::<T, S>(case, factor, &e, &result, &mut verdict);
        }
        verdict
    }

    /// The same call with every length scaled by `factor`.
    fn rescaled<T: Real + FromStr + Into<f64>, S: Subject<T>>(
        case: &Case,
        factor: f64,
        e: &Expect,
        result: &Result<(), Error<f64>>,
        verdict: &mut Verdict,
    ) {
        let lengths = length_slots(case.kind);
        let mut scaled = case.clone();
        scaled.rescale = None;
        scaled.tolerance = case.float.round(case.tolerance * factor);
        for (i, d) in scaled.dims.iter_mut().enumerate() {
            if lengths.contains(&i) {
                *d = case.float.round(*d * factor);
            }
        }
        scaled.coupler = case.coupler.map(|(a, d)| (case.float.round(a * factor), d));
        scaled.near = case.near.as_ref().map(|q| {
            q.iter()
                .zip(&e.model.angles)
                .map(|(v, &angle)| if angle { *v } else { v * factor })
                .collect()
        });
        let exact = factor.log2().fract() == 0.0;
        // The same call scaled: Newton from the same guess, its lengths scaled (a guess made
        // afresh for the scaled case would differ where it mixes angles and lengths).
        let given = guess(case, e, &e.params).map(|(g, outside)| {
            let g = g
                .iter()
                .zip(&e.model.angles)
                .map(|(v, &angle)| {
                    if angle {
                        *v
                    } else {
                        case.float.round(v * factor)
                    }
                })
                .collect();
            (g, outside)
        });
        let far_guess = given.as_ref().is_some_and(|(_, outside)| *outside);
        let again = run_from::<T, S>(&scaled, given);
        for finding in again.findings {
            verdict.findings.push(Finding {
                class: format!(
                    "{} (lengths × {})",
                    finding.class,
                    if exact { "2^k" } else { "a factor" }
                ),
                detail: finding.detail,
            });
        }
        let before = match result {
            Ok(()) => "Ok".to_string(),
            Err(err) => error_name(err).to_string(),
        };
        // A scaled case the oracle cannot set up (no certified guess, or rejected
        // dimensions) says nothing of mechgen.
        if before != again.outcome && again.outcome != "rejected" && again.outcome != "no guess" {
            // By a factor other than a power of two the condition moves by rounding, so an
            // answer whose estimate is at what is required may be `Ok` on one side and
            // `Inaccurate` on the other: both keep the contract there.
            let at_the_threshold = [before.as_str(), again.outcome.as_str()]
                .iter()
                .all(|o| *o == "Ok" || *o == "Inaccurate")
                && [
                    mechgen::Order::Position,
                    mechgen::Order::Velocity,
                    mechgen::Order::Acceleration,
                ]
                .into_iter()
                .any(|order| {
                    e.inaccuracy_allowed(order, matches!(case.api, Api::Position | Api::MotionNear))
                });
            // Rates of lengths (scaled or not) near the float's largest overflow: `NonFinite`
            // is then the answer (the truth is not representable), whatever the factor.
            // Near a toggle the rates grow with κ and the accelerations with κ³.
            // The true rates say it where the oracle has them: a short link's angular rate is
            // the long one's over the ratio, whatever κ (edge run case 43536: a slider-crank
            // whose rod is 1e6 times shorter than its crank, κ 5, its slider's acceleration
            // 1.6e9 times the size).
            let kappa = e.truth.as_ref().map_or(1.0, |t| t.condition.max(1.0));
            // A far coupler point's rates overflow where the loops' do not: only in a scene
            // that tracks it, on either side.
            let point_scene = verdict.point_scene || again.point_scene;
            let by_kappa = e.reach_size(point_scene)
                * kappa.powi(3)
                * (1.0 + case.omega.abs() + case.omega.powi(2) + case.alpha.abs());
            let by_truth = e.truth.as_ref().map_or(0.0, |t| {
                let size = e.size();
                let speed = t
                    .velocity
                    .as_ref()
                    .map_or(0.0, |w| rate_size(t, w, size, 0).to_f64());
                let acceleration = t
                    .acceleration
                    .as_ref()
                    .map_or(0.0, |w| rate_size(t, w, size, 0).to_f64());
                // A point's acceleration sums every link's `|r|·(ω² + |α|)`.
                let spin = |w: f64, a: f64| (w * w + a.abs()).max(w.abs());
                let mut fastest = spin(t.omega, t.alpha);
                if let (Some(w), Some(a)) = (&t.velocity, &t.acceleration) {
                    for (w, a) in w.iter().zip(a) {
                        fastest = fastest.max(spin(w.to_f64(), a.to_f64()));
                    }
                }
                speed
                    .max(acceleration)
                    .max(e.reach_size(point_scene) * fastest)
            });
            let largest = by_kappa.max(by_truth) * factor.max(1.0);
            let rates_overflow = (before == "NonFinite" || again.outcome == "NonFinite")
                && (largest > T::max_value().to_f64().unwrap_or(f64::MAX) / 64.0
                    || e.rates_unbounded_near_limit(e.size() * factor.max(1.0)));
            // Rates that leave the float's normal range at one of the two sizes (a slider of
            // 1e-250 turning at 1e-40 rad/s, scaled by 1e-64) are known there only to its
            // subnormal spacing, which the contract states: `Inaccurate` on that side, `Ok`
            // on the other, whatever the factor.
            let newton = matches!(case.api, Api::Position | Api::MotionNear);
            let leaves_range = [before.as_str(), again.outcome.as_str()]
                .iter()
                .all(|o| *o == "Ok" || *o == "Inaccurate")
                && [mechgen::Order::Velocity, mechgen::Order::Acceleration]
                    .into_iter()
                    .any(|order| {
                        [1.0, factor]
                            .into_iter()
                            .any(|f| e.inaccuracy_allowed_scaled(order, newton, f))
                    });
            // From a guess outside the ball Kantorovich certifies, Newton's path is rounding's
            // to choose, and a factor other than a power of two rounds every length anew:
            // any of its documented outcomes, on either side, keeps the contract (edge run
            // seed 35, case 187841: an f32 Stephenson six-bar from a guess 2,800 radii out,
            // `CannotAssemble` as drawn, its iterates a turn from the guess, and `Ok` on the
            // guess's branch with every length × 7.6e-57).
            let documented_far = |o: &str| {
                matches!(
                    o,
                    "Ok" | "OtherBranch" | "NoConvergence" | "CannotAssemble" | "Singular"
                )
            };
            let far_either_way =
                newton && far_guess && documented_far(&before) && documented_far(&again.outcome);
            let excused = rates_overflow
                || leaves_range
                || (!exact
                    && (e.near_limit()
                        || e.singular_allowed()
                        || at_the_threshold
                        || far_either_way));
            if !excused {
                verdict.fail(
                    case.api,
                    if exact {
                        "outcome changes when every length is scaled by 2^k"
                    } else {
                        "outcome changes when every length is scaled"
                    },
                    format!("{before} → {} (× {factor:e})", again.outcome),
                );
            }
        }
        if exact && before == "Ok" && again.outcome == "Ok" {
            // Bit-identical angles: compare the raw answers.
            let (x, y) = (raw::<T, S>(case), raw::<T, S>(&scaled));
            if let (Some(x), Some(y)) = (x, y) {
                let angles = &e.model.angles;
                // A length (or its rate) that scales into the float's subnormal range keeps
                // fewer bits than the float has: there it cannot be the same bits, scaled.
                let smallest = T::min_positive_value().to_f64().unwrap_or(0.0);
                let differs = x.iter().zip(&y).any(|((i, level, a), (_, _, b))| {
                    let length = *i < angles.len() && !angles[*i] && *level < 3;
                    if length {
                        a * factor != *b && (a * factor).abs().min(a.abs()) >= smallest
                    } else {
                        a.to_bits() != b.to_bits()
                    }
                });
                if differs {
                    verdict.fail(
                        case.api,
                        "not bit-identical when every length is scaled by 2^k",
                        format!("× {factor:e}: {x:?} vs {y:?}"),
                    );
                }
            }
        }
    }

    /// The unknowns' values, rates and accelerations a case returns, as (unknown, level, value).
    fn raw<T: Real + FromStr + Into<f64>, S: Subject<T>>(
        case: &Case,
    ) -> Option<Vec<(usize, usize, f64)>> {
        let dims: Vec<T> = case.dims.iter().map(|d| T::constant(*d)).collect();
        let m = S::build(&dims, None)?;
        let input = T::constant(case.input);
        let (w, a) = (T::constant(case.omega), T::constant(case.alpha));
        let spread = |levels: [Vec<f64>; 3]| {
            levels
                .iter()
                .enumerate()
                .flat_map(|(l, v)| v.iter().enumerate().map(move |(i, x)| (i, l, *x)))
                .collect::<Vec<_>>()
        };
        match case.api {
            Api::Assemble => S::assemble(&m, input, &case.branches)?
                .ok()
                .map(|q| spread([q, vec![], vec![]])),
            Api::Motion => S::motion(&m, input, &case.branches, w, a)?
                .ok()
                .map(|(levels, _)| spread(levels)),
            // Newton's guesses are lengths scaled too; the raw comparison needs the same guess.
            _ => None,
        }
    }

    /// Which constructor arguments are lengths (scaled) rather than angles.
    pub fn length_slots(kind: Kind) -> Vec<usize> {
        match kind {
            Kind::FourBar => vec![0, 1, 2, 3],
            Kind::SliderCrank => vec![0, 1, 2],
            Kind::InvertedSliderCrank => vec![0, 1, 2],
            Kind::WattSixBar | Kind::StephensonSixBar => vec![0, 1, 2, 3, 4, 6, 7, 8, 9],
            Kind::JansenLeg => (0..13).collect(),
        }
    }
}

/// The cases the edge tests and the large run draw: mechanisms with link ratios up to a
/// family's bound at scales across the float's range (powers of two and arbitrary factors),
/// inputs anywhere or placed relative to the limit angles, every entry point, both floats.
pub mod draw {
    use super::*;
    use mechgen::Real;
    use std::f64::consts::PI;
    use std::str::FromStr;

    /// SplitMix64: small, fast, and the same on every machine.
    #[derive(Clone, Debug)]
    pub struct Rng(pub u64);

    impl Rng {
        pub fn next_u64(&mut self) -> u64 {
            self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
            let mut z = self.0;
            z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            z ^ (z >> 31)
        }

        /// Uniform in [0, 1).
        pub fn unit(&mut self) -> f64 {
            (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
        }

        pub fn range(&mut self, a: f64, b: f64) -> f64 {
            a + (b - a) * self.unit()
        }

        /// Log-uniform in [a, b], both positive.
        pub fn log(&mut self, a: f64, b: f64) -> f64 {
            (a.ln() + (b.ln() - a.ln()) * self.unit()).exp()
        }

        pub fn chance(&mut self, p: f64) -> bool {
            self.unit() < p
        }

        pub fn pick<T: Copy>(&mut self, items: &[T]) -> T {
            items[(self.next_u64() % items.len() as u64) as usize]
        }

        pub fn sign(&mut self) -> f64 {
            if self.chance(0.5) { 1.0 } else { -1.0 }
        }

        pub fn angle(&mut self) -> f64 {
            self.range(-PI, PI)
        }
    }

    /// How big the mechanisms are.
    #[derive(Clone, Copy, Debug, PartialEq, Eq)]
    pub enum Scales {
        /// The longest link in [1e-3, 1e3].
        Moderate,
        /// The longest link anywhere the float allows with the shortest still normal (f64:
        /// 1e-300 to 1e300; f32: 1e-37 to 1e37).
        Extreme,
    }

    /// Where the input goes.
    #[derive(Clone, Copy, Debug, PartialEq, Eq)]
    pub enum Placement {
        /// Uniform over a turn (sometimes a turn or two away).
        Anywhere,
        /// 1e-12, 1e-9 or 1e-6 rad inside a limit angle.
        Inside,
        /// As far outside.
        Outside,
        /// On a limit angle, rounded, or an ulp either side.
        AtLimit,
        /// With the crank along the ground line (θ = 0 or π) or 1e-12, 1e-9, 1e-6 rad from it:
        /// dead centres, and the folded positions where a chord nearly vanishes.
        Flat,
    }

    /// A family of cases: what the draw varies over.
    #[derive(Clone, Debug)]
    pub struct Family {
        pub kinds: Vec<Kind>,
        pub floats: Vec<Float>,
        pub apis: Vec<Api>,
        pub scales: Scales,
        /// The largest ratio of two lengths of a mechanism (at least 1).
        pub ratio: f64,
        pub placements: Vec<Placement>,
        /// Whether to repeat each case with every length scaled.
        pub rescale: bool,
        /// The share of the shipped examples' shapes among the mechanisms.
        pub examples: f64,
    }

    impl Family {
        /// Everything: every mechanism, float, entry point and placement, extreme scales and
        /// link ratios to 1e8.
        pub fn everything() -> Family {
            Family {
                kinds: Kind::ALL.to_vec(),
                floats: vec![Float::F32, Float::F64],
                apis: Api::ALL.to_vec(),
                scales: Scales::Extreme,
                ratio: 1e8,
                placements: vec![
                    Placement::Anywhere,
                    Placement::Inside,
                    Placement::Outside,
                    Placement::AtLimit,
                    Placement::Flat,
                ],
                rescale: true,
                examples: 0.2,
            }
        }
    }

    /// The families the edge tests run, by name: each isolates one kind of difficulty, so a
    /// failing one names its class. `everything` mixes them all (the large run).
    pub fn family(name: &str) -> Option<Family> {
        // Modifiers after the base name narrow it: `/closed` (assemble, motion, scenes),
        // `/newton` (position, motion_near), `/one-loop`, `/multi-loop`, or one mechanism
        // (`/four-bar`, `/slider-crank`, `/inverted`, `/watt`, `/stephenson`, `/jansen`).
        let mut parts = name.split('/');
        let base = family_base(parts.next()?)?;
        parts
            .try_fold(base, |f, modifier| {
                let keep = |kinds: &[Kind]| -> Vec<Kind> {
                    f.kinds
                        .iter()
                        .copied()
                        .filter(|k| kinds.contains(k))
                        .collect()
                };
                Some(match modifier {
                    "closed" => Family {
                        kinds: f
                            .kinds
                            .iter()
                            .copied()
                            .filter(|k| *k != Kind::StephensonSixBar)
                            .collect(),
                        apis: vec![Api::Assemble, Api::Motion, Api::Scenes],
                        ..f
                    },
                    "newton" => Family {
                        apis: vec![Api::Position, Api::MotionNear],
                        ..f
                    },
                    "one-loop" => Family {
                        kinds: keep(&[Kind::FourBar, Kind::SliderCrank, Kind::InvertedSliderCrank]),
                        ..f
                    },
                    "multi-loop" => Family {
                        kinds: keep(&[Kind::WattSixBar, Kind::StephensonSixBar, Kind::JansenLeg]),
                        ..f
                    },
                    "four-bar" => Family {
                        kinds: keep(&[Kind::FourBar]),
                        ..f
                    },
                    "slider-crank" => Family {
                        kinds: keep(&[Kind::SliderCrank]),
                        ..f
                    },
                    "inverted" => Family {
                        kinds: keep(&[Kind::InvertedSliderCrank]),
                        ..f
                    },
                    "watt" => Family {
                        kinds: keep(&[Kind::WattSixBar]),
                        ..f
                    },
                    "stephenson" => Family {
                        kinds: keep(&[Kind::StephensonSixBar]),
                        ..f
                    },
                    "jansen" => Family {
                        kinds: keep(&[Kind::JansenLeg]),
                        ..f
                    },
                    _ => return None,
                })
            })
            .filter(|f| !f.kinds.is_empty())
    }

    fn family_base(name: &str) -> Option<Family> {
        let all = Family::everything();
        let mut f = Family {
            scales: Scales::Moderate,
            ratio: 10.0,
            placements: vec![Placement::Anywhere],
            rescale: false,
            ..all.clone()
        };
        match name {
            "everything" => return Some(all),
            // Ordinary mechanisms: moderate sizes and ratios, inputs anywhere.
            "ordinary" => {}
            // Link ratios to 1e8 at moderate sizes.
            "ratios" => f.ratio = 1e8,
            // Inputs just inside the limit angles, and on them.
            "inside" => f.placements = vec![Placement::Inside, Placement::AtLimit],
            // Inputs just outside the limit angles.
            "outside" => f.placements = vec![Placement::Outside],
            // The crank on the ground line, and just off it.
            "flat" => f.placements = vec![Placement::Flat],
            // Every length scaled by a power of two or another factor, at moderate sizes.
            "rescaled" => f.rescale = true,
            // Sizes across the float's range.
            "extreme" => {
                f.scales = Scales::Extreme;
                f.examples = 0.5;
            }
            _ => return None,
        }
        Some(f)
    }

    /// The family names, in the order the tests use them.
    pub const FAMILIES: [&str; 8] = [
        "ordinary",
        "ratios",
        "inside",
        "outside",
        "flat",
        "rescaled",
        "extreme",
        "everything",
    ];
    // Each may end in `/closed` (assemble, motion, scenes) or `/newton` (position, motion_near).

    /// The parameters a mechanism built from `dims` holds (its derived ones included), or
    /// `None` where its constructor refuses them.
    pub fn held(kind: Kind, float: Float, dims: &[f64]) -> Option<Params> {
        match float {
            Float::F32 => held_in::<f32>(kind, dims),
            Float::F64 => held_in::<f64>(kind, dims),
        }
    }

    fn held_in<T: Real + FromStr + Into<f64>>(kind: Kind, dims: &[f64]) -> Option<Params> {
        use judge::Subject;
        use mechanisms::*;
        let d: Vec<T> = dims.iter().map(|x| T::constant(*x)).collect();
        let debug = match kind {
            Kind::FourBar => format!("{:?}", FourBar::<T>::build(&d, None)?),
            Kind::SliderCrank => format!("{:?}", SliderCrank::<T>::build(&d, None)?),
            Kind::InvertedSliderCrank => {
                format!("{:?}", InvertedSliderCrank::<T>::build(&d, None)?)
            }
            Kind::WattSixBar => format!("{:?}", WattSixBar::<T>::build(&d, None)?),
            Kind::StephensonSixBar => format!("{:?}", StephensonSixBar::<T>::build(&d, None)?),
            Kind::JansenLeg => format!("{:?}", JansenLeg::<T>::build(&d, None)?),
        };
        Some(Params::from_debug::<T>(&debug))
    }

    /// A shape: dimensions with the longest length about 1, the branches and (for the
    /// constructed multi-loop ones) an input and a position near which the loops close.
    struct Shape {
        dims: Vec<f64>,
        branches: Vec<Branch>,
        at: Option<(f64, Vec<f64>)>,
    }

    fn expi(t: f64) -> (f64, f64) {
        (t.cos(), t.sin())
    }

    fn add(a: (f64, f64), r: f64, t: f64) -> (f64, f64) {
        (a.0 + r * t.cos(), a.1 + r * t.sin())
    }

    fn dist(a: (f64, f64), b: (f64, f64)) -> f64 {
        (a.0 - b.0).hypot(a.1 - b.1)
    }

    fn arg(a: (f64, f64), b: (f64, f64)) -> f64 {
        (b.1 - a.1).atan2(b.0 - a.0)
    }

    fn branch(sign: f64) -> Branch {
        if sign >= 0.0 {
            Branch::Open
        } else {
            Branch::Crossed
        }
    }

    /// Lengths log-uniform in [1/r, 1] with one of them 1 and another 1/r.
    fn lengths(rng: &mut Rng, count: usize, ratio: f64) -> Vec<f64> {
        let r = rng.log(1.0, ratio.max(1.0));
        let mut v: Vec<f64> = (0..count).map(|_| rng.log(1.0 / r, 1.0)).collect();
        let i = (rng.next_u64() % count as u64) as usize;
        v[i] = 1.0;
        if count > 1 {
            let j = (i + 1 + (rng.next_u64() % (count as u64 - 1)) as usize) % count;
            v[j] = 1.0 / r;
        }
        v
    }

    fn random_branches(rng: &mut Rng, n: usize) -> Vec<Branch> {
        (0..n)
            .map(|_| {
                if rng.chance(0.5) {
                    Branch::Open
                } else {
                    Branch::Crossed
                }
            })
            .collect()
    }

    fn example(kind: Kind) -> Shape {
        let (dims, branches): (Vec<f64>, Vec<Branch>) = match kind {
            Kind::FourBar => (vec![180.0, 80.0, 200.0, 150.0], vec![Branch::Open]),
            Kind::SliderCrank => (vec![50.0, 150.0, 20.0], vec![Branch::Open]),
            Kind::InvertedSliderCrank => (vec![150.0, 60.0, 20.0, 0.3], vec![Branch::Open]),
            Kind::WattSixBar => (
                vec![
                    180.0, 80.0, 200.0, 150.0, 100.0, 0.8, 220.0, 160.0, 300.0, 150.0,
                ],
                vec![Branch::Open, Branch::Open],
            ),
            Kind::StephensonSixBar => (
                vec![
                    100.0, 20.0, 117.0, 60.0, 63.0, -0.97, 52.0, 85.0, 189.0, -26.0,
                ],
                vec![Branch::Open; 2],
            ),
            Kind::JansenLeg => (
                vec![
                    38.0, 41.5, 39.3, 40.1, 55.8, 39.4, 36.7, 65.7, 49.0, 50.0, 61.9, 7.8, 15.0,
                ],
                vec![Branch::Crossed, Branch::Open, Branch::Crossed],
            ),
        };
        let at = (kind == Kind::StephensonSixBar).then(|| (0.0, vec![-0.25, 0.63, 1.43, 1.46]));
        Shape { dims, branches, at }
    }

    fn shape(kind: Kind, rng: &mut Rng, ratio: f64) -> Shape {
        for _ in 0..200 {
            let s = match kind {
                Kind::FourBar => {
                    let dims = lengths(rng, 4, ratio);
                    Shape {
                        dims,
                        branches: random_branches(rng, 1),
                        at: None,
                    }
                }
                Kind::SliderCrank => {
                    let l = lengths(rng, 3, ratio);
                    let c = if rng.chance(0.2) {
                        0.0
                    } else {
                        rng.sign() * l[2]
                    };
                    Shape {
                        dims: vec![l[0], l[1], c],
                        branches: random_branches(rng, 1),
                        at: None,
                    }
                }
                Kind::InvertedSliderCrank => {
                    let l = lengths(rng, 3, ratio);
                    let c = if rng.chance(0.2) {
                        0.0
                    } else {
                        rng.sign() * l[2]
                    };
                    let gamma = if rng.chance(0.3) { 0.0 } else { rng.angle() };
                    Shape {
                        dims: vec![l[0], l[1], c, gamma],
                        branches: random_branches(rng, 1),
                        at: None,
                    }
                }
                Kind::WattSixBar => {
                    // From a configuration: O2, O4 = (l1, 0), A, B, C, D, O6.
                    let l = lengths(rng, 6, ratio);
                    let (l1, l2, l4, l5, l6, l7) = (l[0], l[1], l[2], l[3], l[4], l[5]);
                    let (t2, t4, beta, t5, t6) = (
                        rng.angle(),
                        rng.angle(),
                        rng.angle(),
                        rng.angle(),
                        rng.angle(),
                    );
                    let a = add((0.0, 0.0), l2, t2);
                    let b = add((l1, 0.0), l4, t4);
                    let l3 = dist(a, b);
                    let c = add((l1, 0.0), l5, t4 + beta);
                    let d = add(c, l6, t5);
                    let o6 = add(d, -l7, t6);
                    let t3 = arg(a, b);
                    let branches = vec![branch((t4 - t3).sin()), branch((t6 - t5).sin())];
                    Shape {
                        dims: vec![l1, l2, l3, l4, l5, beta, l6, l7, o6.0, o6.1],
                        branches,
                        at: Some((t2, vec![t3, t4, t5, t6])),
                    }
                }
                Kind::StephensonSixBar => {
                    let l = lengths(rng, 6, ratio);
                    let (l1, l2, l3, bc, cd, l6) = (l[0], l[1], l[2], l[3], l[4], l[5]);
                    let (t2, t3, t5, beta, t6) = (
                        rng.angle(),
                        rng.angle(),
                        rng.angle(),
                        rng.angle(),
                        rng.angle(),
                    );
                    let a = add((0.0, 0.0), l2, t2);
                    let b = add(a, l3, t3);
                    let c = add(b, bc, t5);
                    let l4 = dist((l1, 0.0), c);
                    let t4 = arg((l1, 0.0), c);
                    let d = add(c, cd, t5 + beta);
                    let o6 = add(d, -l6, t6);
                    Shape {
                        dims: vec![l1, l2, l3, bc, cd, beta, l4, l6, o6.0, o6.1],
                        branches: vec![Branch::Open; 2],
                        at: Some((t2, vec![t3, t4, t5, t6])),
                    }
                }
                Kind::JansenLeg => {
                    // Z = (−a, −l), the crank pin M, P1 … P5.
                    let v = lengths(rng, 8, ratio);
                    let (a, l, m, b, c, d, g, i) = (v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7]);
                    let (theta, pb, pc, pg) = (rng.angle(), rng.angle(), rng.angle(), rng.angle());
                    let (delta1, delta2) = (rng.range(0.05, PI - 0.05), rng.range(0.05, PI - 0.05));
                    let z = (-a, -l);
                    let mm = expi(theta);
                    let crank = (m * mm.0, m * mm.1);
                    let p1 = add(z, b, pb);
                    let p2 = add(z, c, pc);
                    let p3 = add(z, d, pb + delta1);
                    let p4 = add(p2, g, pg);
                    let p5 = add(p2, i, pg + delta2);
                    let (j, k, e, f, h) = (
                        dist(crank, p1),
                        dist(crank, p2),
                        dist(p1, p3),
                        dist(p3, p4),
                        dist(p4, p5),
                    );
                    let pj = arg(crank, p1);
                    let pk = arg(crank, p2);
                    let pf = arg(p3, p4);
                    let branches = vec![
                        branch((pb - pj).sin()),
                        branch((pc - pk).sin()),
                        branch((pg - pf).sin()),
                    ];
                    Shape {
                        dims: vec![a, b, c, d, e, f, g, h, i, j, k, l, m],
                        branches,
                        at: Some((theta, vec![pj, pb, pk, pc, pf, pg])),
                    }
                }
            };
            if valid_dimensions(kind, &s.dims, 1e-6) == Some(true) {
                return s;
            }
        }
        example(kind)
    }

    /// `10^(lo..hi)` log-uniform, or the power of two nearest it.
    fn scale(rng: &mut Rng, lo: f64, hi: f64) -> f64 {
        let s = 10f64.powf(rng.range(lo, hi));
        if rng.chance(0.5) {
            2f64.powi(s.log2().round() as i32)
        } else {
            s
        }
    }

    /// The exponent range (decimal) of the longest length at these scales.
    fn exponents(scales: Scales, float: Float, ratio: f64) -> (f64, f64) {
        let r = ratio.max(1.0).log10();
        match (scales, float) {
            (Scales::Moderate, _) => (-3.0, 3.0),
            (Scales::Extreme, Float::F64) => (-300.0 + r, 300.0),
            (Scales::Extreme, Float::F32) => (-37.0 + r, 37.0),
        }
    }

    /// Rates far from 1, at extreme scales: time counted in units of `2^-k`, so that the
    /// input turns at `ω·2^k` and accelerates at `α·4^k` (exact but where that is below the
    /// float's normal range), with `k` from −1000 to 504 (f64) or −110 to 56 (f32), far beyond
    /// where `motion` and the rest count time afresh ([2^-600, 2^600] and [2^-60, 2^60] for
    /// `Σω² + Σ|α|`) and slow enough for `ω²` to underflow on a mechanism of 1e300; for the
    /// scene kernels up to 420 or 40, rates whose squares times a ratio of lengths of 1e8 are
    /// still normal numbers, as they require (README, **Rates**). The size times the rate
    /// squared, at the size drawn and at the size rescaled to, stays within 2^-1200 to
    /// 2^1100 (2^-160 to 2^150 in f32), past the float's range on both sides: tiny
    /// mechanisms turn slowly, their rates of lengths and angles' accelerations below the
    /// float's range, which the contract then says (`Inaccurate`); huge ones turn fast, their
    /// lengths' accelerations and points' beyond it (`NonFinite`), their angles' within it,
    /// judged against rate sizes the judge holds at 256 bits ([`super::rate_size`]). The
    /// scene kernels' within 2^±900 (2^±100), their domain (README, **Rates**: the size
    /// times the rate squared a normal number too).
    /// `Some` for one case in seven at extreme scales, drawn from a stream of its own, so
    /// that every other draw stays as it was: a case number the README or a regression test
    /// names is the same mechanism, input, branch and guess, its rates (unused by `position`
    /// and `assemble`) far from 1 in one case in seven.
    fn tempo(
        scales: Scales,
        float: Float,
        dims: &[f64],
        rescale: Option<f64>,
        kind: Kind,
        api: Api,
        rng: &Rng,
    ) -> Option<i32> {
        if scales == Scales::Moderate {
            return None;
        }
        let mut side = Rng(rng.0 ^ 0x7E3A_0C1D_5B29_F461);
        if !side.chance(1.0 / 7.0) {
            return None;
        }
        let slots = judge::length_slots(kind);
        let longest = dims
            .iter()
            .enumerate()
            .filter(|(i, _)| slots.contains(i))
            .fold(0.0f64, |m, (_, d)| m.max(d.abs()));
        // The scene kernels' documented domain, or every rate that is a normal number and
        // every acceleration (`α·4^k`, |α| ≤ 10, next to `ω²` ≤ 1e4·4^k) below the largest.
        // The size times the rate squared, in base-2 exponents: above `-below` and below
        // `above` (past the float's smallest subnormal below, except for the scenes).
        let (slowest, fastest, below, above): (f64, f64, f64, f64) =
            match (float, api == Api::Scenes) {
                (Float::F64, true) => (-420.0, 420.0, 900.0, 900.0),
                (Float::F64, false) => (-1000.0, 504.0, 1200.0, 1100.0),
                (Float::F32, true) => (-40.0, 40.0, 100.0, 100.0),
                (Float::F32, false) => (-110.0, 56.0, 160.0, 150.0),
            };
        let sizes = [longest.log2(), (longest * rescale.unwrap_or(1.0)).log2()];
        let slowest = sizes
            .iter()
            .fold(slowest, |k, size| k.max(((-below - size) / 2.0).ceil()));
        let fastest = sizes
            .iter()
            .fold(fastest, |k, size| k.min(((above - size) / 2.0).floor()));
        (slowest < fastest).then(|| side.range(slowest, fastest).round() as i32)
    }

    /// One case of `family`.
    pub fn case(family: &Family, rng: &mut Rng) -> Case {
        let kind = rng.pick(&family.kinds);
        let float = rng.pick(&family.floats);
        let mut api = rng.pick(&family.apis);
        if kind == Kind::StephensonSixBar
            && matches!(api, Api::Assemble | Api::Motion | Api::Scenes)
        {
            api = if rng.chance(0.5) {
                Api::Position
            } else {
                Api::MotionNear
            };
        }
        let base = if rng.chance(family.examples) {
            example(kind)
        } else {
            shape(kind, rng, family.ratio)
        };
        let longest = base
            .dims
            .iter()
            .enumerate()
            .filter(|(i, _)| judge::length_slots(kind).contains(i))
            .fold(0.0f64, |m, (_, d)| m.max(d.abs()));
        let (lo, hi) = exponents(family.scales, float, family.ratio);
        let s = scale(rng, lo, hi) / longest;
        let slots = judge::length_slots(kind);
        let dims: Vec<f64> = base
            .dims
            .iter()
            .enumerate()
            .map(|(i, d)| float.round(if slots.contains(&i) { d * s } else { *d }))
            .collect();
        let coupler = (kind == Kind::FourBar).then(|| {
            (
                float.round(rng.range(0.0, 2.0) * dims[2]),
                float.round(rng.angle()),
            )
        });
        let omega = if rng.chance(0.3) {
            1.0
        } else {
            float.round(rng.sign() * rng.log(0.01, 100.0))
        };
        let alpha = float.round(rng.range(-10.0, 10.0));
        let nudge = (0..kind.unknowns())
            .map(|_| {
                if rng.chance(0.2) {
                    0.0
                } else {
                    rng.range(-1.0, 1.0)
                }
            })
            .collect();
        let mut branches = base.branches.clone();
        let mut near = None;
        let placement = rng.pick(&family.placements);
        let (input, placement) = match (&base.at, kind) {
            (Some((t, q)), Kind::StephensonSixBar) => {
                near = Some(q.clone());
                let d = if rng.chance(0.5) {
                    0.0
                } else {
                    rng.sign() * rng.log(1e-12, 1e-3)
                };
                (t + d, format!("{d:.1e} from a constructed position"))
            }
            _ => {
                if kind.loops() == 1 && rng.chance(0.5) {
                    branches = random_branches(rng, 1);
                }
                place(
                    kind,
                    float,
                    &dims,
                    &branches,
                    placement,
                    base.at.as_ref().map(|a| a.0),
                    rng,
                )
            }
        };
        let rescale = (family.rescale && rng.chance(0.5)).then(|| {
            let (lo, hi) = exponents(family.scales, float, family.ratio);
            let longest = dims
                .iter()
                .enumerate()
                .filter(|(i, _)| slots.contains(i))
                .fold(0.0f64, |m, (_, d)| m.max(d.abs()));
            let shortest = dims
                .iter()
                .enumerate()
                .filter(|(i, d)| slots.contains(i) && **d != 0.0)
                .fold(f64::INFINITY, |m, (_, d)| m.min(d.abs()));
            // Keep the scaled lengths within the family's range (in base-2 exponents).
            let up = hi * std::f64::consts::LOG2_10 - longest.log2();
            let down =
                (lo - family.ratio.max(1.0).log10()) * std::f64::consts::LOG2_10 - shortest.log2();
            // The factor itself must be a normal f64 too.
            let k = rng.range(down.clamp(-1000.0, 0.0), up.clamp(0.0, 1000.0));
            let k = if k.round() == 0.0 { 1.0 } else { k };
            if rng.chance(0.5) {
                2f64.powi(k.round() as i32)
            } else {
                2f64.powf(k)
            }
        });
        let (omega, alpha) = match tempo(family.scales, float, &dims, rescale, kind, api, rng) {
            // An acceleration below the float's smallest is rounded as the call will take it.
            Some(k) => (
                float.round(omega * 2f64.powi(k)),
                float.round(alpha * 2f64.powi(2 * k)),
            ),
            None => (omega, alpha),
        };
        // Drawn last (the turns, then the tolerance), so that every earlier draw of a seed
        // stays as it was.
        let turns = if matches!(api, Api::Position | Api::MotionNear) && rng.chance(0.1) {
            rng.sign() * rng.log(1.0, 1e6).round()
        } else {
            0.0
        };
        // A stated tolerance for a quarter of Newton's cases, from below the rounding floor
        // (where it is the default) to far above it (where `motion_near` says its rates are
        // inaccurate, and `position` stops short): of the declared lengths' sum, 1e-15 to
        // 1e-5 in f64, 1e-7 to 1e-2 in f32.
        let tolerance = if matches!(api, Api::Position | Api::MotionNear) && rng.chance(0.25) {
            let size = dims
                .iter()
                .enumerate()
                .filter(|(i, _)| slots.contains(i))
                .fold(0.0, |sum, (_, d)| sum + d.abs());
            let (lo, hi) = match float {
                Float::F64 => (1e-15, 1e-5),
                Float::F32 => (1e-7, 1e-2),
            };
            float.round(size * rng.log(lo, hi))
        } else {
            0.0
        };
        // A tenth of the four-bars' coupler points far off or close in, 1e-12 to 1e120 times
        // the coupler (1e-6 to 1e20 in f32), within the float's range: the scenes scale the
        // loops, not the point (an adversarial review found points from 1e80 times the links
        // in f64, 1e12 in f32, shrinking them into underflow). Drawn last, so the case is
        // otherwise as it was.
        let coupler = match coupler {
            Some((_, angle)) if rng.chance(0.1) => {
                let (lo, hi, smallest, largest) = match float {
                    Float::F64 => (1e-12, 1e120, f64::MIN_POSITIVE, f64::MAX),
                    Float::F32 => (
                        1e-6,
                        1e20,
                        f64::from(f32::MIN_POSITIVE),
                        f64::from(f32::MAX),
                    ),
                };
                let distance = (rng.log(lo, hi) * dims[2]).clamp(smallest * 1e6, largest / 1e6);
                Some((float.round(distance), angle))
            }
            coupler => coupler,
        };
        // A tenth of Newton's guesses beyond Kantorovich's ball, 2 to 10⁴ times as far
        // (angles off by up to thousands of radians): Newton promises no root from there,
        // but any `Ok` must be a root on the guess's own branch, as accurate as stated.
        // Drawn last, so the case is otherwise as it was.
        let mut nudge: Vec<f64> = nudge;
        if matches!(api, Api::Position | Api::MotionNear) && rng.chance(0.1) {
            let far = rng.log(2.0, 1e4);
            for n in &mut nudge {
                *n *= far;
            }
        }
        Case {
            kind,
            float,
            api,
            dims,
            coupler,
            input: float.round(input),
            branches,
            omega,
            alpha,
            near,
            nudge,
            placement,
            rescale,
            turns,
            tolerance,
        }
    }

    /// An input for `placement`, and how it was placed.
    fn place(
        kind: Kind,
        float: Float,
        dims: &[f64],
        branches: &[Branch],
        placement: Placement,
        at: Option<f64>,
        rng: &mut Rng,
    ) -> (f64, String) {
        let anywhere = |rng: &mut Rng| {
            let turns = if rng.chance(0.1) {
                rng.pick(&[-2.0, -1.0, 1.0, 2.0])
            } else {
                0.0
            };
            let t = at
                .filter(|_| rng.chance(0.5))
                .unwrap_or_else(|| rng.angle());
            (t + turns * std::f64::consts::TAU, "anywhere".to_string())
        };
        if placement == Placement::Anywhere {
            return anywhere(rng);
        }
        let Some(p) = held(kind, float, dims) else {
            return anywhere(rng);
        };
        let limits = if placement == Placement::Flat {
            // The crank along the ground line: dead centres, folded and flat positions.
            vec![0.0, PI, -PI]
        } else {
            limit_angles(kind, &p, branches)
        };
        if limits.is_empty() {
            // A crank that turns fully has no limits: anywhere, then.
            return anywhere(rng);
        }
        let limit = rng.pick(&limits);
        let reachable = |t: f64| {
            let t = float.round(t);
            match closed_form(kind, &p, t, branches, 0.0, 0.0) {
                Some(o) if kind.loops() == 1 => o.reach.reachable(),
                _ => chain_gap(kind, &p, t, branches) >= 0.0,
            }
        };
        match placement {
            Placement::AtLimit => {
                let t = float.round(limit);
                let ulp = |x: f64| match float {
                    Float::F32 => f64::from(f32::from_bits((x as f32).to_bits() + 1)) - x,
                    Float::F64 => f64::from_bits(x.to_bits() + 1) - x,
                };
                let step = rng.pick(&[-1.0, 0.0, 1.0]);
                (t + step * ulp(t).abs(), format!("{step} ulp from a limit"))
            }
            Placement::Flat => {
                let d = rng.sign() * rng.pick(&[0.0, 1e-12, 1e-9, 1e-6]);
                (limit + d, format!("{d:e} rad from the ground line"))
            }
            _ => {
                let d = rng.pick(&[1e-12, 1e-9, 1e-6]);
                let up = reachable(limit + d);
                let inside = placement == Placement::Inside;
                let sign = if up == inside { 1.0 } else { -1.0 };
                (
                    limit + sign * d,
                    format!(
                        "{d:e} rad {} a limit",
                        if inside { "inside" } else { "outside" }
                    ),
                )
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::{self, Status};

    /// Subnormal doubles come in exactly (astro-float alone reads them as half their value,
    /// which judged a correct rate of 1e-308 wrong by half its size).
    #[test]
    fn subnormals_convert_exactly() {
        for x in [
            9.99963012973789e-309,
            1e-310,
            -7e-315,
            3e-320,
            5e-324,
            2.5e-308,
            1.0,
        ] {
            assert_eq!(Big::from_f64(x).to_f64(), x);
        }
        assert_eq!(
            (Big::from_f64(1e-310) * Big::from_f64(2.0)).to_f64(),
            2e-310
        );
    }

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
