//! Progress on the terminal for the long steps: one line per stage with its elapsed time
//! ([`StageBars`]), and a counting bar with the running item and an ETA for the pipeline's
//! long steps ([`BARS`]). Everything goes to stderr; when stderr is not a terminal (a log, a
//! pipe) the bars are hidden (indicatif's default) and a long step prints a plain line every
//! [`PLAIN_EVERY`] instead (`sweep: 40/201 mu values, 3.1 s`), so a long run is never silent;
//! text printed while a bar is drawn goes through [`say`], which lifts the bar for it.

use indicatif::{ProgressBar, ProgressStyle};
use squeal_pipeline::progress::Progress;
use std::io::IsTerminal;
use std::sync::{Mutex, PoisonError};
use std::time::{Duration, Instant};

/// The bar of the pipeline's current long step, if one is running.
pub static BARS: Bars = Bars {
    bar: Mutex::new(None),
    plain: Mutex::new(None),
};

/// How often a long step prints its line when stderr is not a terminal.
pub const PLAIN_EVERY: Duration = Duration::from_secs(3);

/// A long step told in plain lines: its name, when it began, when it last printed.
struct Plain {
    step: String,
    began: Instant,
    printed: Instant,
}

/// Prints a line to stdout without tearing the bar being drawn.
pub fn say(text: &str) {
    match BARS.current() {
        Some(bar) => bar.suspend(|| println!("{text}")),
        None => println!("{text}"),
    }
}

/// A counting bar per long step of the pipeline (see [`Progress`]).
pub struct Bars {
    bar: Mutex<Option<(ProgressBar, bool)>>,
    plain: Mutex<Option<Plain>>,
}

impl Bars {
    fn current(&self) -> Option<ProgressBar> {
        let guard = self.bar.lock().unwrap_or_else(PoisonError::into_inner);
        guard.as_ref().map(|(b, _)| b.clone())
    }
}

impl Bars {
    /// The plain line of an item, when stderr is not a terminal and the last line is
    /// [`PLAIN_EVERY`] old.
    fn plain_line(&self, what: &str) -> Option<String> {
        let mut guard = self.plain.lock().unwrap_or_else(PoisonError::into_inner);
        let p = guard.as_mut()?;
        let now = Instant::now();
        if now.duration_since(p.printed) < PLAIN_EVERY {
            return None;
        }
        p.printed = now;
        let t = now.duration_since(p.began).as_secs_f64();
        Some(format!("{}: {what}, {t:.1} s", p.step))
    }
}

impl Progress for Bars {
    fn begin(&self, step: &str, total: usize) {
        if !std::io::stderr().is_terminal() {
            let now = Instant::now();
            *self.plain.lock().unwrap_or_else(PoisonError::into_inner) = Some(Plain {
                step: step.to_string(),
                began: now,
                printed: now,
            });
        }
        let bar = ProgressBar::new(total as u64);
        bar.set_style(style(
            "  {prefix} {pos}/{len} [{bar:20}] {elapsed}{wide_msg}",
        ));
        bar.set_prefix(step.to_string());
        bar.enable_steady_tick(Duration::from_millis(250));
        let mut guard = self.bar.lock().unwrap_or_else(PoisonError::into_inner);
        if let Some((old, _)) = guard.replace((bar, false)) {
            old.finish();
        }
    }

    fn item(&self, what: &str) {
        if let Some(line) = self.plain_line(what) {
            eprintln!("{line}");
        }
        let mut guard = self.bar.lock().unwrap_or_else(PoisonError::into_inner);
        if let Some((bar, started)) = guard.as_mut() {
            if *started {
                bar.inc(1);
            }
            *started = true;
            // The items differ in cost by orders of magnitude (a reference integration
            // against a CHBM solve), so indicatif's smoothed rate swings wildly; the mean
            // time per item done so far is steadier.
            let (done, total) = (bar.position(), bar.length().unwrap_or(0));
            let left =
                (done > 0).then(|| bar.elapsed().mul_f64((total - done) as f64 / done as f64));
            let eta = left.map_or(String::new(), |t| format!(", about {} left", duration(t)));
            bar.set_message(format!("{eta}: {what}"));
        }
    }

    fn end(&self) {
        *self.plain.lock().unwrap_or_else(PoisonError::into_inner) = None;
        let mut guard = self.bar.lock().unwrap_or_else(PoisonError::into_inner);
        if let Some((bar, _)) = guard.take() {
            bar.set_position(bar.length().unwrap_or(0));
            bar.finish_and_clear();
        }
    }
}

/// One spinner per stage, left on the terminal with its time when the next stage starts.
#[derive(Default)]
pub struct StageBars {
    current: Option<ProgressBar>,
}

impl StageBars {
    /// Finishes the running stage and starts `stage` of `part`.
    pub fn start(&mut self, part: &str, stage: &str) {
        self.finish();
        let bar = ProgressBar::new_spinner();
        bar.set_style(style("{spinner} {prefix:<5} {msg:<24} {elapsed_precise}"));
        bar.set_prefix(part.to_string());
        bar.set_message(stage.to_string());
        bar.enable_steady_tick(Duration::from_millis(120));
        self.current = Some(bar);
    }

    /// Leaves the running stage on the terminal with its time.
    pub fn finish(&mut self) {
        if let Some(bar) = self.current.take() {
            bar.set_style(style("  {prefix:<5} {msg:<24} {elapsed_precise}"));
            bar.finish();
        }
    }
}

impl Drop for StageBars {
    fn drop(&mut self) {
        self.finish();
    }
}

/// `42 s`, `3 min`, `1.5 h`.
fn duration(t: Duration) -> String {
    let s = t.as_secs_f64();
    if s < 90.0 {
        format!("{s:.0} s")
    } else if s < 5400.0 {
        format!("{:.0} min", s / 60.0)
    } else {
        format!("{:.1} h", s / 3600.0)
    }
}

fn style(template: &str) -> ProgressStyle {
    // The templates are constants; a bad one falls back to indicatif's default look.
    ProgressStyle::with_template(template)
        .map(|s| s.progress_chars("=> "))
        .unwrap_or_else(|_| ProgressStyle::default_spinner())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_item_counts_once_the_next_one_starts() {
        let bars = Bars {
            bar: Mutex::new(None),
            plain: Mutex::new(None),
        };
        bars.begin("runs", 3);
        bars.item("first");
        let bar = bars.current().unwrap();
        assert_eq!(bar.position(), 0, "the first run is under way, none done");
        bars.item("second");
        assert_eq!(bar.position(), 1);
        assert!(bar.message().ends_with(": second"), "{}", bar.message());
        assert!(bar.message().contains("left"), "{}", bar.message());
        bars.end();
        assert_eq!(bar.position(), 3, "an ended step is complete");
        assert!(bars.current().is_none());
    }

    #[test]
    fn a_plain_line_comes_at_most_every_few_seconds() {
        let bars = Bars {
            bar: Mutex::new(None),
            plain: Mutex::new(None),
        };
        assert_eq!(bars.plain_line("1/9"), None, "no plain step: a terminal");
        let began = Instant::now() - 2 * PLAIN_EVERY;
        *bars.plain.lock().unwrap() = Some(Plain {
            step: "sweep".into(),
            began,
            printed: began,
        });
        let line = bars.plain_line("40/201 mu values").unwrap();
        assert!(line.starts_with("sweep: 40/201 mu values, "), "{line}");
        assert!(line.ends_with(" s"), "{line}");
        assert_eq!(
            bars.plain_line("41/201 mu values"),
            None,
            "printed just now"
        );
        bars.end();
        assert!(
            bars.plain.lock().unwrap().is_none(),
            "an ended step prints no more"
        );
    }

    #[test]
    fn durations_read_in_the_unit_that_fits() {
        assert_eq!(duration(Duration::from_secs(42)), "42 s");
        assert_eq!(duration(Duration::from_secs(600)), "10 min");
        assert_eq!(duration(Duration::from_secs(9000)), "2.5 h");
    }
}
