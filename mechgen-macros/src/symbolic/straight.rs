//! Straight-line kernels: a closed-form plan, the rate solves and the points as one
//! expression graph, so that every product is formed once, everything that depends on the
//! dimensions alone can be computed once per mechanism, and nothing is computed that an
//! output does not read.
//!
//! Each loop's closed form (Chace's cases, as `mechgen::closed` solves them) is written out
//! as expressions; where it needs a value that can fail (a square root that says the loop
//! cannot close, a reciprocal that says the configuration is degenerate or singular) the
//! value is an auxiliary variable ([`Var::Aux`]) computed by a checked runtime helper. A
//! solved angle is read through its unit vector `(cos θ, sin θ)`; the angle itself is an
//! `atan2` of it, computed only if an output needs it. The rates then come from the Jacobian,
//! block lower-triangular in plan order, by Cramer's rule on each loop's 2×2 block, with the
//! block's reciprocal determinant checked once and shared by velocity and acceleration. The
//! determinant is the one the closed form already holds (the triangle's height, the
//! quadratic's root), which keeps its digits where `j00·j11 − j01·j10` would cancel, near a
//! toggle; each rate gets a name, so an acceleration reads its square as one product.

use std::collections::HashMap;

use crate::model::SymbolRef;

use super::closed_form::{Case, Complex, Step};
use super::graph::{ExprId, Graph, Node, Var};
use super::rewrite::Rewriter;

/// What [`build`] reads: the expressions scene kernels evaluate: those of the closed form, the rates and the
/// points, with angle sums taken apart (see [`super::angles`]) so a solved angle is only
/// ever read through its unit vector.
pub struct SceneExprs {
    /// Each closed-form step's coefficients, as [`super::Case::coefficients`] orders them.
    pub coefficients: Vec<Vec<ExprId>>,
    /// The Jacobian, row-major.
    pub jacobian: Vec<ExprId>,
    pub velocity_rhs: Vec<ExprId>,
    pub acceleration_rhs: Vec<ExprId>,
    /// Each point's `[position, velocity, acceleration]`, each `(x, y)`.
    pub points: Vec<[[ExprId; 2]; 3]>,
}

/// How an auxiliary variable is computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum AuxKind {
    /// `±√(plus − minus)` with the sign of branch `branch`; a radicand below zero by more
    /// than rounding of `plus + |minus|` means the loop cannot close.
    BranchRoot {
        plus: ExprId,
        minus: ExprId,
        branch: usize,
    },
    /// `±½·√((sum − span)(sum + span)(span − |difference|)(span + |difference|))`, twice the
    /// area of the triangle with sides `r1`, `r2` and `span` (`sum = r1 + r2`,
    /// `difference = r1 − r2`), with the sign of branch `branch`: a gap (`sum − span` or
    /// `span − |difference|`) below zero by more than rounding of the sides means the loop
    /// cannot close.
    ///
    /// The squares (`span_squared` is what `span` is the root of) are for kernels that decide
    /// only that the circles meet: `(sum² − span²)·(span² − difference²)` is the same product
    /// without a square root, and its sign is the gaps' (both cannot be negative, as
    /// `sum ≥ |difference|`), so a failure there is passed on to the checked form.
    TriangleRoot {
        sum: ExprId,
        difference: ExprId,
        span: ExprId,
        sum_squared: ExprId,
        difference_squared: ExprId,
        span_squared: ExprId,
        branch: usize,
    },
    /// `1/x`; a zero `x` is a degenerate configuration.
    Inverse(ExprId),
    /// `1/det` of a 2×2 block whose columns' norms multiply to `1/inverse_norms`; singular
    /// where the relative determinant `|det|·inverse_norms` is at or below the threshold.
    ///
    /// Where the norms move (a column of a changing length), `squared_norms` is their
    /// product's square, for kernels that only decide: `det² > threshold²·norms²` says the
    /// same as the relative determinant without its square root and division.
    ///
    /// `turning` holds the squared lengths of the block's angle columns whose length moves
    /// (an angle whose vector is a slide): a rate block is refused beyond the ordinary aspect
    /// at the position, which the mechanism's thresholds do not see.
    InverseDeterminant {
        det: ExprId,
        inverse_norms: ExprId,
        squared_norms: Option<ExprId>,
        threshold: Threshold,
        turning: [Option<ExprId>; 2],
    },
    /// A solved angle from its unit vector `(x, y)`, as `atan2(y, x)` would give it.
    Angle { y: ExprId, x: ExprId },
    /// A value given a name of its own, so that products read it whole: a rate, whose
    /// square the accelerations read, is one product there rather than the four of its
    /// factors.
    Bind(ExprId),
}

/// Where a 2×2 block counts as singular.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Threshold {
    /// Two unknown lengths along parallel directions: within rounding of parallel.
    Position,
    /// The rates: `mechgen::singular_threshold()`, as every rate solve.
    Rates,
}

/// A scene's everything, as expressions over the input, its rates and [`Var::Aux`] values.
pub struct Straight {
    /// Auxiliary variable `k` is `aux[k]`; each reads only expressions of earlier ones.
    pub aux: Vec<AuxKind>,
    /// Each unknown's value: a length's expression, or an angle's `atan2`.
    pub values: Vec<ExprId>,
    pub rates: Vec<ExprId>,
    pub accelerations: Vec<ExprId>,
    /// Each point's `[position, velocity, acceleration]`, each `(x, y)`.
    pub points: Vec<[[ExprId; 2]; 3]>,
}

struct Builder<'g> {
    graph: &'g mut Graph,
    aux: Vec<AuxKind>,
    known: HashMap<AuxKind, ExprId>,
    /// Nodes of the model's expressions and what they become here.
    replace: HashMap<ExprId, ExprId>,
    /// For each closed-form step, `1/(‖c0‖·‖c1‖)` of its loop's Jacobian block: the case
    /// knows the columns' norms (`|w1|` and `|w2|` for two angles, say), which for fixed
    /// vectors are constants of the mechanism.
    inverse_norms: Vec<ExprId>,
    /// For each closed-form step, the product of its block's columns' squared norms, where
    /// that moves (see [`AuxKind::InverseDeterminant`]).
    squared_norms: Vec<Option<ExprId>>,
    /// For each closed-form step, the squared norms of its block's angle columns whose length
    /// moves (see [`AuxKind::InverseDeterminant`]).
    turning: Vec<[Option<ExprId>; 2]>,
    /// For each closed-form step, its loop's Jacobian block's determinant as the closed form
    /// knows it (the triangle's height, the quadratic's root): the same value as Cramer's
    /// `j00·j11 − j01·j10`, without that difference's cancellation near a toggle.
    determinants: Vec<ExprId>,
}

impl Builder<'_> {
    fn aux(&mut self, kind: AuxKind) -> ExprId {
        if let Some(&var) = self.known.get(&kind) {
            return var;
        }
        let index = u32::try_from(self.aux.len()).expect("auxiliary variables fit in u32");
        let var = self.graph.var(Var::Aux(index));
        self.aux.push(kind);
        self.known.insert(kind, var);
        var
    }

    /// `value` as a [`AuxKind::Bind`] value, unless it depends on the dimensions alone (a
    /// constant of the mechanism, computed once).
    fn bound(&mut self, value: ExprId) -> ExprId {
        if self.graph.is_fixed(value) {
            value
        } else {
            self.aux(AuxKind::Bind(value))
        }
    }

    /// `exprs` with every solved quantity so far replaced by its expression.
    fn substituted(&mut self, exprs: &[ExprId]) -> Vec<ExprId> {
        let replace = &self.replace;
        Rewriter::new(|_, id| replace.get(&id).copied()).all(self.graph, exprs)
    }

    fn dot(&mut self, a: Complex, b: Complex) -> ExprId {
        let (x, y) = (self.graph.mul(a[0], b[0]), self.graph.mul(a[1], b[1]));
        self.graph.add(x, y)
    }

    /// `a × b`, the z component.
    fn cross(&mut self, a: Complex, b: Complex) -> ExprId {
        let (x, y) = (self.graph.mul(a[0], b[1]), self.graph.mul(a[1], b[0]));
        self.graph.sub(x, y)
    }

    fn scaled(&mut self, a: Complex, s: ExprId) -> Complex {
        [self.graph.mul(a[0], s), self.graph.mul(a[1], s)]
    }

    fn plus(&mut self, a: Complex, b: Complex) -> Complex {
        [self.graph.add(a[0], b[0]), self.graph.add(a[1], b[1])]
    }

    fn negated(&mut self, a: Complex) -> Complex {
        [self.graph.neg(a[0]), self.graph.neg(a[1])]
    }

    /// The unit vector `e^{iq}` that turns `from` onto `to` when `|to| = |from|`:
    /// `to·conj(from)/|from|²`.
    fn turn(&mut self, to: Complex, from: Complex) -> Complex {
        let product = [self.dot(to, from), self.cross(from, to)];
        let squared = self.dot(from, from);
        let inverse = self.graph.recip(squared);
        self.scaled(product, inverse)
    }

    /// Records an unknown angle's unit vector: its sine and cosine, and (through `atan2`) its
    /// value, wherever the model's expressions read them.
    ///
    /// `flipped`: `unit` is that of `q' = −q` ([`Step::flipped`]), whose conjugate is `q`'s.
    fn solved_angle(
        &mut self,
        (unknown, flipped): (usize, bool),
        unit: Complex,
        values: &mut [ExprId],
    ) {
        let unit = if flipped {
            [unit[0], self.graph.neg(unit[1])]
        } else {
            unit
        };
        let var = self.graph.var(Var::Value(SymbolRef::Unknown(unknown)));
        let angle = self.aux(AuxKind::Angle {
            y: unit[1],
            x: unit[0],
        });
        values[unknown] = angle;
        self.replace.insert(var, angle);
        for (node, value) in [(Node::Cos(var), unit[0]), (Node::Sin(var), unit[1])] {
            if let Some(id) = self.graph.lookup(node) {
                self.replace.insert(id, value);
            }
        }
    }

    fn solved_length(&mut self, unknown: usize, value: ExprId, values: &mut [ExprId]) {
        let var = self.graph.var(Var::Value(SymbolRef::Unknown(unknown)));
        values[unknown] = value;
        self.replace.insert(var, value);
    }

    /// Records `1/(‖c0‖·‖c1‖)` for the step's Jacobian block from its columns' squared norms,
    /// `angles` telling which columns are an angle's.
    fn block_columns(&mut self, squares: [ExprId; 2], angles: [bool; 2]) {
        let [first, second] = squares.map(|square| self.graph.sqrt(square));
        let product = self.graph.mul(first, second);
        let inverse = self.graph.recip(product);
        self.inverse_norms.push(inverse);
        let squared = self.graph.mul(squares[0], squares[1]);
        let moving = !self.graph.is_fixed(squared);
        self.squared_norms.push(moving.then_some(squared));
        let turning =
            [0, 1].map(|k| (angles[k] && !self.graph.is_fixed(squares[k])).then_some(squares[k]));
        self.turning.push(turning);
    }

    /// One loop in closed form; `branch` counts the branching loops so far.
    fn close(
        &mut self,
        step: &Step,
        coefficients: &[ExprId],
        branch: &mut usize,
        values: &mut [ExprId],
    ) {
        let coefficients = self.substituted(coefficients);
        let vector = |i: usize| [coefficients[2 * i], coefficients[2 * i + 1]];
        let [a, b] = step.unknowns;
        let [solved_a, solved_b] = step.solved();
        let mut branch_root = |builder: &mut Self, plus: ExprId, minus: ExprId| {
            let root = builder.aux(AuxKind::BranchRoot {
                plus,
                minus,
                branch: *branch,
            });
            *branch += 1;
            root
        };
        match step.case {
            Case::TwoLengths { .. } => {
                let (k, v1, v2) = (vector(0), vector(1), vector(2));
                let det = self.cross(v1, v2);
                let columns = [self.dot(v1, v1), self.dot(v2, v2)];
                self.block_columns(columns, [false, false]);
                let inverse_norms = *self.inverse_norms.last().expect("just recorded");
                // ∂/∂l1 = v1, ∂/∂l2 = v2: the block is the one solved here.
                self.determinant(step, det);
                let inverse = self.aux(AuxKind::InverseDeterminant {
                    det,
                    inverse_norms,
                    squared_norms: *self.squared_norms.last().expect("just recorded"),
                    threshold: Threshold::Position,
                    turning: [None, None],
                });
                let (first, second) = (self.cross(v2, k), self.cross(k, v1));
                let first = self.graph.mul(first, inverse);
                let second = self.graph.mul(second, inverse);
                self.solved_length(a, first, values);
                self.solved_length(b, second, values);
            }
            Case::TwoAngles { .. } => {
                // P1 = e^{iq1}·w1 and P2 = e^{iq2}·w2 span the chord −K: P1's tip is where
                // circles of radii |w1| and |w2| about the chord's ends meet. With c = |K|,
                // P1 = (a·K̂ ± h·iK̂), where a·c = (|w1|² − |w2|² + c²)/2 and
                // h·c = √(|w1|²·c² − (a·c)²): one square root and one reciprocal, of c².
                let (k, w1, w2) = (vector(0), vector(1), vector(2));
                // The chord, and below the distance along it, are named: every product reads
                // them whole.
                let chord = self.negated(k).map(|c| self.bound(c));
                let chord_squared = self.dot(chord, chord);
                let (r1, r2) = (self.dot(w1, w1), self.dot(w2, w2));
                // ∂/∂q1 = i·e^{iq1}·w1, ∂/∂q2 = i·e^{iq2}·w2.
                self.block_columns([r1, r2], [true, true]);
                let half = self.graph.constant(0.5);
                let difference = self.graph.sub(r1, r2);
                let sum = self.graph.add(difference, chord_squared);
                let along = self.graph.mul(half, sum);
                let along = self.bound(along);
                // h·c is twice the area of the triangle (|w1|, |w2|, c), by Heron's formula
                // in factors: a thin triangle keeps its digits (|w1|²·c² − (a·c)² would
                // cancel), and whether the circles meet is decided on the gaps themselves,
                // in lengths, so the band for rounding is a few units of the sides'.
                let (n1, n2) = (self.graph.sqrt(r1), self.graph.sqrt(r2));
                let span = self.graph.sqrt(chord_squared);
                let sides_sum = self.graph.add(n1, n2);
                let sides_difference = self.graph.sub(n1, n2);
                let sum_squared = self.graph.mul(sides_sum, sides_sum);
                let difference_squared = self.graph.mul(sides_difference, sides_difference);
                let height = self.aux(AuxKind::TriangleRoot {
                    sum: sides_sum,
                    difference: sides_difference,
                    span,
                    sum_squared,
                    difference_squared,
                    span_squared: chord_squared,
                    branch: *branch,
                });
                *branch += 1;
                // After the triangle's test, so that circles about one centre (a zero chord)
                // that never meet say so (`CannotClose`), and only the same circle, met
                // everywhere, leaves the angles undetermined.
                let inverse = self.aux(AuxKind::Inverse(chord_squared));
                // The block's columns are i·P1 and i·P2, so its determinant is
                // P1 × P2 = P1 × chord = −height (P1 = (chord·along + i·chord·height)/c²).
                let det = self.graph.neg(height);
                self.determinant(step, det);
                let normal = [self.graph.neg(chord[1]), chord[0]];
                let (on, off) = (self.scaled(chord, along), self.scaled(normal, height));
                let sum = self.plus(on, off);
                // Named, so that the rates' and points' products read P1 whole.
                let p1 = self.scaled(sum, inverse).map(|c| self.bound(c));
                let minus_p1 = self.negated(p1);
                let p2 = self.plus(chord, minus_p1);
                let (e1, e2) = (self.turn(p1, w1), self.turn(p2, w2));
                self.solved_angle(solved_a, e1, values);
                self.solved_angle(solved_b, e2, values);
            }
            Case::LengthAndOwnAngle { .. } => {
                // |l·w1 + w0| = |K|: a quadratic in l; then the vector turns onto −K.
                let (k, w0, w1) = (vector(0), vector(1), vector(2));
                let quadratic = self.dot(w1, w1);
                let half_b = self.dot(w1, w0);
                let k_squared = self.dot(k, k);
                // ∂/∂l = e^{iq}·w1, ∂/∂q = i·e^{iq}·(l·w1 + w0), of norm |K|.
                self.block_columns([quadratic, k_squared], [false, true]);
                // (w1·w0)² − |w1|²·(|w0|² − |K|²) = |w1|²·|K|² − (w1×w0)² (Lagrange's
                // identity): no cancellation between large squares.
                let plus = self.graph.mul(quadratic, k_squared);
                let skew = self.cross(w1, w0);
                let minus = self.graph.mul(skew, skew);
                let root = branch_root(self, plus, minus);
                let length = self.quadratic_solution(half_b, root, quadratic);
                // Columns e^{iq}·w1 and i·e^{iq}·(l·w1 + w0): the determinant is
                // w1·(l·w1 + w0) = l·|w1|² + w1·w0, the root.
                self.determinant(step, root);
                let moving = self.scaled(w1, length);
                let turned = self.plus(moving, w0);
                let target = self.negated(k);
                // |turned| = |K|, and a zero |K| leaves the angle undetermined.
                let product = [self.dot(target, turned), self.cross(turned, target)];
                let inverse = self.aux(AuxKind::Inverse(k_squared));
                let unit = self.scaled(product, inverse);
                self.solved_length(a, length, values);
                self.solved_angle(solved_b, unit, values);
            }
            Case::LengthAndOtherAngle { .. } => {
                // The point K + l·v on a line meets the circle of radius |w0|.
                let (k, v, w0) = (vector(0), vector(1), vector(2));
                let quadratic = self.dot(v, v);
                let radius_squared = self.dot(w0, w0);
                // ∂/∂l = v, ∂/∂q = i·e^{iq}·w0.
                self.block_columns([quadratic, radius_squared], [false, true]);
                let half_b = self.dot(v, k);
                // (v·K)² − |v|²·(|K|² − |w0|²) = |v|²·|w0|² − (v×K)² (Lagrange's identity).
                let plus = self.graph.mul(quadratic, radius_squared);
                let skew = self.cross(v, k);
                let minus = self.graph.mul(skew, skew);
                let root = branch_root(self, plus, minus);
                let length = self.quadratic_solution(half_b, root, quadratic);
                // Columns v and i·W with W = −(K + l·v): the determinant is
                // v·W = −(v·K + l·|v|²), minus the root.
                let det = self.graph.neg(root);
                self.determinant(step, det);
                let along = self.scaled(v, length);
                let point = self.plus(k, along);
                let target = self.negated(point);
                let unit = self.turn(target, w0);
                self.solved_length(a, length, values);
                self.solved_angle(solved_b, unit, values);
            }
        }
    }

    /// Records the step's Jacobian block determinant, `det` as the case knows it for its
    /// unknowns: a [flipped](Step::flipped) angle's column is minus the case's, in `q'`.
    fn determinant(&mut self, step: &Step, det: ExprId) {
        let det = if step.flips_determinant() {
            self.graph.neg(det)
        } else {
            det
        };
        self.determinants.push(det);
    }

    /// `(−half_b + root) / a`.
    fn quadratic_solution(&mut self, half_b: ExprId, root: ExprId, a: ExprId) -> ExprId {
        let numerator = self.graph.sub(root, half_b);
        let inverse = self.graph.recip(a);
        self.graph.mul(numerator, inverse)
    }

    /// Solves `J·x = rhs` block by block in plan order (the Jacobian is block
    /// lower-triangular in that order), each 2×2 block by Cramer's rule.
    /// Each solution is named (a [`AuxKind::Bind`] value), so products read it whole.
    fn solve(&mut self, steps: &[Step], jacobian: &[ExprId], rhs: &[ExprId]) -> Vec<ExprId> {
        let n = rhs.len();
        let entry = |row: usize, column: usize| jacobian[row * n + column];
        let mut x: Vec<Option<ExprId>> = vec![None; n];
        for (s, step) in steps.iter().enumerate() {
            let rows = [2 * step.loop_index, 2 * step.loop_index + 1];
            let [a, b] = step.unknowns;
            let right = rows.map(|row| {
                (0..n).fold(rhs[row], |sum, u| match x[u] {
                    Some(known) if !self.graph.is_zero(entry(row, u)) => {
                        let moved = self.graph.mul(entry(row, u), known);
                        self.graph.sub(sum, moved)
                    }
                    _ => sum,
                })
            });
            let [[j00, j01], [j10, j11]] = rows.map(|row| [entry(row, a), entry(row, b)]);
            let inverse = self.aux(AuxKind::InverseDeterminant {
                det: self.determinants[s],
                inverse_norms: self.inverse_norms[s],
                squared_norms: self.squared_norms[s],
                threshold: Threshold::Rates,
                turning: self.turning[s],
            });
            let second = self.cross([j00, j10], [right[0], right[1]]);
            let second = self.graph.mul(second, inverse);
            let second = self.bound(second);
            // A column of numbers with a zero (a slider along a fixed axis) makes the block
            // triangular: the first unknown then comes from the other row by substitution,
            // which is cheaper than Cramer's rule and exact in the same way.
            let triangular = [(0, 1), (1, 0)].into_iter().find_map(|(zero, other)| {
                let entries = [[j00, j01], [j10, j11]];
                let pivot = self.graph.constant_value(entries[other][0])?;
                (self.graph.is_zero(entries[zero][0]) && pivot != 0.0).then_some((
                    other,
                    pivot,
                    entries[other][1],
                ))
            });
            let first = match triangular {
                Some((other, pivot, coupling)) => {
                    let moved = self.graph.mul(coupling, second);
                    let rest = self.graph.sub(right[other], moved);
                    let factor = self.graph.constant(1.0 / pivot);
                    self.graph.mul(factor, rest)
                }
                None => {
                    let numerator = self.cross([right[0], right[1]], [j01, j11]);
                    self.graph.mul(numerator, inverse)
                }
            };
            let first = self.bound(first);
            x[a] = Some(first);
            x[b] = Some(second);
        }
        x.into_iter()
            .map(|value| value.expect("a closed-form plan solves every unknown"))
            .collect()
    }

    /// Records the unknowns' rates (or accelerations) where the model's expressions read them.
    fn solved_derivatives(&mut self, derivative: fn(SymbolRef) -> Var, values: &[ExprId]) {
        for (u, &value) in values.iter().enumerate() {
            let var = self.graph.var(derivative(SymbolRef::Unknown(u)));
            self.replace.insert(var, value);
        }
    }
}

/// Builds the straight-line form of a closed-form plan from the scene expressions
/// (angle sums already taken apart). `lengths` says which unknowns are lengths: those, and
/// the points, come out times [`Var::Unscale`], in the mechanism's units.
pub fn build(graph: &mut Graph, steps: &[Step], exprs: &SceneExprs, lengths: &[bool]) -> Straight {
    let n = exprs.velocity_rhs.len();
    let mut builder = Builder {
        graph,
        aux: Vec::new(),
        known: HashMap::new(),
        replace: HashMap::new(),
        inverse_norms: Vec::new(),
        squared_norms: Vec::new(),
        turning: Vec::new(),
        determinants: Vec::new(),
    };
    let mut values = vec![ExprId::from_index(0); n];
    let mut branch = 0;
    for (step, coefficients) in steps.iter().zip(&exprs.coefficients) {
        builder.close(step, coefficients, &mut branch, &mut values);
    }
    let jacobian = builder.substituted(&exprs.jacobian);
    let velocity_rhs = builder.substituted(&exprs.velocity_rhs);
    let rates = builder.solve(steps, &jacobian, &velocity_rhs);
    builder.solved_derivatives(Var::Rate, &rates);
    // The product rule makes a Coriolis term twice; the rates known, it is one term doubled.
    let acceleration_rhs: Vec<ExprId> = builder
        .substituted(&exprs.acceleration_rhs)
        .into_iter()
        .map(|rhs| builder.graph.gather_like_terms(rhs))
        .collect();
    let accelerations = builder.solve(steps, &jacobian, &acceleration_rhs);
    builder.solved_derivatives(Var::Accel, &accelerations);
    let points: Vec<[[ExprId; 2]; 3]> = exprs
        .points
        .iter()
        .map(|point| {
            point.map(|pair| {
                let rewritten = builder.substituted(&pair);
                [rewritten[0], rewritten[1]]
            })
        })
        .collect();
    // Back to the mechanism's units, with `1/scale` among the fixed factors: where a product
    // has one (a length), it costs nothing.
    let unscale = builder.graph.var(Var::Unscale);
    let mut unscaled = |e: ExprId| builder.graph.mul(unscale, e);
    let [values, rates, accelerations] = [values, rates, accelerations].map(|all| {
        all.into_iter()
            .zip(lengths)
            .map(|(e, &length)| if length { unscaled(e) } else { e })
            .collect::<Vec<_>>()
    });
    let points: Vec<[[ExprId; 2]; 3]> = points
        .into_iter()
        .map(|point: [[ExprId; 2]; 3]| point.map(|pair| pair.map(&mut unscaled)))
        .collect();
    Straight {
        aux: builder.aux,
        values,
        rates,
        accelerations,
        points,
    }
}
