//! Where a sweep's outputs go, and what it says of the samples it could not compute.

use super::*;

/// Samples that could not be computed inside a piece, by reason, with the first few inputs.
#[derive(Default)]
pub(super) struct Failures {
    pub(super) singular: u64,
    pub(super) inaccurate: u64,
    pub(super) overflow: u64,
    pub(super) other: u64,
    pub(super) first: Vec<(f64, String)>,
}

impl Failures {
    pub(super) fn count(&self) -> u64 {
        self.singular + self.inaccurate + self.overflow + self.other
    }

    pub(super) fn add(&mut self, input: f64, error: &Error<f64>) {
        let why = match error {
            Error::Singular { .. } => {
                self.singular += 1;
                "singular".to_string()
            }
            Error::Inaccurate { estimate, .. } => {
                self.inaccurate += 1;
                format!("inaccurate, estimated error {estimate:.1e}")
            }
            Error::NonFinite { quantity } => {
                self.overflow += 1;
                format!("{quantity} not finite (overflow)")
            }
            other => {
                self.other += 1;
                output::error(other)
            }
        };
        if self.first.len() < 3 {
            self.first.push((input, why));
        }
    }

    /// "3 not computed (2 singular, 1 inaccurate): at 0° singular, …", or nothing.
    pub(super) fn words(&self) -> Option<String> {
        if self.count() == 0 {
            return None;
        }
        let kinds: Vec<String> = [
            (self.singular, "singular"),
            (self.inaccurate, "inaccurate"),
            (self.overflow, "not finite"),
            (self.other, "other"),
        ]
        .into_iter()
        .filter(|(n, _)| *n > 0)
        .map(|(n, kind)| format!("{n} {kind}"))
        .collect();
        let at: Vec<String> = self
            .first
            .iter()
            .map(|(input, why)| format!("{}° {why}", tidy(*input)))
            .collect();
        Some(format!(
            "{} not computed ({}): at {}{}",
            self.count(),
            kinds.join(", "),
            at.join(", "),
            if self.count() > self.first.len() as u64 {
                ", …"
            } else {
                ""
            }
        ))
    }
}

/// Where an output goes: standard output for `-`, else the path under `--out-dir`.
pub(super) enum Target {
    Stdout,
    File(PathBuf),
}

impl Target {
    pub(super) fn new(path: &Path, out_dir: &Path) -> Self {
        if path == Path::new("-") {
            Target::Stdout
        } else {
            Target::File(out_dir.join(path))
        }
    }

    pub(super) fn name(&self) -> String {
        match self {
            Target::Stdout => "standard output".into(),
            Target::File(path) => path.display().to_string(),
        }
    }

    pub(super) fn open(&self) -> Result<Box<dyn Write>, String> {
        Ok(match self {
            Target::Stdout => Box::new(BufWriter::new(io::stdout())),
            Target::File(path) => Box::new(BufWriter::new(
                File::create(path).map_err(|e| format!("cannot write {}: {e}", path.display()))?,
            )),
        })
    }

    /// A failed write: a closed pipe ends the program quietly, anything else is an error.
    pub(super) fn failed(&self, error: io::Error) -> String {
        match self {
            Target::Stdout => output::gone(error),
            Target::File(path) => format!("cannot write {}: {error}", path.display()),
        }
    }

    pub(super) fn write(&self, text: &str) -> Result<(), String> {
        let mut out = self.open()?;
        out.write_all(text.as_bytes())
            .and_then(|()| out.flush())
            .map_err(|e| self.failed(e))
    }
}
