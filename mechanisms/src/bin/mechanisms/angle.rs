//! Angles as the command line takes them: degrees, reduced by whole turns in degrees before
//! they become radians; and radians within half a turn, as a trace prints them.
//!
//! `degrees.to_radians()` rounds a large angle's product with π/180, so its remainder in a
//! turn is lost long before the angle overflows: 1e20° would land anywhere on the circle.
//! The remainder in degrees, `degrees % 360`, is exact (a floating-point remainder always is),
//! so an angle of any size means the same direction it does on paper.

/// `degrees` in radians, after whole turns are taken off exactly (the sign kept: −370° is
/// −10°); a non-finite angle stays non-finite for the caller's check to name.
pub fn radians(degrees: f64) -> f64 {
    (degrees % 360.0).to_radians()
}

/// `angle` (radians) less the whole turns that take it within half a turn of zero, for a
/// Newton trace: a step through a nearly singular Jacobian can throw an iterate many turns,
/// where a float holds its direction to fewer digits than the trace prints (at 1e18° the
/// spacing of floats is 256°). The loops are the same a turn on, so the iteration is too,
/// but for that rounding.
pub fn within_a_turn(angle: f64) -> f64 {
    use std::f64::consts::{PI, TAU};
    // The remainder is exact, where subtracting a rounded multiple of a turn is not.
    let rest = angle % TAU;
    if rest > PI {
        rest - TAU
    } else if rest < -PI {
        rest + TAU
    } else {
        rest
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn whole_turns_come_off_exactly_in_degrees() {
        // 1e20 = 280 (mod 360): 10^20 is a multiple of 8, and 10 more than a multiple of 45.
        assert_eq!(radians(1e20), 280f64.to_radians());
        assert_eq!(radians(-370.0), (-10f64).to_radians());
        assert_eq!(radians(45.0), 45f64.to_radians());
        // The double nearest 1e308 is 296 more than a multiple of 360 (as Python's integers
        // say: `int(1e308) % 360`).
        assert_eq!(radians(1e308), 296f64.to_radians());
        assert!(radians(f64::INFINITY).is_nan());
    }

    #[test]
    fn an_angle_within_a_turn_is_its_direction_within_half_a_turn_of_zero() {
        use std::f64::consts::{PI, TAU};
        assert_eq!(within_a_turn(1.0), 1.0);
        assert_eq!(within_a_turn(-PI), -PI);
        assert!((within_a_turn(4.0) - (4.0 - TAU)).abs() < 1e-15);
        assert!((within_a_turn(-4.0) - (TAU - 4.0)).abs() < 1e-15);
        assert!((within_a_turn(1.0 + 3.0 * TAU) - 1.0).abs() < 1e-14);
        // Thrown 1e16 turns: within half a turn, whatever direction the float holds.
        assert!(within_a_turn(-2.35e16).abs() <= PI);
        assert!(within_a_turn(f64::NAN).is_nan());
    }
}
