//! The shipped mechanisms' public API: the seeds' values on both branches, Grashof's law for
//! every class and inversion, limit angles and dead centres against the generated Jacobian
//! and velocity, mechanical advantage, acceleration parts, and the slider-crank's stroke and
//! time ratio against sweeps.

mod common;

use common::*;
use mechanisms::{FourBar, FourBarUnknowns, InvertedSliderCrank, SliderCrank};
use mechgen::grashof::{self, Class, Inversion, Special};
use mechgen::{Branch, Error, MechanicalAdvantage, Vec2};

const TAU: f64 = std::f64::consts::TAU;

#[test]
fn seeds_worked_values_on_both_branches() {
    let example_1 = FourBar::new(180.0, 80.0, 200.0, 150.0).unwrap();
    let theta2 = rad(60.0);
    let open = example_1.assemble(theta2, Branch::Open).unwrap();
    let crossed = example_1.assemble(theta2, Branch::Crossed).unwrap();
    assert_eq!(
        rounded(example_1.transmission_angle(&open).to_degrees(), 2),
        50.58
    );
    assert_eq!(
        rounded(example_1.transmission_angle(&crossed).to_degrees(), 2),
        50.58
    );
    assert_eq!(rounded(normalised_deg(open.theta4), 2), 72.14);
    assert_eq!(rounded(normalised_deg(crossed.theta4), 2), 235.20);
    assert_eq!(rounded(normalised_deg(open.theta3), 4), 21.5576);
    assert_eq!(example_1.branch_of(theta2, &open), Branch::Open);
    assert_eq!(example_1.branch_of(theta2, &crossed), Branch::Crossed);

    let exercise_3 = FourBar::new(300.0, 100.0, 250.0, 200.0).unwrap();
    let open = exercise_3.assemble(rad(45.0), Branch::Open).unwrap();
    let crossed = exercise_3.assemble(rad(45.0), Branch::Crossed).unwrap();
    assert_eq!(
        rounded(exercise_3.transmission_angle(&open).to_degrees(), 2),
        63.30
    );
    assert_eq!(rounded(normalised_deg(open.theta4), 2), 94.30);
    assert_eq!(rounded(normalised_deg(crossed.theta4), 2), 231.43);

    // Exercise 4's Newton answer is the open branch's closed form.
    let q = exercise_3.assemble(rad(60.0), Branch::Open).unwrap();
    assert_eq!(rounded(deg(q.theta3), 3), 26.528);
    assert_eq!(rounded(deg(q.theta4), 3), 97.562);
}

#[test]
fn closed_form_branches_agree_with_newton_started_nearby() {
    let linkage = example_1::<f64>();
    for branch in [Branch::Open, Branch::Crossed] {
        for degree in (0..360).step_by(7) {
            let theta2 = rad(f64::from(degree));
            let q = linkage.assemble(theta2, branch).unwrap();
            let nudged = FourBarUnknowns {
                theta3: q.theta3 + 0.01,
                theta4: q.theta4 - 0.01,
            };
            let newton = linkage
                .position(theta2, &nudged, &Default::default())
                .unwrap()
                .value;
            assert!(
                (newton.theta3 - q.theta3).abs() < 1e-12,
                "{branch:?} {degree}°"
            );
            assert!(
                (newton.theta4 - q.theta4).abs() < 1e-12,
                "{branch:?} {degree}°"
            );
            assert_eq!(linkage.branch_of(theta2, &newton), branch);
        }
    }
}

/// Every class and inversion, with each of the four links as the shortest, exact change
/// points, parallelograms and kites.
#[test]
fn grashof_table() {
    use Class::*;
    use Inversion::*;
    // (ground, input, coupler, output) → (class, inversion, special)
    let table = [
        ([180.0, 80.0, 200.0, 150.0], (Grashof, CrankRocker, None)),
        ([180.0, 150.0, 200.0, 80.0], (Grashof, RockerCrank, None)),
        ([80.0, 180.0, 200.0, 150.0], (Grashof, DoubleCrank, None)),
        ([180.0, 150.0, 80.0, 200.0], (Grashof, DoubleRocker, None)),
        // Non-Grashof (80 + 120 > 90 + 100): a triple-rocker whatever the ground.
        ([100.0, 120.0, 90.0, 80.0], (NonGrashof, TripleRocker, None)),
        ([120.0, 90.0, 80.0, 100.0], (NonGrashof, TripleRocker, None)),
        ([90.0, 80.0, 100.0, 120.0], (NonGrashof, TripleRocker, None)),
        ([80.0, 100.0, 120.0, 90.0], (NonGrashof, TripleRocker, None)),
        // Change points, 2 + 5 = 3 + 4 exactly, with the shortest link in each place.
        ([3.0, 2.0, 4.0, 5.0], (ChangePoint, CrankRocker, None)),
        ([3.0, 5.0, 4.0, 2.0], (ChangePoint, RockerCrank, None)),
        ([2.0, 3.0, 5.0, 4.0], (ChangePoint, DoubleCrank, None)),
        ([3.0, 4.0, 2.0, 5.0], (ChangePoint, DoubleRocker, None)),
        // Parallelograms: both cranks turn fully; a rhombus counts as one.
        (
            [100.0, 50.0, 100.0, 50.0],
            (ChangePoint, DoubleCrank, Some(Special::Parallelogram)),
        ),
        (
            [50.0, 100.0, 50.0, 100.0],
            (ChangePoint, DoubleCrank, Some(Special::Parallelogram)),
        ),
        (
            [70.0, 70.0, 70.0, 70.0],
            (ChangePoint, DoubleCrank, Some(Special::Parallelogram)),
        ),
        // Kites (deltoids): two pairs of equal adjacent links.
        (
            [50.0, 50.0, 100.0, 100.0],
            (ChangePoint, DoubleCrank, Some(Special::Kite)),
        ),
        (
            [100.0, 50.0, 50.0, 100.0],
            (ChangePoint, CrankRocker, Some(Special::Kite)),
        ),
        (
            [100.0, 100.0, 50.0, 50.0],
            (ChangePoint, RockerCrank, Some(Special::Kite)),
        ),
    ];
    for (lengths, (class, inversion, special)) in table {
        let [ground, input, coupler, output] = lengths;
        let g = grashof::classify(ground, input, coupler, output);
        assert_eq!(
            (g.class, g.inversion, g.special),
            (class, inversion, special),
            "{lengths:?}"
        );
    }
}

#[test]
fn grashof_equality_is_decided_within_a_tolerance() {
    // 0.1 + 0.7 and 0.3 + 0.5 differ by one ulp in f64: still the change point meant.
    assert_ne!(0.1 + 0.7, 0.3 + 0.5);
    assert_eq!(
        grashof::classify(0.3, 0.1, 0.5, 0.7).class,
        Class::ChangePoint
    );
    // A margin well above rounding is Grashof or not.
    assert_eq!(
        grashof::classify(3.0, 2.0, 4.0, 5.0 - 1e-9).class,
        Class::Grashof
    );
    assert_eq!(
        grashof::classify(3.0, 2.0, 4.0, 5.0 + 1e-9).class,
        Class::NonGrashof
    );
    // A looser tolerance for measured lengths.
    let measured = grashof::classify_with_tolerance(3.0, 2.0, 4.0, 5.0 + 1e-9, 1e-6);
    assert_eq!(measured.class, Class::ChangePoint);
    // f32 has its own rounding.
    assert_eq!(
        grashof::classify(0.3f32, 0.1, 0.5, 0.7).class,
        Class::ChangePoint
    );
}

/// The relative determinant of the generated Jacobian at a position.
fn relative_determinant(linkage: &FourBar<f64>, theta2: f64, q: &FourBarUnknowns<f64>) -> f64 {
    let j = linkage.jacobian(theta2, q);
    let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
    let [_, _, l3, l4] = linkage.lengths();
    det / (l3 * l4)
}

#[test]
fn limit_angles_are_where_the_jacobian_is_singular_and_assembly_ends() {
    // A rocker-crank whose crank meets both toggles, and a triple-rocker.
    for lengths in [[180.0, 150.0, 200.0, 80.0], [100.0, 120.0, 90.0, 80.0]] {
        let linkage = FourBar::new(lengths[0], lengths[1], lengths[2], lengths[3]).unwrap();
        let limits = linkage.limit_angles();
        assert!(!limits.full_turn());
        // Moving outward from a limit leaves the range: toward 0 from the folded one, toward
        // π from the extended one.
        let toggles = [(limits.folded, -1.0), (limits.extended, 1.0)];
        for (limit, outward) in toggles.into_iter().filter_map(|(l, o)| Some((l?, o))) {
            for branch in [Branch::Open, Branch::Crossed] {
                let q = linkage.assemble(limit, branch).unwrap();
                assert!(
                    relative_determinant(&linkage, limit, &q).abs() < 1e-7,
                    "{lengths:?}"
                );
                assert!(matches!(
                    linkage.velocity(limit, &q, 1.0),
                    Err(Error::Singular { .. })
                ));
                let past = limit + outward * 1e-6;
                assert_eq!(
                    linkage.assemble(past, branch),
                    Err(Error::CannotAssemble { input: past })
                );
                assert!(!limits.reaches(past));
                let within = limit - outward * 1e-6;
                assert!(linkage.assemble(within, branch).is_ok());
                assert!(limits.reaches(within));
            }
        }
    }
    let rocker_crank = FourBar::new(180.0, 150.0, 200.0, 80.0)
        .unwrap()
        .limit_angles();
    assert!(rocker_crank.folded.is_some() && rocker_crank.extended.is_some());
    assert!(example_1::<f64>().limit_angles().full_turn());
}

#[test]
fn dead_centres_stop_the_rocker_at_its_extremes() {
    let linkage = example_1::<f64>();
    for branch in [Branch::Open, Branch::Crossed] {
        let centres = linkage.dead_centres(branch).unwrap();
        // The rocker's extremes over a fine sweep.
        let sweep: Vec<f64> = (0..36000)
            .map(|i| {
                linkage
                    .assemble(f64::from(i) * TAU / 36000.0, branch)
                    .unwrap()
                    .theta4
            })
            .map(|theta4| theta4.rem_euclid(TAU))
            .collect();
        let (low, high) = sweep
            .iter()
            .fold((f64::MAX, f64::MIN), |(lo, hi), t| (lo.min(*t), hi.max(*t)));
        let mut stops: Vec<f64> = centres.iter().map(|c| c.theta4.rem_euclid(TAU)).collect();
        stops.sort_by(f64::total_cmp);
        assert!(
            (stops[0] - low).abs() < 1e-6 && (stops[1] - high).abs() < 1e-6,
            "{branch:?}"
        );
        for centre in centres {
            let q = linkage.assemble(centre.theta2, branch).unwrap();
            assert!((q.theta4 - centre.theta4).abs() < 1e-12);
            let omega4 = linkage.velocity(centre.theta2, &q, 1.0).unwrap().theta4;
            assert!(omega4.abs() < 1e-12, "{omega4}");
            let advantage = linkage.mechanical_advantage(centre.theta2, &q).unwrap();
            assert!(
                advantage.finite().is_none_or(|ma| ma.abs() > 1e12),
                "{advantage:?}"
            );
        }
    }
    assert!(
        FourBar::new(100.0, 120.0, 90.0, 80.0)
            .unwrap()
            .dead_centres(Branch::Open)
            .is_none()
    );
}

#[test]
fn transmission_extremes_bound_a_sweep() {
    for lengths in [[180.0, 80.0, 200.0, 150.0], [100.0, 120.0, 90.0, 80.0]] {
        let linkage = FourBar::new(lengths[0], lengths[1], lengths[2], lengths[3]).unwrap();
        let extremes = linkage.transmission_extremes();
        let limits = linkage.limit_angles();
        // A sweep of [0, π], with the limit angles themselves.
        let angles: Vec<f64> = (0..=3600)
            .map(|i| f64::from(i) * std::f64::consts::PI / 3600.0)
            .chain(limits.folded)
            .chain(limits.extended)
            .filter(|theta2| limits.reaches(*theta2))
            .filter_map(|theta2| linkage.assemble(theta2, Branch::Open).ok())
            .map(|q| linkage.transmission_angle(&q))
            .collect();
        let (low, high) = angles
            .iter()
            .fold((f64::MAX, f64::MIN), |(lo, hi), g| (lo.min(*g), hi.max(*g)));
        assert!(
            extremes.min <= low + 1e-9 && low - extremes.min < 1e-3,
            "{lengths:?}"
        );
        assert!(
            extremes.max >= high - 1e-9 && extremes.max - high < 1e-3,
            "{lengths:?}"
        );
        assert!(!extremes.within_guideline());
    }
    let extremes = example_1::<f64>().transmission_extremes();
    assert_eq!(
        (extremes.min_at, extremes.max_at),
        (0.0, std::f64::consts::PI)
    );
}

#[test]
fn mechanical_advantage_is_the_velocity_ratio() {
    let four_bar = example_1::<f64>();
    let slider = slider_crank::<f64>();
    let inverted = inverted_slider_crank::<f64>();
    for degree in (5..360).step_by(10) {
        let theta2 = rad(f64::from(degree));
        let q = four_bar.assemble(theta2, Branch::Open).unwrap();
        let v = four_bar.velocity(theta2, &q, 7.0).unwrap();
        let ma = four_bar
            .mechanical_advantage(theta2, &q)
            .unwrap()
            .finite()
            .unwrap();
        assert_close("four-bar MA", ma, 7.0 / v.theta4, 1e-12);

        let q = slider.assemble(theta2, Branch::Open).unwrap();
        let v = slider.velocity(theta2, &q, 7.0).unwrap();
        let ma = slider
            .mechanical_advantage(theta2, &q)
            .unwrap()
            .finite()
            .unwrap();
        assert_close("slider-crank MA", ma, 7.0 / v.d, 1e-12);

        let q = inverted.assemble(theta2, Branch::Open).unwrap();
        let v = inverted.velocity(theta2, &q, 7.0).unwrap();
        let ma = inverted
            .mechanical_advantage(theta2, &q)
            .unwrap()
            .finite()
            .unwrap();
        assert_close("inverted slider-crank MA", ma, 7.0 / v.theta4, 1e-12);
    }
    assert_eq!(
        MechanicalAdvantage::from_rates(1.0, 0.0),
        Ok(MechanicalAdvantage::Unbounded)
    );
}

fn assert_vec_close(what: &str, a: Vec2<f64>, b: Vec2<f64>, scale: f64) {
    assert!(
        (a.x - b.x).abs() < 1e-9 * scale && (a.y - b.y).abs() < 1e-9 * scale,
        "{what}: {a:?} vs {b:?}"
    );
}

#[test]
fn acceleration_parts_sum_to_the_total() {
    let (omega2, alpha2) = (12.0, -30.0);
    let four_bar = example_1::<f64>();
    let inverted = inverted_slider_crank::<f64>();
    let slider = slider_crank::<f64>();
    for degree in (0..360).step_by(15) {
        let theta2 = rad(f64::from(degree));

        let q = four_bar.assemble(theta2, Branch::Open).unwrap();
        let v = four_bar.velocity(theta2, &q, omega2).unwrap();
        let a = four_bar
            .acceleration(theta2, &q, omega2, &v, alpha2)
            .unwrap();
        let total = four_bar
            .point_accelerations(theta2, &q, omega2, &v, alpha2, &a)
            .unwrap();
        let parts = four_bar
            .point_acceleration_parts(theta2, &q, omega2, &v, alpha2, &a)
            .unwrap();
        let scale = 1e5;
        assert_vec_close(
            "A",
            parts.crank_pin.total().unwrap(),
            total.crank_pin,
            scale,
        );
        assert_vec_close(
            "B",
            parts.rocker_pin.total().unwrap(),
            total.rocker_pin,
            scale,
        );
        assert_vec_close(
            "P",
            parts.coupler_point.total().unwrap(),
            total.coupler_point,
            scale,
        );
        // The crank pin: tangential l2·α2, normal l2·ω2², no sliding or Coriolis.
        assert_close(
            "|tangential|",
            parts.crank_pin.tangential.norm(),
            80.0 * alpha2.abs(),
            1e-12,
        );
        assert_close(
            "|normal|",
            parts.crank_pin.normal.norm(),
            80.0 * omega2 * omega2,
            1e-12,
        );
        assert_eq!(parts.crank_pin.sliding, Vec2::default());
        assert_eq!(parts.crank_pin.coriolis, Vec2::default());

        let q = slider.assemble(theta2, Branch::Open).unwrap();
        let v = slider.velocity(theta2, &q, omega2).unwrap();
        let a = slider.acceleration(theta2, &q, omega2, &v, alpha2).unwrap();
        let total = slider
            .point_accelerations(theta2, &q, omega2, &v, alpha2, &a)
            .unwrap();
        let parts = slider
            .point_acceleration_parts(theta2, &q, omega2, &v, alpha2, &a)
            .unwrap();
        assert_vec_close(
            "B",
            parts.slider_pin.total().unwrap(),
            total.slider_pin,
            scale,
        );
        // The slider pin only slides.
        assert_close("sliding", parts.slider_pin.sliding.x, a.d, 1e-12);

        let q = inverted.assemble(theta2, Branch::Open).unwrap();
        let v = inverted.velocity(theta2, &q, omega2).unwrap();
        let a = inverted
            .acceleration(theta2, &q, omega2, &v, alpha2)
            .unwrap();
        let total = inverted
            .point_accelerations(theta2, &q, omega2, &v, alpha2, &a)
            .unwrap();
        let parts = inverted
            .point_acceleration_parts(theta2, &q, omega2, &v, alpha2, &a)
            .unwrap();
        for (name, part, whole) in [
            ("A", parts.crank_pin, total.crank_pin),
            ("A via the rocker", parts.block_pin, total.block_pin),
            ("slide origin", parts.slide_origin, total.slide_origin),
            ("P", parts.coupler_point, total.coupler_point),
        ] {
            assert_vec_close(name, part.total().unwrap(), whole, scale);
        }
        // One point, two paths: the same acceleration.
        assert_vec_close("A both ways", total.block_pin, total.crank_pin, scale);
        // Coriolis: 2·ḃ·ω4 in magnitude; sliding: b̈.
        let coriolis = parts.block_pin.coriolis.norm();
        assert_close("|Coriolis|", coriolis, 2.0 * (v.b * v.theta4).abs(), 1e-12);
        assert_close(
            "|sliding|",
            parts.block_pin.sliding.norm(),
            a.b.abs(),
            1e-12,
        );
    }
}

#[test]
fn slider_crank_stroke_time_ratio_and_dead_centres_match_a_sweep() {
    for offset in [0.0, 20.0, -35.0] {
        let linkage = SliderCrank::new(50.0, 150.0, offset).unwrap();
        let n = 100_000;
        let positions: Vec<(f64, f64)> = (0..n)
            .map(|i| f64::from(i) * TAU / f64::from(n))
            .map(|theta2| (theta2, linkage.assemble(theta2, Branch::Open).unwrap().d))
            .collect();
        let outer = positions
            .iter()
            .copied()
            .fold((0.0, f64::MIN), |m, p| if p.1 > m.1 { p } else { m });
        let inner = positions
            .iter()
            .copied()
            .fold((0.0, f64::MAX), |m, p| if p.1 < m.1 { p } else { m });
        let stroke = linkage.stroke().unwrap();
        assert!(
            (stroke - (outer.1 - inner.1)).abs() < 1e-6,
            "offset {offset}"
        );
        let [outer_angle, inner_angle] = linkage.dead_centres().unwrap();
        let step = TAU / f64::from(n);
        assert!(
            (outer_angle.rem_euclid(TAU) - outer.0).abs() < 2.0 * step,
            "offset {offset}"
        );
        assert!(
            (inner_angle.rem_euclid(TAU) - inner.0).abs() < 2.0 * step,
            "offset {offset}"
        );
        for angle in [outer_angle, inner_angle] {
            let q = linkage.assemble(angle, Branch::Open).unwrap();
            assert!(linkage.velocity(angle, &q, 1.0).unwrap().d.abs() < 1e-9);
        }
        let inward = (inner.0 - outer.0).rem_euclid(TAU);
        let measured = inward / (TAU - inward);
        assert!(
            (linkage.time_ratio().unwrap() - measured).abs() < 1e-3,
            "offset {offset}"
        );
    }
    assert_eq!(
        SliderCrank::new(50.0, 150.0, 0.0).unwrap().time_ratio(),
        Some(1.0)
    );
    // A rod too short for a full turn has no stroke to speak of.
    assert_eq!(SliderCrank::new(50.0, 60.0, 20.0).unwrap().stroke(), None);
}

#[test]
fn constructors_reject_bad_dimensions() {
    assert_eq!(
        FourBar::new(180.0, 0.0, 200.0, 150.0).unwrap_err().name,
        "crank"
    );
    assert_eq!(
        FourBar::new(f64::INFINITY, 80.0, 200.0, 150.0)
            .unwrap_err()
            .name,
        "ground"
    );
    assert_eq!(
        FourBar::new(180.0, 80.0, -200.0, 150.0).unwrap_err().name,
        "coupler"
    );
    assert_eq!(
        FourBar::new(180.0, 80.0, 200.0, f64::NAN).unwrap_err().name,
        "rocker"
    );
    let linkage = FourBar::new(180.0, 80.0, 200.0, 150.0).unwrap();
    let err = linkage.with_coupler_point(-1.0, 0.0).unwrap_err();
    assert_eq!(
        err.to_string(),
        "coupler point distance = -1 must be non-negative and finite"
    );
    assert_eq!(
        SliderCrank::new(50.0, 150.0, f64::NAN).unwrap_err().name,
        "offset"
    );
    assert_eq!(
        SliderCrank::new(50.0, 150.0, 500.0).unwrap_err().name,
        "offset"
    );
    assert_eq!(
        InvertedSliderCrank::new(0.0, 60.0, 0.0, 0.0)
            .unwrap_err()
            .name,
        "ground"
    );
    assert_eq!(
        InvertedSliderCrank::new(150.0, 60.0, 500.0, 1.0)
            .unwrap_err()
            .name,
        "offset"
    );
}
