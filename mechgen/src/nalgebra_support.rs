//! Conversions to and from [nalgebra](https://nalgebra.rs) (feature `nalgebra`).
//!
//! [`Vec2`] converts both ways with `nalgebra::Vector2` and `nalgebra::Point2` by `From`.
//! A generated unknowns struct converts through its array (`to_array`, `from_array`, or
//! `From` both ways), and nalgebra converts arrays: [`vector`] and [`unknowns`] do both steps.
//!
//! A Jacobian is an array of rows (row `i` is loop equation `i`, column `j` unknown `j`),
//! but nalgebra reads an array of arrays as columns: `SMatrix::from(jacobian)` is its
//! transpose. [`matrix`] reads the rows as rows.
//!
//! ```
//! use mechgen::nalgebra_support::{matrix, unknowns, vector};
//! use nalgebra::{Matrix2, Point2, Vector2};
//!
//! mechgen::mechanism! {
//!     struct FourBar {
//!         params: l1, l2, l3, l4;
//!         input: theta2: angle;
//!         unknowns: theta3: angle, theta4: angle;
//!         loop: l2 @ theta2 + l3 @ theta3 - l4 @ theta4 - l1 @ 0;
//!         point coupler_pin = l2 @ theta2 + l3 @ theta3;
//!     }
//! }
//!
//! let linkage = FourBar { l1: 180.0, l2: 80.0, l3: 200.0, l4: 150.0 };
//! let theta2 = 60f64.to_radians();
//! let guess = FourBarUnknowns { theta3: 0.3, theta4: 1.3 };
//! let q = linkage.position(theta2, &guess, &Default::default())?.value;
//!
//! let qv: Vector2<f64> = vector(q);
//! assert_eq!((qv[0], qv[1]), (q.theta3, q.theta4));
//! let back: FourBarUnknowns<f64> = unknowns(qv);
//! assert_eq!(back, q);
//!
//! // Row 0 is the loop's x equation, column 1 its derivative by θ4: −(−l4·sin θ4).
//! let j: Matrix2<f64> = matrix(linkage.jacobian(theta2, &q));
//! assert!((j[(0, 1)] - 150.0 * q.theta4.sin()).abs() < 1e-9);
//! // The velocity solves J·q̇ = −(∂residual/∂θ2)·ω2.
//! let v = linkage.velocity(theta2, &q, 10.0)?;
//! let rhs = -vector::<f64, 2>(linkage.input_jacobian(theta2, &q)) * 10.0;
//! assert!((j * vector::<f64, 2>(v) - rhs).norm() < 1e-9);
//!
//! let pin: Point2<f64> = linkage.points(theta2, &q)?.coupler_pin.into();
//! assert_eq!(mechgen::Vec2::from(pin), linkage.points(theta2, &q)?.coupler_pin);
//! # Ok::<(), mechgen::Error<f64>>(())
//! ```

use nalgebra::{Point2, SMatrix, SVector, Scalar, Vector2};

use crate::Vec2;

impl<T: Scalar> From<Vec2<T>> for Vector2<T> {
    fn from(v: Vec2<T>) -> Self {
        Vector2::new(v.x, v.y)
    }
}

impl<T: Scalar> From<Vector2<T>> for Vec2<T> {
    fn from(v: Vector2<T>) -> Self {
        let [x, y]: [T; 2] = v.into();
        Vec2 { x, y }
    }
}

impl<T: Scalar> From<Vec2<T>> for Point2<T> {
    fn from(v: Vec2<T>) -> Self {
        Point2::new(v.x, v.y)
    }
}

impl<T: Scalar> From<Point2<T>> for Vec2<T> {
    fn from(p: Point2<T>) -> Self {
        p.coords.into()
    }
}

/// A generated unknowns struct (or any array of `N` values) as a column vector, in
/// declaration order.
pub fn vector<T: Scalar, const N: usize>(values: impl Into<[T; N]>) -> SVector<T, N> {
    SVector::from(values.into())
}

/// A column vector as a generated unknowns struct (or any type built from an array of `N`
/// values), in declaration order.
pub fn unknowns<T: Scalar, U: From<[T; N]>, const N: usize>(vector: SVector<T, N>) -> U {
    U::from(vector.into())
}

/// A matrix from an array of its rows, as the generated `jacobian` returns it: row `i` is
/// loop equation `i`.
pub fn matrix<T: Scalar, const R: usize, const C: usize>(rows: [[T; C]; R]) -> SMatrix<T, R, C> {
    SMatrix::from_fn(|i, j| rows[i][j].clone())
}
