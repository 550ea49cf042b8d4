//! The five-bar parallel robot: two driven cranks, one end effector.

use mechgen::{Real, Vec2, mechanism};

use crate::dimensions::{DimensionError, non_negative, positive};

mechanism! {
    /// Five-bar parallel robot (a 2-DOF planar manipulator): motors at O1 = (0, 0) and
    /// O5 = (l5, 0) drive the proximal links, `l1` from O1 to the left elbow A1 at the input
    /// `theta1` and `l4` from O5 to the right elbow A2 at the input `theta4`; the distal
    /// links, `l2` from A1 at `theta2` and `l3` from A2 at `theta3`, meet at the end
    /// effector P.
    ///
    /// Loop: `l1 @ theta1 + l2 @ theta2 - l3 @ theta3 - l4 @ theta4 - l5 @ 0 = 0`: P reached
    /// through either leg. Build one with [`FiveBar::new`], which checks the lengths.
    ///
    /// Every generated function takes both inputs, in that order (`theta1`, then `theta4`),
    /// and, for rates and accelerations, both inputs' rates, then both accelerations: the
    /// accelerations are the full second derivative, the terms that cross the two inputs'
    /// motions included. The generated [`assemble`](Self::assemble) places P where the circle
    /// of radius `l2` about A1 meets the circle of radius `l3` about A2; its branch (the
    /// robot's working mode) is the side of the line A1 A2 that P lies on: `Open` to the left
    /// of A1 → A2 (P above the elbows when A2 is to the right of A1), `Crossed` to the
    /// right.
    ///
    /// ```
    /// use mechanisms::FiveBar;
    /// use mechgen::Branch;
    /// // A symmetric robot with both cranks straight up: P straight above the middle.
    /// let robot = FiveBar::new(100.0, 200.0, 200.0, 100.0, 100.0)?;
    /// let (left, right) = (90f64.to_radians(), 90f64.to_radians());
    /// let q = robot.assemble(left, right, Branch::Open)?;
    /// let p = robot.points(left, right, &q)?.end_effector;
    /// assert!((p.x - 50.0).abs() < 1e-12);
    /// assert!((p.y - (100.0 + (200f64.powi(2) - 50f64.powi(2)).sqrt())).abs() < 1e-12);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub struct FiveBar {
        params:
            /// Left proximal link O1 A1, driven at O1.
            l1,
            /// Left distal link A1 P.
            l2,
            /// Right distal link A2 P.
            l3,
            /// Right proximal link O5 A2, driven at O5.
            l4,
            /// Base O1 O5, between the motors.
            l5;
        input: theta1: angle, theta4: angle;
        unknowns: theta2: angle, theta3: angle;
        loop: l1 @ theta1 + l2 @ theta2 - l3 @ theta3 - l4 @ theta4 - l5 @ 0;
        /// A1, the left elbow.
        point left_elbow = l1 @ theta1;
        /// A2, the right elbow.
        point right_elbow = l5 @ 0 + l4 @ theta4;
        /// P, the end effector.
        point end_effector = l1 @ theta1 + l2 @ theta2;
        generate: position, velocity, acceleration;
    }
}

/// How near a five-bar is to each kind of singularity, as sines of the angles that vanish
/// there (each in [0, 1]; 0 at the singularity, 1 at the best posture).
///
/// ```
/// use mechanisms::FiveBar;
/// use mechgen::Branch;
/// let robot = FiveBar::new(100.0, 200.0, 200.0, 100.0, 100.0)?;
/// let (left, right) = (120f64.to_radians(), 60f64.to_radians());
/// let q = robot.assemble(left, right, Branch::Open)?;
/// let near = robot.singularities(left, right, &q);
/// assert!(near.parallel > 0.5 && near.serial[0] > 0.5 && near.serial[1] > 0.5);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Singularities<T> {
    /// `|sin(θ3 − θ2)|`: zero where the distal links line up (the passive joint at P
    /// folds or stretches). There the loop's Jacobian is singular: the motors hold, yet P
    /// can move along the normal to the line (a parallel, or type II, singularity; the
    /// solvers say [`mechgen::Error::Singular`] for its rates, and positions there are at
    /// the edge of the range of motion for the given cranks).
    pub parallel: T,
    /// `[|sin(θ2 − θ1)|, |sin(θ3 − θ4)|]`: zero where a leg's proximal and distal links
    /// line up (the left or right elbow folds or stretches). There P is at the edge of the
    /// workspace of that leg and cannot move along the leg, whatever its motor does (a
    /// serial, or type I, singularity: the inverse kinematics' Jacobian is singular).
    pub serial: [T; 2],
}

impl<T: Real> FiveBar<T> {
    /// A five-bar with proximal links `l1` (left) and `l4` (right), distal links `l2`
    /// (left) and `l3` (right), and motors `l5` apart, each checked: every link positive
    /// and finite, the base not negative (0 puts both motors on one axis).
    pub fn new(l1: T, l2: T, l3: T, l4: T, l5: T) -> Result<Self, DimensionError<T>> {
        Ok(FiveBar {
            l1: positive("l1", l1)?,
            l2: positive("l2", l2)?,
            l3: positive("l3", l3)?,
            l4: positive("l4", l4)?,
            l5: non_negative("l5", l5)?,
        })
    }

    /// How near the position `q` at the cranks' angles `theta1` and `theta4` is to each kind
    /// of singularity (see [`Singularities`]).
    pub fn singularities(&self, theta1: T, theta4: T, q: &FiveBarUnknowns<T>) -> Singularities<T> {
        // `|sin(a − b)|` from each angle's own sine and cosine, whose reduction is exact at
        // any size, rather than from `a − b`, which rounds away the digits of a difference
        // between angles of many turns (0.86608 for 0.86592 at 1e12 turns).
        let apart = |a: T, b: T| {
            let ((sa, ca), (sb, cb)) = (a.sin_cos(), b.sin_cos());
            (sa * cb - ca * sb).abs()
        };
        Singularities {
            parallel: apart(q.theta3, q.theta2),
            serial: [apart(q.theta2, theta1), apart(q.theta3, theta4)],
        }
    }

    /// Whether the end effector can reach `p`: within each leg's annulus, between
    /// `|l1 − l2|` and `l1 + l2` from O1, and between `|l4 − l3|` and `l4 + l3` from O5
    /// (the workspace is the two annuli's intersection; on its boundary a leg is in a
    /// serial singularity).
    pub fn reaches(&self, p: Vec2<T>) -> bool {
        // In half units (exact, but for subnormals), so that no distance or sum of two links
        // near the float's largest overflows (`inf <= inf` put a point at infinity, or one
        // 2e308 away, within reach); a point that is not finite is not.
        if !(p.x.is_finite() && p.y.is_finite()) {
            return false;
        }
        let half = |v: T| v * T::constant(0.5);
        let from_left = half(p.x).hypot(half(p.y));
        let from_right = (half(p.x) - half(self.l5)).hypot(half(p.y));
        let within = |distance: T, a: T, b: T| {
            let (a, b) = (half(a), half(b));
            distance >= (a - b).abs() && distance <= a + b
        };
        within(from_left, self.l1, self.l2) && within(from_right, self.l4, self.l3)
    }

    /// The cranks' angles `[theta1, theta4]` that put the end effector at `p`, with each
    /// leg's elbow on the side `elbows` chooses: `elbows[k]` positive puts the leg's elbow
    /// to the left of the line from its motor to `p` (counter-clockwise from it), negative
    /// to the right: for a point above the base, `[1, -1]` bends both elbows outward, away
    /// from each other. `None` where `p` is outside the workspace ([`FiveBar::reaches`]), or
    /// an elbow's side is NaN (which chooses neither).
    ///
    /// ```
    /// use mechanisms::FiveBar;
    /// use mechgen::{Branch, Vec2};
    /// let robot = FiveBar::new(100.0, 200.0, 200.0, 100.0, 100.0)?;
    /// let [left, right] = robot.inverse(Vec2 { x: 50.0f64, y: 250.0 }, [1.0, -1.0]).unwrap();
    /// let q = robot.assemble(left, right, Branch::Open)?;
    /// let p = robot.points(left, right, &q)?.end_effector;
    /// assert!((p.x - 50.0).abs() < 1e-9 && (p.y - 250.0).abs() < 1e-9);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn inverse(&self, p: Vec2<T>, elbows: [T; 2]) -> Option<[T; 2]> {
        // A NaN side is no choice (it once counted as the right: an adversarial review).
        if !self.reaches(p) || elbows.iter().any(|side| side.is_nan()) {
            return None;
        }
        // Each leg is a triangle motor–elbow–P: the crank leaves the line motor → P at the
        // triangle's angle at the motor, to the side the elbow is on. Both motors are on the
        // x axis, the left at 0 and the right at l5.
        // In half units, as `reaches` measures (the angles are the same at any scale).
        let half = |v: T| v * T::constant(0.5);
        let leg = |motor_x: T, proximal: T, distal: T, side: T| {
            let dx = half(p.x) - half(motor_x);
            let reach = dx.hypot(half(p.y));
            let at_motor = crate::triangle::angle(half(proximal), reach, half(distal));
            let toward = half(p.y).atan2(dx);
            if side >= T::zero() {
                toward + at_motor
            } else {
                toward - at_motor
            }
        };
        Some([
            leg(T::zero(), self.l1, self.l2, elbows[0]),
            leg(self.l5, self.l4, self.l3, elbows[1]),
        ])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use mechgen::Branch;

    /// Unlike legs, so that a mix-up of the two, or of a leg's two links, shows: the left
    /// leg's annulus about O1 = (0, 0) is 60 to 140 wide, the right one's about
    /// O5 = (50, 0) is 30 to 90.
    fn robot() -> FiveBar<f64> {
        FiveBar::new(40.0, 100.0, 60.0, 30.0, 50.0).unwrap()
    }

    fn at(x: f64, y: f64) -> Vec2<f64> {
        Vec2 { x, y }
    }

    /// A robot near the float's largest: a point at infinity, or one beyond its legs' reach
    /// whose distance overflows, is out of reach (both were within it, `inf <= inf`, and the
    /// first's cranks came back as `[0, 0]`); a point within reach has cranks that put the
    /// end effector there.
    #[test]
    fn the_largest_robot_reaches_only_what_it_reaches() {
        let robot = FiveBar::new(1e308, 1e308, 1e308, 1e308, 1e307).unwrap();
        assert!(!robot.reaches(at(f64::INFINITY, 0.0)));
        assert_eq!(robot.inverse(at(f64::INFINITY, 0.0), [1.0, -1.0]), None);
        assert!(!robot.reaches(at(1.5e308, 1.5e308)));
        let p = at(5e306, 1.5e308);
        let [left, right] = robot.inverse(p, [1.0, -1.0]).unwrap();
        let q = robot.assemble(left, right, Branch::Open).unwrap();
        let got = robot.points(left, right, &q).unwrap().end_effector;
        assert!(
            (got.x - p.x).abs() < 1e294 && (got.y - p.y).abs() < 1e294,
            "{got:?}"
        );
    }

    /// At cranks' angles of many turns, each singularity's sine is the one the linkage's own
    /// joints give (the cross product of a crank's and its distal link's directions, from
    /// `points`): it was taken from a difference of angles that rounds at 1e12 turns.
    #[test]
    fn singularities_are_the_joints_own_at_any_number_of_turns() {
        let robot = FiveBar::new(100.0, 200.0, 200.0, 100.0, 100.0).unwrap();
        let turns = 1e12 * core::f64::consts::TAU;
        let (left, right) = (120f64.to_radians() + turns, 60f64.to_radians() - turns);
        let q = robot.assemble(left, right, Branch::Open).unwrap();
        let p = robot.points(left, right, &q).unwrap();
        let (elbow, effector) = (p.left_elbow, p.end_effector);
        let distal = (
            (effector.x - elbow.x) / 200.0,
            (effector.y - elbow.y) / 200.0,
        );
        let crank = (elbow.x / 100.0, elbow.y / 100.0);
        let joints = (crank.0 * distal.1 - crank.1 * distal.0).abs();
        let near = robot.singularities(left, right, &q);
        assert!(
            (near.serial[0] - joints).abs() < 1e-12,
            "{near:?} against {joints}"
        );
    }

    #[test]
    fn the_workspace_is_the_two_annuli_s_intersection() {
        let robot = robot();
        // 100 from O1 and hypot(30, 60) = 67.1 from O5: inside both annuli.
        assert!(robot.reaches(at(80.0, 60.0)));
        // 60 from O1, the left leg folded, and 78.1 from O5: on the left annulus's inner
        // circle, which the leg reaches.
        assert!(robot.reaches(at(0.0, 60.0)));
        // 50 from O1, inside the left annulus's hole (60 wide), and 70.7 from O5.
        assert!(!robot.reaches(at(0.0, 50.0)));
        // 100 from O1 but 136 from O5: beyond the right leg's reach alone.
        assert!(!robot.reaches(at(-60.0, -80.0)));
        // 70 from O1 but 20 from O5, inside the right annulus's hole (30 wide).
        assert!(!robot.reaches(at(70.0, 0.0)));
        // 145 from O1 and 95 from O5: beyond both.
        assert!(!robot.reaches(at(145.0, 0.0)));
    }

    #[test]
    fn inverse_kinematics_puts_the_end_effector_where_asked_with_the_elbows_asked() {
        let robot = robot();
        for (p, elbows) in [
            (at(80.0, 60.0), [1.0, -1.0]),
            (at(80.0, 60.0), [-1.0, 1.0]),
            (at(10.0, 70.0), [1.0, 1.0]),
            (at(40.0, -65.0), [-1.0, -1.0]),
        ] {
            let [left, right] = robot.inverse(p, elbows).expect("within the workspace");
            // The elbows, from the cranks' angles alone.
            let a1 = at(40.0 * left.cos(), 40.0 * left.sin());
            let a2 = at(50.0 + 30.0 * right.cos(), 30.0 * right.sin());
            // Each distal link reaches P from its elbow.
            assert!(
                ((p.x - a1.x).hypot(p.y - a1.y) - 100.0).abs() < 1e-9,
                "{p:?}"
            );
            assert!(
                ((p.x - a2.x).hypot(p.y - a2.y) - 60.0).abs() < 1e-9,
                "{p:?}"
            );
            // Each elbow on the side asked of the line from its motor to P: to the left
            // (counter-clockwise) where (P − motor) × (elbow − motor) is positive.
            let side = |motor: Vec2<f64>, elbow: Vec2<f64>| {
                (p.x - motor.x) * (elbow.y - motor.y) - (p.y - motor.y) * (elbow.x - motor.x)
            };
            assert!(
                side(at(0.0, 0.0), a1) * elbows[0] > 0.0,
                "{p:?} {elbows:?}: left"
            );
            assert!(
                side(at(50.0, 0.0), a2) * elbows[1] > 0.0,
                "{p:?} {elbows:?}: right"
            );
            // And the forward kinematics, on one of its working modes, finds P there.
            let found = [Branch::Open, Branch::Crossed].into_iter().any(|branch| {
                robot.assemble(left, right, branch).is_ok_and(|q| {
                    let e = robot.points(left, right, &q).unwrap().end_effector;
                    (e.x - p.x).hypot(e.y - p.y) < 1e-9
                })
            });
            assert!(found, "{p:?} {elbows:?}: no working mode puts P there");
        }
        assert_eq!(robot.inverse(at(0.0, 50.0), [1.0, 1.0]), None);
        assert_eq!(robot.inverse(at(-60.0, -80.0), [1.0, 1.0]), None);
        // A NaN side chooses no elbow.
        assert_eq!(robot.inverse(at(80.0, 60.0), [f64::NAN, 1.0]), None);
        assert_eq!(robot.inverse(at(80.0, 60.0), [1.0, f64::NAN]), None);
        assert!(robot.inverse(at(80.0, 60.0), [1.0, 1.0]).is_some());
    }
}
