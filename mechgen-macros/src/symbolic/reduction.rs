//! Newton on as few unknowns as the loops allow, the rest in closed form inside each
//! evaluation, for mechanisms whose loops do not all come down to closed forms.
//!
//! Given some unknowns `S`, the loops are ordered, as far as they go, by Chace's cases
//! ([`super::closed_form::plan_from`]). When that solves every other unknown `Y` and leaves
//! `m` loops over, with `S` of `2m` unknowns, those loops' residuals are a function `F(S)` of
//! `2m` equations in `2m` unknowns, and Newton iterates on it alone: each evaluation solves
//! the closed forms for `Y` given `S`, then evaluates `F`. Its Jacobian follows from the
//! loops' Jacobian `J` by implicit differentiation of the closed-form loops `G(S, Y(S)) = 0`,
//! the Schur complement
//!
//! `dF/dS = J[F,S] − J[F,Y]·J[G,Y]⁻¹·J[G,S]`,
//!
//! where `J[G,Y]` is block lower-triangular, one 2×2 block per closed-form loop in the plan's
//! order (a loop reads only the unknowns solved before it and its own two). Only the
//! closed-form loops whose unknowns reach `F` (directly or through later closed forms) or
//! the rounding scale (an unknown length) are solved inside each evaluation; the others
//! follow the iteration and are solved once, at its solution.
//!
//! The smallest `m` is tried first (`m = 1`: every pair of unknowns, in declaration order),
//! and the first `S` that works is taken; `m` stays below the number of loops, so at least
//! one loop is solved in closed form, else there is no reduction and Newton iterates on every
//! unknown. A candidate must also leave `dF/dS` structurally non-singular (a perfect matching
//! in its sparsity pattern), which it is whenever the loops' Jacobian is.
//!
//! Choosing `S` is a tearing problem, and the candidates grow exponentially with the
//! unknowns (a declaration of ten loops that each mention all twenty unknowns has half a
//! million). The search skips, without planning them, the candidates that leave no loop with
//! exactly two open unknowns (no closed form can start there, and planning one would find no
//! step), and with them every `m` too small to leave any loop so; it then stops after
//! [`MAX_CANDIDATES`] candidates or [`MAX_PLANS`] plans, and the declaration gets no
//! reduction: Newton iterates on every unknown, which is always correct, where the search
//! would otherwise run the compiler for minutes.

use crate::model::{Model, SymbolRef};

use super::closed_form::{Step, open_unknowns, plan_from};
use super::graph::{ExprId, Graph};

/// The unknowns Newton iterates on, the loops solved in closed form inside each evaluation,
/// and the expressions the generated code evaluates.
pub struct Reduction {
    /// The iterated unknowns `S` (indices into the model's unknowns), in declaration order.
    pub iterated: Vec<usize>,
    /// The loops solved in closed form inside each evaluation, in the order they are solved.
    pub steps: Vec<Step>,
    /// The loops solved in closed form once, after the iteration, in order: those whose
    /// unknowns the residual `F` does not read.
    pub after: Vec<Step>,
    /// The loops whose residuals `F(S)` Newton drives to zero, in declaration order.
    pub residual_loops: Vec<usize>,
    /// `slopes[s][j]`: whether step `s`'s unknowns move with `iterated[j]` (structurally
    /// non-zero `dY_s/dS_j`).
    pub slopes: Vec<Vec<bool>>,
    /// Each step's closed-form coefficients, as [`super::Case::coefficients`] orders them.
    pub coefficients: Vec<Vec<ExprId>>,
    /// The same for [`Self::after`].
    pub after_coefficients: Vec<Vec<ExprId>>,
    /// `F`: the residual rows of [`Self::residual_loops`], x then y of each.
    pub residual: Vec<ExprId>,
    /// The loops' Jacobian `J`, every row and column, as [`super::Equations::jacobian`].
    pub jacobian: Vec<Vec<ExprId>>,
    /// The velocity and acceleration solves' right-hand sides.
    pub velocity_rhs: Vec<ExprId>,
    pub acceleration_rhs: Vec<ExprId>,
}

/// The expressions [`find`] rewrites for the generated code.
pub struct Full<'a> {
    pub residual: &'a [ExprId],
    pub jacobian: &'a [Vec<ExprId>],
    pub velocity_rhs: &'a [ExprId],
    pub acceleration_rhs: &'a [ExprId],
}

/// The reduction with the fewest iterated unknowns, if there is one.
///
/// Every expression it keeps has its angle sums taken apart (see [`super::angles`]), so a
/// closed-form angle is read only through the unit vector its closed form yields: no
/// `atan2` inside the iteration.
pub fn find(model: &Model, graph: &mut Graph, full: &Full) -> Option<Reduction> {
    let n = model.unknowns.len();
    let loops = model.loops.len();
    let loop_unknowns: Vec<Vec<usize>> = model
        .loops
        .iter()
        .map(|sum| open_unknowns(sum, &vec![false; n]))
        .collect();
    // The first closed-form step needs a loop with exactly two unknowns outside `S`, so `S`
    // holds all but two of some loop's unknowns.
    let fewest = loop_unknowns.iter().map(Vec::len).min().unwrap_or(0);
    let smallest_m = fewest.saturating_sub(2).div_ceil(2).max(1);
    let (mut candidates, mut plans) = (0, 0);
    for m in smallest_m..loops {
        for iterated in combinations(n, 2 * m) {
            candidates += 1;
            if candidates > MAX_CANDIDATES {
                return None;
            }
            let mut solved = vec![false; n];
            iterated.iter().for_each(|&u| solved[u] = true);
            // Planning a candidate that opens no step would find none and touch nothing.
            let opens_a_step = loop_unknowns
                .iter()
                .any(|unknowns| unknowns.iter().filter(|&&u| !solved[u]).count() == 2);
            if !opens_a_step {
                continue;
            }
            plans += 1;
            if plans > MAX_PLANS {
                return None;
            }
            let steps = plan_from(model, graph, &mut solved);
            if steps.len() != loops - m || solved.contains(&false) {
                continue;
            }
            let mut residual_loops: Vec<usize> = (0..loops)
                .filter(|&l| steps.iter().all(|s| s.loop_index != l))
                .collect();
            residual_loops.sort_unstable();
            let nonzero = |r: usize, c: usize| !graph.is_zero(full.jacobian[r][c]);
            let (steps, after) = split_after(model, steps, &residual_loops, &nonzero);
            let slopes = slope_pattern(&iterated, &steps, &nonzero);
            if !reduced_is_regular(&iterated, &steps, &residual_loops, &slopes, &nonzero) {
                continue;
            }
            let plan = Plan {
                iterated,
                steps,
                after,
                residual_loops,
                slopes,
            };
            return Some(build(model, graph, full, plan));
        }
    }
    None
}

/// The most candidate sets `S` the search looks at, and the most it plans (each plan
/// classifies loops and builds their closed forms' coefficients): each under a second of
/// expansion in a macro built without optimisation (0.7 s and 0.3 s measured, with
/// declarations made to reach them). The shipped mechanisms' searches end within ten
/// candidates.
const MAX_CANDIDATES: usize = 1 << 18;
const MAX_PLANS: usize = 1 << 12;

/// A reduction's structure, before its expressions are rewritten.
struct Plan {
    iterated: Vec<usize>,
    steps: Vec<Step>,
    after: Vec<Step>,
    residual_loops: Vec<usize>,
    slopes: Vec<Vec<bool>>,
}

/// The closed-form steps split into those solved inside each evaluation (their unknowns
/// reach the residual, directly or through a later step, or the magnitudes) and those solved
/// once after the iteration, each list in plan order. No step inside reads one after: a step
/// that another inside step reads is inside too.
fn split_after(
    model: &Model,
    steps: Vec<Step>,
    residual_loops: &[usize],
    nonzero: &dyn Fn(usize, usize) -> bool,
) -> (Vec<Step>, Vec<Step>) {
    let reads = |l: usize, unknowns: &[usize]| {
        [2 * l, 2 * l + 1]
            .iter()
            .any(|&r| unknowns.iter().any(|&u| nonzero(r, u)))
    };
    let mut inside = vec![false; steps.len()];
    for s in (0..steps.len()).rev() {
        let unknowns = &steps[s].unknowns;
        inside[s] = residual_loops.iter().any(|&l| reads(l, unknowns))
            || (s + 1..steps.len()).any(|t| inside[t] && reads(steps[t].loop_index, unknowns))
            || unknowns.iter().any(|&u| {
                model.loops.iter().flat_map(|l| &l.terms).any(|term| {
                    term.magnitude
                        .coefficients
                        .contains_key(&SymbolRef::Unknown(u))
                })
            });
    }
    let (mut within, mut after) = (Vec::new(), Vec::new());
    for (step, inside) in steps.into_iter().zip(inside) {
        if inside {
            within.push(step);
        } else {
            after.push(step);
        }
    }
    (within, after)
}

fn build(model: &Model, graph: &mut Graph, full: &Full, plan: Plan) -> Reduction {
    let Plan {
        iterated,
        steps,
        after,
        residual_loops,
        slopes,
    } = plan;
    let n = model.unknowns.len();
    let coefficients: Vec<Vec<ExprId>> = steps.iter().map(|s| s.case.coefficients()).collect();
    let after_coefficients: Vec<Vec<ExprId>> =
        after.iter().map(|s| s.case.coefficients()).collect();
    let residual: Vec<ExprId> = residual_loops
        .iter()
        .flat_map(|&l| [full.residual[2 * l], full.residual[2 * l + 1]])
        .collect();
    // One pass over every root, so shared subexpressions are rewritten once.
    let roots: Vec<ExprId> = coefficients
        .iter()
        .chain(&after_coefficients)
        .flatten()
        .chain(&residual)
        .chain(full.jacobian.iter().flatten())
        .chain(full.velocity_rhs)
        .chain(full.acceleration_rhs)
        .copied()
        .collect();
    let expanded = super::angles::expand(graph, &roots);
    let mut rest = expanded.into_iter();
    let mut take = |count: usize| -> Vec<ExprId> { rest.by_ref().take(count).collect() };
    let coefficients = coefficients.iter().map(|c| take(c.len())).collect();
    let after_coefficients = after_coefficients.iter().map(|c| take(c.len())).collect();
    let residual = take(residual.len());
    let jacobian = (0..full.jacobian.len()).map(|_| take(n)).collect();
    let velocity_rhs = take(full.velocity_rhs.len());
    let acceleration_rhs = take(full.acceleration_rhs.len());
    Reduction {
        iterated,
        steps,
        after,
        residual_loops,
        slopes,
        coefficients,
        after_coefficients,
        residual,
        jacobian,
        velocity_rhs,
        acceleration_rhs,
    }
}

/// `slopes[s][j]` (see [`Reduction::slopes`]): step `s`'s unknowns move with `S_j` when its
/// loop reads `S_j`, or an unknown of an earlier step that moves with it.
fn slope_pattern(
    iterated: &[usize],
    steps: &[Step],
    nonzero: &dyn Fn(usize, usize) -> bool,
) -> Vec<Vec<bool>> {
    let mut slopes: Vec<Vec<bool>> = Vec::new();
    for step in steps {
        let rows = [2 * step.loop_index, 2 * step.loop_index + 1];
        let row: Vec<bool> = iterated
            .iter()
            .enumerate()
            .map(|(j, &s)| {
                rows.iter().any(|&r| {
                    nonzero(r, s)
                        || steps.iter().zip(&slopes).any(|(earlier, moves)| {
                            moves[j] && earlier.unknowns.iter().any(|&y| nonzero(r, y))
                        })
                })
            })
            .collect();
        slopes.push(row);
    }
    slopes
}

/// Whether `dF/dS` has a perfect matching in its sparsity pattern.
fn reduced_is_regular(
    iterated: &[usize],
    steps: &[Step],
    residual_loops: &[usize],
    slopes: &[Vec<bool>],
    nonzero: &dyn Fn(usize, usize) -> bool,
) -> bool {
    let rows: Vec<usize> = residual_loops
        .iter()
        .flat_map(|&l| [2 * l, 2 * l + 1])
        .collect();
    let pattern: Vec<Vec<bool>> = rows
        .iter()
        .map(|&r| {
            iterated
                .iter()
                .enumerate()
                .map(|(j, &s)| {
                    nonzero(r, s)
                        || steps.iter().zip(slopes).any(|(step, moves)| {
                            moves[j] && step.unknowns.iter().any(|&y| nonzero(r, y))
                        })
                })
                .collect()
        })
        .collect();
    let mut row_of_column = vec![None; iterated.len()];
    (0..iterated.len()).all(|column| {
        let mut visited = vec![false; rows.len()];
        augment(column, &pattern, &mut visited, &mut row_of_column)
    })
}

/// Kuhn's augmenting path from `column` in the bipartite graph of `pattern[row][column]`.
fn augment(
    column: usize,
    pattern: &[Vec<bool>],
    visited: &mut [bool],
    row_of_column: &mut [Option<usize>],
) -> bool {
    for row in 0..pattern.len() {
        if pattern[row][column] && !visited[row] {
            visited[row] = true;
            let holder = row_of_column.iter().position(|&r| r == Some(row));
            let free = match holder {
                None => true,
                Some(other) => augment(other, pattern, visited, row_of_column),
            };
            if free {
                if let Some(other) = holder {
                    row_of_column[other] = None;
                }
                row_of_column[column] = Some(row);
                return true;
            }
        }
    }
    false
}

/// The `k`-element subsets of `0..n`, in lexicographic order, made one at a time: there can
/// be far more than the search looks at.
fn combinations(n: usize, k: usize) -> impl Iterator<Item = Vec<usize>> {
    let mut next = (k <= n).then(|| (0..k).collect::<Vec<usize>>());
    std::iter::from_fn(move || {
        let current = next.take()?;
        // The rightmost entry that can still move right.
        if let Some(i) = (0..k).rev().find(|&i| current[i] < n - k + i) {
            let mut following = current.clone();
            following[i] += 1;
            for j in i + 1..k {
                following[j] = following[j - 1] + 1;
            }
            next = Some(following);
        }
        Some(current)
    })
}

#[cfg(test)]
mod tests {
    use super::combinations;

    /// Twelve loops that each mention all twenty-four unknowns: eight million candidate sets,
    /// of which only the last size can start a closed form. The search goes straight there
    /// (it took minutes when it tried every smaller size first).
    #[test]
    fn dense_coupled_loops_search_only_where_a_closed_form_can_start() {
        let loops = 12;
        let unknowns: Vec<String> = (0..2 * loops).map(|j| format!("q{j}")).collect();
        let mut params = Vec::new();
        let sums: Vec<String> = (0..loops)
            .map(|i| {
                params.push(format!("p{i}"));
                let mut terms = vec![format!("p{i} @ theta")];
                for q in &unknowns {
                    params.push(format!("r{i}_{q}"));
                    terms.push(format!("r{i}_{q} @ {q}"));
                }
                format!("loop: {};", terms.join(" + "))
            })
            .collect();
        let declaration = format!(
            "pub struct Dense {{ params: {}; input: theta: angle; unknowns: {}; {} }}",
            params.join(", "),
            unknowns
                .iter()
                .map(|q| format!("{q}: angle"))
                .collect::<Vec<_>>()
                .join(", "),
            sums.join(" ")
        );
        let start = std::time::Instant::now();
        let expansion = crate::expand::expand(declaration.parse().expect("tokens")).to_string();
        assert!(!expansion.contains("compile_error"));
        // Well under a second here; minutes before.
        assert!(start.elapsed() < std::time::Duration::from_secs(30));
    }

    #[test]
    fn combinations_come_in_lexicographic_order() {
        let all = |n, k| combinations(n, k).collect::<Vec<_>>();
        assert_eq!(all(4, 2), [[0, 1], [0, 2], [0, 3], [1, 2], [1, 3], [2, 3]]);
        assert_eq!(all(3, 3), [[0, 1, 2]]);
        assert_eq!(all(3, 0), [Vec::<usize>::new()]);
        assert!(all(2, 3).is_empty());
    }
}
