//! Helpers shared by the integration tests.
#![allow(dead_code)]

use mechanisms::{FourBar, FourBarUnknowns};

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

/// A four-bar with these lengths and Example 1's coupler point.
pub fn four_bar(l1: f64, l2: f64, l3: f64, l4: f64) -> FourBar<f64> {
    FourBar::new(l1, l2, l3, l4)
        .and_then(|linkage| linkage.with_coupler_point(100.0, 0.5))
        .expect("valid lengths")
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

/// The three shipped single-loop mechanisms behind one interface, so sweeps and checks are
/// written once. Unknowns as arrays in declaration order.
pub trait Linkage<T: mechgen::Real> {
    fn solve(&self, input: T, guess: [T; 2]) -> Result<[T; 2], mechgen::Error<T>>;
    fn rates(&self, input: T, q: [T; 2], input_dot: T) -> Result<[T; 2], mechgen::Error<T>>;
    fn accelerations(
        &self,
        input: T,
        q: [T; 2],
        input_dot: T,
        q_dot: [T; 2],
        input_ddot: T,
    ) -> Result<[T; 2], mechgen::Error<T>>;
    /// Every tracked point's (x, y), flattened.
    fn point_positions(&self, input: T, q: [T; 2]) -> Vec<T>;
    fn point_velocities(&self, input: T, q: [T; 2], input_dot: T, q_dot: [T; 2]) -> Vec<T>;
    #[allow(clippy::too_many_arguments)]
    fn point_accelerations(
        &self,
        input: T,
        q: [T; 2],
        input_dot: T,
        q_dot: [T; 2],
        input_ddot: T,
        q_ddot: [T; 2],
    ) -> Vec<T>;
}

macro_rules! impl_linkage {
    ($mechanism:ident, $unknowns:ident, $points:ident) => {
        fn flatten<T: Copy>(p: mechanisms::$points<mechgen::Vec2<T>>) -> Vec<T> {
            impl_linkage!(@points p, $points)
        }
        impl<T: mechgen::Real> Linkage<T> for mechanisms::$mechanism<T> {
            fn solve(&self, input: T, guess: [T; 2]) -> Result<[T; 2], mechgen::Error<T>> {
                let guess = mechanisms::$unknowns::from_array(guess);
                self.position(input, &guess, &mechgen::NewtonOptions::default())
                    .map(|s| s.value.to_array())
            }
            fn rates(&self, input: T, q: [T; 2], input_dot: T) -> Result<[T; 2], mechgen::Error<T>> {
                let q = mechanisms::$unknowns::from_array(q);
                self.velocity(input, &q, input_dot).map(|v| v.to_array())
            }
            fn accelerations(
                &self,
                input: T,
                q: [T; 2],
                input_dot: T,
                q_dot: [T; 2],
                input_ddot: T,
            ) -> Result<[T; 2], mechgen::Error<T>> {
                let q = mechanisms::$unknowns::from_array(q);
                let q_dot = mechanisms::$unknowns::from_array(q_dot);
                self.acceleration(input, &q, input_dot, &q_dot, input_ddot)
                    .map(|a| a.to_array())
            }
            fn point_positions(&self, input: T, q: [T; 2]) -> Vec<T> {
                flatten(self.points(input, &mechanisms::$unknowns::from_array(q)).unwrap())
            }
            fn point_velocities(&self, input: T, q: [T; 2], input_dot: T, q_dot: [T; 2]) -> Vec<T> {
                let (q, q_dot) = (
                    mechanisms::$unknowns::from_array(q),
                    mechanisms::$unknowns::from_array(q_dot),
                );
                flatten(mechanisms::$mechanism::point_velocities(self, input, &q, input_dot, &q_dot).unwrap())
            }
            fn point_accelerations(
                &self,
                input: T,
                q: [T; 2],
                input_dot: T,
                q_dot: [T; 2],
                input_ddot: T,
                q_ddot: [T; 2],
            ) -> Vec<T> {
                let (q, q_dot, q_ddot) = (
                    mechanisms::$unknowns::from_array(q),
                    mechanisms::$unknowns::from_array(q_dot),
                    mechanisms::$unknowns::from_array(q_ddot),
                );
                flatten(
                    mechanisms::$mechanism::point_accelerations(
                        self, input, &q, input_dot, &q_dot, input_ddot, &q_ddot,
                    )
                    .unwrap(),
                )
            }
        }
    };
    (@points $p:ident, FourBarPoints) => {
        [$p.crank_pin, $p.rocker_pin, $p.coupler_point].iter().flat_map(|v| [v.x, v.y]).collect()
    };
    (@points $p:ident, SliderCrankPoints) => {
        [$p.crank_pin, $p.slider_pin, $p.coupler_point].iter().flat_map(|v| [v.x, v.y]).collect()
    };
    (@points $p:ident, InvertedSliderCrankPoints) => {
        [$p.crank_pin, $p.block_pin, $p.slide_origin, $p.coupler_point]
            .iter()
            .flat_map(|v| [v.x, v.y])
            .collect()
    };
}

mod four_bar_impl {
    use super::Linkage;
    impl_linkage!(FourBar, FourBarUnknowns, FourBarPoints);
}
mod slider_crank_impl {
    use super::Linkage;
    impl_linkage!(SliderCrank, SliderCrankUnknowns, SliderCrankPoints);
}
mod inverted_slider_crank_impl {
    use super::Linkage;
    impl_linkage!(
        InvertedSliderCrank,
        InvertedSliderCrankUnknowns,
        InvertedSliderCrankPoints
    );
}

/// The shipped mechanisms with the dimensions the tests and tables use, and a guess on the
/// open branch at input 0.
pub fn slider_crank<T: mechgen::Real>() -> mechanisms::SliderCrank<T> {
    let c = T::constant;
    mechanisms::SliderCrank::new(c(50.0), c(150.0), c(20.0))
        .and_then(|linkage| linkage.with_coupler_point(c(75.0), c(0.2)))
        .expect("valid dimensions")
}

pub fn inverted_slider_crank<T: mechgen::Real>() -> mechanisms::InvertedSliderCrank<T> {
    let c = T::constant;
    mechanisms::InvertedSliderCrank::new(c(150.0), c(60.0), c(20.0), c(0.3))
        .and_then(|linkage| linkage.with_coupler_point(c(30.0), c(1.0)))
        .expect("valid dimensions")
}

/// The Watt six-bar the tests and tables use: Example 1's four-bar, its rocker extended by 100
/// at 0.8 rad, and a dyad of 220 and 160 to the pivot (300, 150).
pub fn watt_six_bar<T: mechgen::Real>() -> mechanisms::WattSixBar<T> {
    let c = T::constant;
    mechanisms::WattSixBar::new(
        [c(180.0), c(80.0), c(200.0), c(150.0)],
        c(100.0),
        c(0.8),
        c(220.0),
        c(160.0),
        (c(300.0), c(150.0)),
    )
    .expect("valid dimensions")
}

/// The seeds' Example 1 four-bar (180, 80, 200, 150 mm) with a coupler point, in the float
/// type `T`.
pub fn example_1<T: mechgen::Real>() -> mechanisms::FourBar<T> {
    let c = T::constant;
    mechanisms::FourBar::new(c(180.0), c(80.0), c(200.0), c(150.0))
        .and_then(|linkage| linkage.with_coupler_point(c(100.0), c(0.5)))
        .expect("valid lengths")
}

/// One sample of a sweep: input and unknowns (values and their derivatives with respect to
/// the input, i.e. rates at unit input rate).
#[derive(Clone, Copy, Debug)]
pub struct Sample<T> {
    pub input: T,
    pub q: [T; 2],
}

/// Solves at every `step_deg` degrees over a full turn starting from `guess` at 0, staying
/// on the branch by walking in 1° steps with a velocity predictor.
pub fn sweep<T: mechgen::Real, L: Linkage<T>>(
    linkage: &L,
    guess: [T; 2],
    step_deg: u32,
) -> Vec<Sample<T>> {
    let one_degree = T::constant(1f64.to_radians());
    let mut q = linkage
        .solve(T::zero(), guess)
        .expect("assembles at input 0");
    let mut samples = Vec::new();
    for degree in 0..360u32 {
        let input = T::constant(f64::from(degree).to_radians());
        if degree > 0 {
            let previous = input - one_degree;
            let slope = linkage
                .rates(previous, q, T::one())
                .expect("not at a toggle");
            let predicted = [q[0] + slope[0] * one_degree, q[1] + slope[1] * one_degree];
            q = linkage
                .solve(input, predicted)
                .expect("assembles over the sweep");
        }
        if degree % step_deg == 0 {
            samples.push(Sample { input, q });
        }
    }
    samples
}
