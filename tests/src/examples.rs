//! Example mechanisms that more than one test, table or benchmark builds.

use mechanisms::{StephensonSixBar, StephensonSixBarUnknowns};

/// The Stephenson six-bar of the crate's example, with a guess near its drawn branch at
/// θ2 = 0: its loops are coupled, so every caller starts Newton from here.
pub fn stephenson_six_bar() -> (StephensonSixBar<f64>, StephensonSixBarUnknowns<f64>) {
    let linkage = StephensonSixBar::new(
        100.0,
        20.0,
        117.0,
        [60.0, 63.0],
        -0.97,
        52.0,
        85.0,
        (189.0, -26.0),
    )
    .expect("the example's dimensions are valid");
    let guess = StephensonSixBarUnknowns {
        theta3: -0.25,
        theta4: 0.63,
        theta5: 1.43,
        theta6: 1.46,
    };
    (linkage, guess)
}
