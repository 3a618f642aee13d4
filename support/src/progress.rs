//! A progress bar for runs over many images: drawn (indicatif) only when
//! stderr is a terminal, so logs and CI output stay plain.

use std::io::IsTerminal as _;

use indicatif::{ProgressBar, ProgressStyle};

/// Progress over a known number of items.
pub struct Progress {
    bar: Option<ProgressBar>,
}

impl Progress {
    /// A bar over `len` items when stderr is a terminal, else nothing.
    pub fn new(len: usize) -> Self {
        Self::with_bar(std::io::stderr().is_terminal(), len)
    }

    /// A bar over `len` items when `visible`.
    pub fn with_bar(visible: bool, len: usize) -> Self {
        let bar = visible.then(|| {
            let bar = ProgressBar::new(len as u64);
            let style = ProgressStyle::with_template(
                "{bar:40} {pos}/{len} [{elapsed_precise}, eta {eta}] {wide_msg}",
            )
            .unwrap_or_else(|_| ProgressStyle::default_bar());
            bar.set_style(style);
            bar
        });
        Self { bar }
    }

    /// Whether a bar is drawn.
    pub fn is_visible(&self) -> bool {
        self.bar.is_some()
    }

    /// One more item done; `msg` names it.
    pub fn inc(&self, msg: &str) {
        if let Some(bar) = &self.bar {
            bar.set_message(msg.to_string());
            bar.inc(1);
        }
    }

    /// Prints `line` on stderr (above the bar, when there is one).
    pub fn println(&self, line: &str) {
        match &self.bar {
            Some(bar) => bar.println(line),
            None => eprintln!("{line}"),
        }
    }

    /// Removes the bar.
    pub fn finish(&self) {
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
    }
}
