//! Small dense linear solves on the stack, with a singularity check.
//!
//! Generated code calls [`solve2`] or [`solve3`] (closed form, Cramer's rule) for the common
//! sizes and [`solve_lu`] (partial pivoting) for larger systems. Each reports a singular
//! matrix as [`Error::Singular`] rather than dividing by (nearly) zero.

use crate::Error;
use crate::Real;

/// The relative determinant below which a matrix counts as singular: a few units of
/// rounding per row, so only matrices singular to working precision are rejected.
fn singular_threshold<T: Real>(rows: usize) -> T {
    T::constant(4.0 * rows as f64) * T::epsilon()
}

fn row_norm<T: Real>(row: &[T]) -> T {
    row.iter().fold(T::zero(), |acc, v| acc.hypot(*v))
}

/// Checks `determinant` against Hadamard's bound for `rows`.
fn check_determinant<T: Real, const N: usize>(
    determinant: T,
    rows: &[[T; N]; N],
) -> Result<(), Error<T>> {
    let bound = rows.iter().fold(T::one(), |acc, row| acc * row_norm(row));
    let relative_determinant = if bound > T::zero() {
        determinant.abs() / bound
    } else {
        T::zero()
    };
    if !determinant.is_finite() || !bound.is_finite() {
        return Err(Error::NonFinite {
            quantity: "Jacobian",
        });
    }
    if relative_determinant <= singular_threshold::<T>(N) {
        return Err(Error::Singular {
            determinant,
            relative_determinant,
        });
    }
    Ok(())
}

/// Solves the 2×2 system `a·x = b` by Cramer's rule.
#[inline]
pub fn solve2<T: Real>(a: [[T; 2]; 2], b: [T; 2]) -> Result<[T; 2], Error<T>> {
    let [[a00, a01], [a10, a11]] = a;
    let determinant = a00 * a11 - a01 * a10;
    check_determinant(determinant, &a)?;
    let inverse = T::one() / determinant;
    Ok([
        (b[0] * a11 - a01 * b[1]) * inverse,
        (a00 * b[1] - b[0] * a10) * inverse,
    ])
}

/// Solves the 3×3 system `a·x = b` by Cramer's rule.
#[inline]
pub fn solve3<T: Real>(a: [[T; 3]; 3], b: [T; 3]) -> Result<[T; 3], Error<T>> {
    let [[a00, a01, a02], [a10, a11, a12], [a20, a21, a22]] = a;
    // Cofactors of the first row, reused for the determinant.
    let c00 = a11 * a22 - a12 * a21;
    let c01 = a12 * a20 - a10 * a22;
    let c02 = a10 * a21 - a11 * a20;
    let determinant = a00 * c00 + a01 * c01 + a02 * c02;
    check_determinant(determinant, &a)?;
    let inverse = T::one() / determinant;
    let [b0, b1, b2] = b;
    let x0 = b0 * c00 + a01 * (b2 * a12 - b1 * a22) + a02 * (b1 * a21 - b2 * a11);
    let x1 = a00 * (b1 * a22 - b2 * a12) + b0 * c01 + a02 * (b2 * a10 - b1 * a20);
    let x2 = a00 * (b2 * a11 - b1 * a21) + a01 * (b1 * a20 - b2 * a10) + b0 * c02;
    Ok([x0 * inverse, x1 * inverse, x2 * inverse])
}

/// Solves the N×N system `a·x = b` by LU factorisation with partial pivoting, in place on
/// stack copies.
pub fn solve_lu<T: Real, const N: usize>(a: [[T; N]; N], b: [T; N]) -> Result<[T; N], Error<T>> {
    let original = a;
    let mut lu = a;
    let mut x = b;
    let mut determinant = T::one();
    for k in 0..N {
        let pivot_row = (k..N).fold(k, |best, i| {
            if lu[i][k].abs() > lu[best][k].abs() {
                i
            } else {
                best
            }
        });
        if pivot_row != k {
            lu.swap(k, pivot_row);
            x.swap(k, pivot_row);
            determinant = -determinant;
        }
        let pivot = lu[k][k];
        let x_k = x[k];
        determinant = determinant * pivot;
        if pivot == T::zero() {
            break;
        }
        let (upper, lower) = lu.split_at_mut(k + 1);
        let pivot_row = &upper[k];
        for (row, xi) in lower.iter_mut().zip(x.iter_mut().skip(k + 1)) {
            let factor = row[k] / pivot;
            for (entry, above) in row.iter_mut().zip(pivot_row).skip(k + 1) {
                *entry = *entry - factor * *above;
            }
            *xi = *xi - factor * x_k;
        }
    }
    check_determinant(determinant, &original)?;
    for k in (0..N).rev() {
        let sum = ((k + 1)..N).fold(x[k], |acc, j| acc - lu[k][j] * x[j]);
        x[k] = sum / lu[k][k];
    }
    Ok(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    const A3: [[f64; 3]; 3] = [[2.0, -1.0, 0.5], [1.0, 3.0, -2.0], [0.0, 4.0, 1.0]];
    const X3: [f64; 3] = [1.0, -2.0, 0.25];

    fn multiply<const N: usize>(a: &[[f64; N]; N], x: &[f64; N]) -> [f64; N] {
        let mut b = [0.0; N];
        for (bi, row) in b.iter_mut().zip(a) {
            *bi = row.iter().zip(x).map(|(r, x)| r * x).sum();
        }
        b
    }

    fn assert_close<const N: usize>(x: [f64; N], expected: [f64; N]) {
        for (got, want) in x.iter().zip(expected) {
            assert!((got - want).abs() < 1e-13, "{x:?} != {expected:?}");
        }
    }

    #[test]
    fn solve2_recovers_known_solution() {
        let a = [[3.0, 1.0], [-2.0, 4.0]];
        let x = [0.5, -1.5];
        assert_close(solve2(a, multiply(&a, &x)).unwrap(), x);
    }

    #[test]
    fn solve3_and_lu_recover_known_solution() {
        let b = multiply(&A3, &X3);
        assert_close(solve3(A3, b).unwrap(), X3);
        assert_close(solve_lu(A3, b).unwrap(), X3);
    }

    #[test]
    fn lu_pivots_past_a_zero_leading_entry() {
        let a = [
            [0.0, 1.0, 2.0, 0.0],
            [1.0, 0.0, 0.0, 3.0],
            [2.0, 1.0, 0.0, 1.0],
            [0.0, 2.0, 1.0, 1.0],
        ];
        let x = [1.0, 2.0, -1.0, 0.5];
        assert_close(solve_lu(a, multiply(&a, &x)).unwrap(), x);
    }

    #[test]
    fn singular_matrices_are_errors_with_their_determinant() {
        let rank_one = [[1.0, 2.0], [2.0, 4.0]];
        match solve2(rank_one, [1.0, 1.0]) {
            Err(Error::Singular {
                determinant,
                relative_determinant,
            }) => {
                assert_eq!(determinant, 0.0);
                assert_eq!(relative_determinant, 0.0);
            }
            other => panic!("expected Singular, got {other:?}"),
        }
        let dependent = [[1.0, 2.0, 3.0], [2.0, 4.0, 6.0], [0.0, 1.0, 1.0]];
        assert!(matches!(
            solve3(dependent, [1.0; 3]),
            Err(Error::Singular { .. })
        ));
        assert!(matches!(
            solve_lu(dependent, [1.0; 3]),
            Err(Error::Singular { .. })
        ));
    }

    #[test]
    fn non_finite_matrices_are_errors() {
        let a = [[f64::NAN, 0.0], [0.0, 1.0]];
        assert!(matches!(
            solve2(a, [1.0, 1.0]),
            Err(Error::NonFinite { .. })
        ));
    }
}
