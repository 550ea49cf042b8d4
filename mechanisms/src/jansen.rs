//! Theo Jansen's walking linkage, one leg, with the published ("holy") lengths.

use mechgen::grashof::normalised;
use mechgen::{Branch, Real, mechanism};

use crate::dimensions::{DimensionError, positive};

mechanism! {
    /// One leg of Theo Jansen's strandbeest. The crank `m` turns about O = (0, 0); the
    /// frame's pivot Z is at (−a, −l). Bars `j` (crank pin to P1) and `b` (Z to P1) form the
    /// upper joint; `k` (crank pin to P2) and `c` (Z to P2) the lower. The rigid triangle Z P1
    /// P3 (sides `b`, `d`, `e`) puts P3 at `d @ (phi_b + delta1)` from Z; bars `f` (P3 to P4)
    /// and `g` (P2 to P4) meet at P4; the rigid foot triangle P2 P4 P5 (sides `g`, `h`, `i`)
    /// puts the foot P5 at `i @ (phi_g + delta2)` from P2.
    ///
    /// Three loops, each closing with two unknowns once the ones before it are solved, so
    /// [`assemble`](Self::assemble) is closed form with a branch per loop;
    /// [`JansenLeg::DRAWN`] are the branches of the usual drawing (P1 above, P2 below, the
    /// knee P4 out to the side). Build one with [`JansenLeg::holy`] or [`JansenLeg::new`].
    ///
    /// ```
    /// use mechanisms::JansenLeg;
    /// let leg = JansenLeg::<f64>::holy();
    /// let q = leg.assemble(0.0, JansenLeg::<f64>::DRAWN)?;
    /// let foot = leg.points(0.0, &q)?.foot;
    /// assert!((foot.y + 91.757).abs() < 1e-3);
    /// # Ok::<(), mechgen::Error<f64>>(())
    /// ```
    pub struct JansenLeg {
        params:
            /// Horizontal distance from the crank axle O to the frame pivot Z.
            a,
            /// Vertical distance from O down to Z.
            l,
            /// Crank.
            m,
            /// Crank pin to P1.
            j,
            /// Z to P1.
            b,
            /// Crank pin to P2.
            k,
            /// Z to P2.
            c,
            /// Z to P3.
            d,
            /// P3 to P4.
            f,
            /// P2 to P4.
            g,
            /// P2 to the foot P5.
            i,
            /// Angle of Z P3 from Z P1 (from the triangle b, d, e), radians.
            delta1: angle,
            /// Angle of P2 P5 from P2 P4 (from the triangle g, h, i), radians.
            delta2: angle;
        input: theta: angle;
        unknowns: phi_j: angle, phi_b: angle, phi_k: angle, phi_c: angle, phi_f: angle, phi_g: angle;
        loop: m @ theta + j @ phi_j - b @ phi_b + a @ 0 + l @ pi / 2;
        loop: m @ theta + k @ phi_k - c @ phi_c + a @ 0 + l @ pi / 2;
        loop: d @ (phi_b + delta1) + f @ phi_f - c @ phi_c - g @ phi_g;
        /// The crank pin.
        point crank_pin = m @ theta;
        /// P1, the upper joint.
        point upper = -a @ 0 - l @ pi / 2 + b @ phi_b;
        /// P2, the lower joint.
        point lower = -a @ 0 - l @ pi / 2 + c @ phi_c;
        /// P3, the back of the upper triangle.
        point back = -a @ 0 - l @ pi / 2 + d @ (phi_b + delta1);
        /// P4, the knee.
        point knee = -a @ 0 - l @ pi / 2 + c @ phi_c + g @ phi_g;
        /// P5, the foot.
        point foot = -a @ 0 - l @ pi / 2 + c @ phi_c + i @ (phi_g + delta2);
        generate: position, velocity, acceleration;
        /// The foot's path alone.
        scene foot_path: foot;
        /// The foot's position, velocity and acceleration.
        scene foot_motion: foot, foot_dot, foot_ddot;
    }
}

impl<T: Real> JansenLeg<T> {
    /// The branches of the usual drawing of the leg, one per loop.
    pub const DRAWN: [Branch; 3] = [Branch::Crossed, Branch::Open, Branch::Crossed];

    /// A leg from Jansen's thirteen lengths `[a, b, c, d, e, f, g, h, i, j, k, l, m]`.
    ///
    /// Errors: a length that is not positive and finite, or a triangle (b, d, e or g, h, i)
    /// whose sides cannot close.
    ///
    /// ```
    /// use mechanisms::JansenLeg;
    /// let mut lengths = [38.0, 41.5, 39.3, 40.1, 55.8, 39.4, 36.7, 65.7, 49.0, 50.0, 61.9, 7.8, 15.0];
    /// assert!(JansenLeg::new(lengths).is_ok());
    /// lengths[4] = 100.0; // e longer than b + d
    /// assert_eq!(JansenLeg::new(lengths).unwrap_err().name, "e");
    /// ```
    pub fn new(lengths: [T; 13]) -> Result<Self, DimensionError<T>> {
        const NAMES: [&str; 13] = [
            "a", "b", "c", "d", "e", "f", "g", "h", "i", "j", "k", "l", "m",
        ];
        let mut checked = lengths;
        for (value, name) in checked.iter_mut().zip(NAMES) {
            *value = positive(name, *value)?;
        }
        let [a, b, c, d, e, f, g, h, i, j, k, l, m] = checked;
        // The angle at a triangle's vertex between sides p and q, opposite r, from the lengths
        // scaled by a power of two (the same cosine, bit for bit, where nothing overflows), and
        // whether the triangle closes decided on the lengths, not on the rounded cosine.
        let angle = |p: T, q: T, r: T, name: &'static str| {
            let [p, q, r] = normalised([p, q, r]);
            if r <= p + q && r >= (p - q).abs() {
                let cosine = (p * p + q * q - r * r) / ((p + p) * q);
                Ok(cosine.max(-T::one()).min(T::one()).acos())
            } else {
                Err(DimensionError {
                    name,
                    value: r,
                    requirement: "short enough to close its triangle",
                })
            }
        };
        Ok(JansenLeg {
            a,
            l,
            m,
            j,
            b,
            k,
            c,
            d,
            f,
            g,
            i,
            delta1: angle(b, d, e, "e")?,
            delta2: angle(g, i, h, "h")?,
        })
    }

    /// Jansen's published lengths: a = 38, b = 41.5, c = 39.3, d = 40.1, e = 55.8, f = 39.4,
    /// g = 36.7, h = 65.7, i = 49, j = 50, k = 61.9, l = 7.8, m = 15.
    ///
    /// ```
    /// let leg = mechanisms::JansenLeg::<f64>::holy();
    /// assert!(leg.assemble(1.0, mechanisms::JansenLeg::<f64>::DRAWN).is_ok());
    /// ```
    pub fn holy() -> Self {
        let c = T::constant;
        let lengths = [
            38.0, 41.5, 39.3, 40.1, 55.8, 39.4, 36.7, 65.7, 49.0, 50.0, 61.9, 7.8, 15.0,
        ];
        match Self::new(lengths.map(c)) {
            Ok(leg) => leg,
            // The published lengths close both triangles.
            Err(_) => unreachable!("Jansen's lengths are valid"),
        }
    }
}
