//! Scene kernels agree with the general functions (`motion`, `points`, `point_velocities`,
//! `point_accelerations`) to rounding, over full turns of every shipped mechanism that has
//! scenes, in f64 and f32, and on random assemblable four-bars.

mod common;

use mechanisms::{InvertedSliderCrank, JansenLeg, SliderCrank, WattSixBar};
use mechgen::{Branch, Error, Real, Vec2};
use proptest::prelude::*;

const RATE: f64 = 10.0;
const ACCELERATION: f64 = 2.0;

/// Asserts `|got − want| ≤ tolerance·scale`, naming what differs.
fn close<T: Real>(what: &str, input: T, got: T, want: T, scale: T, tolerance: f64) {
    let error = (got - want).abs();
    assert!(
        error <= T::constant(tolerance) * scale,
        "{what} at {input}: scene {got}, general {want} (error {error}, allowed {} × {scale})",
        tolerance
    );
}

fn close2<T: Real>(what: &str, input: T, got: Vec2<T>, want: Vec2<T>, scale: T, tolerance: f64) {
    close(what, input, got.x, want.x, scale, tolerance);
    close(what, input, got.y, want.y, scale, tolerance);
}

/// Rounding allowance: a few hundred units of rounding of the float type.
fn tolerance<T: Real>() -> f64 {
    256.0 * T::epsilon().to_f64().unwrap_or(1e-7)
}

fn inputs<T: Real>() -> impl Iterator<Item = T> {
    (0..360).map(|degree| T::constant(f64::from(degree).to_radians()))
}

fn four_bar_scenes_agree<T: Real>() {
    let linkage = common::example_1::<T>();
    let scenes = linkage.scenes().unwrap();
    let (w, a) = (T::constant(RATE), T::constant(ACCELERATION));
    let tol = tolerance::<T>();
    for t in inputs::<T>() {
        let motion = linkage.motion(t, Branch::Open, w, a).unwrap();
        let angles = scenes.angles(t, Branch::Open, w, a).unwrap();
        let (q, v, acc) = (motion.position, motion.velocity, motion.acceleration);
        close("θ3", t, angles.theta3, q.theta3, T::one(), tol);
        close("θ4", t, angles.theta4, q.theta4, T::one(), tol);
        close("ω3", t, angles.theta3_dot, v.theta3, w, tol);
        close("ω4", t, angles.theta4_dot, v.theta4, w, tol);
        close("α3", t, angles.theta3_ddot, acc.theta3, w * w, tol);
        close("α4", t, angles.theta4_ddot, acc.theta4, w * w, tol);

        let points = linkage.points(t, &q).unwrap();
        let velocities = linkage.point_velocities(t, &q, w, &v).unwrap();
        let accelerations = linkage.point_accelerations(t, &q, w, &v, a, &acc).unwrap();
        let size = T::constant(200.0);
        let path = scenes.coupler_path(t, Branch::Open).unwrap();
        close2("P", t, path.coupler_point, points.coupler_point, size, tol);
        let moving = scenes.coupler_motion(t, Branch::Open, w, a).unwrap();
        close2(
            "P",
            t,
            moving.coupler_point,
            points.coupler_point,
            size,
            tol,
        );
        close2(
            "Ṗ",
            t,
            moving.coupler_point_dot,
            velocities.coupler_point,
            size * w,
            tol,
        );
        close2(
            "P̈",
            t,
            moving.coupler_point_ddot,
            accelerations.coupler_point,
            size * w * w,
            tol,
        );
    }
}

#[test]
fn four_bar_scenes_agree_with_the_general_functions() {
    four_bar_scenes_agree::<f64>();
    four_bar_scenes_agree::<f32>();
}

/// A coupler point far off its link (its distance `a` up to the float's range, the loops'
/// lengths 80 to 200): the scenes' scale is the loops', so their closed forms neither
/// underflow nor lose the angles. Found by an adversarial review: scaled by every length,
/// `a = 1e100` shrank the loops to 1e-98, and `angles` said `Singular`, and from `a = 1e80`
/// (f64) or `1e12` (f32) gave wrong angles, rates and joints as `Ok`.
fn far_coupler_point_scenes_agree<T: Real>(distances: &[f64]) {
    let c = T::constant;
    let (w, acc) = (c(RATE), c(ACCELERATION));
    let tol = tolerance::<T>();
    for &distance in distances {
        let linkage = mechanisms::FourBar::new(c(180.0), c(80.0), c(200.0), c(150.0))
            .and_then(|linkage| linkage.with_coupler_point(c(distance), c(0.3)))
            .unwrap();
        let scenes = linkage.scenes().unwrap();
        for t in inputs::<T>().step_by(7) {
            let motion = linkage.motion(t, Branch::Open, w, acc).unwrap();
            let (q, v) = (motion.position, motion.velocity);
            let angles = scenes.angles(t, Branch::Open, w, acc).unwrap();
            close("θ3", t, angles.theta3, q.theta3, T::one(), tol);
            close("θ4", t, angles.theta4, q.theta4, T::one(), tol);
            close("ω4", t, angles.theta4_dot, v.theta4, w, tol);
            close(
                "α4",
                t,
                angles.theta4_ddot,
                motion.acceleration.theta4,
                w * w,
                tol,
            );
            let points = linkage.points(t, &q).unwrap();
            let joints = scenes.joints(t, Branch::Open).unwrap();
            close2("B", t, joints.rocker_pin, points.rocker_pin, c(200.0), tol);
            let path = scenes.coupler_path(t, Branch::Open).unwrap();
            close2(
                "P",
                t,
                path.coupler_point,
                points.coupler_point,
                c(distance),
                tol,
            );
        }
    }
}

#[test]
fn a_coupler_point_far_off_its_link_leaves_the_loops_to_their_own_scale() {
    far_coupler_point_scenes_agree::<f64>(&[1e13, 1e80, 1e100, 1e160, 1e300]);
    far_coupler_point_scenes_agree::<f32>(&[1e12, 1e13, 1e20, 1e36]);
}

fn slider_crank_scenes_agree<T: Real>() {
    let linkage: SliderCrank<T> = common::slider_crank();
    let scenes = linkage.scenes().unwrap();
    let (w, a) = (T::constant(RATE), T::constant(ACCELERATION));
    let tol = tolerance::<T>();
    let size = T::constant(150.0);
    for t in inputs::<T>() {
        let motion = linkage.motion(t, Branch::Open, w, a).unwrap();
        let (q, v, acc) = (motion.position, motion.velocity, motion.acceleration);
        let state = scenes.state(t, Branch::Open, w, a).unwrap();
        close("θ3", t, state.theta3, q.theta3, T::one(), tol);
        close("d", t, state.d, q.d, size, tol);
        close("ω3", t, state.theta3_dot, v.theta3, w, tol);
        close("ḋ", t, state.d_dot, v.d, size * w, tol);
        close("α3", t, state.theta3_ddot, acc.theta3, w * w, tol);
        close("d̈", t, state.d_ddot, acc.d, size * w * w, tol);
        let slider = scenes.slider(t, Branch::Open, w, a).unwrap();
        assert_eq!(
            [slider.d, slider.d_dot, slider.d_ddot],
            [state.d, state.d_dot, state.d_ddot],
            "the slider scene is the state scene's slider, to the bit"
        );
    }
}

#[test]
fn slider_crank_scenes_agree_with_the_general_functions() {
    slider_crank_scenes_agree::<f64>();
    slider_crank_scenes_agree::<f32>();
}

fn inverted_slider_crank_scenes_agree<T: Real>() {
    let linkage: InvertedSliderCrank<T> = common::inverted_slider_crank();
    let scenes = linkage.scenes().unwrap();
    let (w, a) = (T::constant(RATE), T::constant(ACCELERATION));
    let tol = tolerance::<T>();
    let size = T::constant(200.0);
    for t in inputs::<T>() {
        let motion = linkage.motion(t, Branch::Open, w, a).unwrap();
        let (q, v, acc) = (motion.position, motion.velocity, motion.acceleration);
        let state = scenes.state(t, Branch::Open, w, a).unwrap();
        close("θ4", t, state.theta4, q.theta4, T::one(), tol);
        close("b", t, state.b, q.b, size, tol);
        close("ω4", t, state.theta4_dot, v.theta4, w, tol);
        close("ḃ", t, state.b_dot, v.b, size * w, tol);
        close("α4", t, state.theta4_ddot, acc.theta4, w * w, tol);
        close("b̈", t, state.b_ddot, acc.b, size * w * w, tol);
    }
}

#[test]
fn inverted_slider_crank_scenes_agree_with_the_general_functions() {
    inverted_slider_crank_scenes_agree::<f64>();
    inverted_slider_crank_scenes_agree::<f32>();
}

fn watt<T: Real>() -> WattSixBar<T> {
    common::watt_six_bar()
}

fn watt_scene_agrees<T: Real>() {
    let linkage = watt::<T>();
    let scenes = linkage.scenes().unwrap();
    let (w, a) = (T::constant(RATE), T::constant(ACCELERATION));
    let tol = tolerance::<T>();
    let branches = [Branch::Open, Branch::Open];
    for t in inputs::<T>() {
        let motion = linkage.motion(t, branches, w, a).unwrap();
        let output = scenes.output(t, branches, w, a).unwrap();
        close(
            "θ6",
            t,
            output.theta6,
            motion.position.theta6,
            T::one(),
            tol,
        );
        close("ω6", t, output.theta6_dot, motion.velocity.theta6, w, tol);
        let alpha = motion.acceleration.theta6;
        close("α6", t, output.theta6_ddot, alpha, w * w, tol);
    }
}

#[test]
fn watt_six_bar_scene_agrees_with_motion() {
    watt_scene_agrees::<f64>();
    watt_scene_agrees::<f32>();
}

fn jansen_scenes_agree<T: Real>() {
    let linkage = JansenLeg::<T>::holy();
    let scenes = linkage.scenes().unwrap();
    let (w, a) = (T::constant(RATE), T::constant(ACCELERATION));
    let tol = tolerance::<T>();
    let size = T::constant(100.0);
    let branches = JansenLeg::<T>::DRAWN;
    for t in inputs::<T>() {
        // In f32 the leg's Jacobian is conditioned badly enough (κ up to about 80) over part
        // of the turn that its accelerations are estimated less accurate than required.
        let motion = match linkage.motion(t, branches, w, a) {
            Ok(motion) => motion,
            Err(Error::Inaccurate { .. }) if T::epsilon() > T::constant(1e-10) => continue,
            Err(error) => panic!("{t:?}: {error:?}"),
        };
        let (q, v, acc) = (motion.position, motion.velocity, motion.acceleration);
        // Errors in rates grow with the condition of the Jacobian, once per derivative.
        let kappa = linkage.condition(t, &q);
        let foot = linkage.points(t, &q).unwrap().foot;
        let foot_velocity = linkage.point_velocities(t, &q, w, &v).unwrap().foot;
        let foot_acceleration = linkage
            .point_accelerations(t, &q, w, &v, a, &acc)
            .unwrap()
            .foot;
        let path = scenes.foot_path(t, branches).unwrap();
        close2("foot", t, path.foot, foot, size, tol);
        let moving = scenes.foot_motion(t, branches, w, a).unwrap();
        close2("foot", t, moving.foot, foot, size, tol);
        close2(
            "foot velocity",
            t,
            moving.foot_dot,
            foot_velocity,
            size * w * kappa,
            tol,
        );
        let scale = size * w * w * kappa * kappa;
        close2(
            "foot acceleration",
            t,
            moving.foot_ddot,
            foot_acceleration,
            scale,
            tol,
        );
    }
}

#[test]
fn jansen_leg_scenes_agree_with_the_general_functions() {
    jansen_scenes_agree::<f64>();
    jansen_scenes_agree::<f32>();
}

#[test]
fn scenes_say_why_as_the_general_functions_do() {
    let linkage = common::example_1::<f64>();
    let scenes = linkage.scenes().unwrap();
    // Example 1 is a crank-rocker: a crossed coupler point exists everywhere, but the
    // inputs themselves must be finite.
    assert!(matches!(
        scenes.coupler_path(f64::NAN, Branch::Open),
        Err(mechgen::Error::NonFinite { .. })
    ));
    assert!(matches!(
        scenes.angles(1.0, Branch::Open, f64::INFINITY, 0.0),
        Err(mechgen::Error::NonFinite { .. })
    ));
    // A non-Grashof four-bar cannot reach θ2 = π: the scene says so, as `assemble` does.
    let short = common::four_bar(100.0, 120.0, 90.0, 80.0).scenes().unwrap();
    assert_eq!(
        short.coupler_path(std::f64::consts::PI, Branch::Open),
        Err(mechgen::Error::CannotAssemble {
            input: std::f64::consts::PI
        })
    );
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    /// On any four-bar that assembles at the drawn input, the scene's angles, rates and
    /// coupler point agree with `motion` and the point functions, relative to the
    /// mechanism's size and to the condition of its Jacobian.
    #[test]
    fn random_four_bar_scenes_agree(
        l1 in 0.1f64..10.0,
        l2 in 0.1f64..10.0,
        l3 in 0.1f64..10.0,
        l4 in 0.1f64..10.0,
        a in 0.0f64..10.0,
        delta in -3.0f64..3.0,
        theta2 in -7.0f64..7.0,
        crossed in any::<bool>(),
    ) {
        let linkage = mechanisms::FourBar::new(l1, l2, l3, l4)
            .and_then(|linkage| linkage.with_coupler_point(a, delta));
        // Lengths that never assemble are refused by the constructor.
        prop_assume!(linkage.is_ok());
        let linkage = linkage.unwrap();
        let branch = if crossed { Branch::Crossed } else { Branch::Open };
        let Ok(motion) = linkage.motion(theta2, branch, RATE, ACCELERATION) else {
            // Outside the range of motion or at a toggle: the scene must fail too.
            prop_assert!(linkage.scenes().unwrap().angles(theta2, branch, RATE, ACCELERATION).is_err());
            return Ok(());
        };
        let q = motion.position;
        let kappa = linkage.condition(theta2, &q);
        prop_assume!(kappa < 1e4);
        let scenes = linkage.scenes().unwrap();
        let angles = scenes.angles(theta2, branch, RATE, ACCELERATION).unwrap();
        let size = l1 + l2 + l3 + l4 + a;
        let shortest = l2.min(l3).min(l4).min(l1);
        // Angles are known to ε·κ·size/shortest (an angle's error is a displacement over
        // its link); rates and accelerations to a further κ each.
        let angle_tol = 64.0 * f64::EPSILON * kappa * size / shortest;
        let diff = |x: f64, y: f64| {
            let d = (x - y).rem_euclid(std::f64::consts::TAU);
            d.min(std::f64::consts::TAU - d)
        };
        prop_assert!(diff(angles.theta3, q.theta3) <= angle_tol);
        prop_assert!(diff(angles.theta4, q.theta4) <= angle_tol);
        let w_scale = RATE * size / shortest * kappa;
        prop_assert!((angles.theta3_dot - motion.velocity.theta3).abs() <= angle_tol * w_scale);
        prop_assert!((angles.theta4_dot - motion.velocity.theta4).abs() <= angle_tol * w_scale);
        let path = scenes.coupler_path(theta2, branch).unwrap();
        let point = linkage.points(theta2, &q).unwrap().coupler_point;
        prop_assert!((path.coupler_point - point).norm() <= angle_tol * size);
    }
}

/// The batch form of a scene against its kernel over a turn (and beyond it, for a linkage
/// that cannot turn fully): the same values to rounding, the same errors.
fn batch_agrees<T: Real>() {
    let linkage = common::example_1::<T>();
    let scenes = linkage.scenes().unwrap();
    let (w, a) = (T::constant(RATE), T::constant(ACCELERATION));
    let tol = tolerance::<T>();
    let inputs: Vec<T> = inputs::<T>().collect();
    let mut paths = vec![Default::default(); inputs.len()];
    scenes
        .coupler_path_batch(&inputs, Branch::Open, &mut paths)
        .unwrap();
    let mut motions = vec![Default::default(); inputs.len()];
    scenes
        .coupler_motion_batch(&inputs, Branch::Open, w, a, &mut motions)
        .unwrap();
    let mut angles = vec![Default::default(); inputs.len()];
    scenes
        .angles_batch(&inputs, Branch::Open, w, a, &mut angles)
        .unwrap();
    let size = T::constant(200.0);
    for (i, &t) in inputs.iter().enumerate() {
        let one: mechanisms::FourBarCouplerPath<T> = scenes.coupler_path(t, Branch::Open).unwrap();
        close2(
            "batch P",
            t,
            paths[i].coupler_point,
            one.coupler_point,
            size,
            tol,
        );
        let one = scenes.coupler_motion(t, Branch::Open, w, a).unwrap();
        close2(
            "batch Ṗ",
            t,
            motions[i].coupler_point_dot,
            one.coupler_point_dot,
            size * w,
            tol,
        );
        let scale = size * w * w;
        close2(
            "batch P̈",
            t,
            motions[i].coupler_point_ddot,
            one.coupler_point_ddot,
            scale,
            tol,
        );
        let one = scenes.angles(t, Branch::Open, w, a).unwrap();
        close("batch θ4", t, angles[i].theta4, one.theta4, T::one(), tol);
        close(
            "batch α3",
            t,
            angles[i].theta3_ddot,
            one.theta3_ddot,
            w * w,
            tol,
        );
    }
}

#[test]
fn batches_agree_with_their_kernels() {
    batch_agrees::<f64>();
    batch_agrees::<f32>();
}

#[test]
fn a_batch_stops_where_its_kernel_fails_and_says_why() {
    // Not a Grashof crank: it cannot reach θ2 = π, and its range ends near ±1.76 rad.
    let scenes = common::four_bar(100.0, 120.0, 90.0, 80.0).scenes().unwrap();
    let inputs = [0.0, 0.5, 1.0, std::f64::consts::PI, 0.2];
    let mut out = [Default::default(); 5];
    let stopped = scenes.coupler_path_batch(&inputs, Branch::Open, &mut out);
    assert_eq!(
        stopped,
        Err(mechgen::BatchError {
            index: 3,
            error: mechgen::Error::CannotAssemble {
                input: std::f64::consts::PI
            }
        })
    );
    for (i, &t) in inputs[..3].iter().enumerate() {
        assert_eq!(
            out[i],
            scenes.coupler_path(t, Branch::Open).unwrap(),
            "input {i}"
        );
    }
    // A NaN input is blamed as the kernel blames it.
    let mut out = [Default::default(); 2];
    let stopped = scenes.coupler_path_batch(&[0.1, f64::NAN], Branch::Open, &mut out);
    assert!(matches!(
        stopped,
        Err(mechgen::BatchError {
            index: 1,
            error: mechgen::Error::NonFinite { .. }
        })
    ));
}

mod declarations {
    //! Scenes on declarations the shipped mechanisms do not exercise: a length as the input,
    //! Chace's linear case (two unknown lengths), constant offsets and scaled magnitudes in
    //! the loop, an angle with a constant offset read by a point.

    use mechgen::{Branch, mechanism};

    mechanism! {
        /// A slider-crank driven by its slider (a length input).
        pub struct SliderDriven {
            params: l2, l3;
            input: d: length;
            unknowns: theta2: angle, theta3: angle;
            loop: -d @ 0 + l2 @ theta2 + l3 @ theta3;
            point pin = l2 @ theta2;
            scene all: theta2, theta3, theta2_dot, theta3_ddot, pin, pin_dot, pin_ddot;
        }
    }

    mechanism! {
        /// A cross-slide: two unknown lengths in one loop.
        pub struct CrossSlide {
            params: r;
            input: theta: angle;
            unknowns: x: length, y: length;
            loop: r @ theta - x @ 0 - y @ pi / 2;
            scene all: x, y, x_dot, y_dot, x_ddot, y_ddot;
        }
    }

    mechanism! {
        /// A four-bar written with offsets: the rocker's angle from +y, a scaled coupler,
        /// a crank offset, and a point on the coupler at a fixed angle.
        pub struct Rewritten {
            params: l1, l2, half_l3, l4, offset: angle, a, delta: angle;
            input: phi: angle;
            unknowns: theta3: angle, psi: angle;
            loop: l2 @ (phi + offset) + 2 * half_l3 @ theta3 - l4 @ (psi + pi / 2) - l1 @ 0;
            point p = l2 @ (phi + offset) + a @ (theta3 + delta);
            scene all: psi, psi_dot, psi_ddot, p, p_dot, p_ddot;
        }
    }

    fn close(what: &str, at: f64, got: f64, want: f64, scale: f64) {
        assert!(
            (got - want).abs() <= 1e-12 * scale,
            "{what} at {at}: scene {got}, general {want}"
        );
    }

    #[test]
    fn a_length_input_gets_its_scene() {
        let linkage = SliderDriven {
            l2: 50.0,
            l3: 150.0,
        };
        let scenes = linkage.scenes().unwrap();
        for k in 0..50 {
            let d = 110.0 + 85.0 * f64::from(k) / 50.0;
            let m = linkage.motion(d, Branch::Open, 3.0, -1.0).unwrap();
            let s = scenes.all(d, Branch::Open, 3.0, -1.0).unwrap();
            close("θ2", d, s.theta2, m.position.theta2, 1.0);
            close("θ3", d, s.theta3, m.position.theta3, 1.0);
            close("ω2", d, s.theta2_dot, m.velocity.theta2, 1.0);
            close("α3", d, s.theta3_ddot, m.acceleration.theta3, 1.0);
            let q = m.position;
            let pin = linkage.points(d, &q).unwrap().pin;
            let pin_dot = linkage
                .point_velocities(d, &q, 3.0, &m.velocity)
                .unwrap()
                .pin;
            let pin_ddot = linkage
                .point_accelerations(d, &q, 3.0, &m.velocity, -1.0, &m.acceleration)
                .unwrap()
                .pin;
            for (got, want) in [(s.pin, pin), (s.pin_dot, pin_dot), (s.pin_ddot, pin_ddot)] {
                close("pin", d, got.x, want.x, 200.0);
                close("pin", d, got.y, want.y, 200.0);
            }
        }
        // Pushed beyond the reach of crank and rod: the scene says so, as `motion` does.
        assert_eq!(
            scenes.all(250.0, Branch::Open, 1.0, 0.0).map(|_| ()),
            linkage.motion(250.0, Branch::Open, 1.0, 0.0).map(|_| ())
        );
    }

    #[test]
    fn two_unknown_lengths_get_their_scene() {
        let table = CrossSlide { r: 2.0 };
        let scenes = table.scenes().unwrap();
        for k in 0..36 {
            let t = f64::from(10 * k).to_radians();
            let s = scenes.all(t, 0.7, 0.2).unwrap();
            let m = table.motion(t, 0.7, 0.2).unwrap();
            close("x", t, s.x, m.position.x, 2.0);
            close("y", t, s.y, m.position.y, 2.0);
            close("ẋ", t, s.x_dot, m.velocity.x, 2.0);
            close("ẏ", t, s.y_dot, m.velocity.y, 2.0);
            close("ẍ", t, s.x_ddot, m.acceleration.x, 2.0);
            close("ÿ", t, s.y_ddot, m.acceleration.y, 2.0);
        }
    }

    #[test]
    fn offsets_and_scaled_magnitudes_get_their_scene() {
        let linkage = Rewritten {
            l1: 180.0,
            l2: 80.0,
            half_l3: 100.0,
            l4: 150.0,
            offset: 0.3,
            a: 60.0,
            delta: -0.4,
        };
        let scenes = linkage.scenes().unwrap();
        for branch in [Branch::Open, Branch::Crossed] {
            for k in 0..36 {
                let phi = f64::from(10 * k).to_radians();
                let m = linkage.motion(phi, branch, 10.0, 2.0).unwrap();
                let s = scenes.all(phi, branch, 10.0, 2.0).unwrap();
                close("ψ", phi, s.psi, m.position.psi, 1.0);
                close("ψ̇", phi, s.psi_dot, m.velocity.psi, 10.0);
                close("ψ̈", phi, s.psi_ddot, m.acceleration.psi, 100.0);
                let q = m.position;
                let p = linkage.points(phi, &q).unwrap().p;
                let v = linkage
                    .point_velocities(phi, &q, 10.0, &m.velocity)
                    .unwrap()
                    .p;
                let a = linkage
                    .point_accelerations(phi, &q, 10.0, &m.velocity, 2.0, &m.acceleration)
                    .unwrap()
                    .p;
                for (got, want, scale) in [(s.p, p, 300.0), (s.p_dot, v, 3e3), (s.p_ddot, a, 3e4)] {
                    close("p", phi, got.x, want.x, scale);
                    close("p", phi, got.y, want.y, scale);
                }
            }
        }
    }
}

/// An inverted slider-crank whose slide passes through its pivot (offset 0, crank as long as
/// the ground): as the crank nears 0 the rocker's column (the distance from the pivot to the
/// crank pin, 200·sin(θ2/2)) shrinks toward nothing, and the rocker's direction with it is lost
/// in the rounding of the whole linkage. The scene refuses the rates once their estimate at
/// that aspect exceeds what is required (the acceleration's, ε·257·(ρ/16)², below θ2 ≈ 3e-6),
/// as `motion` does, rather than return rates with no correct digit; before that the two agree,
/// and with the truth (θ4 = π/2 + θ2/2 exactly, so ω4 = ω2/2 and α4 = α2/2).
#[test]
fn a_slide_through_its_pivot_has_no_rates_as_it_passes() {
    let linkage = InvertedSliderCrank::new(100.0f64, 100.0, 0.0, 0.0).unwrap();
    let scenes = linkage.scenes().unwrap();
    let mut out = [scenes.state(1.0, Branch::Open, 1.0, 0.5).unwrap(); 1];
    for t in [1e-12, 1e-9, 1e-6] {
        let scene = scenes.state(t, Branch::Open, 1.0, 0.5);
        let general = linkage.motion(t, Branch::Open, 1.0, 0.5);
        assert!(
            matches!(scene, Err(mechgen::Error::Inaccurate { .. })),
            "θ2 = {t}: {scene:?}"
        );
        assert!(
            matches!(general, Err(mechgen::Error::Inaccurate { .. })),
            "θ2 = {t}: {general:?}"
        );
        assert!(
            scenes
                .state_batch(&[t], Branch::Open, 1.0, 0.5, &mut out)
                .is_err()
        );
    }
    for t in [1e-3f64, 0.5, 1.0, 2.0] {
        let scene = scenes.state(t, Branch::Open, 1.0, 0.5).unwrap();
        let general = linkage.motion(t, Branch::Open, 1.0, 0.5).unwrap();
        assert!((scene.theta4_dot - 0.5).abs() < 1e-9, "θ2 = {t}: {scene:?}");
        assert!(
            (scene.theta4_ddot - 0.25).abs() < 1e-6,
            "θ2 = {t}: {scene:?}"
        );
        assert!((scene.theta4_ddot - general.acceleration.theta4).abs() < 1e-6);
        scenes
            .state_batch(&[t], Branch::Open, 1.0, 0.5, &mut out)
            .unwrap();
        assert_eq!(out[0], scene);
    }
}
