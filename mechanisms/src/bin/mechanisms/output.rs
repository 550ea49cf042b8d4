//! Standard output for a program people pipe into `head`: a closed pipe ends the program
//! quietly, and numbers print tidily, in reports and in the library's errors alike.

use std::fmt;
use std::io::{self, Write};

use mechgen::Error;

/// `println!` for the program's reports: a reader that has gone away (a closed pipe) ends the
/// program quietly with success, as `yes | head` does; any other failure to write is an error.
macro_rules! say {
    ($($arg:tt)*) => {
        $crate::output::say_line(::std::format_args!($($arg)*))
    };
}
pub(crate) use say;

/// `eprintln!` for the program's notices and errors, which does not panic where standard
/// error is gone (a closed pipe: `mechanisms … 2>&1 | head -0`): a notice nobody can read is
/// dropped, and the exit status still says what happened.
macro_rules! tell {
    ($($arg:tt)*) => {
        $crate::output::tell_line(::std::format_args!($($arg)*))
    };
}
pub(crate) use tell;

/// Writes one line to standard error, if it can (see [`tell!`]).
pub fn tell_line(line: std::fmt::Arguments) {
    let mut err = io::stderr().lock();
    let _ = err.write_fmt(line).and_then(|()| err.write_all(b"\n"));
}

/// Writes one line to standard output (see [`say!`]).
pub fn say_line(line: std::fmt::Arguments) {
    let mut out = io::stdout().lock();
    if let Err(error) = out.write_fmt(line).and_then(|()| out.write_all(b"\n")) {
        gone(error);
    }
}

/// Ends the program after a failed write to standard output: quietly with success if the
/// reader closed the pipe (it has all it wanted), else with the error.
pub fn gone(error: io::Error) -> ! {
    if error.kind() == io::ErrorKind::BrokenPipe {
        std::process::exit(0);
    }
    tell!("error: cannot write to standard output: {error}");
    std::process::exit(1);
}

/// `template` with each `{}` in turn replaced by the next of `values`, [`tidy`]: a
/// mechanism's dimensions in its description.
pub fn filled(template: &str, values: &[f64]) -> String {
    let mut values = values.iter();
    let mut parts = template.split("{}");
    let mut text = parts.next().unwrap_or_default().to_string();
    for part in parts {
        text.push_str(&values.next().map_or_else(String::new, |v| tidy(*v)));
        text.push_str(part);
    }
    text
}

/// A number as a person would write it: to 12 significant digits, without the last-digit
/// noise of binary fractions (`30`, not `29.999999999999996`), in exponent form when very
/// large or very small (`1e308`, not 309 digits).
pub fn tidy(value: f64) -> String {
    if !value.is_finite() {
        return value.to_string();
    }
    let rounded: f64 = format!("{value:.11e}").parse().unwrap_or(value);
    let magnitude = rounded.abs();
    if rounded == 0.0 {
        "0".into()
    } else if !(1e-5..1e15).contains(&magnitude) {
        format!("{rounded:e}")
    } else {
        rounded.to_string()
    }
}

/// `value` to `digits` significant digits, written as [`tidy`] writes it (`6.055e-6`, not
/// `0.000006055454452393339`).
pub fn significant(value: f64, digits: usize) -> String {
    if !value.is_finite() {
        return value.to_string();
    }
    let precision = digits.saturating_sub(1);
    tidy(format!("{value:.precision$e}").parse().unwrap_or(value))
}

/// A result to 4 places, or to 4 decimals of an exponent form where 4 places would show
/// nothing or too many digits (below 1e-3, from 1e9).
pub fn figure(value: f64) -> String {
    if value == 0.0 || (1e-3..1e9).contains(&value.abs()) {
        fixed(value, 4)
    } else {
        format!("{value:.4e}")
    }
}

/// A figure inside an error's text: to four significant digits, and an input (an angle: every
/// input the program takes is one) in degrees, as the program takes it.
enum Shown {
    Short(f64),
    Degrees(f64),
}

impl fmt::Display for Shown {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Shown::Short(value) => f.write_str(&significant(value, 4)),
            Shown::Degrees(radians) => write!(f, "{}°", significant(radians.to_degrees(), 4)),
        }
    }
}

/// The library's error in its own words, with its figures to four significant digits (the
/// runtime writes them in full, which reads as noise in a one-line message) and its input
/// in degrees.
pub fn error(error: &Error<f64>) -> String {
    let short = match *error {
        Error::NonFinite { quantity } => Error::NonFinite { quantity },
        Error::CannotAssemble { input } => Error::CannotAssemble {
            input: Shown::Degrees(input),
        },
        Error::Singular {
            determinant,
            relative_determinant,
        } => Error::Singular {
            determinant: Shown::Short(determinant),
            relative_determinant: Shown::Short(relative_determinant),
        },
        Error::Inaccurate {
            order,
            estimate,
            required,
        } => Error::Inaccurate {
            order,
            estimate: Shown::Short(estimate),
            required: Shown::Short(required),
        },
        Error::OtherBranch => Error::OtherBranch,
        Error::NoConvergence {
            iterations,
            residual_norm,
        } => Error::NoConvergence {
            iterations,
            residual_norm: Shown::Short(residual_norm),
        },
        // A kind added to the runtime since: its own words, figures and all.
        _ => return error.to_string(),
    };
    short.to_string()
}

/// `value` to `decimals` places, never as `-0.0000`.
pub fn fixed(value: f64, decimals: usize) -> String {
    let text = format!("{value:.decimals$}");
    if text.starts_with('-') && text[1..].chars().all(|c| c == '0' || c == '.') {
        text[1..].to_string()
    } else {
        text
    }
}

/// An angle in degrees in [0, 360) to `decimals` places: an angle a rounding below a full
/// turn prints as `0.0000`, not `360.0000`.
pub fn degrees(radians: f64, decimals: usize) -> String {
    let text = fixed(radians.to_degrees().rem_euclid(360.0), decimals);
    if text.parse::<f64>() == Ok(360.0) {
        fixed(0.0, decimals)
    } else {
        text
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tidy_numbers_drop_binary_noise_and_long_digit_runs() {
        assert_eq!(tidy(0.1 + 0.2), "0.3");
        assert_eq!(tidy(29.999999999999996), "30");
        assert_eq!(tidy(1e308), "1e308");
        assert_eq!(tidy(-80.0), "-80");
        assert_eq!(tidy(100.81), "100.81");
        assert_eq!(degrees(-1e-15, 4), "0.0000");
        assert_eq!(fixed(-1e-9, 4), "0.0000");
        assert_eq!(significant(0.000006055454452393339, 4), "6.055e-6");
        assert_eq!(significant(123.456789, 4), "123.5");
        assert_eq!(figure(0.16556), "0.1656");
        assert_eq!(figure(2.4529e305), "2.4529e305");
        assert_eq!(figure(1.5e-7), "1.5000e-7");
    }

    #[test]
    fn errors_keep_their_words_with_short_figures() {
        let singular = Error::Singular {
            determinant: 0.000006055454452393339,
            relative_determinant: 1.0 / 3.0,
        };
        assert_eq!(
            error(&singular),
            "the loop Jacobian is singular (determinant 6.055e-6, relative determinant \
             0.3333): the mechanism is at a toggle or change point"
        );
        assert_eq!(
            error(&Error::CannotAssemble {
                input: std::f64::consts::PI
            }),
            "the mechanism cannot be assembled at input 180°: it is outside the range of motion"
        );
        let unchanged = Error::<f64>::NonFinite { quantity: "input" };
        assert_eq!(error(&unchanged), unchanged.to_string());
    }

    #[test]
    fn a_template_is_filled_with_tidy_numbers_in_turn() {
        assert_eq!(
            filled("{} {} mm at {}°", &[180.0, 0.1 + 0.2, 30.0]),
            "180 0.3 mm at 30°"
        );
        // Too few numbers leave the rest empty; too many are not printed.
        assert_eq!(filled("({}, {})", &[1.0]), "(1, )");
        assert_eq!(filled("{}", &[1.0, 2.0]), "1");
    }
}
