//! Assembly branches.

/// Which of a loop's two assemblies to take at a given input.
///
/// A loop with two unknowns closes in two ways where it closes at all (a circle meets a circle
/// or a line twice). Each mechanism documents which geometric sign tells its branches apart;
/// for the four-bar it is the side of the coupler the rocker lies on, so the branch does not
/// change as the crank turns, only at a toggle where the two assemblies meet.
///
/// ```
/// use mechgen::Branch;
/// assert_eq!(Branch::Open.other(), Branch::Crossed);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Branch {
    /// The open (uncrossed) assembly.
    Open,
    /// The crossed assembly.
    Crossed,
}

impl Branch {
    /// The other branch.
    ///
    /// ```
    /// use mechgen::Branch;
    /// assert_eq!(Branch::Crossed.other(), Branch::Open);
    /// ```
    pub fn other(self) -> Self {
        match self {
            Branch::Open => Branch::Crossed,
            Branch::Crossed => Branch::Open,
        }
    }

    /// The branch whose defining sign is `sign` (positive or zero: open).
    ///
    /// ```
    /// use mechgen::Branch;
    /// assert_eq!(Branch::from_sign(0.3), Branch::Open);
    /// assert_eq!(Branch::from_sign(-0.3), Branch::Crossed);
    /// ```
    pub fn from_sign<T: crate::Real>(sign: T) -> Self {
        if sign >= T::zero() {
            Branch::Open
        } else {
            Branch::Crossed
        }
    }

    /// `+1` for open, `-1` for crossed.
    ///
    /// ```
    /// use mechgen::Branch;
    /// assert_eq!(Branch::Crossed.sign::<f64>(), -1.0);
    /// ```
    pub fn sign<T: crate::Real>(self) -> T {
        match self {
            Branch::Open => T::one(),
            Branch::Crossed => -T::one(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_zero_sign_is_open_and_each_branch_has_its_sign() {
        assert_eq!(Branch::from_sign(0.0), Branch::Open);
        assert_eq!(Branch::from_sign(-0.0f32), Branch::Open);
        assert_eq!(Branch::from_sign(-1e-300), Branch::Crossed);
        assert_eq!(Branch::Open.sign::<f64>(), 1.0);
        assert_eq!(Branch::Crossed.sign::<f32>(), -1.0);
        assert_eq!(Branch::Open.other(), Branch::Crossed);
        assert_eq!(Branch::Crossed.other(), Branch::Open);
    }
}
