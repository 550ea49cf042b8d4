//! `mechgen::simd::widest` runs a batch loop compiled a second time for AVX2 and FMA where the
//! processor has them: the two copies must give the same bits. Each batch loop below runs
//! both ways over the same inputs (a dense turn, angles out to `sin_cos`'s limit, and inputs
//! that fail: beyond the limit, infinite, NaN, unreachable), and every output is compared by
//! its shortest round-trip form, which tells apart every two values but NaNs (whose payload
//! no caller can rely on). On a processor without AVX2 both runs take the same path and the
//! test shows nothing: it says so.

use std::fmt::Debug;

use mechanisms::{FourBar, JansenLeg, SliderCrank};
use mechgen::simd::widest;
use mechgen::{Branch, Real};
use mechgen_tests::batch_baseline::{Joints, four_bar_joints, four_bar_joints_portable};

/// A full turn at 1/4096 turn steps, then angles spread over `±sin_cos_limit` (by a fixed
/// linear congruential sequence, so that runs are repeatable), then inputs that fail.
fn inputs<T: Real>() -> Vec<T> {
    let limit = mechgen::fast::sin_cos_limit::<T>();
    let turn = (0..4096).map(|k| T::constant(f64::from(k) * core::f64::consts::TAU / 4096.0));
    let mut state = 0x2545_f491_4f6c_dd1d_u64;
    let spread = (0..4096).map(move |_| {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        let unit = (state >> 11) as f64 / (1u64 << 53) as f64;
        let magnitude = T::constant(10f64.powf(-6.0 + 12.0 * unit)).min(limit);
        if state & 1 == 0 {
            magnitude
        } else {
            -magnitude
        }
    });
    let failing = [
        limit * T::constant(2.0),
        T::infinity(),
        T::neg_infinity(),
        T::nan(),
    ];
    turn.chain(spread).chain(failing).collect()
}

/// Whether the two runs agree to the bit (NaN payloads aside), naming the first difference.
fn same<O: Debug>(what: &str, widest: &[O], portable: &[O]) {
    assert_eq!(widest.len(), portable.len());
    for (index, (a, b)) in widest.iter().zip(portable).enumerate() {
        let (a, b) = (format!("{a:?}"), format!("{b:?}"));
        assert_eq!(a, b, "{what}: input {index} differs between the paths");
    }
}

#[test]
fn says_which_path_it_compares() {
    // Not an assertion: which paths the tests below compared, in the test's output.
    println!("AVX2 and FMA in use: {}", mechgen::simd::avx2_fma());
}

#[test]
fn fast_maths_give_the_same_bits_on_every_path() {
    fn check<T: Real + Debug>() {
        let angles = inputs::<T>();
        let run = |out: &mut Vec<(T, T, T)>| {
            for (slot, &angle) in out.iter_mut().zip(&angles) {
                let (s, c) = mechgen::fast::sin_cos(angle);
                *slot = (s, c, mechgen::fast::unit_angle(s, c));
            }
        };
        let mut wide = vec![(T::zero(), T::zero(), T::zero()); angles.len()];
        let mut portable = wide.clone();
        widest(
            #[inline(always)]
            || run(&mut wide),
        );
        run(&mut portable);
        same("sin_cos and unit_angle", &wide, &portable);
    }
    check::<f64>();
    check::<f32>();
}

#[test]
fn hand_batch_kernel_gives_the_same_bits_on_every_path() {
    fn check<T: Real + Debug>() {
        let c = T::constant;
        // A crank-rocker, and a double rocker whose crank cannot turn fully.
        for lengths in [[180.0, 80.0, 200.0, 150.0], [100.0, 80.0, 30.0, 60.0]] {
            let lengths = lengths.map(c);
            let angles = inputs::<T>();
            let mut wide = vec![Joints::default(); angles.len()];
            let mut portable = wide.clone();
            let a = four_bar_joints(lengths, &angles, &mut wide);
            let b = four_bar_joints_portable(lengths, &angles, &mut portable);
            assert_eq!(a, b);
            same("hand batch", &wide, &portable);
        }
    }
    check::<f64>();
    check::<f32>();
}

/// Each scene's loop of the four-bar through `widest` and as built, and the batch itself
/// (which runs through `widest`) where every lane succeeds.
fn four_bar<T: Real + Debug>(linkage: FourBar<T>) {
    let scenes = linkage.scenes().unwrap();
    let angles = inputs::<T>();
    let n = angles.len();
    let (w, a) = (T::constant(-3.5), T::constant(12.0));
    for branch in [Branch::Open, Branch::Crossed] {
        let (mut wide, mut portable) = (vec![Default::default(); n], vec![Default::default(); n]);
        let failed = widest(
            #[inline(always)]
            || scenes.mechgen_joints_lanes(&angles, branch, &mut wide),
        );
        assert_eq!(
            failed,
            scenes.mechgen_joints_lanes(&angles, branch, &mut portable)
        );
        same("joints", &wide, &portable);

        let (mut wide, mut portable) = (vec![Default::default(); n], vec![Default::default(); n]);
        widest(
            #[inline(always)]
            || scenes.mechgen_coupler_path_lanes(&angles, branch, &mut wide),
        );
        scenes.mechgen_coupler_path_lanes(&angles, branch, &mut portable);
        same("coupler_path", &wide, &portable);

        let (mut wide, mut portable) = (vec![Default::default(); n], vec![Default::default(); n]);
        widest(
            #[inline(always)]
            || scenes.mechgen_coupler_motion_lanes(&angles, branch, w, a, &mut wide),
        );
        scenes.mechgen_coupler_motion_lanes(&angles, branch, w, a, &mut portable);
        same("coupler_motion", &wide, &portable);

        let (mut wide, mut portable) = (vec![Default::default(); n], vec![Default::default(); n]);
        widest(
            #[inline(always)]
            || scenes.mechgen_angles_lanes(&angles, branch, w, a, &mut wide),
        );
        scenes.mechgen_angles_lanes(&angles, branch, w, a, &mut portable);
        same("angles", &wide, &portable);

        // The batch, where nothing is redone, is the loop's result.
        let turn = &angles[..4096];
        let mut batch = vec![Default::default(); turn.len()];
        let mut lanes = batch.clone();
        if !scenes.mechgen_coupler_motion_lanes(turn, branch, w, a, &mut lanes) {
            scenes
                .coupler_motion_batch(turn, branch, w, a, &mut batch)
                .unwrap();
            same("coupler_motion_batch", &batch, &lanes);
        }
    }
}

#[test]
fn generated_four_bar_batches_give_the_same_bits_on_every_path() {
    four_bar(
        FourBar::new(180.0, 80.0, 200.0, 150.0)
            .and_then(|linkage| linkage.with_coupler_point(100.0, 0.5))
            .unwrap(),
    );
    // A double rocker: part of every turn fails.
    four_bar(FourBar::new(100.0, 80.0, 30.0, 60.0).unwrap());
    four_bar(
        FourBar::new(180.0f32, 80.0, 200.0, 150.0)
            .and_then(|linkage| linkage.with_coupler_point(100.0, 0.5))
            .unwrap(),
    );
}

#[test]
fn generated_batches_of_other_mechanisms_give_the_same_bits_on_every_path() {
    let angles = inputs::<f64>();
    let n = angles.len();
    let (w, a) = (2.0, -7.0);

    let slider = SliderCrank::new(50.0, 150.0, 20.0)
        .unwrap()
        .scenes()
        .unwrap();
    let (mut wide, mut portable) = (vec![Default::default(); n], vec![Default::default(); n]);
    widest(
        #[inline(always)]
        || slider.mechgen_state_lanes(&angles, Branch::Open, w, a, &mut wide),
    );
    slider.mechgen_state_lanes(&angles, Branch::Open, w, a, &mut portable);
    same("slider-crank state", &wide, &portable);

    let leg = JansenLeg::<f64>::holy().scenes().unwrap();
    let drawn = JansenLeg::<f64>::DRAWN;
    let (mut wide, mut portable) = (vec![Default::default(); n], vec![Default::default(); n]);
    widest(
        #[inline(always)]
        || leg.mechgen_foot_motion_lanes(&angles, drawn, w, a, &mut wide),
    );
    leg.mechgen_foot_motion_lanes(&angles, drawn, w, a, &mut portable);
    same("Jansen foot motion", &wide, &portable);
}
