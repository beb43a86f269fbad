//! Progress on the terminal for the long steps: one line per stage with its elapsed time.
//! Everything goes to stderr and is hidden when stderr is not a terminal (indicatif's
//! default), so piped output and logs stay clean.

use indicatif::{ProgressBar, ProgressStyle};
use std::time::Duration;

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

fn style(template: &str) -> ProgressStyle {
    // The templates are constants; a bad one falls back to indicatif's default look.
    ProgressStyle::with_template(template)
        .map(|s| s.progress_chars("=> "))
        .unwrap_or_else(|_| ProgressStyle::default_spinner())
}
