//! Progress on stderr, one way for every command: on a terminal an `indicatif` bar with rate and
//! ETA (a spinner with the elapsed time where the total is not known: a remesh, a sketch); off a
//! terminal nothing but the command's final line, unless `--progress` asks for one line every
//! [`EVERY`] (for logs and batch jobs). `--quiet` (run) turns the bar off.

use indicatif::{ProgressBar, ProgressState, ProgressStyle};
use std::io::IsTerminal;
use std::sync::mpsc;
use std::time::{Duration, Instant};

/// How often `--progress` prints a line off a terminal.
pub const EVERY: Duration = Duration::from_secs(5);

pub struct Progress {
    bar: Option<ProgressBar>,
    lines: Option<Lines>,
    /// For a spinner's `--progress` lines: the ticking thread's stop signal.
    ticker: Option<(mpsc::Sender<()>, std::thread::JoinHandle<()>)>,
}

struct Lines {
    label: String,
    unit: &'static str,
    total: u64,
    start: Instant,
    last: Instant,
}

impl Progress {
    /// Progress over `total` `unit`s (steps) labelled `label`; `shown`: a bar on a terminal,
    /// `lines`: `--progress`'s lines off one.
    pub fn counted(label: &str, total: u64, unit: &'static str, shown: bool, lines: bool) -> Self {
        let terminal = std::io::stderr().is_terminal();
        let bar = (shown && terminal).then(|| {
            let b = ProgressBar::new(total);
            let template = format!("{label} {{bar:40}} {{pos}}/{{len}} {unit}  {{rate}} {unit}/s  {{elapsed_precise}} (eta {{eta}})");
            let style = ProgressStyle::with_template(&template).unwrap_or_else(|_| ProgressStyle::default_bar());
            b.set_style(style.with_key("rate", |s: &ProgressState, w: &mut dyn std::fmt::Write| {
                let _ = write!(w, "{:.0}", s.per_sec());
            }));
            b
        });
        let now = Instant::now();
        let lines = (lines && !terminal).then(|| Lines { label: label.into(), unit, total, start: now, last: now });
        Progress { bar, lines, ticker: None }
    }

    /// Work of unknown length (one call into the core): a spinner with the elapsed time on a
    /// terminal; `--progress` lines off one, from a thread, until [`Progress::finish`].
    pub fn spinner(label: &str, shown: bool, lines: bool) -> Self {
        let terminal = std::io::stderr().is_terminal();
        let bar = (shown && terminal).then(|| {
            let b = ProgressBar::new_spinner();
            let template = format!("{{spinner}} {label}  {{elapsed_precise}}");
            b.set_style(ProgressStyle::with_template(&template).unwrap_or_else(|_| ProgressStyle::default_spinner()));
            b.enable_steady_tick(Duration::from_millis(120));
            b
        });
        let ticker = (lines && !terminal).then(|| {
            let (tx, rx) = mpsc::channel::<()>();
            let label = label.to_string();
            let start = Instant::now();
            let handle = std::thread::spawn(move || {
                while let Err(mpsc::RecvTimeoutError::Timeout) = rx.recv_timeout(EVERY) {
                    eprintln!("progress: {label}: {:.0} s", start.elapsed().as_secs_f64());
                }
            });
            (tx, handle)
        });
        Progress { bar, lines: None, ticker }
    }

    /// `pos` units done.
    pub fn set(&mut self, pos: u64) {
        if let Some(b) = &self.bar {
            b.set_position(pos);
        }
        if let Some(l) = &mut self.lines {
            if l.last.elapsed() >= EVERY {
                l.last = Instant::now();
                let t = l.start.elapsed().as_secs_f64();
                let rate = pos as f64 / t.max(1e-9);
                let eta = if rate > 0.0 { (l.total.saturating_sub(pos)) as f64 / rate } else { f64::INFINITY };
                let pct = 100.0 * pos as f64 / l.total.max(1) as f64;
                eprintln!("progress: {}: {pos}/{} {} ({pct:.0} %), {rate:.0} {}/s, eta {eta:.0} s", l.label, l.total, l.unit, l.unit);
            }
        }
    }

    /// Run `f` (printing a result line) with the bar hidden, so the line is not drawn over.
    pub fn suspend(&self, f: impl FnOnce()) {
        match &self.bar {
            Some(b) => b.suspend(f),
            None => f(),
        }
    }

    /// Done: the bar is cleared (the command's final line follows), the ticker stopped.
    pub fn finish(self) {
        if let Some(b) = self.bar {
            b.finish_and_clear();
        }
        if let Some((tx, handle)) = self.ticker {
            let _ = tx.send(());
            let _ = handle.join();
        }
    }
}
