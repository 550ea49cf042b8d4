//! The mechanism's equations as expressions: loop residuals, their derivatives, and the
//! right-hand sides of the velocity and acceleration solves.

mod angles;
mod closed_form;
mod equations;
mod graph;
mod reduction;
mod rewrite;
mod straight;

pub use closed_form::{Case, Step};
pub use equations::{Equations, PointExprs, Sensitivities};
pub use graph::{ExprId, Graph, Node, Var};
pub use reduction::Reduction;
pub use straight::{AuxKind, Straight, Threshold};
