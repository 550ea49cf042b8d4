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

/// Whether the report goes to standard error: where a chart is written to standard output,
/// the report must not be mixed into it (see [`report_on_stderr`]).
static REPORT_ON_STDERR: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

/// Whether `path` names standard output: `-`, or (on Unix) a path to the file standard
/// output is (`/dev/stdout`, `/proc/self/fd/1`, the file it is redirected to), which takes
/// the report off standard output as `-` does, where it would be mixed into the output.
pub fn is_stdout(path: &std::path::Path) -> bool {
    if path.as_os_str() == "-" {
        return true;
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        if let (Ok(given), Ok(stdout)) = (std::fs::metadata(path), std::fs::metadata("/dev/stdout"))
        {
            return given.dev() == stdout.dev() && given.ino() == stdout.ino();
        }
    }
    false
}

/// Sends the report ([`say!`]) to standard error from now on, where it cannot be mistaken for
/// an output written to standard output ([`drawing_to_stdout`]).
pub fn report_on_stderr() {
    REPORT_ON_STDERR.store(true, std::sync::atomic::Ordering::Relaxed);
}

/// Writes one line of the report (see [`say!`]): to standard output, or to standard error
/// after [`report_on_stderr`].
pub fn say_line(line: std::fmt::Arguments) {
    if REPORT_ON_STDERR.load(std::sync::atomic::Ordering::Relaxed) {
        tell_line(line);
        return;
    }
    stdout_line(line);
}

/// A drawing written to standard output, whatever the report's stream.
pub fn drawing_to_stdout(drawing: &str) {
    stdout_line(format_args!("{drawing}"));
}

/// Writes one line to standard output, ending the program as [`gone`] says where it cannot.
fn stdout_line(line: std::fmt::Arguments) {
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

/// `value` to the digits its error `bound` (absolute, in its units) leaves, so that no
/// printed digit is noise: as [`figure`] writes it (4 decimals, or 5 significant digits in
/// exponent form below 1e-3 and from 1e9) where the bound is below the last of those, else
/// to the last digit whose half unit covers the bound (`-183512.4`, `-4.5540e8`); zero
/// where the bound is as large as the value itself (`0 (±b)` where the bound shows at 4
/// decimals), and `undetermined` for an unbounded error.
pub fn within(value: f64, bound: f64) -> String {
    if !value.is_finite() {
        return "not finite".into();
    }
    if bound.is_nan() || bound.is_infinite() {
        return "undetermined".into();
    }
    let bound = bound.max(0.0);
    let magnitude = value.abs();
    if magnitude <= bound && bound > 0.0 {
        // Zero to the 4 decimals printed, or to the bound where that is coarser.
        return if bound < 0.5e-4 {
            fixed(0.0, 4)
        } else {
            format!("0 (±{})", significant(bound, 1))
        };
    }
    let moderate = magnitude == 0.0 || (1e-3..1e9).contains(&magnitude);
    if moderate && bound < 0.5e-4 {
        return fixed(value, 4);
    }
    if moderate && bound < 0.5 {
        // The most decimals whose last digit's half unit still covers the bound.
        let decimals = (-(2.0 * bound).log10()).floor().clamp(0.0, 4.0) as usize;
        return fixed(value, decimals);
    }
    if bound == 0.0 {
        return figure(value);
    }
    // Significant digits: the last one's half unit covers the bound; 1 to 5.
    let exponent = magnitude.log10().floor();
    let digits = (exponent + 1.0 - (2.0 * bound).log10())
        .floor()
        .clamp(1.0, 5.0) as usize;
    format!("{value:.precision$e}", precision = digits - 1)
}

/// [`within`] for a quantity that can take values over a range `span` wide only (a
/// transmission angle's 180°, a slide's stroke): `undetermined` where the bound covers the
/// whole range, which says nothing of the value (at a change point, where the position's
/// error bound grows without limit, the parallelogram's γ was `0 (±90000)`).
pub fn within_span(value: f64, bound: f64, span: f64) -> String {
    if bound >= span {
        return "undetermined".into();
    }
    within(value, bound)
}

/// An angle (radians) in degrees in [0, 360), to the decimals its error `bound` (radians)
/// leaves, at most 4 (see [`within`]).
pub fn degrees_within(radians: f64, bound: f64) -> String {
    if !radians.is_finite() {
        return "not finite".into();
    }
    let bound = bound.to_degrees();
    if bound.is_nan() || bound.is_infinite() || bound >= 90.0 {
        return "undetermined".into();
    }
    let decimals = if bound < 0.5e-4 {
        4
    } else {
        (-(2.0 * bound).log10()).floor().clamp(0.0, 4.0) as usize
    };
    degrees(radians, decimals)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// No digit past what the error leaves: the review's near-toggle rate (true −183512.4172,
    /// printed −183512.4111: off by 6e-3) and mechanical advantage (true −455397458, off by 60), a robot's
    /// velocity at 1e300 that is rounding (4.46e284 where the truth is 0, within 1e286), and
    /// ordinary values as before.
    #[test]
    fn values_print_to_the_digits_their_errors_leave() {
        assert_eq!(within(-183512.4111, 6e-3), "-183512.4");
        assert_eq!(within(-183512.4111, 4e-3), "-183512.41");
        assert_eq!(within(-183512.4111, 0.04), "-183512.4");
        assert_eq!(within(-455397513.1023, 60.0), "-4.5540e8");
        assert_eq!(within(-1.8420e13, 5.5e9), "-1.84e13");
        assert_eq!(within(4.4611e284, 1e286), "0 (±1e286)");
        assert_eq!(within(-1.0000e300, 1e286), "-1.0000e300");
        assert_eq!(within(259.8076211, 1e-12), "259.8076");
        assert_eq!(within(-6.3949e-14, 1e-12), "0.0000");
        assert_eq!(within(-6.3949e-4, 1e-3), "0 (±0.001)");
        assert_eq!(within(0.0, 1e-12), "0.0000");
        assert_eq!(within(1.5e-7, 1e-20), "1.5000e-7");
        assert_eq!(within(1.0, f64::INFINITY), "undetermined");
        assert_eq!(within(f64::NAN, 1.0), "not finite");
        assert_eq!(within(12.5, 0.0), "12.5000");
        assert_eq!(degrees_within(0.5, 1e-12), "28.6479");
        assert_eq!(degrees_within(8.7e-5, 5e-6), "0.005");
        assert_eq!(degrees_within(8.7e-5, 1e-4), "0.0");
        assert_eq!(degrees_within(-8.7e-5, 2e-5), "0.00");
        assert_eq!(degrees_within(-8.7e-5, 2e-6), "359.995");
        assert_eq!(degrees_within(-8.7e-5, 2e-3), "0");
    }

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
