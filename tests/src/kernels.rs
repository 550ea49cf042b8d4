//! The one registry of measured kernels: what the callgrind driver
//! (`src/bin/instructions.rs`), the criterion benchmark (`benches/kinematics.rs`) and the
//! performance report (`src/bin/performance.rs`) run, by name.
//!
//! A kernel is one call a user makes per step of a crank's turn, generated or hand-written.
//! Its factory ([`Kernel::build`]) does every once-per-mechanism thing (constructors,
//! `scenes()`, the hand baselines' precomputed constants, a Newton solver's first guess)
//! and returns a boxed closure: the measured loops call nothing but that closure, so hand
//! and generated code pay the same indirect call, and a kernel's work is inlined into its
//! closure either way. The closure returns the sum of every output, so none of the work is
//! optimised away.
//!
//! The sweep: [`STEPS`] inputs one degree apart, [`input`]`(k)` = k° in radians, crank at
//! ω = [`OMEGA`], α = [`ALPHA`], open branch. Newton kernels keep their own warm start and
//! predict the next step's guess from the rates, `q + (q̇/ω)·Δθ` with Δθ = 1°
//! ([`PREDICTOR`]), hand and generated alike.

use mechanisms::{
    FourBar, FourBarUnknowns, InvertedSliderCrank, SliderCrank, StephensonSixBarUnknowns,
    WattSixBar,
};
use mechgen::{Branch, NewtonOptions};

use crate::baselines::{
    self, FourBarCouplerPoint, FourBarNewton, FourBarNorton, InvertedSliderCrankClosed,
    SliderCrankClosed,
};
use crate::examples;

/// Inputs per sweep: one turn, one degree apart.
pub const STEPS: usize = 360;

/// Sweeps the callgrind driver runs: counts per call are `(total − none)/(STEPS·SWEEPS)`.
pub const SWEEPS: usize = 100;

/// The crank's rate, rad/s.
pub const OMEGA: f64 = 10.0;

/// The crank's acceleration, rad/s².
pub const ALPHA: f64 = 2.0;

/// The sweep's step, one degree, in radians.
pub const STEP: f64 = std::f64::consts::PI / 180.0;

/// The velocity predictor's factor `Δθ/ω`: the next guess is `q + q̇·PREDICTOR`.
pub const PREDICTOR: f64 = STEP / OMEGA;

/// The Newton kernels' tolerance on the loop residual (mm).
pub const NEWTON_TOLERANCE: f64 = 1e-12;

/// The four-bar's lengths `[l1, l2, l3, l4]` (the seeds' Example 1).
pub const FOUR_BAR: [f64; 4] = [180.0, 80.0, 200.0, 150.0];

/// The four-bar's coupler point: distance from A and angle from A B, degrees.
pub const COUPLER_POINT: (f64, f64) = (100.0, 30.0);

/// The slider-crank's crank, rod and offset.
pub const SLIDER_CRANK: [f64; 3] = [50.0, 150.0, 20.0];

/// The inverted slider-crank's ground, crank, slide offset and angle γ (radians).
pub const INVERTED_SLIDER_CRANK: [f64; 4] = [150.0, 60.0, 20.0, 0.3];

/// The `k`th input of the sweep, radians.
#[inline]
pub fn input(k: usize) -> f64 {
    (k as f64).to_radians()
}

/// What a group of kernels computes; kernels in one group return the same outputs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Group {
    /// The boxed identity: the measured loop and the call, to subtract.
    Overhead,
    /// Four-bar θ3, θ4, their rates and accelerations, closed form.
    FourBarAngles,
    /// Four-bar θ3, θ4, rates and accelerations by Newton from a warm start.
    FourBarNewton,
    /// The four-bar's coupler point, position only.
    CouplerPath,
    /// The four-bar's coupler point: position, velocity, acceleration.
    CouplerMotion,
    /// Slider-crank θ3, d, rates and accelerations.
    SliderCrank,
    /// Inverted slider-crank θ4, b, rates and accelerations.
    InvertedSliderCrank,
    /// The six-bars.
    SixBars,
}

/// A reference sweep in `tests/reference/sweeps.csv` that a group's outputs can be held to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Reference {
    /// The sweep's mechanism column.
    pub mechanism: &'static str,
    /// Whether each unknown is an angle (compared modulo 2π, in radians) or a length
    /// (compared relative to its size).
    pub angles: [bool; 2],
}

impl Group {
    /// Every group, in the report's order.
    pub const ALL: [Group; 8] = [
        Group::Overhead,
        Group::FourBarAngles,
        Group::FourBarNewton,
        Group::CouplerPath,
        Group::CouplerMotion,
        Group::SliderCrank,
        Group::InvertedSliderCrank,
        Group::SixBars,
    ];

    /// A heading for the group.
    pub fn title(self) -> &'static str {
        match self {
            Group::Overhead => "overhead: the boxed call",
            Group::FourBarAngles => "four-bar: θ3, θ4, rates and accelerations (closed form)",
            Group::FourBarNewton => {
                "four-bar: Newton from the predicted guess to 1e-12, then rates and accelerations"
            }
            Group::CouplerPath => "four-bar coupler point: position only",
            Group::CouplerMotion => "four-bar coupler point: position, velocity, acceleration",
            Group::SliderCrank => "slider-crank: θ3, d, rates and accelerations",
            Group::InvertedSliderCrank => "inverted slider-crank: θ4, b, rates and accelerations",
            Group::SixBars => "six-bars",
        }
    }

    /// The reference sweep the group's outputs (`[q1, q2, q̇1, q̇2, q̈1, q̈2]`) compare with.
    pub fn reference(self) -> Option<Reference> {
        match self {
            Group::FourBarAngles | Group::FourBarNewton => Some(Reference {
                mechanism: "four_bar",
                angles: [true, true],
            }),
            Group::SliderCrank => Some(Reference {
                mechanism: "slider_crank",
                angles: [true, false],
            }),
            Group::InvertedSliderCrank => Some(Reference {
                mechanism: "inverted_slider_crank",
                angles: [true, false],
            }),
            _ => None,
        }
    }
}

/// The floating-point type a kernel computes in (its input and outputs cross in `f64`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Float {
    F64,
    F32,
}

impl std::fmt::Display for Float {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Float::F64 => "f64",
            Float::F32 => "f32",
        })
    }
}

/// Who wrote a kernel's code.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Origin {
    /// The `mechanism!` macro's output.
    Generated,
    /// A careful hand-written baseline (`crate::baselines`).
    Hand,
    /// A general-purpose library a user might reach for instead (num-dual, nalgebra).
    Library,
    /// Neither: the overhead kernel.
    Overhead,
}

/// A boxed kernel: input in, the sum of every output out.
pub type Boxed = Box<dyn FnMut(f64) -> f64>;

/// A boxed kernel that lists its outputs (widened to `f64`), for accuracy checks.
pub type Listed = Box<dyn FnMut(f64) -> Vec<f64>>;

/// One measured kernel.
#[derive(Clone, Copy)]
pub struct Kernel {
    /// Its name on the command line, in the benchmark and in the report.
    pub name: &'static str,
    /// What it computes.
    pub group: Group,
    /// Who wrote it.
    pub origin: Origin,
    /// The type it computes in.
    pub float: Float,
    /// The mechanism and its dimensions.
    pub mechanism: &'static str,
    /// The calls it makes per step.
    pub description: &'static str,
    /// The kernel it is compared with in the report, if any.
    pub compared_with: Option<&'static str>,
    /// Builds the kernel (once, outside any measured loop).
    pub build: fn() -> Boxed,
    /// Builds the same kernel returning its outputs rather than their sum.
    pub outputs: fn() -> Listed,
}

impl std::fmt::Debug for Kernel {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Kernel").field("name", &self.name).finish()
    }
}

/// The kernel called `name`.
pub fn find(name: &str) -> Option<&'static Kernel> {
    KERNELS.iter().find(|k| k.name == name)
}

/// A kernel's outputs at one input: a fixed number of values of one float type.
pub trait Outputs {
    /// Their sum, in the kernel's own type, then widened.
    fn total(&self) -> f64;
    /// Each of them, widened.
    fn list(&self) -> Vec<f64>;
}

impl<const N: usize> Outputs for [f64; N] {
    #[inline(always)]
    fn total(&self) -> f64 {
        self.iter().sum()
    }
    fn list(&self) -> Vec<f64> {
        self.to_vec()
    }
}

impl<const N: usize> Outputs for [f32; N] {
    #[inline(always)]
    fn total(&self) -> f64 {
        f64::from(self.iter().sum::<f32>())
    }
    fn list(&self) -> Vec<f64> {
        self.iter().map(|&x| f64::from(x)).collect()
    }
}

fn summed<O: Outputs>(mut kernel: impl FnMut(f64) -> O + 'static) -> Boxed {
    Box::new(move |t| called(&mut kernel, t).total())
}

/// `kernel(t)` as a function of its own, which the harness calls: every kernel, hand-written
/// or generated, is compiled whole into it (each kernel's closure is `#[inline(always)]`) and
/// called the same way. Left to itself, the compiler inlines a small kernel into the harness
/// and calls a large one, and the difference is the harness's, not the kernel's.
#[inline(never)]
fn called<O>(kernel: &mut impl FnMut(f64) -> O, t: f64) -> O {
    kernel(t)
}

fn listed<O: Outputs>(mut kernel: impl FnMut(f64) -> O + 'static) -> Listed {
    Box::new(move |t| kernel(t).list())
}

fn flat(state: [[f64; 2]; 3]) -> [f64; 6] {
    let [[a, b], [c, d], [e, f]] = state;
    [a, b, c, d, e, f]
}

fn four_bar() -> FourBar<f64> {
    let [l1, l2, l3, l4] = FOUR_BAR;
    let (distance, angle) = COUPLER_POINT;
    FourBar::new(l1, l2, l3, l4)
        .and_then(|linkage| linkage.with_coupler_point(distance, angle.to_radians()))
        .expect("the four-bar's dimensions are valid")
}

fn four_bar_f32() -> FourBar<f32> {
    let [l1, l2, l3, l4] = FOUR_BAR.map(|l| l as f32);
    let (distance, angle) = COUPLER_POINT;
    FourBar::new(l1, l2, l3, l4)
        .and_then(|linkage| linkage.with_coupler_point(distance as f32, angle.to_radians() as f32))
        .expect("the four-bar's dimensions are valid")
}

fn slider_crank() -> SliderCrank<f64> {
    let [l2, l3, c] = SLIDER_CRANK;
    SliderCrank::new(l2, l3, c).expect("the slider-crank's dimensions are valid")
}

fn inverted_slider_crank() -> InvertedSliderCrank<f64> {
    let [l1, l2, c, gamma] = INVERTED_SLIDER_CRANK;
    InvertedSliderCrank::new(l1, l2, c, gamma)
        .expect("the inverted slider-crank's dimensions are valid")
}

fn watt() -> WattSixBar<f64> {
    WattSixBar::new(FOUR_BAR, 100.0, 0.8, 220.0, 160.0, (300.0, 150.0))
        .expect("the Watt six-bar's dimensions are valid")
}

/// The predicted guess for the next step: `q + q̇·(Δθ/ω)`.
#[inline(always)]
fn predict<const N: usize>(position: [f64; N], rate: [f64; N]) -> [f64; N] {
    let mut guess = position;
    for (g, r) in guess.iter_mut().zip(rate) {
        *g += r * PREDICTOR;
    }
    guess
}

// ---- kernels ------------------------------------------------------------------------------

fn none() -> impl FnMut(f64) -> [f64; 1] {
    |t| [t]
}

fn hand_norton() -> impl FnMut(f64) -> [f64; 6] {
    let hand = FourBarNorton::new(FOUR_BAR);
    #[inline(always)]
    move |t| flat(hand.motion(t, OMEGA, ALPHA))
}

fn scene_angles() -> impl FnMut(f64) -> [f64; 6] {
    let scenes = four_bar().scenes().expect("scene constants");
    #[inline(always)]
    move |t| {
        let s = scenes.angles(t, Branch::Open, OMEGA, ALPHA).unwrap();
        [
            s.theta3,
            s.theta4,
            s.theta3_dot,
            s.theta4_dot,
            s.theta3_ddot,
            s.theta4_ddot,
        ]
    }
}

fn scene_angles_f32() -> impl FnMut(f64) -> [f32; 6] {
    let scenes = four_bar_f32().scenes().expect("scene constants");
    #[inline(always)]
    move |t| {
        let s = scenes
            .angles(t as f32, Branch::Open, OMEGA as f32, ALPHA as f32)
            .unwrap();
        [
            s.theta3,
            s.theta4,
            s.theta3_dot,
            s.theta4_dot,
            s.theta3_ddot,
            s.theta4_ddot,
        ]
    }
}

fn motion() -> impl FnMut(f64) -> [f64; 6] {
    let linkage = four_bar();
    #[inline(always)]
    move |t| {
        let m = linkage.motion(t, Branch::Open, OMEGA, ALPHA).unwrap();
        flat([
            m.position.to_array(),
            m.velocity.to_array(),
            m.acceleration.to_array(),
        ])
    }
}

fn assemble_velocity_acceleration() -> impl FnMut(f64) -> [f64; 6] {
    let linkage = four_bar();
    #[inline(always)]
    move |t| {
        let q = linkage.assemble(t, Branch::Open).unwrap();
        let v = linkage.velocity(t, &q, OMEGA).unwrap();
        let a = linkage.acceleration(t, &q, OMEGA, &v, ALPHA).unwrap();
        flat([q.to_array(), v.to_array(), a.to_array()])
    }
}

/// The open branch at θ2 = 0, where every four-bar Newton kernel starts.
fn four_bar_start() -> [f64; 2] {
    four_bar()
        .assemble(0.0, Branch::Open)
        .expect("assembles at 0")
        .to_array()
}

fn hand_newton() -> impl FnMut(f64) -> [f64; 6] {
    let hand = FourBarNewton::new(FOUR_BAR);
    let mut guess = four_bar_start();
    #[inline(always)]
    move |t| {
        let s = hand.motion(t, guess, NEWTON_TOLERANCE, OMEGA, ALPHA);
        guess = predict(s[0], s[1]);
        flat(s)
    }
}

/// The four-bar's turn by `motion_near(t, &guess, &options, ω, α)` (as `solve` calls it),
/// each guess predicted from the solution before.
fn four_bar_newton_sweep(
    solve: impl Fn(f64, &FourBarUnknowns<f64>, &NewtonOptions<f64>) -> FourBarMotion,
) -> impl FnMut(f64) -> [f64; 6] {
    let options = NewtonOptions::new(NEWTON_TOLERANCE, 50);
    let mut guess = FourBarUnknowns::from_array(four_bar_start());
    #[inline(always)]
    move |t| {
        let m = solve(t, &guess, &options);
        let (q, v) = (m.position.to_array(), m.velocity.to_array());
        guess = FourBarUnknowns::from_array(predict(q, v));
        flat([q, v, m.acceleration.to_array()])
    }
}

type FourBarMotion = mechgen::Motion<FourBarUnknowns<f64>, f64>;

fn motion_near() -> impl FnMut(f64) -> [f64; 6] {
    let linkage = four_bar();
    four_bar_newton_sweep(
        #[inline(always)]
        move |t, guess, options| {
            linkage
                .motion_near(t, guess, options, OMEGA, ALPHA)
                .unwrap()
                .value
        },
    )
}

fn newton_motion_near() -> impl FnMut(f64) -> [f64; 6] {
    let newton = four_bar()
        .newton()
        .expect("the four-bar's dimensions are finite");
    four_bar_newton_sweep(
        #[inline(always)]
        move |t, guess, options| {
            newton
                .motion_near(t, guess, options, OMEGA, ALPHA)
                .unwrap()
                .value
        },
    )
}

fn position_motion_at() -> impl FnMut(f64) -> [f64; 6] {
    let linkage = four_bar();
    let options = NewtonOptions::new(NEWTON_TOLERANCE, 50);
    let mut guess = FourBarUnknowns::from_array(four_bar_start());
    #[inline(always)]
    move |t| {
        let q = linkage.position(t, &guess, &options).unwrap().value;
        let m = linkage.motion_at(t, &q, OMEGA, ALPHA).unwrap();
        let (q, v) = (q.to_array(), m.velocity.to_array());
        guess = FourBarUnknowns::from_array(predict(q, v));
        flat([q, v, m.acceleration.to_array()])
    }
}

fn num_dual_newton() -> impl FnMut(f64) -> [f64; 6] {
    let mut guess = four_bar_start();
    #[inline(always)]
    move |t| {
        let s = baselines::four_bar_num_dual(&FOUR_BAR, t, guess, NEWTON_TOLERANCE, OMEGA, ALPHA);
        guess = predict(s[0], s[1]);
        flat(s)
    }
}

fn nalgebra_newton() -> impl FnMut(f64) -> [f64; 6] {
    let mut guess = four_bar_start();
    #[inline(always)]
    move |t| {
        let s = baselines::four_bar_nalgebra(&FOUR_BAR, t, guess, NEWTON_TOLERANCE, OMEGA, ALPHA);
        guess = predict(s[0], s[1]);
        flat(s)
    }
}

fn hand_point() -> impl FnMut(f64) -> [f64; 2] {
    let (distance, angle) = COUPLER_POINT;
    let hand = FourBarCouplerPoint::new(FOUR_BAR, distance, angle.to_radians());
    #[inline(always)]
    move |t| hand.position(t)
}

fn scene_coupler_path() -> impl FnMut(f64) -> [f64; 2] {
    let scenes = four_bar().scenes().expect("scene constants");
    #[inline(always)]
    move |t| {
        let p = scenes.coupler_path(t, Branch::Open).unwrap().coupler_point;
        [p.x, p.y]
    }
}

fn scene_coupler_path_f32() -> impl FnMut(f64) -> [f32; 2] {
    let scenes = four_bar_f32().scenes().expect("scene constants");
    #[inline(always)]
    move |t| {
        let p = scenes
            .coupler_path(t as f32, Branch::Open)
            .unwrap()
            .coupler_point;
        [p.x, p.y]
    }
}

fn assemble_points() -> impl FnMut(f64) -> [f64; 2] {
    let linkage = four_bar();
    #[inline(always)]
    move |t| {
        let q = linkage.assemble(t, Branch::Open).unwrap();
        let p = linkage.points(t, &q).unwrap().coupler_point;
        [p.x, p.y]
    }
}

fn hand_point_motion() -> impl FnMut(f64) -> [f64; 6] {
    let (distance, angle) = COUPLER_POINT;
    let hand = FourBarCouplerPoint::new(FOUR_BAR, distance, angle.to_radians());
    #[inline(always)]
    move |t| flat(hand.motion(t, OMEGA, ALPHA))
}

fn scene_coupler_motion() -> impl FnMut(f64) -> [f64; 6] {
    let scenes = four_bar().scenes().expect("scene constants");
    #[inline(always)]
    move |t| {
        let m = scenes
            .coupler_motion(t, Branch::Open, OMEGA, ALPHA)
            .unwrap();
        let (p, v, a) = (m.coupler_point, m.coupler_point_dot, m.coupler_point_ddot);
        [p.x, p.y, v.x, v.y, a.x, a.y]
    }
}

fn scene_coupler_motion_f32() -> impl FnMut(f64) -> [f32; 6] {
    let scenes = four_bar_f32().scenes().expect("scene constants");
    #[inline(always)]
    move |t| {
        let m = scenes
            .coupler_motion(t as f32, Branch::Open, OMEGA as f32, ALPHA as f32)
            .unwrap();
        let (p, v, a) = (m.coupler_point, m.coupler_point_dot, m.coupler_point_ddot);
        [p.x, p.y, v.x, v.y, a.x, a.y]
    }
}

fn motion_points() -> impl FnMut(f64) -> [f64; 6] {
    let linkage = four_bar();
    #[inline(always)]
    move |t| {
        let m = linkage.motion(t, Branch::Open, OMEGA, ALPHA).unwrap();
        let (q, v, a) = (m.position, m.velocity, m.acceleration);
        let p = linkage.points(t, &q).unwrap().coupler_point;
        let pv = linkage
            .point_velocities(t, &q, OMEGA, &v)
            .unwrap()
            .coupler_point;
        let pa = linkage
            .point_accelerations(t, &q, OMEGA, &v, ALPHA, &a)
            .unwrap()
            .coupler_point;
        [p.x, p.y, pv.x, pv.y, pa.x, pa.y]
    }
}

fn hand_slider_crank() -> impl FnMut(f64) -> [f64; 6] {
    let [l2, l3, c] = SLIDER_CRANK;
    let hand = SliderCrankClosed::new(l2, l3, c);
    #[inline(always)]
    move |t| flat(hand.motion(t, OMEGA, ALPHA))
}

fn scene_slider_crank() -> impl FnMut(f64) -> [f64; 6] {
    let scenes = slider_crank().scenes().expect("scene constants");
    #[inline(always)]
    move |t| {
        let s = scenes.state(t, Branch::Open, OMEGA, ALPHA).unwrap();
        [
            s.theta3,
            s.d,
            s.theta3_dot,
            s.d_dot,
            s.theta3_ddot,
            s.d_ddot,
        ]
    }
}

fn slider_crank_motion() -> impl FnMut(f64) -> [f64; 6] {
    let linkage = slider_crank();
    #[inline(always)]
    move |t| {
        let m = linkage.motion(t, Branch::Open, OMEGA, ALPHA).unwrap();
        flat([
            m.position.to_array(),
            m.velocity.to_array(),
            m.acceleration.to_array(),
        ])
    }
}

fn hand_inverted_slider_crank() -> impl FnMut(f64) -> [f64; 6] {
    let hand = InvertedSliderCrankClosed::new(INVERTED_SLIDER_CRANK);
    #[inline(always)]
    move |t| flat(hand.motion(t, OMEGA, ALPHA))
}

fn scene_inverted_slider_crank() -> impl FnMut(f64) -> [f64; 6] {
    let scenes = inverted_slider_crank().scenes().expect("scene constants");
    #[inline(always)]
    move |t| {
        let s = scenes.state(t, Branch::Open, OMEGA, ALPHA).unwrap();
        [
            s.theta4,
            s.b,
            s.theta4_dot,
            s.b_dot,
            s.theta4_ddot,
            s.b_ddot,
        ]
    }
}

fn inverted_slider_crank_motion() -> impl FnMut(f64) -> [f64; 6] {
    let linkage = inverted_slider_crank();
    #[inline(always)]
    move |t| {
        let m = linkage.motion(t, Branch::Open, OMEGA, ALPHA).unwrap();
        flat([
            m.position.to_array(),
            m.velocity.to_array(),
            m.acceleration.to_array(),
        ])
    }
}

fn stephenson_motion_near() -> impl FnMut(f64) -> [f64; 12] {
    let (linkage, guess) = examples::stephenson_six_bar();
    let options = NewtonOptions::default();
    let mut guess = linkage
        .position(0.0, &guess, &options)
        .expect("the Stephenson six-bar assembles at 0")
        .value;
    #[inline(always)]
    move |t| {
        let m = linkage
            .motion_near(t, &guess, &options, OMEGA, ALPHA)
            .unwrap()
            .value;
        let (q, v, a) = (
            m.position.to_array(),
            m.velocity.to_array(),
            m.acceleration.to_array(),
        );
        guess = StephensonSixBarUnknowns::from_array(predict(q, v));
        let mut out = [0.0; 12];
        out[..4].copy_from_slice(&q);
        out[4..8].copy_from_slice(&v);
        out[8..].copy_from_slice(&a);
        out
    }
}

fn watt_motion() -> impl FnMut(f64) -> [f64; 12] {
    let linkage = watt();
    #[inline(always)]
    move |t| {
        let m = linkage
            .motion(t, [Branch::Open, Branch::Open], OMEGA, ALPHA)
            .unwrap();
        let (q, v, a) = (
            m.position.to_array(),
            m.velocity.to_array(),
            m.acceleration.to_array(),
        );
        let mut out = [0.0; 12];
        out[..4].copy_from_slice(&q);
        out[4..8].copy_from_slice(&v);
        out[8..].copy_from_slice(&a);
        out
    }
}

fn watt_scene_output() -> impl FnMut(f64) -> [f64; 3] {
    let scenes = watt().scenes().expect("scene constants");
    #[inline(always)]
    move |t| {
        let s = scenes
            .output(t, [Branch::Open, Branch::Open], OMEGA, ALPHA)
            .unwrap();
        [s.theta6, s.theta6_dot, s.theta6_ddot]
    }
}

// ---- the registry -------------------------------------------------------------------------

const FOUR_BAR_DIMENSIONS: &str = "four-bar 180/80/200/150";
const COUPLER_DIMENSIONS: &str = "four-bar 180/80/200/150, coupler point a = 100, δ = 30°";
const SLIDER_CRANK_DIMENSIONS: &str = "slider-crank 50/150, offset 20";
const INVERTED_DIMENSIONS: &str = "inverted slider-crank 150/60, offset 20, γ = 0.3";
const WATT_DIMENSIONS: &str =
    "Watt six-bar: four-bar 180/80/200/150, extension 100 at 0.8, 220/160, pivot (300, 150)";
const STEPHENSON_DIMENSIONS: &str = "Stephenson six-bar of `examples::stephenson_six_bar`";

/// Every kernel, in the report's order: each group's hand-written kernel first, then the
/// generated ones, each f32 kernel beside its f64 twin.
pub static KERNELS: &[Kernel] = &[
    Kernel {
        name: "none",
        group: Group::Overhead,
        origin: Origin::Overhead,
        float: Float::F64,
        mechanism: "–",
        description: "the boxed identity: the measured loop and the indirect call, subtracted from every count",
        compared_with: None,
        build: || summed(none()),
        outputs: || listed(none()),
    },
    // Four-bar angles.
    Kernel {
        name: "hand-norton",
        group: Group::FourBarAngles,
        origin: Origin::Hand,
        float: Float::F64,
        mechanism: FOUR_BAR_DIMENSIONS,
        description: "`baselines::FourBarNorton::motion`: Norton's half-angle closed form, rates from link vectors",
        compared_with: None,
        build: || summed(hand_norton()),
        outputs: || listed(hand_norton()),
    },
    Kernel {
        name: "scene-angles",
        group: Group::FourBarAngles,
        origin: Origin::Generated,
        float: Float::F64,
        mechanism: FOUR_BAR_DIMENSIONS,
        description: "`scenes.angles(θ2, Open, ω, α)`",
        compared_with: Some("hand-norton"),
        build: || summed(scene_angles()),
        outputs: || listed(scene_angles()),
    },
    Kernel {
        name: "scene-angles-f32",
        group: Group::FourBarAngles,
        origin: Origin::Generated,
        float: Float::F32,
        mechanism: FOUR_BAR_DIMENSIONS,
        description: "`scenes.angles(θ2, Open, ω, α)` on `FourBar<f32>`",
        compared_with: Some("scene-angles"),
        build: || summed(scene_angles_f32()),
        outputs: || listed(scene_angles_f32()),
    },
    Kernel {
        name: "motion",
        group: Group::FourBarAngles,
        origin: Origin::Generated,
        float: Float::F64,
        mechanism: FOUR_BAR_DIMENSIONS,
        description: "`motion(θ2, Open, ω, α)`",
        compared_with: Some("hand-norton"),
        build: || summed(motion()),
        outputs: || listed(motion()),
    },
    Kernel {
        name: "assemble-velocity-acceleration",
        group: Group::FourBarAngles,
        origin: Origin::Generated,
        float: Float::F64,
        mechanism: FOUR_BAR_DIMENSIONS,
        description: "`assemble`, then `velocity`, then `acceleration`",
        compared_with: Some("hand-norton"),
        build: || summed(assemble_velocity_acceleration()),
        outputs: || listed(assemble_velocity_acceleration()),
    },
    // Four-bar Newton.
    Kernel {
        name: "hand-newton",
        group: Group::FourBarNewton,
        origin: Origin::Hand,
        float: Float::F64,
        mechanism: FOUR_BAR_DIMENSIONS,
        description: "`baselines::FourBarNewton::motion`: plain Newton with the analytic Jacobian to max|f| < 1e-12, one `sin_cos` per angle at the guess and the link vectors turned through each step, rates from its last evaluation",
        compared_with: None,
        build: || summed(hand_newton()),
        outputs: || listed(hand_newton()),
    },
    Kernel {
        name: "motion-near",
        group: Group::FourBarNewton,
        origin: Origin::Generated,
        float: Float::F64,
        mechanism: FOUR_BAR_DIMENSIONS,
        description: "`motion_near(θ2, &guess, &NewtonOptions::new(1e-12, 50), ω, α)`",
        compared_with: Some("hand-newton"),
        build: || summed(motion_near()),
        outputs: || listed(motion_near()),
    },
    Kernel {
        name: "newton-motion-near",
        group: Group::FourBarNewton,
        origin: Origin::Generated,
        float: Float::F64,
        mechanism: FOUR_BAR_DIMENSIONS,
        description: "`newton()` once, then `motion_near(θ2, &guess, &NewtonOptions::new(1e-12, 50), ω, α)` on it: the dimensions checked and Newton's constants computed once",
        compared_with: Some("hand-newton"),
        build: || summed(newton_motion_near()),
        outputs: || listed(newton_motion_near()),
    },
    Kernel {
        name: "position-motion-at",
        group: Group::FourBarNewton,
        origin: Origin::Generated,
        float: Float::F64,
        mechanism: FOUR_BAR_DIMENSIONS,
        description: "`position(θ2, &guess, &NewtonOptions::new(1e-12, 50))`, then `motion_at`",
        compared_with: Some("hand-newton"),
        build: || summed(position_motion_at()),
        outputs: || listed(position_motion_at()),
    },
    Kernel {
        name: "num-dual-newton",
        group: Group::FourBarNewton,
        origin: Origin::Library,
        float: Float::F64,
        mechanism: FOUR_BAR_DIMENSIONS,
        description: "`baselines::four_bar_num_dual`: Newton to 1e-12 with a forward-mode dual-number Jacobian",
        compared_with: Some("hand-newton"),
        build: || summed(num_dual_newton()),
        outputs: || listed(num_dual_newton()),
    },
    Kernel {
        name: "nalgebra-newton",
        group: Group::FourBarNewton,
        origin: Origin::Library,
        float: Float::F64,
        mechanism: FOUR_BAR_DIMENSIONS,
        description: "`baselines::four_bar_nalgebra`: Newton to 1e-12 on dynamic matrices, finite-difference Jacobians, accelerations by central differences (allocates)",
        compared_with: Some("hand-newton"),
        build: || summed(nalgebra_newton()),
        outputs: || listed(nalgebra_newton()),
    },
    // Coupler point, position only.
    Kernel {
        name: "hand-point",
        group: Group::CouplerPath,
        origin: Origin::Hand,
        float: Float::F64,
        mechanism: COUPLER_DIMENSIONS,
        description: "`baselines::FourBarCouplerPoint::position`: circle intersection, no angle",
        compared_with: None,
        build: || summed(hand_point()),
        outputs: || listed(hand_point()),
    },
    Kernel {
        name: "scene-coupler-path",
        group: Group::CouplerPath,
        origin: Origin::Generated,
        float: Float::F64,
        mechanism: COUPLER_DIMENSIONS,
        description: "`scenes.coupler_path(θ2, Open)`",
        compared_with: Some("hand-point"),
        build: || summed(scene_coupler_path()),
        outputs: || listed(scene_coupler_path()),
    },
    Kernel {
        name: "scene-coupler-path-f32",
        group: Group::CouplerPath,
        origin: Origin::Generated,
        float: Float::F32,
        mechanism: COUPLER_DIMENSIONS,
        description: "`scenes.coupler_path(θ2, Open)` on `FourBar<f32>`",
        compared_with: Some("scene-coupler-path"),
        build: || summed(scene_coupler_path_f32()),
        outputs: || listed(scene_coupler_path_f32()),
    },
    Kernel {
        name: "assemble-points",
        group: Group::CouplerPath,
        origin: Origin::Generated,
        float: Float::F64,
        mechanism: COUPLER_DIMENSIONS,
        description: "`assemble`, then `points(..).coupler_point`",
        compared_with: Some("hand-point"),
        build: || summed(assemble_points()),
        outputs: || listed(assemble_points()),
    },
    // Coupler point, position, velocity, acceleration.
    Kernel {
        name: "hand-point-motion",
        group: Group::CouplerMotion,
        origin: Origin::Hand,
        float: Float::F64,
        mechanism: COUPLER_DIMENSIONS,
        description: "`baselines::FourBarCouplerPoint::motion`: circle intersection, rates from link vectors, no angle",
        compared_with: None,
        build: || summed(hand_point_motion()),
        outputs: || listed(hand_point_motion()),
    },
    Kernel {
        name: "scene-coupler-motion",
        group: Group::CouplerMotion,
        origin: Origin::Generated,
        float: Float::F64,
        mechanism: COUPLER_DIMENSIONS,
        description: "`scenes.coupler_motion(θ2, Open, ω, α)`",
        compared_with: Some("hand-point-motion"),
        build: || summed(scene_coupler_motion()),
        outputs: || listed(scene_coupler_motion()),
    },
    Kernel {
        name: "scene-coupler-motion-f32",
        group: Group::CouplerMotion,
        origin: Origin::Generated,
        float: Float::F32,
        mechanism: COUPLER_DIMENSIONS,
        description: "`scenes.coupler_motion(θ2, Open, ω, α)` on `FourBar<f32>`",
        compared_with: Some("scene-coupler-motion"),
        build: || summed(scene_coupler_motion_f32()),
        outputs: || listed(scene_coupler_motion_f32()),
    },
    Kernel {
        name: "motion-points",
        group: Group::CouplerMotion,
        origin: Origin::Generated,
        float: Float::F64,
        mechanism: COUPLER_DIMENSIONS,
        description: "`motion`, then `points`, `point_velocities`, `point_accelerations` (`.coupler_point` of each)",
        compared_with: Some("hand-point-motion"),
        build: || summed(motion_points()),
        outputs: || listed(motion_points()),
    },
    // Slider-crank.
    Kernel {
        name: "hand-slider-crank",
        group: Group::SliderCrank,
        origin: Origin::Hand,
        float: Float::F64,
        mechanism: SLIDER_CRANK_DIMENSIONS,
        description: "`baselines::SliderCrankClosed::motion`",
        compared_with: None,
        build: || summed(hand_slider_crank()),
        outputs: || listed(hand_slider_crank()),
    },
    Kernel {
        name: "scene-slider-crank",
        group: Group::SliderCrank,
        origin: Origin::Generated,
        float: Float::F64,
        mechanism: SLIDER_CRANK_DIMENSIONS,
        description: "`scenes.state(θ2, Open, ω, α)`",
        compared_with: Some("hand-slider-crank"),
        build: || summed(scene_slider_crank()),
        outputs: || listed(scene_slider_crank()),
    },
    Kernel {
        name: "slider-crank-motion",
        group: Group::SliderCrank,
        origin: Origin::Generated,
        float: Float::F64,
        mechanism: SLIDER_CRANK_DIMENSIONS,
        description: "`motion(θ2, Open, ω, α)`",
        compared_with: Some("hand-slider-crank"),
        build: || summed(slider_crank_motion()),
        outputs: || listed(slider_crank_motion()),
    },
    // Inverted slider-crank.
    Kernel {
        name: "hand-inverted-slider-crank",
        group: Group::InvertedSliderCrank,
        origin: Origin::Hand,
        float: Float::F64,
        mechanism: INVERTED_DIMENSIONS,
        description: "`baselines::InvertedSliderCrankClosed::motion`",
        compared_with: None,
        build: || summed(hand_inverted_slider_crank()),
        outputs: || listed(hand_inverted_slider_crank()),
    },
    Kernel {
        name: "scene-inverted-slider-crank",
        group: Group::InvertedSliderCrank,
        origin: Origin::Generated,
        float: Float::F64,
        mechanism: INVERTED_DIMENSIONS,
        description: "`scenes.state(θ2, Open, ω, α)`",
        compared_with: Some("hand-inverted-slider-crank"),
        build: || summed(scene_inverted_slider_crank()),
        outputs: || listed(scene_inverted_slider_crank()),
    },
    Kernel {
        name: "inverted-slider-crank-motion",
        group: Group::InvertedSliderCrank,
        origin: Origin::Generated,
        float: Float::F64,
        mechanism: INVERTED_DIMENSIONS,
        description: "`motion(θ2, Open, ω, α)`",
        compared_with: Some("hand-inverted-slider-crank"),
        build: || summed(inverted_slider_crank_motion()),
        outputs: || listed(inverted_slider_crank_motion()),
    },
    // Six-bars.
    Kernel {
        name: "stephenson-motion-near",
        group: Group::SixBars,
        origin: Origin::Generated,
        float: Float::F64,
        mechanism: STEPHENSON_DIMENSIONS,
        description: "`motion_near(θ2, &guess, &NewtonOptions::default(), ω, α)`: Newton on θ3 and θ4 (the other loop in closed form inside each iteration) from the predicted guess",
        compared_with: Some("motion"),
        build: || summed(stephenson_motion_near()),
        outputs: || listed(stephenson_motion_near()),
    },
    Kernel {
        name: "watt-motion",
        group: Group::SixBars,
        origin: Origin::Generated,
        float: Float::F64,
        mechanism: WATT_DIMENSIONS,
        description: "`motion(θ2, [Open, Open], ω, α)`: two loops in closed form, rates block by block",
        compared_with: Some("motion"),
        build: || summed(watt_motion()),
        outputs: || listed(watt_motion()),
    },
    Kernel {
        name: "watt-scene-output",
        group: Group::SixBars,
        origin: Origin::Generated,
        float: Float::F64,
        mechanism: WATT_DIMENSIONS,
        description: "`scenes.output(θ2, [Open, Open], ω, α)`: θ6 and its rate and acceleration",
        compared_with: Some("watt-motion"),
        build: || summed(watt_scene_output()),
        outputs: || listed(watt_scene_output()),
    },
];
