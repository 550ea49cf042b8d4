//! Angles as the command line takes them: degrees, reduced by whole turns in degrees before
//! they become radians.
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
}
