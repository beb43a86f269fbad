//! Progress on the terminal for the long steps: one line per stage with its elapsed time
//! ([`StageBars`]), and a counting bar with the running item and an ETA for the pipeline's
//! long steps ([`BARS`]). Everything goes to stderr and is hidden when stderr is not a
//! terminal (indicatif's default), so piped output and logs stay clean; text printed while a
//! bar is drawn goes through [`say`], which lifts the bar for it.

use indicatif::{ProgressBar, ProgressStyle};
use squeal_pipeline::progress::Progress;
use std::sync::{Mutex, PoisonError};
use std::time::Duration;

/// The bar of the pipeline's current long step, if one is running.
pub static BARS: Bars = Bars {
    bar: Mutex::new(None),
};

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
}

impl Bars {
    fn current(&self) -> Option<ProgressBar> {
        let guard = self.bar.lock().unwrap_or_else(PoisonError::into_inner);
        guard.as_ref().map(|(b, _)| b.clone())
    }
}

impl Progress for Bars {
    fn begin(&self, step: &str, total: usize) {
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
    fn durations_read_in_the_unit_that_fits() {
        assert_eq!(duration(Duration::from_secs(42)), "42 s");
        assert_eq!(duration(Duration::from_secs(600)), "10 min");
        assert_eq!(duration(Duration::from_secs(9000)), "2.5 h");
    }
}
