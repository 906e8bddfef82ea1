//! The command line's progress bar on stderr, fed by the same [`Progress`] handle the
//! explorer reads: the running phase (a reduction's factorisation, constraint modes,
//! eigensolve; a benchmark's point k of n) and the simulated time of the running integration.
//! Hidden when stderr is not a terminal, so logs and CI output stay clean.

use std::{
    io::IsTerminal,
    sync::{
        Arc,
        atomic::{AtomicBool, Ordering},
    },
    thread::JoinHandle,
    time::Duration,
};

use indicatif::{MultiProgress, ProgressBar, ProgressDrawTarget, ProgressStyle};

use crate::Progress;

/// Redraw interval of the bar.
const TICK: Duration = Duration::from_millis(100);
/// Resolution of the simulated-time bar.
const STEPS: u64 = 1000;

/// A bar drawn while it lives; dropping it clears the line.
pub struct TerminalProgress {
    stop: Arc<AtomicBool>,
    thread: Option<JoinHandle<()>>,
}

impl TerminalProgress {
    /// Draws `what` (e.g. `slab-sim1 (3 of 10)`) and what `progress` reports, every 100 ms.
    pub fn start(progress: &Progress, what: &str) -> Self {
        Self::start_in(None, progress, what)
    }

    /// A stderr target for bars drawn together (one line each), hidden when stderr is not a
    /// terminal.
    pub fn group() -> MultiProgress {
        MultiProgress::with_draw_target(if std::io::stderr().is_terminal() {
            ProgressDrawTarget::stderr()
        } else {
            ProgressDrawTarget::hidden()
        })
    }

    /// [`start`](Self::start), on a line of `group` when given (work running side by side).
    pub fn start_in(group: Option<&MultiProgress>, progress: &Progress, what: &str) -> Self {
        let stop = Arc::new(AtomicBool::new(false));
        let target = if std::io::stderr().is_terminal() {
            ProgressDrawTarget::stderr()
        } else {
            ProgressDrawTarget::hidden()
        };
        let bar = ProgressBar::with_draw_target(Some(STEPS), target);
        let bar = match group {
            Some(g) => g.add(bar),
            None => bar,
        };
        let style =
            ProgressStyle::with_template("{spinner} {prefix} [{elapsed_precise}] {wide_bar} {msg}")
                .unwrap_or_else(|_| ProgressStyle::default_bar());
        bar.set_style(style);
        bar.set_prefix(what.to_string());
        let (progress, flag) = (progress.clone(), stop.clone());
        let thread = std::thread::spawn(move || {
            while !flag.load(Ordering::Relaxed) {
                let mut message = Vec::new();
                if let Some(p) = progress.phase_reading() {
                    message.push(format!("{} ({:.1} s)", p.name, p.elapsed_s));
                }
                match progress.reading() {
                    Some(r) if r.end_time > 0.0 && r.time < r.end_time => {
                        bar.set_position((r.time / r.end_time * STEPS as f64) as u64);
                        message.push(format!(
                            "simulation {}: t = {:.2} of {:.2} s",
                            r.simulations, r.time, r.end_time
                        ));
                    }
                    _ => bar.set_position(0),
                }
                bar.set_message(message.join(" · "));
                bar.tick();
                // Parked, not asleep: dropping the bar unparks it, so the work it follows
                // does not wait out the tick (it cost every scene up to 0.1 s).
                std::thread::park_timeout(TICK);
            }
            bar.finish_and_clear();
        });
        Self {
            stop,
            thread: Some(thread),
        }
    }
}

impl Drop for TerminalProgress {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
        if let Some(t) = self.thread.take() {
            t.thread().unpark();
            let _ = t.join();
        }
    }
}
