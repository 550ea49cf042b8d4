//! The scalar type generated code is generic over.

use core::fmt::{Debug, Display};

/// A floating-point scalar the generated kinematics run on: `f32` or `f64`.
///
/// All the maths comes from [`num_traits::Float`]; this trait only adds the one conversion
/// generated code needs, from the `f64` constants the macro folded at compile time.
pub trait Real: num_traits::Float + Debug + Display + Default + Send + Sync + 'static {
    /// Converts a compile-time constant to this type, rounding to nearest.
    fn constant(value: f64) -> Self;
}

impl Real for f64 {
    #[inline(always)]
    fn constant(value: f64) -> Self {
        value
    }
}

impl Real for f32 {
    #[inline(always)]
    fn constant(value: f64) -> Self {
        // Rounding to nearest is what a literal of type f32 would do.
        value as f32
    }
}
