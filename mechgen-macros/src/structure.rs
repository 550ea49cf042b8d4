//! Rule: the loop equations must be able to determine the unknowns.
//!
//! Structurally, that means a matching between scalar equations and unknowns in which each
//! unknown is paired with an equation that depends on it (the Jacobian's sparsity pattern has
//! a perfect matching). When there is none, some set of unknowns appears in fewer equations
//! than there are of them, and no value of the lengths can make the Jacobian invertible.
//! This runs on the derived Jacobian rather than on which names a loop mentions, so a slider
//! along a fixed direction (`d @ 0`, which enters only the x equation) is seen for what it is.

use crate::errors::Errors;
use crate::model::{Model, SymbolRef};
use crate::symbolic::{Equations, Var};

pub fn check(model: &Model, equations: &Equations) -> syn::Result<()> {
    let mut errors = Errors::default();
    if let Err(missing) = &equations.closed_form {
        // Rule: a scene kernel is straight-line code, so every loop must close in closed form.
        for scene in &model.scenes {
            errors.error_at(
                &scene.name,
                format!(
                    "scene `{}` needs every loop solved in closed form, but these loops must be \
                     solved together by Newton-Raphson ({}): use `motion_near` (Newton, then \
                     the rates)",
                    scene.name,
                    missing.sentence(model)
                ),
            );
        }
        // Rule: `generate: assemble` asks for the closed forms, so a loop without one is an
        // error there, not a type that silently lacks `assemble`.
        if model.outputs.assemble {
            let loop_sum = &model.loops[missing.loop_index];
            errors.push(loop_sum.error(
                missing.term,
                format!(
                    "`generate: assemble` asks for every loop in closed form, but loop {} {}; \
                     without `assemble`, `position` solves the loops by Newton-Raphson",
                    missing.loop_index + 1,
                    missing.reason
                ),
            ));
        }
    }
    let rows = equations.jacobian.len();
    let columns = model.unknowns.len();
    if rows != columns {
        // Already reported by the count rule.
        return Ok(());
    }
    let depends: Vec<Vec<bool>> = equations
        .jacobian
        .iter()
        .map(|row| row.iter().map(|&d| !equations.graph.is_zero(d)).collect())
        .collect();

    let mut row_of_column: Vec<Option<usize>> = vec![None; columns];
    let mut column_of_row: Vec<Option<usize>> = vec![None; rows];
    for column in 0..columns {
        let mut visited = vec![false; rows];
        augment(
            column,
            &depends,
            &mut visited,
            &mut row_of_column,
            &mut column_of_row,
        );
    }

    for column in (0..columns).filter(|&c| row_of_column[c].is_none()) {
        // Columns reachable from the unmatched one by alternating paths, and their rows:
        // a set with more unknowns than equations (Hall's condition fails on it).
        let mut stuck_columns = vec![column];
        let mut stuck_rows: Vec<usize> = Vec::new();
        let mut next = 0;
        while next < stuck_columns.len() {
            let c = stuck_columns[next];
            next += 1;
            for row in (0..rows).filter(|&r| depends[r][c]) {
                if !stuck_rows.contains(&row) {
                    stuck_rows.push(row);
                    if let Some(matched) = column_of_row[row]
                        && !stuck_columns.contains(&matched)
                    {
                        stuck_columns.push(matched);
                    }
                }
            }
        }
        stuck_columns.sort_unstable();
        stuck_rows.sort_unstable();
        let names: Vec<String> = stuck_columns
            .iter()
            .map(|&c| format!("`{}`", model.unknowns[c].name))
            .collect();
        let equations_text = match stuck_rows.len() {
            0 => "no equation".to_string(),
            1 => format!("only 1 scalar equation ({})", describe_rows(&stuck_rows)),
            n => format!("only {n} scalar equations ({})", describe_rows(&stuck_rows)),
        };
        errors.error_at(
            &model.unknowns[column].name,
            format!(
                "the loops cannot determine `{}`: the unknowns {} enter {equations_text}, \
                 fewer than there are unknowns (the system is structurally singular)",
                model.unknowns[column].name,
                names.join(", "),
            ),
        );
    }
    if errors.is_empty() {
        generic_rank(model, equations, &mut errors);
    }
    errors.finish(())
}

/// Rule: the Jacobian must be invertible somewhere. A matching only says each unknown has an
/// equation; the unknowns may still enter only in a fixed combination (`l3 @ (theta3 +
/// theta4)`), and then the Jacobian is singular for every value of everything. Its rank as
/// a matrix of expressions is its rank at a point chosen at random (almost surely), so it is
/// evaluated at a few such points: singular at all of them, it is singular everywhere.
fn generic_rank(model: &Model, equations: &Equations, errors: &mut Errors) {
    let n = model.unknowns.len();
    // A fixed sequence, so that the macro's verdict is the same on every build.
    let mut random = crate::sample::fixed_sequence();
    let mut dependent = None;
    // Three points where the Jacobian is defined, among at most twelve drawn.
    let mut tested = 0;
    for _ in 0..12 {
        if tested == 3 {
            break;
        }
        let params: Vec<f64> = (0..model.params.len()).map(|_| 1.0 + random()).collect();
        let inputs = model.inputs.len();
        let point: Vec<f64> = (0..n + inputs)
            .map(|_| std::f64::consts::TAU * random())
            .collect();
        let values = equations.graph.evaluate_all(|var| match var {
            Var::Value(SymbolRef::Param(i)) => params[i],
            Var::Value(SymbolRef::Unknown(i)) => point[i],
            Var::Value(SymbolRef::Input(i)) => point[n + i],
            // Rates: the Jacobian holds none.
            _ => 0.5,
        });
        let matrix: Vec<Vec<f64>> = equations
            .jacobian
            .iter()
            .map(|row| row.iter().map(|e| values[e.index()]).collect())
            .collect();
        // A formula of the parameters can be undefined at random dimensions (the square
        // root of a difference): such a point tells nothing.
        if matrix.iter().flatten().any(|value| !value.is_finite()) {
            continue;
        }
        tested += 1;
        match dependent_column(matrix) {
            Some(column) => dependent = Some(column),
            None => return,
        }
    }
    if let Some(column) = dependent {
        let name = &model.unknowns[column].name;
        errors.error_at(
            name,
            format!(
                "the loops never determine `{name}`: the Jacobian is singular for every value \
                 of the dimensions and unknowns (`{name}` enters only together with other \
                 unknowns, as in a sum of angles), so no position can be solved"
            ),
        );
    }
}

/// The first column of `matrix` that is a combination of the ones before it (to a relative
/// 1e-9), by Gaussian elimination with partial pivoting; `None` where it is invertible.
fn dependent_column(mut matrix: Vec<Vec<f64>>) -> Option<usize> {
    let n = matrix.len();
    let scale = matrix
        .iter()
        .flatten()
        .fold(0.0f64, |m, v| m.max(v.abs()))
        .max(f64::MIN_POSITIVE);
    for (row, column) in (0..n).enumerate() {
        let pivot = (row..n)
            .max_by(|&a, &b| matrix[a][column].abs().total_cmp(&matrix[b][column].abs()))?;
        if matrix[pivot][column].abs() <= 1e-9 * scale {
            return Some(column);
        }
        matrix.swap(row, pivot);
        let (above, below) = matrix.split_at_mut(row + 1);
        let pivot_row = &above[row];
        for other in below {
            let factor = other[column] / pivot_row[column];
            for (entry, pivot_entry) in other[column..].iter_mut().zip(&pivot_row[column..]) {
                *entry -= factor * pivot_entry;
            }
        }
    }
    None
}

/// Kuhn's augmenting path step: tries to match `column`, re-matching others as needed.
fn augment(
    column: usize,
    depends: &[Vec<bool>],
    visited: &mut [bool],
    row_of_column: &mut [Option<usize>],
    column_of_row: &mut [Option<usize>],
) -> bool {
    for row in 0..depends.len() {
        if !depends[row][column] || visited[row] {
            continue;
        }
        visited[row] = true;
        let free = match column_of_row[row] {
            None => true,
            Some(other) => augment(other, depends, visited, row_of_column, column_of_row),
        };
        if free {
            row_of_column[column] = Some(row);
            column_of_row[row] = Some(column);
            return true;
        }
    }
    false
}

fn describe_rows(rows: &[usize]) -> String {
    rows.iter()
        .map(|r| format!("loop {} {}", r / 2 + 1, if r % 2 == 0 { "x" } else { "y" }))
        .collect::<Vec<_>>()
        .join(", ")
}
