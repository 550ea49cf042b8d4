//! Formulas: constants of a mechanism computed from its parameters by functions or products
//! (`sqrt(l1 * l1 + l2 * l2)`, `l3 * cos(gamma)`, `atan2(b, a)`). They are not linear in the
//! parameters, so a loop holds each as a term of its own; they depend on the dimensions
//! alone, so the generated code computes them with the other such quantities (once per
//! mechanism in `scenes()`).
//!
//! A formula has a dimension, its degree in length: a length parameter is of degree 1, an
//! angle parameter or a number of degree 0, a product adds degrees, a square root halves
//! them. A magnitude must be of degree 1 and an angle of degree 0, so that a formula scales
//! with the mechanism as a declared length does (the solvers scale every length by a power
//! of two, and a formula must come out scaled by the same).

use std::collections::BTreeSet;
use std::fmt;

/// A function a declaration may apply to numbers and parameters.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Function {
    Sqrt,
    Sin,
    Cos,
    Tan,
    Atan2,
    Hypot,
}

impl Function {
    /// The function a name in a declaration calls, with its number of arguments.
    pub fn named(name: &str) -> Option<(Function, usize)> {
        Some(match name {
            "sqrt" => (Function::Sqrt, 1),
            "sin" => (Function::Sin, 1),
            "cos" => (Function::Cos, 1),
            "tan" => (Function::Tan, 1),
            "atan2" => (Function::Atan2, 2),
            "hypot" => (Function::Hypot, 2),
            _ => return None,
        })
    }

    pub fn name(self) -> &'static str {
        match self {
            Function::Sqrt => "sqrt",
            Function::Sin => "sin",
            Function::Cos => "cos",
            Function::Tan => "tan",
            Function::Atan2 => "atan2",
            Function::Hypot => "hypot",
        }
    }

    /// The degree of the result from the arguments' degrees, or why they do not fit.
    pub fn degree(self, arguments: &[f64]) -> Result<f64, &'static str> {
        match (self, arguments) {
            (Function::Sqrt, [d]) => Ok(d / 2.0),
            (Function::Sin | Function::Cos | Function::Tan, [0.0]) => Ok(0.0),
            (Function::Sin | Function::Cos | Function::Tan, _) => {
                Err("takes an angle or a number, not a length")
            }
            (Function::Atan2, [y, x]) if y == x => Ok(0.0),
            (Function::Hypot, [a, b]) if a == b => Ok(*a),
            (Function::Atan2 | Function::Hypot, _) => {
                Err("takes two of a kind: two lengths, or two numbers")
            }
            _ => Err("takes another number of arguments"),
        }
    }
}

/// A formula over numbers and parameters (by index).
#[derive(Clone, Debug, PartialEq)]
pub enum Formula {
    Param(usize),
    Number(f64),
    Neg(Box<Formula>),
    Add(Box<Formula>, Box<Formula>),
    Sub(Box<Formula>, Box<Formula>),
    Mul(Box<Formula>, Box<Formula>),
    Div(Box<Formula>, Box<Formula>),
    Call(Function, Vec<Formula>),
}

impl Formula {
    /// Its value with each parameter's from `param`, as the generated code computes it.
    pub fn value(&self, param: &mut dyn FnMut(usize) -> f64) -> f64 {
        match self {
            Formula::Param(i) => param(*i),
            Formula::Number(value) => *value,
            Formula::Neg(inner) => -inner.value(param),
            Formula::Add(a, b) => a.value(param) + b.value(param),
            Formula::Sub(a, b) => a.value(param) - b.value(param),
            Formula::Mul(a, b) => a.value(param) * b.value(param),
            Formula::Div(a, b) => a.value(param) / b.value(param),
            Formula::Call(function, arguments) => {
                let values: Vec<f64> = arguments.iter().map(|a| a.value(param)).collect();
                match (function, values.as_slice()) {
                    (Function::Sqrt, [x]) => x.sqrt(),
                    (Function::Sin, [x]) => x.sin(),
                    (Function::Cos, [x]) => x.cos(),
                    (Function::Tan, [x]) => x.tan(),
                    (Function::Atan2, [y, x]) => y.atan2(*x),
                    (Function::Hypot, [x, y]) => x.hypot(*y),
                    // The parser takes each function with its number of arguments.
                    _ => f64::NAN,
                }
            }
        }
    }

    /// The parameters it reads, into `params`.
    pub fn params(&self, params: &mut BTreeSet<usize>) {
        match self {
            Formula::Param(i) => {
                params.insert(*i);
            }
            Formula::Number(_) => {}
            Formula::Neg(inner) => inner.params(params),
            Formula::Add(a, b) | Formula::Sub(a, b) | Formula::Mul(a, b) | Formula::Div(a, b) => {
                a.params(params);
                b.params(params);
            }
            Formula::Call(_, arguments) => arguments.iter().for_each(|a| a.params(params)),
        }
    }

    /// As the declaration would write it, with `name` for each parameter.
    pub fn display<'a>(&'a self, name: &'a dyn Fn(usize) -> String) -> impl fmt::Display + 'a {
        Shown {
            formula: self,
            name,
        }
    }
}

struct Shown<'a> {
    formula: &'a Formula,
    name: &'a dyn Fn(usize) -> String,
}

impl fmt::Display for Shown<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write(f, self.formula, self.name, false)
    }
}

/// `formula` as written, in parentheses where it is a sum inside a product or a negation.
fn write(
    f: &mut fmt::Formatter<'_>,
    formula: &Formula,
    name: &dyn Fn(usize) -> String,
    in_product: bool,
) -> fmt::Result {
    match formula {
        Formula::Param(i) => f.write_str(&name(*i)),
        Formula::Number(value) => write!(f, "{value}"),
        Formula::Neg(inner) => {
            f.write_str("-")?;
            write(f, inner, name, true)
        }
        Formula::Add(a, b) | Formula::Sub(a, b) => {
            let sign = if matches!(formula, Formula::Add(..)) {
                " + "
            } else {
                " - "
            };
            if in_product {
                f.write_str("(")?;
            }
            write(f, a, name, false)?;
            f.write_str(sign)?;
            write(f, b, name, true)?;
            if in_product {
                f.write_str(")")?;
            }
            Ok(())
        }
        Formula::Mul(a, b) | Formula::Div(a, b) => {
            let sign = if matches!(formula, Formula::Mul(..)) {
                " * "
            } else {
                " / "
            };
            write(f, a, name, true)?;
            f.write_str(sign)?;
            write(f, b, name, true)
        }
        Formula::Call(function, arguments) => {
            write!(f, "{}(", function.name())?;
            for (k, argument) in arguments.iter().enumerate() {
                if k > 0 {
                    f.write_str(", ")?;
                }
                write(f, argument, name, false)?;
            }
            f.write_str(")")
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn degrees_follow_the_functions() {
        assert_eq!(Function::Sqrt.degree(&[2.0]), Ok(1.0));
        assert_eq!(Function::Sqrt.degree(&[1.0]), Ok(0.5));
        assert_eq!(Function::Hypot.degree(&[1.0, 1.0]), Ok(1.0));
        assert_eq!(Function::Atan2.degree(&[1.0, 1.0]), Ok(0.0));
        assert_eq!(Function::Cos.degree(&[0.0]), Ok(0.0));
        assert!(Function::Sin.degree(&[1.0]).is_err());
        assert!(Function::Atan2.degree(&[1.0, 0.0]).is_err());
        assert!(Function::Hypot.degree(&[0.0, 1.0]).is_err());
        assert_eq!(Function::named("hypot"), Some((Function::Hypot, 2)));
        assert_eq!(Function::named("exp"), None);
    }

    #[test]
    fn a_formula_shows_as_written_with_the_parentheses_it_needs() {
        let p = |i| Box::new(Formula::Param(i));
        let names = ["a", "b", "c"];
        let name = |i: usize| names[i].to_string();
        let difference = Formula::Sub(
            Box::new(Formula::Mul(p(0), p(0))),
            Box::new(Formula::Mul(p(1), p(1))),
        );
        let root = Formula::Call(Function::Sqrt, vec![difference.clone()]);
        assert_eq!(root.display(&name).to_string(), "sqrt(a * a - b * b)");
        let scaled = Formula::Mul(p(2), Box::new(difference));
        assert_eq!(scaled.display(&name).to_string(), "c * (a * a - b * b)");
    }
}
