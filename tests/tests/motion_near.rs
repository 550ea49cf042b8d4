//! `motion_near` (Newton, then the rates from its last evaluation) gives what `position`
//! followed by `motion_at` gives, for one loop and for coupled loops, in f64 and f32.

mod common;

use mechgen::{Branch, NewtonOptions, Real};
use mechgen_tests::examples::stephenson_six_bar;

fn agree<T: Real>(what: &str, input: T, got: T, want: T, scale: T) {
    let allowed = T::constant(64.0) * T::epsilon() * scale;
    assert!(
        (got - want).abs() <= allowed,
        "{what} at {input}: motion_near {got}, position then motion_at {want}"
    );
}

fn four_bar_agrees<T: Real>() {
    let linkage = common::example_1::<T>();
    let options = NewtonOptions::default();
    let (w, a) = (T::constant(10.0), T::constant(2.0));
    let step = T::constant(1f64.to_radians());
    let mut guess = linkage.assemble(T::zero(), Branch::Open).unwrap();
    for degree in 1..360 {
        let t = T::constant(f64::from(degree).to_radians());
        let near = linkage.motion_near(t, &guess, &options, w, a).unwrap();
        let position = linkage.position(t, &guess, &options).unwrap();
        assert_eq!(near.value.position, position.value, "the same Newton solve");
        assert_eq!(near.iterations, position.iterations);
        let at = linkage.motion_at(t, &position.value, w, a).unwrap();
        agree("ω3", t, near.value.velocity.theta3, at.velocity.theta3, w);
        agree("ω4", t, near.value.velocity.theta4, at.velocity.theta4, w);
        agree(
            "α3",
            t,
            near.value.acceleration.theta3,
            at.acceleration.theta3,
            w * w,
        );
        agree(
            "α4",
            t,
            near.value.acceleration.theta4,
            at.acceleration.theta4,
            w * w,
        );
        // The next guess from the velocity predictor.
        let q = near.value.position;
        let v = near.value.velocity;
        guess = mechanisms::FourBarUnknowns {
            theta3: q.theta3 + v.theta3 / w * step,
            theta4: q.theta4 + v.theta4 / w * step,
        };
    }
}

#[test]
fn four_bar_motion_near_matches_position_and_motion_at() {
    four_bar_agrees::<f64>();
    four_bar_agrees::<f32>();
}

#[test]
fn coupled_loops_motion_near_matches_position_and_motion_at() {
    let (linkage, mut guess) = stephenson_six_bar();
    let options = NewtonOptions::default();
    let (w, a) = (10.0, 2.0);
    for degree in 0..360 {
        let t = f64::from(degree).to_radians();
        let near = linkage.motion_near(t, &guess, &options, w, a).unwrap();
        let position = linkage.position(t, &guess, &options).unwrap();
        assert_eq!(near.value.position, position.value);
        let at = linkage.motion_at(t, &position.value, w, a).unwrap();
        let kappa = position.condition;
        let rates = near
            .value
            .velocity
            .to_array()
            .into_iter()
            .zip(at.velocity.to_array());
        for (got, want) in rates {
            agree("rate", t, got, want, w * kappa);
        }
        let accelerations = near
            .value
            .acceleration
            .to_array()
            .into_iter()
            .zip(at.acceleration.to_array());
        for (got, want) in accelerations {
            agree("acceleration", t, got, want, w * w * kappa * kappa);
        }
        guess = near.value.position;
    }
}
