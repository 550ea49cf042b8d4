//! The mechanism's equations as expressions: loop residuals, their derivatives, and the
//! right-hand sides of the velocity and acceleration solves.

mod closed_form;
mod equations;
mod graph;

pub use closed_form::{Case, Step};
pub use equations::{Equations, PointExprs};
pub use graph::{ExprId, Graph, Node, Var};
