//! Standard output for a program people pipe into `head`: a closed pipe ends the program
//! quietly, and numbers print tidily.

use std::io::{self, Write};

/// `println!` for the program's reports: a reader that has gone away (a closed pipe) ends the
/// program quietly with success, as `yes | head` does; any other failure to write is an error.
macro_rules! say {
    ($($arg:tt)*) => {
        $crate::output::say_line(::std::format_args!($($arg)*))
    };
}
pub(crate) use say;

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
    eprintln!("error: cannot write to standard output: {error}");
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
