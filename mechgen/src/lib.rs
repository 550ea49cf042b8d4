#![doc = include_str!("../README.md")]
#![no_std]
// One unsafe call, in `simd`, with its reason beside it; nothing else may use unsafe.
#![deny(unsafe_code)]

#[cfg(feature = "std")]
extern crate std;

mod accuracy;
mod advantage;
mod angle_sum;
mod branch;
pub mod closed;
mod design;
mod error;
pub mod fast;
pub mod grashof;
mod kernel;
mod linear;
#[cfg(feature = "nalgebra")]
pub mod nalgebra_support;
mod newton;
mod rate_limits;
mod real;
pub mod simd;
pub mod sweep;
mod vec2;

pub use accuracy::{Accuracy, Order};
pub use advantage::MechanicalAdvantage;
pub use branch::Branch;
pub use design::Design;
pub use error::{BatchError, Error};
pub use linear::{condition, singular_threshold};
pub use newton::{Motion, NewtonOptions, Solved};
pub use real::Real;
pub use sweep::Kinematics;
pub use vec2::{AccelerationParts, Vec2};

/// Declares a planar mechanism by its vector loops and generates its kinematics.
///
/// See the [crate documentation](crate) for the declaration language and what is generated.
pub use mechgen_macros::mechanism;

/// Items the generated code names. Not public API: they may change in any release.
#[doc(hidden)]
pub mod __private {
    pub use crate::accuracy::{
        KnownAspect, floor_position_accuracy, given_position, rates_accuracy,
        rates_accuracy_at_aspect,
    };
    pub use crate::angle_sum::sin_cos_of_sum;
    pub use crate::kernel::{
        all_finite as finite_all, angle, as_given, at_input, blame, branch_root, inverse,
        inverse_determinant, lanes, length_scale, newton_at_scale, outputs_finite, rate_scale,
        rates_as_given, retimed, scale_within_range, scaled, stated_in_own_units, triangle_root,
        unit_angle, unscaled, untimed,
    };
    pub use crate::linear::{
        Columns, Factored, KnownColumns, orientation, solve_lu, solve_scaled, solve2,
    };
    pub use crate::newton::{
        Linearisation, NewtonConstants, Orientation, Started, Turning, Turnings, all_finite,
        angle_near, certified_start, check_all_finite, check_finite, closes_within_rounding,
        finite, guess_certified, loop_weight, newton, newton_common, newton_common_at_finite_scale,
        root_elsewhere, same_sides, sin_cos, stagnated, within_sin_cos_range, within_whole_turns,
    };
    pub use crate::rate_limits::{RateLimits, aspect};
    pub use core::result::Result::{Err, Ok};
}
