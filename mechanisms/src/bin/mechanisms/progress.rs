//! Progress for a run that takes a while, on standard error: shown once the run has taken a
//! second, and only on a terminal, so that standard output stays the data and a quick or
//! redirected run shows nothing.

use std::io::{self, IsTerminal};
use std::sync::mpsc::{self, RecvTimeoutError};
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// How long a run goes on before it shows its progress.
const QUIET_FOR: Duration = Duration::from_secs(1);

/// A bar of `total` steps, hidden until [`advance`] shows it.
pub fn bar(total: u64) -> ProgressBar {
    ProgressBar::with_draw_target(Some(total), ProgressDrawTarget::hidden())
}

/// Moves `bar` to `done` steps, showing it once the run `started` a second ago, on a terminal.
pub fn advance(bar: &ProgressBar, started: Instant, done: u64) {
    if bar.is_hidden() && started.elapsed() > QUIET_FOR && io::stderr().is_terminal() {
        bar.set_draw_target(ProgressDrawTarget::stderr());
    }
    bar.set_position(done);
}

/// `work`'s result, with a spinner saying `what` and the time taken shown while it runs, past
/// a second, on a terminal: for work that cannot count its steps as it goes (the synthesis'
/// restarts run inside the library, in parallel).
pub fn while_running<T>(what: &str, work: impl FnOnce() -> T) -> T {
    let spinner = ProgressBar::with_draw_target(None, ProgressDrawTarget::hidden())
        .with_message(what.to_string());
    if let Ok(style) = ProgressStyle::with_template("{spinner} {msg} ({elapsed})") {
        spinner.set_style(style);
    }
    let (done, finished) = mpsc::channel::<()>();
    let spinner = &spinner;
    std::thread::scope(|scope| {
        scope.spawn(move || {
            // Dropping `done` ends the wait early: then nothing is shown.
            if finished.recv_timeout(QUIET_FOR) == Err(RecvTimeoutError::Timeout)
                && io::stderr().is_terminal()
            {
                spinner.set_draw_target(ProgressDrawTarget::stderr());
                spinner.enable_steady_tick(Duration::from_millis(100));
                finished.recv().ok();
            }
            spinner.finish_and_clear();
        });
        let result = work();
        drop(done);
        result
    })
}
