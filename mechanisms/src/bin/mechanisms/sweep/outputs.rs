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
        let joined = out_dir.join(path);
        if crate::output::is_stdout(path) || crate::output::is_stdout(&joined) {
            Target::Stdout
        } else {
            Target::File(joined)
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

/// Refuses two outputs to one file, before anything is written (the last written would be all
/// that is left of them): the files as the file system finds them, so that `./x.svg` and
/// `x.svg`, `sub/../x.svg` and `x.svg`, a link and what it links to, are one. An output whose
/// directory does not exist is refused here too, rather than after the others are written.
pub(super) fn distinct(outputs: &[(&str, &Target)]) -> Result<(), String> {
    let mut files: Vec<(&str, PathBuf)> = Vec::new();
    for (flag, target) in outputs {
        let Target::File(path) = target else {
            continue;
        };
        let file = resolved(path)?;
        if let Some((other, _)) = files.iter().find(|(_, seen)| *seen == file) {
            return Err(format!(
                "{other} and {flag} both write {}: give each output its own file",
                path.display()
            ));
        }
        files.push((flag, file));
    }
    Ok(())
}

/// The file `path` names: itself, links followed, where it exists; what a link to a file not
/// yet written links to; else its directory's, joined with its name.
fn resolved(path: &Path) -> Result<PathBuf, String> {
    let mut path = path.to_path_buf();
    // A few links deep (a loop of links is refused by the file system as it is written).
    for _ in 0..8 {
        if let Ok(file) = std::fs::canonicalize(&path) {
            return Ok(file);
        }
        let directory = match path.parent() {
            Some(parent) if !parent.as_os_str().is_empty() => parent.to_path_buf(),
            _ => PathBuf::from("."),
        };
        match std::fs::read_link(&path) {
            Ok(target) => path = directory.join(target),
            Err(_) => {
                let name = path
                    .file_name()
                    .ok_or_else(|| format!("cannot write {}: it names no file", path.display()))?;
                let directory = std::fs::canonicalize(&directory)
                    .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
                return Ok(directory.join(name));
            }
        }
    }
    Err(format!("cannot write {}: too many links", path.display()))
}
