//! The planar mechanisms mechgen ships, each declared with [`mechgen::mechanism!`] and given
//! the analyses the course notes teach.
//!
//! Each mechanism is the macro's generated type (its `position` from a guess, `velocity`,
//! `acceleration`, `points`, `point_velocities`, `point_accelerations` and
//! `point_acceleration_parts` are generated), with a constructor that checks its dimensions,
//! a closed-form `assemble` on a named [`Branch`](mechgen::Branch), and analyses:
//!
//! | | [`FourBar`] | [`SliderCrank`] | [`InvertedSliderCrank`] |
//! |---|---|---|---|
//! | branches | `sin(θ4 − θ3)` | `cos θ3` | `b + c·cos γ` |
//! | classification | Grashof | crank turns fully? | |
//! | transmission angle | at a position, extremes | at a position | |
//! | limits | toggle angles, dead centres | dead centres, stroke, time ratio | |
//! | mechanical advantage | `ω2/ω4` | `ω2/ḋ` | `ω2/ω4` |
//!
//! Multi-loop mechanisms, declared with several loops sharing unknowns:
//! [`WattSixBar`] (two loops solved one after the other in closed form, a branch each, rates
//! solved block by block), [`StephensonSixBar`] (two coupled loops: Newton on two unknowns,
//! the other loop in closed form inside each iteration) and [`JansenLeg`] (Theo Jansen's walking leg with his published lengths, three
//! loops in closed form, the foot's trajectory, velocity and acceleration).
//!
//! Design from the generated sensitivities (`generate: sensitivities`): [`tolerance`] (how
//! far the four-bar's output and coupler point move within its dimensions' tolerances) and,
//! with the `std` feature, [`synthesis`] (the four-bar's dimensions for a function or a path,
//! the Watt six-bar's for a function, and any declaration's through [`mechgen::Design`], by
//! Levenberg–Marquardt).
//!
//! Conventions (KINEMATICS.md in the project's notes): vectors are `r @ θ` = `r·e^{iθ}`,
//! angles in radians counter-clockwise from +x, the crank pivot O2 at the origin.
#![no_std]

#[cfg(feature = "std")]
extern crate std;

mod dimensions;
mod five_bar;
mod four_bar;
mod inverted_slider_crank;
mod jansen;
mod random;
mod six_bar;
mod slider_crank;
mod sums;
#[cfg(feature = "std")]
pub mod synthesis;
pub mod tolerance;
mod triangle;

pub use dimensions::DimensionError;
pub use five_bar::{FiveBar, FiveBarPoints, FiveBarUnknowns, Singularities};
pub use four_bar::{
    DeadCentre, FourBar, FourBarAngles, FourBarCouplerMotion, FourBarCouplerPath, FourBarJoints,
    FourBarPoints, FourBarScenes, FourBarSensitivities, FourBarUnknowns, LimitAngles,
    TransmissionExtremes,
};
pub use inverted_slider_crank::{
    InvertedSliderCrank, InvertedSliderCrankPoints, InvertedSliderCrankScenes,
    InvertedSliderCrankState, InvertedSliderCrankUnknowns,
};
pub use jansen::{
    JansenLeg, JansenLegBranches, JansenLegFootMotion, JansenLegFootPath, JansenLegPoints,
    JansenLegScenes, JansenLegUnknowns,
};
pub use six_bar::{
    StephensonSixBar, StephensonSixBarPoints, StephensonSixBarUnknowns, WattSixBar,
    WattSixBarBranches, WattSixBarOutput, WattSixBarPoints, WattSixBarScenes,
    WattSixBarSensitivities, WattSixBarUnknowns,
};
pub use slider_crank::{
    SliderCrank, SliderCrankPoints, SliderCrankScenes, SliderCrankSlider, SliderCrankState,
    SliderCrankUnknowns,
};
pub use tolerance::{Deviation, FourBarDeviations, FourBarTolerances};
