//! A `#![no_std]` crate that declares a mechanism and uses its generated code, as firmware
//! would. CI builds it for a bare-metal target (`thumbv7em-none-eabihf`), which has no `std`
//! to fall back on, so anything in the generated code or the runtime that needs `std` or an
//! allocator fails the build.
#![no_std]

use mechgen::{Error, NewtonOptions, mechanism};

mechanism! {
    /// A slider-crank with offset, as a controller would carry it.
    pub struct SliderCrank {
        params: pub l2, pub l3, pub c;
        input: theta2: angle;
        unknowns: theta3: angle, d: length;
        loop: l2 @ theta2 + l3 @ theta3 - c @ pi / 2 - d @ 0;
        point pin = d @ 0 + c @ pi / 2;
        generate: position, velocity, acceleration;
    }
}

/// Slider position, velocity and acceleration at a crank angle, in f32, warm-started from
/// `previous`.
pub fn slider_state(
    linkage: &SliderCrank<f32>,
    theta2: f32,
    omega2: f32,
    previous: &SliderCrankUnknowns<f32>,
) -> Result<[f32; 3], Error<f32>> {
    let q = linkage
        .position(theta2, previous, &NewtonOptions::default())?
        .value;
    let v = linkage.velocity(theta2, &q, omega2)?;
    let a = linkage.acceleration(theta2, &q, omega2, &v, 0.0)?;
    let pin = linkage
        .point_accelerations(theta2, &q, omega2, &v, 0.0, &a)?
        .pin;
    Ok([q.d, v.d, pin.x])
}
