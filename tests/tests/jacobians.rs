//! The generated Jacobians against central finite differences of the generated residual, on
//! random configurations (assembled or not: the Jacobian is defined everywhere), in f64, and
//! the f32 code against the f64 code.

use mechanisms::{
    FourBar, FourBarUnknowns, InvertedSliderCrank, InvertedSliderCrankUnknowns, SliderCrank,
    SliderCrankUnknowns,
};
use proptest::prelude::*;

type Residual<'a> = &'a dyn Fn(f64, [f64; 2]) -> [f64; 2];

/// Checks `jacobian` and `input_jacobian` against central differences of `residual`.
fn check(
    residual: Residual,
    jacobian: [[f64; 2]; 2],
    input_jacobian: [f64; 2],
    input: f64,
    q: [f64; 2],
    scale: f64,
) -> Result<(), TestCaseError> {
    let difference = |f: &dyn Fn(f64) -> [f64; 2], x: f64| {
        let h = 1e-6 * x.abs().max(1.0);
        let (plus, minus) = (f(x + h), f(x - h));
        [
            (plus[0] - minus[0]) / (2.0 * h),
            (plus[1] - minus[1]) / (2.0 * h),
        ]
    };
    let tolerance = 1e-7 * scale;
    for column in 0..2 {
        let along = |x: f64| {
            let mut moved = q;
            moved[column] = x;
            residual(input, moved)
        };
        let estimate = difference(&along, q[column]);
        for row in 0..2 {
            prop_assert!(
                (jacobian[row][column] - estimate[row]).abs() <= tolerance,
                "J[{row}][{column}] = {} but finite differences give {}",
                jacobian[row][column],
                estimate[row]
            );
        }
    }
    let estimate = difference(&|u| residual(u, q), input);
    for row in 0..2 {
        prop_assert!((input_jacobian[row] - estimate[row]).abs() <= tolerance);
    }
    Ok(())
}

fn length() -> impl Strategy<Value = f64> {
    0.1f64..10.0
}

fn angle() -> impl Strategy<Value = f64> {
    -std::f64::consts::PI..std::f64::consts::PI
}

/// `a ≈ b` to f32 precision, relative to `scale`.
fn close_in_f32(a: f32, b: f64, scale: f64) -> bool {
    (f64::from(a) - b).abs() <= 1e-5 * scale
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn four_bar_jacobians(
        l in [length(), length(), length(), length()],
        input in angle(),
        q in [angle(), angle()],
    ) {
        let linkage = FourBar::new(l[0], l[1], l[2], l[3]);
        prop_assume!(linkage.is_ok(), "lengths that never assemble");
        let linkage = linkage.unwrap();
        let unknowns = FourBarUnknowns::from_array(q);
        let residual = |u, q| linkage.residual(u, &FourBarUnknowns::from_array(q));
        check(
            &residual,
            linkage.jacobian(input, &unknowns),
            linkage.input_jacobian(input, &unknowns),
            input,
            q,
            l.iter().sum(),
        )?;

        let single = FourBar::new(l[0] as f32, l[1] as f32, l[2] as f32, l[3] as f32).unwrap();
        let unknowns32 = FourBarUnknowns::from_array(q.map(|x| x as f32));
        let j32 = single.jacobian(input as f32, &unknowns32);
        let j64 = linkage.jacobian(input, &unknowns);
        for (row32, row64) in j32.iter().zip(&j64) {
            for (a, b) in row32.iter().zip(row64) {
                prop_assert!(close_in_f32(*a, *b, l.iter().sum()));
            }
        }
    }

    #[test]
    fn slider_crank_jacobians(
        l in (length(), length(), -10.0f64..10.0).prop_map(|(a, b, c)| [a, b, c]),
        input in angle(),
        theta3 in angle(),
        d in -20.0f64..20.0,
    ) {
        let linkage = SliderCrank::new(l[0], l[1], l[2]);
        prop_assume!(linkage.is_ok(), "offset out of reach");
        let linkage = linkage.unwrap();
        let q = [theta3, d];
        let unknowns = SliderCrankUnknowns::from_array(q);
        let residual = |u, q| linkage.residual(u, &SliderCrankUnknowns::from_array(q));
        check(
            &residual,
            linkage.jacobian(input, &unknowns),
            linkage.input_jacobian(input, &unknowns),
            input,
            q,
            l.iter().map(|x| x.abs()).sum::<f64>() + d.abs(),
        )?;
    }

    #[test]
    fn inverted_slider_crank_jacobians(
        l in (length(), length(), -10.0f64..10.0).prop_map(|(a, b, c)| [a, b, c]),
        gamma in angle(),
        input in angle(),
        theta4 in angle(),
        b in -20.0f64..20.0,
    ) {
        let linkage = InvertedSliderCrank::new(l[0], l[1], l[2], gamma);
        prop_assume!(linkage.is_ok(), "offset out of reach");
        let linkage = linkage.unwrap();
        let q = [theta4, b];
        let unknowns = InvertedSliderCrankUnknowns::from_array(q);
        let residual = |u, q| linkage.residual(u, &InvertedSliderCrankUnknowns::from_array(q));
        check(
            &residual,
            linkage.jacobian(input, &unknowns),
            linkage.input_jacobian(input, &unknowns),
            input,
            q,
            l.iter().map(|x| x.abs()).sum::<f64>() + b.abs(),
        )?;
    }
}
