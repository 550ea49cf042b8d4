//! Small dense linear solves on the stack, with a singularity check.
//!
//! Generated code calls [`solve2`] (closed form, Cramer's rule) for a single loop's 2×2
//! system and [`solve_lu`] (partial pivoting) for larger ones. Loops give two equations each,
//! so systems always have an even size. Each solver first scales the system by one factor
//! (a power of two near its largest entry's inverse), which leaves the solution unchanged and keeps the arithmetic from
//! overflowing or underflowing for very large or small mechanisms.
//!
//! Singularity is measured on the columns, one per unknown: the relative determinant is
//! `|det J| / Π‖column‖`, in [0, 1] by Hadamard's bound, 1 when the unknowns move the loop in
//! independent (orthogonal) directions and 0 when two of them move it the same way. It does
//! not depend on the frame (a rotation of x and y) or on the units of the unknowns, and its
//! inverse is the condition estimate κ of the accuracy contract. For a four-bar it is
//! `|sin(θ4 − θ3)|`, the sine of the transmission angle.

use crate::Error;
use crate::Real;

/// The relative determinant (`|det| / Π‖column‖`, in [0, 1]) at or below which a Jacobian
/// counts as singular: `√ε`. Within about one unit of rounding in the
/// input from a toggle, a position is itself only determined to `√ε` relative, so rates
/// computed from it would carry no correct digits; there the solvers say
/// [`Error::Singular`] instead.
///
/// ```
/// assert_eq!(mechgen::singular_threshold::<f64>(), f64::EPSILON.sqrt());
/// ```
pub fn singular_threshold<T: Real>() -> T {
    T::epsilon().sqrt()
}

/// Scales each column of `a` by a power of two that brings its largest entry into
/// `[1/2, 1)`: the solution of the scaled system, times the same powers, is the solution, to
/// the bit (they are exact), and the relative determinant is unchanged; but no product below
/// can overflow or underflow, however large or small the mechanism, and however its
/// unknowns' units differ (an angle's column is a length, a length's a pure direction).
/// Returns the product of the scaled matrix's column norms, which divides its determinant
/// into the relative determinant, and the columns' scales.
/// Errors: a zero column, a non-finite entry.
fn normalise<T: Real, const N: usize>(a: &mut [[T; N]; N]) -> Result<(T, [T; N]), Error<T>> {
    if !a.iter().flatten().all(|v| v.is_finite()) {
        return Err(Error::NonFinite {
            quantity: "linear system",
        });
    }
    let singular = Error::Singular {
        determinant: T::zero(),
        relative_determinant: T::zero(),
    };
    // Rows zipped with the columns' accumulators, not indexed: no bounds check, so no panic
    // path, is left for the compiler to prove away.
    let mut largest = [T::zero(); N];
    for row in a.iter() {
        for (m, v) in largest.iter_mut().zip(row) {
            *m = m.max(v.abs());
        }
    }
    if largest.iter().any(|m| *m == T::zero()) {
        return Err(singular);
    }
    let scales = largest.map(crate::real::normaliser);
    let mut column_squares = [T::zero(); N];
    for row in a.iter_mut() {
        for ((v, square), scale) in row.iter_mut().zip(column_squares.iter_mut()).zip(scales) {
            *v = *v * scale;
            *square = *square + *v * *v;
        }
    }
    let product = column_squares
        .iter()
        .fold(T::one(), |product, square| product * *square);
    Ok((product.sqrt(), scales))
}

/// The product of a 2×2 matrix's column norms without scaling it, when that is safe: the
/// common case, several times cheaper than [`normalise`]. `None` when the squares overflow,
/// underflow or are not finite, and the matrix must be scaled first.
#[inline]
fn unscaled_columns2<T: Real>(a: &[[T; 2]; 2]) -> Option<T> {
    let [[a00, a01], [a10, a11]] = *a;
    let product = (a00 * a00 + a10 * a10) * (a01 * a01 + a11 * a11);
    normal(product).then(|| product.sqrt())
}

/// Normal and finite, in two comparisons (false for NaN, zero, subnormals and infinity).
fn normal<T: Real>(value: T) -> bool {
    value >= T::min_positive_value() && value <= T::max_value()
}

/// The product of a 2×2 matrix's squared column norms, which its regularity test and its
/// relative determinant weigh the determinant against: computed from the matrix's entries,
/// or known where the dimensions fix the columns' lengths (a loop's angle unknown turns one
/// vector of fixed length, whose column is that length at every angle). Known, it costs no
/// arithmetic in each evaluation, and it is the exact lengths' rather than those of the
/// rounded sines and cosines (a few units of rounding apart). Larger matrices ignore it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Columns<T> {
    /// From the matrix's entries.
    FromMatrix,
    /// This product ([`Columns::known`]).
    Known(KnownColumns<T>),
}

impl<T: Real> Columns<T> {
    /// The known product `product`, with what the factoring reads of it.
    #[inline(always)]
    pub fn known(product: T) -> Self {
        Columns::Known(KnownColumns::new(product))
    }
}

/// A known product of squared column norms and what the 2×2 factoring reads of it: its
/// regularity test's bound and its square root, the column norms' product. Computed where
/// the product is, once for the dimensions (a `{Name}Newton` keeps it), rather than in every
/// solve; the same bits either way.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KnownColumns<T> {
    product: T,
    /// `4ε·product`, which a regular determinant's square exceeds; infinite where the
    /// product is not normal, which nothing exceeds.
    bound: T,
    norms: T,
}

impl<T: Real> KnownColumns<T> {
    /// `product` with its bound and square root.
    #[inline(always)]
    pub fn new(product: T) -> Self {
        let bound = if product >= T::min_positive_value() {
            T::constant(4.0) * T::epsilon() * product
        } else {
            T::infinity()
        };
        KnownColumns {
            product,
            bound,
            norms: product.sqrt(),
        }
    }
}

/// The signed relative determinant from the scaled determinant and [`normalise`]'s column
/// norms; an error where its magnitude is at or below [`singular_threshold`].
fn check_determinant<T: Real>(scaled_determinant: T, column_norms: T) -> Result<T, Error<T>> {
    let relative = scaled_determinant / column_norms;
    // NaN (a non-finite determinant) is singular too.
    if relative.is_nan() || relative.abs() <= singular_threshold::<T>() {
        return Err(Error::Singular {
            determinant: scaled_determinant,
            relative_determinant: relative.abs(),
        });
    }
    Ok(relative)
}

/// The solution of `a·x = b` with `a` factored, both first multiplied by a power of two
/// `scale` where their largest entry is beyond the square root of the float's largest or
/// smallest normal number (the one that brings it into `[1/2, 1)`; else 1): the unscaled
/// solution, bit for bit, where that neither overflows nor underflows, and finite at the
/// float's extremes too, where the unscaled solve's products overflow though the solution
/// is ordinary (a mechanism of 1e307 mm, whose rates in radians are of order 1). Returns
/// the factors of the scaled matrix and `scale`, by which errors in `b`'s units are
/// multiplied before [`Factored::uncertainty`]. A matrix with an entry that is not finite
/// is refused by [`Factored::new`], as unscaled.
pub fn solve_scaled<T: Real, const N: usize>(
    a: [[T; N]; N],
    b: [T; N],
) -> Result<([T; N], Factored<T, N>, T), Error<T>> {
    let largest = a
        .iter()
        .flatten()
        .chain(&b)
        .fold(T::zero(), |largest, v| largest.max(v.abs()));
    // Only at the extremes, where scaling is needed: elsewhere an entry far smaller than the
    // largest keeps every bit it has unscaled (the factoring scales each column on its own).
    let extreme = largest > T::max_value().sqrt() || largest < T::min_positive_value().sqrt();
    let scale = if extreme && largest > T::zero() && largest <= T::max_value() {
        crate::real::normaliser(largest)
    } else {
        T::one()
    };
    let factored = Factored::new(a.map(|row| row.map(|v| v * scale)))?;
    Ok((factored.solve(b.map(|v| v * scale)), factored, scale))
}

/// Solves the 2×2 system `a·x = b` by Cramer's rule; returns `x` and the signed relative
/// determinant `det / (‖column 0‖·‖column 1‖)`, whose sign is the matrix's orientation.
#[inline]
pub fn solve2<T: Real>(mut a: [[T; 2]; 2], b: [T; 2]) -> Result<([T; 2], T), Error<T>> {
    if !crate::newton::all_finite(&b) {
        return Err(Error::NonFinite {
            quantity: "linear system",
        });
    }
    let (columns, scales) = match unscaled_columns2(&a) {
        Some(columns) => (columns, [T::one(); 2]),
        None => normalise(&mut a)?,
    };
    let [[a00, a01], [a10, a11]] = a;
    let determinant = a00 * a11 - a01 * a10;
    let relative = check_determinant(determinant, columns)?;
    let inverse = T::one() / determinant;
    Ok((
        [
            (b[0] * a11 - a01 * b[1]) * inverse * scales[0],
            (a00 * b[1] - b[0] * a10) * inverse * scales[1],
        ],
        relative,
    ))
}

/// Solves the N×N system `a·x = b` by LU factorisation with partial pivoting, in place on
/// stack copies; returns `x` and the signed relative determinant.
pub fn solve_lu<T: Real, const N: usize>(
    a: [[T; N]; N],
    b: [T; N],
) -> Result<([T; N], T), Error<T>> {
    let (lu, pivots, scales, relative) = factor_lu(a)?;
    Ok((solve_factors(&lu, &pivots, scales, b), relative))
}

/// LU with partial pivoting on the scaled matrix: the factors, the pivots, the columns'
/// scales and the signed relative determinant.
#[allow(clippy::type_complexity)]
fn factor_lu<T: Real, const N: usize>(
    a: [[T; N]; N],
) -> Result<([[T; N]; N], [usize; N], [T; N], T), Error<T>> {
    let mut lu = a;
    let (columns, scales) = normalise(&mut lu)?;
    let mut pivots = [0; N];
    let determinant = eliminate(&mut lu, &mut pivots);
    let relative = check_determinant(determinant, columns)?;
    Ok((lu, pivots, scales, relative))
}

/// The solution of `a·x = b` from [`factor_lu`]'s factors of `a`.
fn solve_factors<T: Real, const N: usize>(
    lu: &[[T; N]; N],
    pivots: &[usize; N],
    scales: [T; N],
    b: [T; N],
) -> [T; N] {
    let mut x = b;
    // Whole rows were swapped while factoring, multipliers included: P·A = L·U.
    for (k, &pivot) in pivots.iter().enumerate() {
        swap(&mut x, k, pivot);
    }
    // Rows are zipped with `x`, and `x` read with `get`, rather than indexed with indices
    // the compiler cannot always bound: no bounds check, so no panic path, is left.
    for k in 0..N {
        let x_k = x[k];
        for (xi, row) in x.iter_mut().zip(lu).skip(k + 1) {
            *xi = *xi - row[k] * x_k;
        }
    }
    for (k, row) in lu.iter().enumerate().rev() {
        // (row[k], x[k]), then the entries right of the diagonal.
        let mut entries = row.iter().zip(&x).skip(k);
        if let Some((&diagonal, &x_k)) = entries.next() {
            let sum = entries.fold(x_k, |acc, (r, xj)| acc - *r * *xj);
            if let Some(x_k) = x.get_mut(k) {
                *x_k = sum / diagonal;
            }
        }
    }
    for (xi, scale) in x.iter_mut().zip(scales) {
        *xi = *xi * scale;
    }
    x
}

/// Swaps entries `i` and `j` of `v`, both in range (else it leaves `v` as it is): unlike
/// `<[T]>::swap`, with no panic path for the compiler to prove unreachable.
fn swap<T: Copy>(v: &mut [T], i: usize, j: usize) {
    if let (Some(&a), Some(&b)) = (v.get(i), v.get(j)) {
        if let Some(slot) = v.get_mut(i) {
            *slot = b;
        }
        if let Some(slot) = v.get_mut(j) {
            *slot = a;
        }
    }
}

/// Gaussian elimination with partial pivoting in place: `lu` becomes the multipliers below the
/// diagonal and U on and above it, `pivots[k]` the row swapped into row `k`. Returns the
/// determinant. Stops at a zero pivot (the determinant is then zero).
fn eliminate<T: Real, const N: usize>(lu: &mut [[T; N]; N], pivots: &mut [usize; N]) -> T {
    let mut determinant = T::one();
    for k in 0..N {
        // The first row at or below k with the largest magnitude in column k.
        let mut pivot_row = k;
        let mut largest = lu[k][k].abs();
        for (i, row) in lu.iter().enumerate().skip(k + 1) {
            if row[k].abs() > largest {
                pivot_row = i;
                largest = row[k].abs();
            }
        }
        pivots[k] = pivot_row;
        if pivot_row != k {
            swap(lu, k, pivot_row);
            determinant = -determinant;
        }
        let pivot = lu[k][k];
        determinant = determinant * pivot;
        if pivot == T::zero() {
            break;
        }
        let (upper, lower) = lu.split_at_mut(k + 1);
        for row in lower.iter_mut() {
            let factor = row[k] / pivot;
            row[k] = factor;
            for (entry, above) in row.iter_mut().zip(&upper[k]).skip(k + 1) {
                *entry = *entry - factor * *above;
            }
        }
    }
    determinant
}

/// A matrix factored once (LU with partial pivoting, on the stack) to solve for several
/// right-hand sides: the velocity's and the acceleration's share their Jacobian.
#[derive(Clone, Copy, Debug)]
pub struct Factored<T, const N: usize> {
    /// LU factors, or for a 2×2 matrix (which [`Factored::new`] always inverts) the inverse
    /// of the scaled matrix. No flag says which: an `Option` or `Result` of a `Factored`
    /// would keep its tag in the flag's byte, and the optimiser the factors in memory.
    lu: [[T; N]; N],
    pivots: [usize; N],
    /// The powers of two the matrix's columns were scaled by, for the solutions.
    scales: [T; N],
    /// The signed relative determinant.
    relative: T,
}

impl<T: Real, const N: usize> Factored<T, N> {
    /// Factors `a`. Errors: as [`solve_lu`] (a singular or non-finite matrix).
    pub fn new(a: [[T; N]; N]) -> Result<Self, Error<T>> {
        Self::new_with(a, Columns::FromMatrix)
    }

    /// [`Factored::new`], with a 2×2 matrix's column norms from `columns` where they are
    /// known (and their product's square is normal), else from the matrix.
    #[inline]
    pub fn new_with(a: [[T; N]; N], columns: Columns<T>) -> Result<Self, Error<T>> {
        if N == 2 {
            // Two unknowns (one loop): keep the inverse, by Cramer's rule.
            let (i, j) = (0, N - 1);
            // Scaled (by a power of two, so the inverse is the same, bit for bit, as at any
            // other scale) only where the squares would overflow or underflow.
            let mut a = a;
            let known = match columns {
                Columns::Known(known) => normal(known.product).then_some(known.norms),
                Columns::FromMatrix => None,
            };
            let (columns, scales) = match known
                .or_else(|| unscaled_columns2(&[[a[i][i], a[i][j]], [a[j][i], a[j][j]]]))
            {
                Some(columns) => (columns, [T::one(); N]),
                None => normalise(&mut a)?,
            };
            let determinant = a[i][i] * a[j][j] - a[i][j] * a[j][i];
            let relative = check_determinant(determinant, columns)?;
            let inverse = T::one() / determinant;
            let mut lu = a;
            lu[i][i] = a[j][j] * inverse;
            lu[i][j] = -a[i][j] * inverse;
            lu[j][i] = -a[j][i] * inverse;
            lu[j][j] = a[i][i] * inverse;
            return Ok(Factored {
                lu,
                pivots: [0; N],
                scales,
                relative,
            });
        }
        let (lu, pivots, scales, relative) = factor_lu(a)?;
        Ok(Factored {
            lu,
            pivots,
            scales,
            relative,
        })
    }

    /// [`Factored::new_with`] (with the same `columns`) where its verdict is certain without
    /// its square root and division (a 2×2 matrix that needs no scaling and whose relative
    /// determinant exceeds `2√ε`, tested on squares), else `None` and the caller asks
    /// [`Factored::new_with`]. The factors are
    /// `new_with`'s, bit for bit; the relative determinant is left to [`Quick::relative`] and
    /// [`Quick::finish`], which compute it as `new_with` does. Larger matrices are factored by
    /// `new` itself.
    #[inline(always)]
    pub(crate) fn quick_with(a: [[T; N]; N], columns: Columns<T>) -> Option<Quick<T, N>> {
        if N != 2 {
            let factored = Self::new(a).ok()?;
            return Some(Quick {
                factored,
                determinant: factored.relative,
                norms: Norms::Known(T::one()),
            });
        }
        let (i, j) = (0, N - 1);
        let (a00, a01, a10, a11) = (a[i][i], a[i][j], a[j][i], a[j][j]);
        let determinant = a00 * a11 - a01 * a10;
        // `unscaled_columns2`'s test: the squares neither overflow nor underflow (nor are NaN);
        // and |det|/√product > 2√ε, so `check_determinant`'s rounded ratio exceeds √ε (false
        // for NaN; an overflowing square is a determinant far from singular). A product that
        // overflows fails the last test (nothing exceeds `4ε·∞`), so it needs no test of its
        // own. The two together (`&`, not `&&`), for one branch; for a known product, which
        // the iteration does not change, one comparison against its bound, computed with it
        // ([`KnownColumns::new`]).
        let (norms, regular) = match columns {
            Columns::Known(known) => (
                Norms::Known(known.norms),
                determinant * determinant > known.bound,
            ),
            Columns::FromMatrix => {
                let product = (a00 * a00 + a10 * a10) * (a01 * a01 + a11 * a11);
                let four_epsilon = T::constant(4.0) * T::epsilon();
                let regular = (product >= T::min_positive_value())
                    & (determinant * determinant > four_epsilon * product);
                (Norms::OfProduct(product), regular)
            }
        };
        if !regular {
            return None;
        }
        let inverse = T::one() / determinant;
        let mut lu = a;
        lu[i][i] = a11 * inverse;
        lu[i][j] = -a01 * inverse;
        lu[j][i] = -a10 * inverse;
        lu[j][j] = a00 * inverse;
        Some(Quick {
            factored: Factored {
                lu,
                pivots: [0; N],
                scales: [T::one(); N],
                // Until `finish`.
                relative: T::zero(),
            },
            determinant,
            norms,
        })
    }

    /// The signed relative determinant, `det / Π‖column‖`: its sign is the matrix's
    /// orientation, its inverse magnitude the condition estimate.
    pub fn relative(&self) -> T {
        self.relative
    }

    /// How far each unknown may lie from the solution of `a·x = b` when component `k` of `b`
    /// may be off by `errors[k]`: `Σ_k |(a⁻¹)_ik|·errors[k]`, the bound that holds for every
    /// such error (not finite where it overflows: nothing is fixed there). The sweep reads it
    /// through `Kinematics::slope_within`.
    pub fn uncertainty(&self, errors: [T; N]) -> [T; N] {
        let mut bound = [T::zero(); N];
        for (k, error) in errors.into_iter().enumerate() {
            let mut unit = [T::zero(); N];
            unit[k] = error;
            for (b, v) in bound.iter_mut().zip(self.solve(unit)) {
                *b = *b + v.abs();
            }
        }
        bound
    }

    /// The solution of `a·x = b`.
    #[inline(always)]
    pub fn solve(&self, b: [T; N]) -> [T; N] {
        if N == 2 {
            // The explicit inverse of `new`'s 2×2 case: each row's two products summed (not
            // added to a zero first, which would cost an addition for the sign of a zero).
            let mut x = b;
            for ((xi, row), scale) in x.iter_mut().zip(&self.lu).zip(self.scales) {
                let mut products = row.iter().zip(&b).map(|(r, v)| *r * *v);
                if let Some(first) = products.next() {
                    *xi = products.fold(first, |acc, product| acc + product) * scale;
                }
            }
            return x;
        }
        solve_factors(&self.lu, &self.pivots, self.scales, b)
    }
}

/// A matrix factored by [`Factored::quick`], its relative determinant not yet computed.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Quick<T, const N: usize> {
    /// `relative` is not yet set for a 2×2 matrix.
    factored: Factored<T, N>,
    /// The determinant (for a larger matrix, the relative determinant).
    determinant: T,
    /// The column norms' product (for a larger matrix, 1).
    norms: Norms<T>,
}

/// [`Quick`]'s column norms' product: the square root of the squared norms' product, taken
/// only where the relative determinant is asked for, or known.
#[derive(Clone, Copy, Debug)]
enum Norms<T> {
    OfProduct(T),
    Known(T),
}

impl<T: Real, const N: usize> Quick<T, N> {
    /// The signed relative determinant, as [`Factored::new`] computes it.
    #[inline(always)]
    pub(crate) fn relative(&self) -> T {
        if N == 2 {
            // `check_determinant(determinant, unscaled_columns2(a))`.
            let norms = match self.norms {
                Norms::OfProduct(product) => product.sqrt(),
                Norms::Known(norms) => norms,
            };
            self.determinant / norms
        } else {
            self.factored.relative
        }
    }

    /// Whether the determinant is negative (the sign of [`Quick::relative`]), by its sign
    /// bit: a regular matrix's determinant is not zero, nor NaN, so this is `!(det > 0)`,
    /// and two signs compare as one exclusive or of their bits.
    #[inline(always)]
    pub(crate) fn negative(&self) -> bool {
        self.determinant.is_sign_negative()
    }

    /// The solution of `a·x = b`, as [`Factored::solve`].
    #[inline(always)]
    pub(crate) fn solve(&self, b: [T; N]) -> [T; N] {
        self.factored.solve(b)
    }

    /// What [`Factored::new`] returns for the matrix.
    #[inline(always)]
    pub(crate) fn finish(self) -> Factored<T, N> {
        Factored {
            relative: self.relative(),
            ..self.factored
        }
    }
}

/// The orientation of a square matrix, the sign of its determinant (`true` for positive),
/// or `None` where it is singular (or not finite), by the same test as the solvers.
pub fn orientation<T: Real, const N: usize>(a: [[T; N]; N]) -> Option<bool> {
    // Scaled as `solve_scaled` scales (only at the float's extremes), which keeps a matrix
    // near its largest from overflowing in the factoring.
    solve_scaled(a, [T::zero(); N])
        .ok()
        .map(|(_, factored, _)| factored.relative > T::zero())
}

/// The condition estimate of a Jacobian, `κ = Π‖column‖ / |det|`: 1 when the unknowns move
/// the loops in orthogonal directions, growing without bound toward a singular matrix
/// (infinite at one).
///
/// ```
/// assert_eq!(mechgen::condition([[2.0, 0.0], [0.0, 3.0]]), 1.0);
/// // Columns at 30°: κ = 1/sin(30°).
/// let (s, c) = 30f64.to_radians().sin_cos();
/// assert!((mechgen::condition([[1.0, c], [0.0, s]]) - 2.0).abs() < 1e-12);
/// assert_eq!(mechgen::condition([[1.0, 2.0], [2.0, 4.0]]), f64::INFINITY);
/// ```
pub fn condition<T: Real, const N: usize>(jacobian: [[T; N]; N]) -> T {
    let mut a = jacobian;
    let Ok((columns, _)) = normalise(&mut a) else {
        return T::infinity();
    };
    let mut pivots = [0; N];
    let determinant = eliminate(&mut a, &mut pivots);
    columns / determinant.abs()
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
        for x in [[0.5, -1.5], [2.0, 0.25]] {
            assert_close(solve2(a, multiply(&a, &x)).unwrap().0, x);
        }
    }

    #[test]
    fn lu_recovers_known_solution() {
        let b = multiply(&A3, &X3);
        assert_close(solve_lu(A3, b).unwrap().0, X3);
        let a2 = [[3.0, 1.0], [-2.0, 4.0]];
        let x2 = [0.5, -1.5];
        assert_close(solve_lu(a2, multiply(&a2, &x2)).unwrap().0, x2);
    }

    #[test]
    fn extreme_scales_neither_overflow_nor_underflow() {
        // Row norms whose product overflows f32 (or underflows), with a well-conditioned
        // matrix: the scaled determinant is 1, so both solve.
        for scale in [1e25f32, 1e-25] {
            let a = [[scale, 0.0], [0.0, scale]];
            let (x, _) = solve2(a, [scale, 2.0 * scale]).unwrap();
            assert_eq!(x, [1.0, 2.0]);
            let a4 = [
                [scale, 0.0, 0.0, 0.0],
                [0.0, scale, 0.0, 0.0],
                [0.0, 0.0, scale, 0.0],
                [0.0, 0.0, 0.0, scale],
            ];
            let (x, _) = solve_lu(a4, [scale; 4]).unwrap();
            assert_eq!(x, [1.0; 4]);
        }
    }

    #[test]
    fn a_factored_matrix_solves_several_right_hand_sides() {
        let factored = Factored::new(A3).unwrap();
        assert_close(factored.solve(multiply(&A3, &X3)), X3);
        let other = [0.5, 0.0, -3.0];
        assert_close(factored.solve(multiply(&A3, &other)), other);
        let pivoting = [[0.0, 1.0], [2.0, 3.0]];
        assert_close(
            Factored::new(pivoting)
                .unwrap()
                .solve(multiply(&pivoting, &[1.0, -1.0])),
            [1.0, -1.0],
        );
        assert!(Factored::new([[1.0, 2.0], [2.0, 4.0]]).is_err());
    }

    #[test]
    fn lu_pivots_on_the_first_of_equal_candidates() {
        // Column 0 has 1 in rows 0 and 1: row 0 stays; then column 1 below it has −2 and 2
        // (after elimination): row 1 stays.
        let a = [[1.0, 1.0, 0.0], [1.0, -1.0, 1.0], [0.0, 2.0, 1.0]];
        let (_, pivots, _, _) = factor_lu(a).unwrap();
        assert_eq!(pivots, [0, 1, 2]);
        let x = [1.0, 2.0, -1.0];
        assert_close(solve_lu(a, multiply(&a, &x)).unwrap().0, x);
        // A larger entry below is taken.
        let (_, pivots, _, _) = factor_lu([[1.0, 0.0], [-2.0, 1.0]]).unwrap();
        assert_eq!(pivots, [1, 1]);
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
        assert_close(solve_lu(a, multiply(&a, &x)).unwrap().0, x);
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
        let zero_row = [[1.0, 2.0], [0.0, 0.0]];
        assert!(matches!(
            solve2(zero_row, [1.0; 2]),
            Err(Error::Singular { .. })
        ));
        assert!(matches!(
            solve_lu(dependent, [1.0; 3]),
            Err(Error::Singular { .. })
        ));
    }

    /// `a`'s factors, its relative determinant and its solutions of two right-hand sides, bit
    /// for bit.
    fn bits<const N: usize>(factored: &Factored<f64, N>) -> ([u64; N], [u64; N], u64) {
        let mut b = [1.0; N];
        b[0] = -2.0;
        (
            factored.solve(b).map(f64::to_bits),
            factored.solve([0.5; N]).map(f64::to_bits),
            factored.relative().to_bits(),
        )
    }

    #[test]
    fn every_solver_returns_the_signed_relative_determinant() {
        // det 14 over column norms √13·√17.
        let a = [[3.0, 1.0], [-2.0, 4.0]];
        let relative = 14.0 / 221f64.sqrt();
        let b = [1.0, 1.0];
        assert_eq!(solve2(a, b).unwrap().1, relative);
        assert!((solve_lu(a, b).unwrap().1 - relative).abs() < 1e-15);
        assert_eq!(Factored::new(a).unwrap().relative(), relative);
        let swapped = [[1.0, 3.0], [4.0, -2.0]];
        assert_eq!(solve2(swapped, b).unwrap().1, -relative);
        // det 25 over column norms √5·√26·√5.25.
        let relative3 = 25.0 / 682.5f64.sqrt();
        assert!((solve_lu(A3, [1.0; 3]).unwrap().1 - relative3).abs() < 1e-15);
        assert!((Factored::new(A3).unwrap().relative() - relative3).abs() < 1e-15);
        assert!((condition(A3) - 1.0 / relative3).abs() < 1e-13);
        assert_eq!(orientation(A3), Some(true));
        assert_eq!(orientation([A3[1], A3[0], A3[2]]), Some(false));
        assert_eq!(orientation(swapped), Some(false));
        assert_eq!(orientation([[1.0, 2.0], [2.0, 4.0]]), None);
        assert_eq!(condition([[1.0, 0.0], [0.0, 0.0]]), f64::INFINITY);
        assert_eq!(condition([[f64::NAN, 0.0], [0.0, 1.0]]), f64::INFINITY);
    }

    #[test]
    fn singular_means_a_relative_determinant_at_or_below_the_square_root_of_epsilon() {
        // Columns of norm 1 (to rounding) whose determinant is √ε = 2⁻²⁶, then 2⁻²⁵.
        let at = [[1.0, 1.0], [0.0, f64::EPSILON.sqrt()]];
        let above = [[1.0, 1.0], [0.0, 2.0 * f64::EPSILON.sqrt()]];
        let singular = Err(Error::Singular {
            determinant: f64::EPSILON.sqrt(),
            relative_determinant: f64::EPSILON.sqrt(),
        });
        assert_eq!(solve2(at, [1.0, 1.0]).map(|(_, r)| r), singular);
        assert_eq!(Factored::new(at).map(|f| f.relative()), singular);
        let twice = 2.0 * f64::EPSILON.sqrt();
        assert!((solve2(above, [1.0, 1.0]).unwrap().1 - twice).abs() <= 1e-12 * twice);
        assert!(Factored::new(above).is_ok());
        let at3 = [
            [1.0, 1.0, 0.0],
            [0.0, f64::EPSILON.sqrt(), 0.0],
            [0.0, 0.0, 1.0],
        ];
        assert!(matches!(
            solve_lu(at3, [1.0; 3]),
            Err(Error::Singular { .. })
        ));
        let above3 = [
            [1.0, 1.0, 0.0],
            [0.0, 2.0 * f64::EPSILON.sqrt(), 0.0],
            [0.0, 0.0, 1.0],
        ];
        assert!((solve_lu(above3, [1.0; 3]).unwrap().1 - twice).abs() <= 1e-12 * twice);
    }

    #[test]
    fn scaled_and_unscaled_systems_solve_alike() {
        // Entries whose squares overflow, underflow, or neither: the same solution, scaled.
        let a = [[3.0, 1.0], [-2.0, 4.0]];
        let x = [0.5, -1.5];
        let b = multiply(&a, &x);
        for scale in [2f64.powi(600), 2f64.powi(-600), 1.0] {
            let scaled_a = a.map(|row| row.map(|v| v * scale));
            let (solved, relative) = solve2(scaled_a, b.map(|v| v * scale)).unwrap();
            assert_close(solved, x);
            assert!((relative - 14.0 / 221f64.sqrt()).abs() < 1e-15);
            let factored = Factored::new(scaled_a).unwrap();
            assert_close(factored.solve(b.map(|v| v * scale)), x);
            assert!((factored.relative() - 14.0 / 221f64.sqrt()).abs() < 1e-15);
            let (solved, _) = solve_lu(scaled_a, b.map(|v| v * scale)).unwrap();
            assert_close(solved, x);
        }
        // Columns of very different sizes (an angle's column beside a length's).
        let mixed = [[2f64.powi(600), 1.0], [0.0, 1.0]];
        let (solved, relative) = solve2(mixed, [2f64.powi(600), 1.0]).unwrap();
        assert_eq!(solved, [1.0 - 2f64.powi(-600), 1.0]);
        assert!((relative - 0.5f64.sqrt()).abs() < 1e-15);
        let columns = [
            [2f64.powi(600), 0.0, 0.0],
            [0.0, 2f64.powi(-600), 0.0],
            [0.0, 0.0, 1.0],
        ];
        let (solved, relative) = solve_lu(columns, [2f64.powi(600), 2f64.powi(-600), 3.0]).unwrap();
        assert_eq!((solved, relative), ([1.0, 1.0, 3.0], 1.0));
    }

    #[test]
    fn non_finite_right_hand_sides_and_zero_columns_are_errors() {
        let a = [[3.0, 1.0], [-2.0, 4.0]];
        assert_eq!(
            solve2(a, [1.0, f64::INFINITY]),
            Err(Error::NonFinite {
                quantity: "linear system"
            })
        );
        let zero_column = [[1.0, 0.0, 2.0], [3.0, 0.0, 4.0], [5.0, 0.0, 6.0]];
        assert_eq!(
            solve_lu(zero_column, [1.0; 3]).map(|(_, r)| r),
            Err(Error::Singular {
                determinant: 0.0,
                relative_determinant: 0.0
            })
        );
        let infinite = [[1.0, 0.0, 2.0], [3.0, f64::INFINITY, 4.0], [5.0, 0.0, 6.0]];
        assert_eq!(
            solve_lu(infinite, [1.0; 3]).map(|(_, r)| r),
            Err(Error::NonFinite {
                quantity: "linear system"
            })
        );
    }

    #[test]
    fn quick_factors_are_new_factors_or_none() {
        for a in [
            [[3.0f64, 1.0], [-2.0, 4.0]],
            [[1.0, 3.0], [4.0, -2.0]],
            [[0.0, 1.0], [2.0, 3.0]],
        ] {
            let quick = Factored::quick_with(a, Columns::FromMatrix).expect("regular and unscaled");
            let new = Factored::new(a).unwrap();
            assert_eq!(quick.negative(), new.relative() < 0.0);
            assert_eq!(quick.relative().to_bits(), new.relative().to_bits());
            assert_eq!(
                quick.solve([1.0, -2.0]).map(f64::to_bits),
                new.solve([1.0, -2.0]).map(f64::to_bits)
            );
            assert_eq!(bits(&quick.finish()), bits(&new));
        }
        // Larger matrices are `new`'s, and a singular one is none.
        let quick = Factored::quick_with(A3, Columns::FromMatrix).unwrap();
        assert_eq!(bits(&quick.finish()), bits(&Factored::new(A3).unwrap()));
        assert_eq!(quick.relative(), Factored::new(A3).unwrap().relative());
        assert!(
            Factored::quick_with(
                [[1.0, 2.0, 3.0], [2.0, 4.0, 6.0], [0.0, 1.0, 1.0]],
                Columns::FromMatrix
            )
            .is_none()
        );
        // Near singular (relative determinant 2√ε and below), in need of scaling, or not
        // finite: left to `new`.
        let e = f64::EPSILON.sqrt();
        for a in [
            [[1.0, 1.0], [0.0, 2.0 * e]],
            [[1.0, 1.0], [0.0, e]],
            [[1.0, 2.0], [2.0, 4.0]],
            [[2f64.powi(600), 0.0], [0.0, 1.0]],
            [[2f64.powi(-600), 0.0], [0.0, 1.0]],
            [[f64::NAN, 0.0], [0.0, 1.0]],
        ] {
            assert!(
                Factored::quick_with(a, Columns::FromMatrix).is_none(),
                "{a:?}"
            );
        }
        assert!(Factored::quick_with([[1.0, 1.0], [0.0, 4.0 * e]], Columns::FromMatrix).is_some());
    }

    /// Known column norms stand in for the computed ones in the relative determinant and the
    /// regularity test, the same in `quick_with` and `new_with`; a known product that is not
    /// normal is not used (`new_with` computes the norms, scaling as `new` does, and
    /// `quick_with` leaves the matrix to it). The factors are the matrix's either way.
    #[test]
    fn known_columns_are_read_where_their_product_is_normal() {
        // Columns of lengths 2 and 3 (a loop's vectors turned), rounded a little: the known
        // product is the exact lengths' 36.
        let a: [[f64; 2]; 2] = [[2.0 * 0.6, -3.0 * 0.8], [2.0 * 0.8, 3.0 * 0.6]];
        let known = Columns::known(36.0);
        let new = Factored::new_with(a, known).unwrap();
        let quick = Factored::quick_with(a, known).unwrap();
        let determinant = a[0][0] * a[1][1] - a[0][1] * a[1][0];
        assert_eq!(new.relative(), determinant / 6.0);
        assert_eq!(quick.relative().to_bits(), new.relative().to_bits());
        assert_eq!(bits(&quick.finish()), bits(&new));
        assert_eq!(
            new.solve([1.0, 2.0]).map(f64::to_bits),
            Factored::new(a)
                .unwrap()
                .solve([1.0, 2.0])
                .map(f64::to_bits)
        );
        // The regularity test against the known product: a matrix whose own columns would
        // pass is singular against columns said to be far longer.
        assert!(Factored::quick_with(a, Columns::known(1e40)).is_none());
        assert!(matches!(
            Factored::new_with(a, Columns::known(1e40)),
            Err(Error::Singular { .. })
        ));
        // The bound is 4ε times the product, passed only above it: a determinant of 2⁻²⁰
        // against a product of 2¹⁰ sits on it (its square is 2⁻⁴⁰ = 4ε·2¹⁰), and one of 1e-9
        // against 1 is below it.
        let on_bound = [[1.0, 0.0], [0.0, 2f64.powi(-20)]];
        assert!(Factored::quick_with(on_bound, Columns::known(1024.0)).is_none());
        assert!(Factored::quick_with(on_bound, Columns::known(1023.0)).is_some());
        assert!(Factored::quick_with([[1.0, 1.0], [0.0, 1e-9]], Columns::known(1.0)).is_none());
        // Not normal (overflowed, underflowed, NaN): the matrix's own norms.
        for product in [f64::INFINITY, 0.0, 1e-320, f64::NAN] {
            let unknown = Columns::known(product);
            assert!(Factored::quick_with(a, unknown).is_none(), "{product}");
            assert_eq!(
                bits(&Factored::new_with(a, unknown).unwrap()),
                bits(&Factored::new(a).unwrap()),
                "{product}"
            );
        }
    }

    /// Solved scaled, a system gives the unscaled solution's bits where that is finite, and
    /// the same solution near the float's largest, where the unscaled solve overflows; the
    /// orientation too, and the uncertainty of errors scaled alike.
    #[test]
    fn a_scaled_solve_is_the_solve_at_any_size() {
        let a = [[3.0, -1.0, 0.5], [1.0, 2.0, -2.0], [0.25, 1.0, 4.0]];
        let b = [1.0, -2.0, 3.0];
        let (x, factored, scale) = solve_scaled(a, b).unwrap();
        // Not scaled at an ordinary size (its largest entry, 4, is not in [1/2, 1)).
        assert_eq!(scale, 1.0);
        let plain = Factored::new(a).unwrap();
        assert_eq!(
            bits(&factored),
            bits(&Factored::new(a.map(|r| r.map(|v| v * scale))).unwrap())
        );
        assert_eq!(x.map(f64::to_bits), plain.solve(b).map(f64::to_bits));
        assert_eq!(
            factored.uncertainty([1e-3 * scale; 3]).map(f64::to_bits),
            plain.uncertainty([1e-3; 3]).map(f64::to_bits)
        );
        assert_eq!(orientation(a), Some(true));
        // A solution of 20 from a matrix of 2^1020 and a right-hand side of 2^1021, whose
        // unscaled solve sums products of 10·2^1021, past the largest float.
        let big = 2f64.powi(1020);
        let near = [[big, 0.9 * big], [0.9 * big, big]];
        let b = [2.0 * big, -2.0 * big];
        assert!(
            Factored::new(near)
                .unwrap()
                .solve(b)
                .iter()
                .any(|v| !v.is_finite())
        );
        let (x, _, scale) = solve_scaled(near, b).unwrap();
        assert!(scale < 2f64.powi(-1000), "{scale:e}");
        let expected = solve_scaled([[1.0, 0.9], [0.9, 1.0]], [2.0, -2.0])
            .unwrap()
            .0;
        assert_eq!(x.map(f64::to_bits), expected.map(f64::to_bits));
        assert!(
            (x[0] - 20.0).abs() < 1e-13 && (x[1] + 20.0).abs() < 1e-13,
            "{x:?}"
        );
        assert_eq!(orientation(near), Some(true));
        // At the other extreme, scaled up: the same solution.
        let tiny = 2f64.powi(-1000);
        let small = near.map(|r| r.map(|v| v / big * tiny));
        let (x, _, scale) = solve_scaled(small, [2.0 * tiny, -2.0 * tiny]).unwrap();
        assert!(scale > 2f64.powi(990), "{scale:e}");
        assert_eq!(x.map(f64::to_bits), expected.map(f64::to_bits));
        // Not finite: refused, as unscaled.
        assert!(solve_scaled([[f64::INFINITY, 0.0], [0.0, 1.0]], [1.0, 1.0]).is_err());
        assert!(solve_scaled([[f64::NAN, 0.0], [0.0, 1.0]], [1.0, 1.0]).is_err());
    }

    /// Row sums of the inverse's magnitudes, times the errors: for a 2×2 matrix (its kept
    /// inverse) and a 3×3 one (LU), with a column scaled by a power of two.
    #[test]
    fn uncertainty_is_the_inverse_rows_magnitudes_times_the_error() {
        // Inverse [[1, −1], [0, 0.5]].
        let two = Factored::new([[1.0, 2.0], [0.0, 2.0]]).unwrap();
        assert_eq!(two.uncertainty([1.0, 1.0]), [2.0, 0.5]);
        assert_eq!(two.uncertainty([3.0, 3.0]), [6.0, 1.5]);
        // Each component's error through its own column of the inverse.
        assert_eq!(two.uncertainty([0.0, 4.0]), [4.0, 2.0]);
        // Inverse [[0.5, 0, 0], [0, 1, −1], [0, 0, 1]], then the first column scaled by 2⁻⁶⁰⁰
        // (its unknown's row by 2⁶⁰⁰), which LU scales back.
        let tiny = 2f64.powi(-600);
        let three =
            Factored::new([[2.0 * tiny, 0.0, 0.0], [0.0, 1.0, 1.0], [0.0, 0.0, 1.0]]).unwrap();
        assert_eq!(three.uncertainty([0.25; 3]), [0.125 / tiny, 0.5, 0.25]);
        // An error too large for the float: nothing is fixed.
        assert!(two.uncertainty([f64::MAX; 2])[0].is_infinite());
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
