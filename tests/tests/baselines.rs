//! The benchmarks' baselines compute what the generated code computes, so timing them side
//! by side compares like with like.

use mechanisms::{FourBar, InvertedSliderCrank, SliderCrank};
use mechgen::Branch;
use mechgen_tests::baselines::{self, State};

fn close(what: &str, got: State, want: State, tolerance: f64) {
    for (g, w) in got.iter().flatten().zip(want.iter().flatten()) {
        let d =
            (g - w + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU) - std::f64::consts::PI;
        let d = if (g - w).abs() < d.abs() { g - w } else { d };
        assert!(
            d.abs() <= tolerance * w.abs().max(1.0),
            "{what}: {got:?} vs {want:?}"
        );
    }
}

#[test]
fn baselines_agree_with_the_generated_code() {
    let l = [180.0, 80.0, 200.0, 150.0];
    let four_bar = FourBar::new(l[0], l[1], l[2], l[3]).unwrap();
    let slider = SliderCrank::new(50.0, 150.0, 20.0).unwrap();
    let p = [150.0, 60.0, 20.0, 0.3];
    let inverted = InvertedSliderCrank::new(p[0], p[1], p[2], p[3]).unwrap();
    for degree in (0..360).step_by(7) {
        let t = f64::from(degree).to_radians();
        let m = four_bar.motion(t, Branch::Open, 10.0, 2.0).unwrap();
        let want = [
            m.position.to_array(),
            m.velocity.to_array(),
            m.acceleration.to_array(),
        ];
        close(
            "Norton",
            baselines::four_bar_norton(&l, t, 10.0, 2.0),
            want,
            1e-12,
        );
        let guess = [want[0][0] + 0.01, want[0][1] - 0.01];
        close(
            "Newton",
            baselines::four_bar_newton(&l, t, guess, 1e-12, 10.0, 2.0),
            want,
            1e-9,
        );
        close(
            "num-dual",
            baselines::four_bar_num_dual(&l, t, guess, 1e-12, 10.0, 2.0),
            want,
            1e-9,
        );
        close(
            "nalgebra",
            baselines::four_bar_nalgebra(&l, t, guess, 1e-12, 10.0, 2.0),
            want,
            1e-2,
        );

        let m = slider.motion(t, Branch::Open, 10.0, 2.0).unwrap();
        let want = [
            m.position.to_array(),
            m.velocity.to_array(),
            m.acceleration.to_array(),
        ];
        close(
            "slider",
            baselines::slider_crank_closed(50.0, 150.0, 20.0, t, 10.0, 2.0),
            want,
            1e-12,
        );

        let m = inverted.motion(t, Branch::Open, 10.0, 2.0).unwrap();
        let want = [
            m.position.to_array(),
            m.velocity.to_array(),
            m.acceleration.to_array(),
        ];
        close(
            "inverted",
            baselines::inverted_slider_crank_closed(p, t, 10.0, 2.0),
            want,
            1e-11,
        );
    }
}
