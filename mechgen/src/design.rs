//! What design by gradients (tolerance analysis, dimensional synthesis) needs of a
//! mechanism, whatever it is: its dimensions as an array, and the derivatives of its
//! unknowns and tracked points with respect to them.

use crate::{Error, Real, Vec2};

/// A mechanism's dimensions and their sensitivities, as arrays in declaration order: `N`
/// unknowns, `P` parameters, `M` tracked points. Generated code implements it for every
/// declaration that asks for sensitivities (`generate: …, sensitivities`), so that a design
/// method written once (such as `mechanisms::synthesis::fit`) serves every mechanism.
///
/// ```
/// use mechgen::{Design, mechanism};
/// mechanism! {
///     pub struct FourBar {
///         params: l1, l2, l3, l4;
///         input: theta2: angle;
///         unknowns: theta3: angle, theta4: angle;
///         loop: l2 @ theta2 + l3 @ theta3 - l4 @ theta4 - l1 @ 0;
///         point b = l1 @ 0 + l4 @ theta4;
///         generate: position, velocity, sensitivities;
///     }
/// }
/// let linkage = FourBar { l1: 180.0, l2: 80.0, l3: 200.0, l4: 150.0 };
/// assert_eq!(FourBar::<f64>::PARAMETERS, ["l1", "l2", "l3", "l4"]);
/// assert_eq!(linkage.parameters(), [180.0, 80.0, 200.0, 150.0]);
/// let longer = FourBar::with_parameters([180.0, 80.0, 210.0, 150.0]);
/// assert_eq!(longer.l3, 210.0);
/// ```
pub trait Design<T: Real, const N: usize, const P: usize, const M: usize>: Sized {
    /// The parameters' names, in declaration order.
    const PARAMETERS: [&'static str; P];
    /// Which parameters are lengths (the others are angles).
    const PARAMETER_LENGTHS: [bool; P];
    /// Which unknowns are angles (the others are lengths).
    const UNKNOWN_ANGLES: [bool; N];

    /// The parameters' values, in declaration order.
    fn parameters(&self) -> [T; P];

    /// The mechanism with these parameters, in declaration order (unchecked, as a struct
    /// literal is).
    fn with_parameters(values: [T; P]) -> Self;

    /// `∂q/∂p` at a solved `position` (the generated `sensitivities`): for each parameter,
    /// the unknowns' derivatives.
    fn unknown_sensitivities(&self, input: T, position: [T; N]) -> Result<[[T; N]; P], Error<T>>;

    /// The tracked points at `position` (the generated `points`), in declaration order.
    fn point_positions(&self, input: T, position: [T; N]) -> Result<[Vec2<T>; M], Error<T>>;

    /// `∂P/∂p` at a solved `position` (the generated `point_sensitivities`): for each
    /// parameter, the points' derivatives.
    fn point_sensitivities(
        &self,
        input: T,
        position: [T; N],
    ) -> Result<[[Vec2<T>; M]; P], Error<T>>;
}
