//! Builds every expression the generated code evaluates from the model's vector sums.
//!
//! Velocity and acceleration come from differentiating the loop equations in time, so the
//! centripetal, Coriolis and sliding terms fall out of the chain rule and no mechanism
//! needs them written by hand. With `f(q, u) = 0` (unknowns `q`, input `u`):
//! - velocity: `J·q̇ = -∂f/∂u·u̇`;
//! - acceleration: `J·q̈ = -(d/dt(J·q̇ + ∂f/∂u·u̇) with q̈ = 0)`.

use crate::model::{Model, SymbolRef, VectorSum};

use super::graph::{ExprId, Graph, Var};
use super::straight::{SceneExprs, Straight};

/// A tracked point's position, velocity and acceleration as `(x, y)` expressions, and its
/// acceleration split into tangential, normal, sliding and Coriolis parts.
pub struct PointExprs {
    pub position: [ExprId; 2],
    pub velocity: [ExprId; 2],
    pub acceleration: [ExprId; 2],
    /// `[tangential, normal, sliding, coriolis]`, each `(x, y)`.
    pub acceleration_parts: [[ExprId; 2]; 4],
}

pub struct Equations {
    pub graph: Graph,
    /// Loop residuals: loop k gives rows 2k (x) and 2k+1 (y).
    pub residual: Vec<ExprId>,
    /// `∂residual/∂unknowns`, row-major.
    pub jacobian: Vec<Vec<ExprId>>,
    /// `∂residual/∂inputs`, row-major (a row per residual, a column per input).
    pub input_jacobian: Vec<Vec<ExprId>>,
    /// `-∂f/∂u·u̇`: the velocity solve's right-hand side.
    pub velocity_rhs: Vec<ExprId>,
    /// The acceleration solve's right-hand side.
    pub acceleration_rhs: Vec<ExprId>,
    /// The magnitude of every loop term, whose absolute sum scales the residual's rounding.
    pub magnitudes: Vec<ExprId>,
    /// The loop each of `magnitudes` belongs to: a loop's own sum is the rounding its two
    /// residual rows can close to.
    pub magnitude_loops: Vec<usize>,
    pub points: Vec<PointExprs>,
    /// What the sensitivities to the parameters solve, where the declaration asks for them.
    pub sensitivities: Option<Sensitivities>,
    /// The loops in the order they solve in closed form, if every one does; otherwise the
    /// loop that does not, and why.
    pub closed_form: Result<Vec<super::closed_form::Step>, super::closed_form::Missing>,
    /// Without a closed form, the fewest unknowns Newton can iterate on, the rest solved in
    /// closed form inside each evaluation, if the loops allow it.
    pub reduction: Option<super::reduction::Reduction>,
    /// What scene kernels evaluate, when the declaration has scenes and a closed form.
    pub scenes: Option<Straight>,
}

/// The derivatives of the loops and the points with respect to the parameters:
/// `J·∂q/∂p = −∂f/∂p` gives the unknowns' sensitivity to each parameter `p` at a solved
/// position, and `dP/dp = ∂P/∂p + Σ ∂P/∂q_j·∂q_j/∂p` each point's.
pub struct Sensitivities {
    /// For each parameter, `−∂f/∂p`: one right-hand side per parameter, row by row.
    pub rhs: Vec<Vec<ExprId>>,
    /// For each point and each coordinate (`x`, `y`), `∂P/∂p` for each parameter.
    pub point_parameters: Vec<[Vec<ExprId>; 2]>,
    /// For each point and each coordinate, `∂P/∂q_j` for each unknown.
    pub point_unknowns: Vec<[Vec<ExprId>; 2]>,
}

impl Sensitivities {
    fn derive(
        graph: &mut Graph,
        model: &Model,
        residual: &[ExprId],
        points: &[PointExprs],
    ) -> Self {
        let parameters: Vec<Var> = (0..model.params.len())
            .map(|i| Var::Value(SymbolRef::Param(i)))
            .collect();
        let unknowns: Vec<Var> = (0..model.unknowns.len())
            .map(|i| Var::Value(SymbolRef::Unknown(i)))
            .collect();
        let rhs = parameters
            .iter()
            .map(|&p| {
                residual
                    .iter()
                    .map(|&f| {
                        let partial = graph.partial(f, p);
                        graph.neg(partial)
                    })
                    .collect()
            })
            .collect();
        let mut partials = |vars: &[Var]| -> Vec<[Vec<ExprId>; 2]> {
            points
                .iter()
                .map(|point| {
                    point
                        .position
                        .map(|c| vars.iter().map(|&v| graph.partial(c, v)).collect())
                })
                .collect()
        };
        Sensitivities {
            point_parameters: partials(&parameters),
            point_unknowns: partials(&unknowns),
            rhs,
        }
    }
}

impl Equations {
    pub fn derive(model: &Model) -> Self {
        let mut graph = Graph::default();
        let mut magnitudes = Vec::new();
        let mut magnitude_loops = Vec::new();
        let mut residual = Vec::new();
        for (index, loop_sum) in model.loops.iter().enumerate() {
            let [x, y] = vector_sum(&mut graph, loop_sum, &mut magnitudes);
            magnitude_loops.resize(magnitudes.len(), index);
            residual.extend([x, y]);
        }

        let unknowns: Vec<Var> = (0..model.unknowns.len())
            .map(|i| Var::Value(SymbolRef::Unknown(i)))
            .collect();
        let inputs: Vec<Var> = (0..model.inputs.len())
            .map(|i| Var::Value(SymbolRef::Input(i)))
            .collect();
        let jacobian: Vec<Vec<ExprId>> = residual
            .iter()
            .map(|&f| unknowns.iter().map(|&q| graph.partial(f, q)).collect())
            .collect();
        // Each row's partial derivatives by the inputs, in their order.
        let input_jacobian: Vec<Vec<ExprId>> = residual
            .iter()
            .map(|&f| inputs.iter().map(|&u| graph.partial(f, u)).collect())
            .collect();

        // −Σ ∂f/∂u·u̇ over the inputs.
        let input_rates: Vec<ExprId> = (0..model.inputs.len())
            .map(|i| graph.var(Var::Rate(SymbolRef::Input(i))))
            .collect();
        let velocity_rhs: Vec<ExprId> = input_jacobian
            .iter()
            .map(|row| {
                let mut sum = None;
                for (&fu, &rate) in row.iter().zip(&input_rates) {
                    let product = graph.mul(fu, rate);
                    sum = Some(match sum {
                        None => product,
                        Some(sum) => graph.add(sum, product),
                    });
                }
                let sum = sum.expect("a mechanism has an input");
                graph.neg(sum)
            })
            .collect();

        // Every variable a loop can depend on, in a fixed order so expansions are stable.
        let position_vars: Vec<Var> = inputs.iter().chain(unknowns.iter()).copied().collect();
        let rate_vars: Vec<Var> = position_vars
            .iter()
            .filter_map(|v| v.time_derivative())
            .collect();
        let all_vars: Vec<Var> = position_vars.iter().chain(&rate_vars).copied().collect();
        let unknown_accel = |v: Var| matches!(v, Var::Accel(SymbolRef::Unknown(_)));

        let acceleration_rhs: Vec<ExprId> = residual
            .iter()
            .map(|&f| {
                // d/dt f = J·q̇ + ∂f/∂u·u̇; differentiate once more with q̈ left out.
                let velocity_residual = graph.time_derivative(f, &position_vars, |_| true);
                let derivative =
                    graph.time_derivative(velocity_residual, &all_vars, |v| !unknown_accel(v));
                graph.neg(derivative)
            })
            .collect();

        let mut point_magnitudes = Vec::new();
        let points: Vec<PointExprs> = model
            .points
            .iter()
            .map(|point| {
                let position = vector_sum(&mut graph, &point.position, &mut point_magnitudes);
                let velocity = position.map(|p| graph.time_derivative(p, &position_vars, |_| true));
                let acceleration = velocity.map(|v| graph.time_derivative(v, &all_vars, |_| true));
                let acceleration_parts =
                    acceleration_parts(&mut graph, &point.position, &position_vars, &all_vars);
                PointExprs {
                    position,
                    velocity,
                    acceleration,
                    acceleration_parts,
                }
            })
            .collect();

        let closed_form = super::closed_form::plan(model, &mut graph);
        let reduction = closed_form.is_err().then(|| {
            let full = super::reduction::Full {
                residual: &residual,
                jacobian: &jacobian,
                velocity_rhs: &velocity_rhs,
                acceleration_rhs: &acceleration_rhs,
            };
            super::reduction::find(model, &mut graph, &full)
        });
        let scenes = match &closed_form {
            Ok(steps) if !model.scenes.is_empty() => {
                graph.group_fixed_factors();
                let mut expand = |roots: &[ExprId]| super::angles::expand(&mut graph, roots);
                Some(SceneExprs {
                    coefficients: steps
                        .iter()
                        .map(|s| expand(&s.case.coefficients()))
                        .collect(),
                    jacobian: expand(&jacobian.concat()),
                    velocity_rhs: expand(&velocity_rhs),
                    acceleration_rhs: expand(&acceleration_rhs),
                    points: points
                        .iter()
                        .map(|p: &PointExprs| {
                            [p.position, p.velocity, p.acceleration].map(|v| {
                                let e = expand(&v);
                                [e[0], e[1]]
                            })
                        })
                        .collect(),
                })
            }
            _ => None,
        };
        let scenes = scenes.map(|exprs| {
            let steps = closed_form.as_deref().unwrap_or_default();
            let lengths: Vec<bool> = model
                .unknowns
                .iter()
                .map(|unknown| unknown.kind == crate::model::Kind::Length)
                .collect();
            super::straight::build(&mut graph, steps, &exprs, &lengths)
        });
        // Last, so that the other functions' expressions keep their order in the graph.
        let sensitivities = model
            .outputs
            .sensitivities
            .then(|| Sensitivities::derive(&mut graph, model, &residual, &points));
        Equations {
            sensitivities,
            closed_form,
            reduction: reduction.flatten(),
            scenes,
            graph,
            residual,
            jacobian,
            input_jacobian,
            velocity_rhs,
            acceleration_rhs,
            magnitudes,
            magnitude_loops,
            points,
        }
    }
}

/// `Σ ± r·(cos θ, sin θ)`, recording each magnitude `r`.
fn vector_sum(graph: &mut Graph, sum: &VectorSum, magnitudes: &mut Vec<ExprId>) -> [ExprId; 2] {
    let zero = graph.constant(0.0);
    let mut components = [zero, zero];
    for term in &sum.terms {
        let magnitude = graph.linear(&term.magnitude);
        let angle = graph.linear(&term.angle);
        magnitudes.push(magnitude);
        let cosine = graph.cos(angle);
        let sine = graph.sin(angle);
        for (component, unit) in components.iter_mut().zip([cosine, sine]) {
            let part = graph.mul(magnitude, unit);
            *component = if term.negated {
                graph.sub(*component, part)
            } else {
                graph.add(*component, part)
            };
        }
    }
    components
}

/// The parts of `d²/dt² Σ ± r·e^{iθ}`, term by term: for each `r·e^{iθ}`,
/// `(r̈ − r·θ̇²)·e^{iθ} + i·(r·θ̈ + 2·ṙ·θ̇)·e^{iθ}`, grouped as tangential `i·r·θ̈·e^{iθ}`,
/// normal `−r·θ̇²·e^{iθ}`, sliding `r̈·e^{iθ}` and Coriolis `2·i·ṙ·θ̇·e^{iθ}`.
fn acceleration_parts(
    graph: &mut Graph,
    sum: &VectorSum,
    position_vars: &[Var],
    all_vars: &[Var],
) -> [[ExprId; 2]; 4] {
    let zero = graph.constant(0.0);
    let two = graph.constant(2.0);
    let mut parts = [[zero; 2]; 4];
    for term in &sum.terms {
        let r = graph.linear(&term.magnitude);
        let theta = graph.linear(&term.angle);
        let r_dot = graph.time_derivative(r, position_vars, |_| true);
        let r_ddot = graph.time_derivative(r_dot, all_vars, |_| true);
        let theta_dot = graph.time_derivative(theta, position_vars, |_| true);
        let theta_ddot = graph.time_derivative(theta_dot, all_vars, |_| true);
        let (cos, sin) = (graph.cos(theta), graph.sin(theta));
        let minus_sin = graph.neg(sin);
        // Each part is a coefficient times e^{iθ} = (cos, sin) or i·e^{iθ} = (−sin, cos).
        let tangential = graph.mul(r, theta_ddot);
        let theta_dot_squared = graph.mul(theta_dot, theta_dot);
        let centripetal = graph.mul(r, theta_dot_squared);
        let normal = graph.neg(centripetal);
        let rates = graph.mul(r_dot, theta_dot);
        let coriolis = graph.mul(two, rates);
        let coefficients = [
            (tangential, [minus_sin, cos]),
            (normal, [cos, sin]),
            (r_ddot, [cos, sin]),
            (coriolis, [minus_sin, cos]),
        ];
        for (part, (coefficient, direction)) in parts.iter_mut().zip(coefficients) {
            for (component, unit) in part.iter_mut().zip(direction) {
                let value = graph.mul(coefficient, unit);
                *component = if term.negated {
                    graph.sub(*component, value)
                } else {
                    graph.add(*component, value)
                };
            }
        }
    }
    parts
}
