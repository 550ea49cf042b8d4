//! Helpers shared by the integration tests.
#![allow(dead_code)]

use mechanisms::{FourBar, FourBarUnknowns};

pub const EXAMPLE_1: FourBar<f64> = FourBar {
    l1: 180.0,
    l2: 80.0,
    l3: 200.0,
    l4: 150.0,
    a: 100.0,
    delta: 0.5,
};

pub fn deg(radians: f64) -> f64 {
    radians.to_degrees()
}

pub fn rad(degrees: f64) -> f64 {
    degrees.to_radians()
}

/// An angle in degrees, normalised to [0, 360) for comparison with the seeds' tables.
pub fn normalised_deg(radians: f64) -> f64 {
    deg(radians).rem_euclid(360.0)
}

/// `value` rounded to `decimals` places, for comparing with values printed to that many.
pub fn rounded(value: f64, decimals: i32) -> f64 {
    let scale = 10f64.powi(decimals);
    (value * scale).round() / scale
}

pub fn four_bar(l1: f64, l2: f64, l3: f64, l4: f64) -> FourBar<f64> {
    FourBar {
        l1,
        l2,
        l3,
        l4,
        ..EXAMPLE_1
    }
}

pub fn guess_deg(theta3: f64, theta4: f64) -> FourBarUnknowns<f64> {
    FourBarUnknowns {
        theta3: rad(theta3),
        theta4: rad(theta4),
    }
}

/// `|a - b| <= tolerance·max(1, |b|)`, with a message naming what was compared.
#[track_caller]
pub fn assert_close(what: &str, a: f64, b: f64, tolerance: f64) {
    assert!(
        (a - b).abs() <= tolerance * b.abs().max(1.0),
        "{what}: {a} vs {b} (tolerance {tolerance})"
    );
}
